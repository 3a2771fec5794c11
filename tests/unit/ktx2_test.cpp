// KTX 2.0 reader and writer (src/texture_file/container_ktx2.cpp): round trips of real encodes
// in every shape, the exact bytes of the header, DFD, key/value data and level layout, and
// bad input (truncation, lying offsets and sizes, unsupported features, zstd bombs).
#include <gtest/gtest.h>
#include <zstd.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "ktx2_test_util.h"
#include "tessera/texture_file.h"

namespace tessera::texture_file {
namespace {

using Bytes = std::vector<std::uint8_t>;
using test::Ktx2Variant;

constexpr std::uint32_t kVk4Unorm = 1000054001u;

void put_u32(Bytes& b, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b[at + std::size_t(i)] = std::uint8_t(v >> (8 * i));
}
void put_u64(Bytes& b, std::size_t at, std::uint64_t v) {
  put_u32(b, at, std::uint32_t(v));
  put_u32(b, at + 4, std::uint32_t(v >> 32));
}
std::uint32_t get_u32(const Bytes& b, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= std::uint32_t(b[at + std::size_t(i)]) << (8 * i);
  return v;
}
std::uint64_t get_u64(const Bytes& b, std::size_t at) {
  return get_u32(b, at) | std::uint64_t(get_u32(b, at + 4)) << 32;
}

Bytes serialise(const CompressedTexture& t, int zstd_level = 0) {
  Result<Bytes> b = serialise_ktx2(t, Ktx2Options{zstd_level});
  EXPECT_TRUE(b.ok()) << b.status().message;
  return b.ok() ? *b : Bytes{};
}

CompressedTexture encode(const Ktx2Variant& v) {
  Result<CompressedTexture> t = test::encode_ktx2_variant(v);
  EXPECT_TRUE(t.ok()) << t.status().message;
  return t.ok() ? *t : CompressedTexture{};
}

const Ktx2Variant& variant(const std::string& name) {
  static const std::vector<Ktx2Variant> all = test::ktx2_variants();
  for (const Ktx2Variant& v : all) {
    if (v.name == name) return v;
  }
  ADD_FAILURE() << "no variant " << name;
  return all.front();
}

void expect_identical(const CompressedTexture& a, const CompressedTexture& b) {
  EXPECT_EQ(a.format, b.format);
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.has_alpha, b.has_alpha);
  EXPECT_EQ(a.srgb, b.srgb);
  EXPECT_EQ(a.premultiplied, b.premultiplied);
  EXPECT_EQ(a.faces, b.faces);
  EXPECT_EQ(a.layers, b.layers);
  EXPECT_EQ(a.array, b.array);
  EXPECT_EQ(a.levels, b.levels);
}

/// The DFD tessera must write for PVRTC1 4 bpp, linear, straight alpha (44 bytes).
const Bytes kDfd4bppLinear = {
    44,  0,   0,   0,               // dfdTotalSize
    0,   0,   0,   0,               // vendorId 0, descriptorType 0
    2,   0,   40,  0,               // versionNumber 2 (1.3), descriptorBlockSize 40
    164, 1,   1,   0,               // model PVRTC, primaries BT709, transfer linear, flags 0
    3,   3,   0,   0,               // texelBlockDimension 4x4x1x1
    8,   0,   0,   0,  0, 0, 0, 0,  // bytesPlane0 = 8
    0,   0,   63,  0,               // sample: bitOffset 0, bitLength 63, channel PVRTC_COLOR
    0,   0,   0,   0,               // samplePosition
    0,   0,   0,   0,               // sampleLower
    255, 255, 255, 255              // sampleUpper
};

/// A KTX 2.0 file laid out by the test itself (not by the writer under test): header, level
/// index, `dfd`, `kvd`, then `levels` smallest first, each at an 8-byte boundary.
struct Parts {
  std::uint32_t vk_format = kVk4Unorm, type_size = 1, width = 16, height = 16, depth = 0;
  std::uint32_t layers = 0, faces = 1, level_count = 1, scheme = 0;
  Bytes dfd = kDfd4bppLinear;
  Bytes kvd;
  std::vector<Bytes> levels;
  std::vector<std::uint64_t> uncompressed;  ///< per level; empty = the payload sizes
};

Bytes assemble(const Parts& p) {
  Bytes out = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
  out.resize(80 + 24 * p.levels.size());
  const std::size_t dfd_at = out.size();
  out.insert(out.end(), p.dfd.begin(), p.dfd.end());
  const std::size_t kvd_at = out.size();
  out.insert(out.end(), p.kvd.begin(), p.kvd.end());
  const std::uint32_t header[] = {p.vk_format,
                                  p.type_size,
                                  p.width,
                                  p.height,
                                  p.depth,
                                  p.layers,
                                  p.faces,
                                  p.level_count,
                                  p.scheme,
                                  std::uint32_t(dfd_at),
                                  std::uint32_t(p.dfd.size()),
                                  p.kvd.empty() ? 0u : std::uint32_t(kvd_at),
                                  std::uint32_t(p.kvd.size())};
  for (std::size_t i = 0; i < std::size(header); ++i) put_u32(out, 12 + 4 * i, header[i]);
  for (std::size_t i = p.levels.size(); i-- > 0;) {
    out.resize((out.size() + 7) / 8 * 8, 0);
    put_u64(out, 80 + 24 * i, out.size());
    put_u64(out, 88 + 24 * i, p.levels[i].size());
    put_u64(out, 96 + 24 * i, p.uncompressed.empty() ? p.levels[i].size() : p.uncompressed[i]);
    out.insert(out.end(), p.levels[i].begin(), p.levels[i].end());
  }
  return out;
}

/// A 16x16 4 bpp linear opaque texture, one level, as `Parts`.
Parts plain_parts() {
  Parts p;
  p.levels.push_back(encode(variant("4bpp-linear-opaque")).levels[0]);
  return p;
}

Status parse_error(const Bytes& bytes) {
  Result<CompressedTexture> r = parse_ktx2(bytes, "bad.ktx2");
  if (r.ok()) return Status::success();
  EXPECT_EQ(r.status().message.rfind("bad.ktx2: ", 0), 0u) << r.status().message;
  EXPECT_EQ(r.status().message.find('\n'), std::string::npos) << r.status().message;
  return r.status();
}

void expect_error(const Bytes& bytes, ErrorCode code, const std::string& part) {
  const Status s = parse_error(bytes);
  EXPECT_EQ(s.code, code) << s.message;
  EXPECT_NE(s.message.find(part), std::string::npos)
      << "'" << s.message << "' lacks '" << part << "'";
}

// ---------------------------------------------------------------------------------------------
// Round trips and layout
// ---------------------------------------------------------------------------------------------

TEST(Ktx2RoundTrip, EveryVariantReadsBackIdentical) {
  for (const Ktx2Variant& v : test::ktx2_variants()) {
    SCOPED_TRACE(v.name);
    const CompressedTexture t = encode(v);
    ASSERT_EQ(t.has_alpha, v.alpha) << "the encode itself should (not) have alpha";
    for (int zstd : {v.zstd_level, v.zstd_level == 0 ? 3 : 0}) {
      SCOPED_TRACE("zstd " + std::to_string(zstd));
      Result<CompressedTexture> back = parse_ktx2(serialise(t, zstd), "rt.ktx2");
      ASSERT_TRUE(back.ok()) << back.status().message;
      expect_identical(t, *back);
      // The generic entry points dispatch to the same reader.
      Result<CompressedTexture> any = parse_texture(serialise(t, zstd), "rt.ktx2");
      ASSERT_TRUE(any.ok()) << any.status().message;
      expect_identical(t, *any);
    }
  }
}

TEST(Ktx2RoundTrip, OutputIsDeterministic) {
  const Ktx2Variant& v = variant("4bpp-cube-array2-alpha-premultiplied-mips-zstd3");
  for (int zstd : {0, 3, 19}) {
    EXPECT_EQ(serialise(encode(v), zstd), serialise(encode(v), zstd)) << "zstd " << zstd;
  }
}

TEST(Ktx2Layout, HeaderDfdKeyValuesAndLevelsAreExact) {
  const CompressedTexture t = encode(variant("4bpp-srgb-alpha-mips"));  // 32x16, 6 levels
  const Bytes b = serialise(t);
  ASSERT_EQ(t.level_count(), 6);
  EXPECT_EQ(std::memcmp(b.data(), "\xABKTX 20\xBB\r\n\x1A\n", 12), 0);
  const std::uint32_t header[] = {1000054005u, 1, 32, 16, 0, 0, 1, 6, 0, 224, 44, 268, 52};
  for (std::size_t i = 0; i < std::size(header); ++i) {
    EXPECT_EQ(get_u32(b, 12 + 4 * i), header[i]) << "header field " << i;
  }
  EXPECT_EQ(get_u64(b, 64), 0u);  // sgdByteOffset
  EXPECT_EQ(get_u64(b, 72), 0u);  // sgdByteLength
  Bytes dfd = kDfd4bppLinear;
  dfd[14] = 2;  // transfer sRGB
  EXPECT_EQ(Bytes(b.begin() + 224, b.begin() + 268), dfd);
  const std::string writer = "tessera " TESSERA_VERSION_STRING;
  ASSERT_EQ(writer.size(), 13u) << "the expected key/value bytes below assume a 5-char version";
  std::string kvd("\x12\0\0\0KTXorientation\0rd\0\0\0\x18\0\0\0KTXwriter\0", 38);
  kvd += writer + std::string(1, '\0');
  EXPECT_EQ(std::string(b.begin() + 268, b.begin() + 320), kvd);
  // Level data from byte 320, smallest level first, 8-byte aligned, level 0 ending the file.
  std::uint64_t at = 320;
  for (int i = 5; i >= 0; --i) {
    const std::size_t e = 80 + 24 * std::size_t(i);
    EXPECT_EQ(get_u64(b, e), at) << "level " << i;
    EXPECT_EQ(get_u64(b, e + 8), t.levels[std::size_t(i)].size());
    EXPECT_EQ(get_u64(b, e + 16), t.levels[std::size_t(i)].size());
    EXPECT_EQ(Bytes(b.begin() + std::ptrdiff_t(at),
                    b.begin() + std::ptrdiff_t(at + t.levels[std::size_t(i)].size())),
              t.levels[std::size_t(i)]);
    at += t.levels[std::size_t(i)].size();
  }
  EXPECT_EQ(at, b.size());
}

TEST(Ktx2Layout, ZstdLevelsAreOneFramePerLevelPackedTightly) {
  const CompressedTexture t = encode(variant("2bpp-array3-srgb-mips-zstd19"));
  const Bytes b = serialise(t, 19);
  EXPECT_EQ(get_u32(b, 44), 2u);                        // supercompressionScheme
  EXPECT_EQ(get_u32(b, 32), 3u);                        // layerCount
  std::uint64_t end = get_u32(b, 56) + get_u32(b, 60);  // after the key/value data
  for (int i = t.level_count() - 1; i >= 0; --i) {
    const std::size_t e = 80 + 24 * std::size_t(i);
    const std::uint64_t offset = get_u64(b, e), length = get_u64(b, e + 8);
    EXPECT_EQ(offset, end) << "no padding between supercompressed levels";
    EXPECT_EQ(get_u64(b, e + 16), t.levels[std::size_t(i)].size());
    EXPECT_EQ(ZSTD_getFrameContentSize(b.data() + offset, length), t.levels[std::size_t(i)].size());
    Bytes raw(t.levels[std::size_t(i)].size());
    EXPECT_EQ(ZSTD_decompress(raw.data(), raw.size(), b.data() + offset, length), raw.size());
    EXPECT_EQ(raw, t.levels[std::size_t(i)]);
    end = offset + length;
  }
  EXPECT_EQ(end, b.size());
}

TEST(Ktx2Layout, ReadsFilesLaidOutByAnotherWriter) {
  Parts p = plain_parts();
  p.kvd = {8, 0, 0, 0, 'a', 0, 'b', 'c', 'd', 0, 0, 0};  // an unknown key; a value with NUL
  Result<CompressedTexture> r = parse_ktx2(assemble(p), "x.ktx2");
  ASSERT_TRUE(r.ok()) << r.status().message;
  EXPECT_EQ(r->levels, p.levels);
  EXPECT_FALSE(r->has_alpha);
  EXPECT_FALSE(r->srgb);
  EXPECT_FALSE(r->array);
  // levelCount 0 ("generate the rest at load"): one level is stored and read.
  p.level_count = 0;
  r = parse_ktx2(assemble(p), "x.ktx2");
  ASSERT_TRUE(r.ok()) << r.status().message;
  EXPECT_EQ(r->level_count(), 1);
  // A hand-made zstd frame (one RLE block of 128 zero bytes, single segment): 16x16 of zero
  // blocks, whose endpoints are translucent, so the texture has alpha.
  p.scheme = 2;
  p.levels = {{0x28, 0xB5, 0x2F, 0xFD, 0x20, 128, 0x03, 0x04, 0x00, 0x00}};
  p.uncompressed = {128};
  r = parse_ktx2(assemble(p), "x.ktx2");
  ASSERT_TRUE(r.ok()) << r.status().message;
  EXPECT_EQ(r->levels[0], Bytes(128, 0));
  EXPECT_TRUE(r->has_alpha);
}

TEST(Ktx2Layout, PremultipliedAndSrgbComeFromTheDfd) {
  Parts p = plain_parts();
  p.dfd[15] = 1;  // ALPHA_PREMULTIPLIED
  Result<CompressedTexture> r = parse_ktx2(assemble(p), "x.ktx2");
  ASSERT_TRUE(r.ok()) << r.status().message;
  EXPECT_TRUE(r->premultiplied);
  p.vk_format = 1000054005u;  // 4 bpp sRGB
  p.dfd[14] = 2;
  r = parse_ktx2(assemble(p), "x.ktx2");
  ASSERT_TRUE(r.ok()) << r.status().message;
  EXPECT_TRUE(r->srgb);
}

TEST(Ktx2Writer, RefusesBadOptionsAndTextures) {
  const CompressedTexture t = encode(variant("4bpp-linear-opaque"));
  for (int level : {-1, 23}) {
    Result<Bytes> b = serialise_ktx2(t, Ktx2Options{level});
    ASSERT_FALSE(b.ok());
    EXPECT_EQ(b.status().code, ErrorCode::invalid_argument);
    EXPECT_NE(b.status().message.find("zstd level"), std::string::npos) << b.status().message;
  }
  CompressedTexture bad = t;
  bad.levels[0].pop_back();
  EXPECT_EQ(serialise_ktx2(bad).status().code, ErrorCode::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// Bad input
// ---------------------------------------------------------------------------------------------

TEST(Ktx2Errors, EveryTruncationIsAnErrorNeverACrash) {
  for (const char* name :
       {"4bpp-array1", "2bpp-linear-opaque-zstd19", "2bpp-cube-array2-srgb-mips"}) {
    const Ktx2Variant& v = variant(name);
    const Bytes full = serialise(encode(v), v.zstd_level);
    for (std::size_t n = 0; n < full.size(); ++n) {
      const Status s = parse_error(Bytes(full.begin(), full.begin() + std::ptrdiff_t(n)));
      ASSERT_EQ(s.code, ErrorCode::corrupt_data) << name << " cut at " << n << ": " << s.message;
    }
  }
}

TEST(Ktx2Errors, EveryFlippedByteParsesOrFailsCleanly) {
  for (const char* name : {"4bpp-array1", "2bpp-linear-opaque-zstd19"}) {
    const Ktx2Variant& v = variant(name);
    const Bytes full = serialise(encode(v), v.zstd_level);
    for (std::size_t at = 0; at < full.size(); ++at) {
      Bytes b = full;
      b[at] ^= 0xFF;
      Result<CompressedTexture> r = parse_ktx2(b, "bad.ktx2");
      if (r.ok()) {
        EXPECT_TRUE(validate_texture(*r, "flipped").ok()) << name << " byte " << at;
      } else {
        EXPECT_EQ(r.status().message.rfind("bad.ktx2: ", 0), 0u) << r.status().message;
      }
    }
  }
}

TEST(Ktx2Errors, IdentifierAndHeader) {
  Bytes b = assemble(plain_parts());
  b[5] = '1';  // «KTX 10»
  EXPECT_EQ(parse_error(b).message, "bad.ktx2: not a KTX 2.0 file (bad identifier)");
  expect_error(Bytes(b.begin(), b.begin() + 40), ErrorCode::corrupt_data, "not a KTX 2.0 file");
  Parts p = plain_parts();
  p.type_size = 4;
  expect_error(assemble(p), ErrorCode::corrupt_data, "typeSize 4");
  p = plain_parts();
  p.width = 0;
  expect_error(assemble(p), ErrorCode::corrupt_data, "pixelWidth 0");
  p = plain_parts();
  p.height = 0;
  expect_error(assemble(p), ErrorCode::unsupported, "1D textures");
  p = plain_parts();
  p.depth = 1;
  EXPECT_EQ(parse_error(assemble(p)).message,
            "bad.ktx2: 3D textures (pixelDepth 1) are not supported");
  p = plain_parts();
  p.level_count = 6;  // 16x16 has 5 levels at most
  p.levels.resize(6, Bytes(32, 0));
  expect_error(assemble(p), ErrorCode::corrupt_data,
               "levelCount 6 is impossible for 16x16 (1 to 5)");
  p = plain_parts();
  p.width = 12;
  expect_error(assemble(p), ErrorCode::invalid_argument, "power-of-two");
}

TEST(Ktx2Errors, FacesAndLayers) {
  Parts p = plain_parts();
  p.faces = 5;
  EXPECT_EQ(parse_error(assemble(p)).message, "bad.ktx2: faceCount 5 (1, or 6 for a cube map)");
  p.faces = 6;
  p.width = 32;  // 32x16 cube
  expect_error(assemble(p), ErrorCode::corrupt_data, "must be square, not 32x16");
  p = plain_parts();
  p.layers = 2049;
  p.faces = 6;
  expect_error(assemble(p), ErrorCode::too_large, "layerCount 2049 exceeds");
  // A cube map with one face's worth of data: the level size gives it away.
  p = plain_parts();
  p.faces = 6;
  expect_error(assemble(p), ErrorCode::corrupt_data,
               "level 0 uncompressedByteLength 128 does not match 16x16 PVRTC x 6 image(s) (768 "
               "bytes)");
}

TEST(Ktx2Errors, UnsupportedFormatsAndSchemes) {
  Parts p = plain_parts();
  p.vk_format = 37;
  EXPECT_EQ(parse_error(assemble(p)).message,
            "bad.ktx2: vkFormat 37 (VK_FORMAT_R8G8B8A8_UNORM) is not supported (only PVRTC1: "
            "VK_FORMAT_PVRTC1_{2,4}BPP_{UNORM,SRGB}_BLOCK_IMG)");
  EXPECT_EQ(parse_error(assemble(p)).code, ErrorCode::unsupported);
  p.vk_format = 1000054003u;
  expect_error(assemble(p), ErrorCode::unsupported, "(VK_FORMAT_PVRTC2_4BPP_UNORM_BLOCK_IMG)");
  p.vk_format = 158;
  expect_error(assemble(p), ErrorCode::unsupported, "(VK_FORMAT_ASTC_4x4_SRGB_BLOCK)");
  p.vk_format = 123456;
  expect_error(assemble(p), ErrorCode::unsupported, "vkFormat 123456 is not supported");
  p = plain_parts();
  p.scheme = 1;
  EXPECT_EQ(parse_error(assemble(p)).message,
            "bad.ktx2: supercompressionScheme 1 (BasisLZ) is not supported (only 0, none, and 2, "
            "Zstandard)");
  p.scheme = 3;
  expect_error(assemble(p), ErrorCode::unsupported, "supercompressionScheme 3 (ZLIB)");
}

TEST(Ktx2Errors, DataFormatDescriptor) {
  Parts p = plain_parts();
  p.dfd.clear();
  expect_error(assemble(p), ErrorCode::corrupt_data, "no Data Format Descriptor");
  p = plain_parts();
  p.dfd[12] = 162;  // ASTC
  expect_error(assemble(p), ErrorCode::corrupt_data, "colour model 162 does not match");
  p = plain_parts();
  p.dfd[14] = 2;  // sRGB transfer on a UNORM vkFormat
  expect_error(assemble(p), ErrorCode::corrupt_data,
               "transfer function sRGB contradicts VK_FORMAT_PVRTC1_4BPP_UNORM_BLOCK_IMG");
  p.vk_format = 1000054005u;
  p.dfd[14] = 1;
  expect_error(assemble(p), ErrorCode::corrupt_data, "transfer function linear contradicts");
  p = plain_parts();
  p.dfd[16] = 7;  // 8x4: a 2 bpp descriptor on a 4 bpp vkFormat
  expect_error(assemble(p), ErrorCode::corrupt_data, "texel block 8x4x1x1 does not match");
  p = plain_parts();
  p.dfd[0] = 48;
  expect_error(assemble(p), ErrorCode::corrupt_data, "dfdTotalSize 48 differs");
  p = plain_parts();
  p.dfd[10] = 56;  // descriptorBlockSize beyond the DFD
  expect_error(assemble(p), ErrorCode::corrupt_data, "block size 56");
  p = plain_parts();
  p.dfd.resize(20);
  expect_error(assemble(p), ErrorCode::corrupt_data, "too short");
  Bytes b = assemble(plain_parts());
  put_u32(b, 48, 40);  // dfdByteOffset inside the header
  expect_error(b, ErrorCode::corrupt_data, "dfdByteOffset 40 lies inside the header");
}

TEST(Ktx2Errors, LyingLevelIndex) {
  const Bytes good = assemble(plain_parts());
  const std::uint64_t offset = get_u64(good, 80);
  Bytes b = good;
  put_u64(b, 80, good.size() - 64);  // past the end
  expect_error(b, ErrorCode::corrupt_data, "truncated: level 0 (128 bytes at byte");
  b = good;
  put_u64(b, 80, ~std::uint64_t{0} - 7);  // offset + length wraps around 2^64
  expect_error(b, ErrorCode::corrupt_data, "extends past the end of the file");
  b = good;
  put_u64(b, 88, ~std::uint64_t{0});  // byteLength near 2^64
  put_u64(b, 96, ~std::uint64_t{0});
  expect_error(b, ErrorCode::corrupt_data, "uncompressedByteLength 18446744073709551615");
  b = good;
  put_u64(b, 80, offset + 4);
  expect_error(b, ErrorCode::corrupt_data, "is not a multiple of 8");
  b = good;
  put_u64(b, 80, 96);  // inside the DFD
  expect_error(b, ErrorCode::corrupt_data, "lies inside the header, index or metadata");
  b = good;
  put_u64(b, 88, 120);
  expect_error(b, ErrorCode::corrupt_data,
               "byteLength 120 differs from its uncompressedByteLength");
  // Two levels sharing bytes.
  Parts p = plain_parts();
  p.level_count = 2;
  p.levels.push_back(Bytes(32, 0));
  b = assemble(p);
  put_u64(b, 104, get_u64(b, 80) + 64);  // level 1 inside level 0
  expect_error(b, ErrorCode::corrupt_data, "levels 0 and 1 overlap");
  // Supercompression global data where the scheme has none.
  b = good;
  put_u64(b, 64, 200);
  put_u64(b, 72, 8);
  expect_error(b, ErrorCode::corrupt_data, "supercompression global data of 8 bytes");
  // Key/value data overrunning its block.
  p = plain_parts();
  p.kvd = {40, 0, 0, 0, 'a', 0, 'b', 0};
  expect_error(assemble(p), ErrorCode::corrupt_data, "malformed key/value data");
}

// ---------------------------------------------------------------------------------------------
// Zstandard: lying frames and bombs
// ---------------------------------------------------------------------------------------------

/// One zstd frame of `n` zero bytes, streamed from a 1 MiB buffer (level 1), with or without
/// the content size in its header.
Bytes zstd_zeros(std::uint64_t n, bool declare_size) {
  ZSTD_CCtx* cctx = ZSTD_createCCtx();
  EXPECT_FALSE(ZSTD_isError(ZSTD_CCtx_setParameter(cctx, ZSTD_c_compressionLevel, 1)));
  EXPECT_FALSE(ZSTD_isError(ZSTD_CCtx_setParameter(cctx, ZSTD_c_contentSizeFlag, declare_size)));
  if (declare_size) {
    EXPECT_FALSE(ZSTD_isError(ZSTD_CCtx_setPledgedSrcSize(cctx, n)));
  }
  const Bytes zeros(std::size_t{1} << 20, 0);
  Bytes out, buf(ZSTD_CStreamOutSize());
  for (std::uint64_t done = 0; done < n;) {
    const std::size_t chunk = std::size_t(std::min<std::uint64_t>(zeros.size(), n - done));
    done += chunk;
    const ZSTD_EndDirective mode = done == n ? ZSTD_e_end : ZSTD_e_continue;
    ZSTD_inBuffer in{zeros.data(), chunk, 0};
    std::size_t left = 0;
    do {
      ZSTD_outBuffer o{buf.data(), buf.size(), 0};
      left = ZSTD_compressStream2(cctx, &o, &in, mode);
      EXPECT_FALSE(ZSTD_isError(left));
      out.insert(out.end(), buf.begin(), buf.begin() + std::ptrdiff_t(o.pos));
    } while (in.pos < in.size || (mode == ZSTD_e_end && left != 0));
  }
  ZSTD_freeCCtx(cctx);
  return out;
}

/// Rewrites the Frame_Content_Size field of a zstd frame (which must be wide enough).
void set_content_size(Bytes& frame, std::uint64_t v) {
  const std::uint8_t fhd = frame[4];
  const bool single = (fhd >> 5) & 1;
  const int dict_bytes[] = {0, 1, 2, 4};
  const std::size_t at = 5 + (single ? 0 : 1) + std::size_t(dict_bytes[fhd & 3]);
  const int fcs_bytes[] = {single ? 1 : 0, 2, 4, 8};
  const int n = fcs_bytes[fhd >> 6];
  ASSERT_GT(n, 0);
  if (n == 2) v -= 256;
  ASSERT_TRUE(n == 8 || v < (std::uint64_t{1} << (8 * n)));
  for (int i = 0; i < n; ++i) frame[at + std::size_t(i)] = std::uint8_t(v >> (8 * i));
}

Parts zstd_parts(Bytes frame) {
  Parts p = plain_parts();
  p.scheme = 2;
  p.uncompressed = {p.levels[0].size()};
  p.levels[0] = std::move(frame);
  return p;
}

Bytes compress(const Bytes& raw) {
  Bytes out(ZSTD_compressBound(raw.size()));
  const std::size_t n = ZSTD_compress(out.data(), out.size(), raw.data(), raw.size(), 3);
  EXPECT_FALSE(ZSTD_isError(n));
  out.resize(n);
  return out;
}

TEST(Ktx2Zstd, LyingFramesAreRefused) {
  const Bytes level = plain_parts().levels[0];  // 128 bytes
  ASSERT_TRUE(parse_ktx2(assemble(zstd_parts(compress(level))), "ok.ktx2").ok());
  // The frame declares 120 bytes; the header's shape needs 128.
  Bytes frame = compress(Bytes(level.begin(), level.begin() + 120));
  expect_error(assemble(zstd_parts(frame)), ErrorCode::corrupt_data,
               "level 0: the Zstandard frame declares 120 bytes, 128 bytes expected");
  // The frame says 128 but holds 120: zstd's own check.
  set_content_size(frame, 128);
  expect_error(assemble(zstd_parts(frame)), ErrorCode::corrupt_data, "level 0: bad Zstandard data");
  // uncompressedByteLength disagreeing with the shape.
  Parts p = zstd_parts(compress(level));
  p.uncompressed = {256};
  expect_error(assemble(p), ErrorCode::corrupt_data, "uncompressedByteLength 256 does not match");
  // Not a frame; a frame followed by junk; a frame cut short.
  expect_error(assemble(zstd_parts(Bytes(40, 7))), ErrorCode::corrupt_data,
               "level 0: not a Zstandard frame");
  frame = compress(level);
  frame.insert(frame.end(), {1, 2, 3});
  expect_error(assemble(zstd_parts(frame)), ErrorCode::corrupt_data,
               "level 0: 3 bytes after the Zstandard frame");
  frame = compress(level);
  frame.resize(frame.size() - 2);
  expect_error(assemble(zstd_parts(frame)), ErrorCode::corrupt_data,
               "level 0: bad Zstandard frame");
  // A level of zero bytes.
  expect_error(assemble(zstd_parts(Bytes{})), ErrorCode::corrupt_data,
               "0 bytes of Zstandard data cannot hold 128 bytes");
}

TEST(Ktx2Zstd, BombsAreRefusedBeforeTheyExpand) {
  constexpr std::uint64_t kGiB = std::uint64_t{1} << 30;
  // A frame of 1 GiB of zeros (a few KiB) where the header's 16x16 level needs 128 bytes.
  Bytes bomb = zstd_zeros(kGiB, true);
  ASSERT_LT(bomb.size(), std::size_t{1} << 20);
  ASSERT_EQ(ZSTD_getFrameContentSize(bomb.data(), bomb.size()), kGiB);
  expect_error(assemble(zstd_parts(bomb)), ErrorCode::corrupt_data,
               "the Zstandard frame declares 1073741824 bytes, 128 bytes expected");
  // The same frame claiming 128 bytes: decompressed into the level's 128 bytes, zstd stops at
  // the first block that does not fit.
  set_content_size(bomb, 128);
  expect_error(assemble(zstd_parts(bomb)), ErrorCode::corrupt_data, "level 0: bad Zstandard data");
  // A frame that does not say how big it is.
  const Bytes unsized = zstd_zeros(kGiB, false);
  ASSERT_EQ(ZSTD_getFrameContentSize(unsized.data(), unsized.size()), ZSTD_CONTENTSIZE_UNKNOWN);
  expect_error(assemble(zstd_parts(unsized)), ErrorCode::corrupt_data,
               "the Zstandard frame does not declare its size");
  // A header whose shape needs 8 MiB (4096x4096 at 4 bpp) with a 13-byte frame that says so:
  // no zstd data that short can expand that far, so nothing is allocated.
  Parts p =
      zstd_parts({0x28, 0xB5, 0x2F, 0xFD, 0xA0, 0x00, 0x00, 0x80, 0x00, 0x0B, 0x00, 0x00, 0x00});
  p.width = p.height = 4096;
  p.uncompressed = {std::uint64_t{8} << 20};
  expect_error(assemble(p), ErrorCode::corrupt_data,
               "level 0: 13 bytes of Zstandard data cannot hold 8388608 bytes");
}

}  // namespace
}  // namespace tessera::texture_file
