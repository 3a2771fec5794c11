// Tests of tessera/texture_file.h (PVR v3 and KTX 1.1) and tessera/mipmap.h: round trips,
// exact header bytes, every malformed-header path, truncation at every offset, and — when
// PVRTexToolCLI is available — files exchanged with the oracle in both directions.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

#include "tessera/io.h"
#include "tessera/metrics.h"
#include "tessera/mipmap.h"
#include "tessera/procedural.h"
#include "tessera/texture_file.h"
#include "test_support.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;

/// A texture with deterministic pseudo-random block data (not necessarily a meaningful image).
CompressedTexture fake_texture(pvrtc::Format format, int w, int h, int levels, bool alpha,
                               bool srgb) {
  CompressedTexture t;
  t.format = format;
  t.width = w;
  t.height = h;
  t.has_alpha = alpha;
  t.srgb = srgb;
  std::uint32_t state = 12345u + std::uint32_t(w * 31 + h);
  for (int i = 0; i < levels; ++i) {
    Bytes data(pvrtc::level_size(format, mip_dimension(w, i), mip_dimension(h, i)));
    for (auto& b : data) {
      state = state * 1664525u + 1013904223u;
      b = std::uint8_t(state >> 24);
    }
    t.levels.push_back(std::move(data));
  }
  return t;
}

void expect_same(const CompressedTexture& a, const CompressedTexture& b) {
  EXPECT_EQ(a.format, b.format);
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.has_alpha, b.has_alpha);
  EXPECT_EQ(a.srgb, b.srgb);
  EXPECT_EQ(a.levels, b.levels);
}

void put_u32(Bytes& b, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b[at + std::size_t(i)] = std::uint8_t(v >> (8 * i));
}
std::uint32_t get_u32(const Bytes& b, std::size_t at) {
  return std::uint32_t(b[at]) | std::uint32_t(b[at + 1]) << 8 | std::uint32_t(b[at + 2]) << 16 |
         std::uint32_t(b[at + 3]) << 24;
}

Bytes pvr_bytes(const CompressedTexture& t) {
  Result<Bytes> b = serialize_pvr3(t);
  EXPECT_TRUE(b.ok()) << b.status().message;
  return b.ok() ? *b : Bytes{};
}
Bytes ktx_bytes(const CompressedTexture& t) {
  Result<Bytes> b = serialize_ktx1(t);
  EXPECT_TRUE(b.ok()) << b.status().message;
  return b.ok() ? *b : Bytes{};
}

/// Parses and expects failure with `code` and a one-line message naming "f.pvr" that
/// contains `needle`.
void expect_pvr_error(const Bytes& bytes, ErrorCode code, const std::string& needle) {
  Result<CompressedTexture> r = parse_pvr3(bytes, "f.pvr");
  ASSERT_FALSE(r.ok()) << "accepted, expected: " << needle;
  EXPECT_EQ(r.status().code, code) << r.status().message;
  EXPECT_EQ(r.status().message.rfind("f.pvr: ", 0), 0u) << r.status().message;
  EXPECT_NE(r.status().message.find(needle), std::string::npos) << r.status().message;
  EXPECT_EQ(r.status().message.find('\n'), std::string::npos);
}
void expect_ktx_error(const Bytes& bytes, ErrorCode code, const std::string& needle) {
  Result<CompressedTexture> r = parse_ktx1(bytes, "f.ktx");
  ASSERT_FALSE(r.ok()) << "accepted, expected: " << needle;
  EXPECT_EQ(r.status().code, code) << r.status().message;
  EXPECT_EQ(r.status().message.rfind("f.ktx: ", 0), 0u) << r.status().message;
  EXPECT_NE(r.status().message.find(needle), std::string::npos) << r.status().message;
  EXPECT_EQ(r.status().message.find('\n'), std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// PVR v3
// ---------------------------------------------------------------------------------------------

TEST(Pvr3, RoundTripsEveryVariant) {
  for (pvrtc::Format f : {pvrtc::Format::pvrtc1_4bpp, pvrtc::Format::pvrtc1_2bpp}) {
    for (bool alpha : {false, true}) {
      for (bool srgb : {false, true}) {
        for (auto [w, h] : {std::pair{4, 4}, {64, 16}, {8, 128}, {32, 32}}) {
          for (int levels : {1, mip_level_count(w, h)}) {
            CompressedTexture t = fake_texture(f, w, h, levels, alpha, srgb);
            t.premultiplied = alpha && srgb;
            Result<CompressedTexture> back = parse_pvr3(pvr_bytes(t), "mem");
            ASSERT_TRUE(back.ok()) << back.status().message;
            expect_same(t, *back);
            EXPECT_EQ(back->premultiplied, t.premultiplied);
          }
        }
      }
    }
  }
}

TEST(Pvr3, HeaderMatchesPvrTexToolLayout) {
  CompressedTexture t = fake_texture(pvrtc::Format::pvrtc1_4bpp, 256, 128, 3, true, true);
  const Bytes b = pvr_bytes(t);
  ASSERT_GE(b.size(), 67u);
  EXPECT_EQ(get_u32(b, 0), 0x03525650u);
  EXPECT_EQ(get_u32(b, 4), 0u);            // flags
  EXPECT_EQ(get_u32(b, 8), 3u);            // PVRTC1 4bpp RGBA
  EXPECT_EQ(get_u32(b, 12), 0u);           // pixel format high word
  EXPECT_EQ(get_u32(b, 16), 1u);           // sRGB
  EXPECT_EQ(get_u32(b, 20), 0u);           // channel type
  EXPECT_EQ(get_u32(b, 24), 128u);         // height
  EXPECT_EQ(get_u32(b, 28), 256u);         // width
  EXPECT_EQ(get_u32(b, 32), 1u);           // depth
  EXPECT_EQ(get_u32(b, 36), 1u);           // surfaces
  EXPECT_EQ(get_u32(b, 40), 1u);           // faces
  EXPECT_EQ(get_u32(b, 44), 3u);           // mip count
  EXPECT_EQ(get_u32(b, 48), 15u);          // metadata size
  const std::uint8_t meta[15] = {'P', 'V', 'R', 3, 3, 0, 0, 0, 3, 0, 0, 0, 0, 0, 0};
  EXPECT_EQ(std::memcmp(b.data() + 52, meta, 15), 0);
  EXPECT_EQ(b.size(), 67u + 256 * 128 / 2 + 128 * 64 / 2 + 64 * 32 / 2);
  // 2bpp RGB code is 0, 4bpp RGB 2, 2bpp RGBA 1.
  EXPECT_EQ(get_u32(pvr_bytes(fake_texture(pvrtc::Format::pvrtc1_2bpp, 16, 16, 1, false, false)), 8), 0u);
  EXPECT_EQ(get_u32(pvr_bytes(fake_texture(pvrtc::Format::pvrtc1_4bpp, 16, 16, 1, false, false)), 8), 2u);
  EXPECT_EQ(get_u32(pvr_bytes(fake_texture(pvrtc::Format::pvrtc1_2bpp, 16, 16, 1, true, false)), 8), 1u);
}

TEST(Pvr3, SmallLevelsArePaddedToTwoByTwoBlocks) {
  CompressedTexture t = fake_texture(pvrtc::Format::pvrtc1_4bpp, 8, 2, 4, false, false);
  for (const Bytes& l : t.levels) EXPECT_EQ(l.size(), 32u);  // 2x2 blocks of 8 bytes
  Result<CompressedTexture> back = parse_pvr3(pvr_bytes(t), "mem");
  ASSERT_TRUE(back.ok()) << back.status().message;
  EXPECT_EQ(back->level_count(), 4);
  EXPECT_EQ(back->level_width(3), 1);
  EXPECT_EQ(back->level_height(3), 1);
}

TEST(Pvr3, EveryTruncationIsRejected) {
  const Bytes good = pvr_bytes(fake_texture(pvrtc::Format::pvrtc1_4bpp, 16, 8, 2, true, false));
  for (std::size_t n = 0; n < good.size(); ++n) {
    Result<CompressedTexture> r = parse_pvr3(std::span(good.data(), n), "f.pvr");
    ASSERT_FALSE(r.ok()) << "prefix of " << n << " bytes accepted";
    EXPECT_EQ(r.status().code, ErrorCode::corrupt_data) << r.status().message;
    EXPECT_EQ(r.status().message.rfind("f.pvr: ", 0), 0u);
  }
  Bytes cut(good.begin(), good.end() - 5);
  expect_pvr_error(cut, ErrorCode::corrupt_data, "need 96 bytes of data, file has 91 bytes");
}

TEST(Pvr3, HeaderLiesAreRejected) {
  const Bytes good = pvr_bytes(fake_texture(pvrtc::Format::pvrtc1_4bpp, 16, 16, 1, false, false));
  Bytes b = good;
  b[0] = 'X';
  expect_pvr_error(b, ErrorCode::corrupt_data, "bad magic");
  b = good;
  put_u32(b, 0, 0x50565203u);
  expect_pvr_error(b, ErrorCode::unsupported, "big-endian");
  b = good;
  put_u32(b, 8, 7);
  expect_pvr_error(b, ErrorCode::unsupported, "BC1");
  b = good;
  put_u32(b, 8, 0x61626772);  // 'rgba'
  put_u32(b, 12, 0x08080808);
  expect_pvr_error(b, ErrorCode::unsupported, "uncompressed rgba8888");
  b = good;
  put_u32(b, 16, 7);
  expect_pvr_error(b, ErrorCode::corrupt_data, "colour space 7");
  b = good;
  put_u32(b, 32, 4);
  expect_pvr_error(b, ErrorCode::unsupported, "depth 4");
  b = good;
  put_u32(b, 36, 6);
  expect_pvr_error(b, ErrorCode::unsupported, "6 surfaces");
  b = good;
  put_u32(b, 40, 6);
  expect_pvr_error(b, ErrorCode::unsupported, "cube maps");
  b = good;
  put_u32(b, 28, 24);  // width 24: not a power of two
  expect_pvr_error(b, ErrorCode::invalid_argument, "power");
  b = good;
  put_u32(b, 28, 0);
  expect_pvr_error(b, ErrorCode::corrupt_data, "zero size");
  b = good;
  put_u32(b, 28, 0x80000000u);  // absurd size: rejected before any allocation
  expect_pvr_error(b, ErrorCode::too_large, "");
  b = good;
  put_u32(b, 24, 1u << 16);
  put_u32(b, 28, 1u << 16);
  expect_pvr_error(b, ErrorCode::too_large, "");
  b = good;
  put_u32(b, 28, 32);  // claims twice the data it has
  expect_pvr_error(b, ErrorCode::corrupt_data, "truncated");
  b = good;
  put_u32(b, 28, 8);  // claims half: the rest is unexpected
  expect_pvr_error(b, ErrorCode::corrupt_data, "unexpected data");
  b = good;
  put_u32(b, 44, 6);  // 16x16 has 5 levels at most
  expect_pvr_error(b, ErrorCode::corrupt_data, "mip count 6");
  b = good;
  put_u32(b, 44, 0);
  expect_pvr_error(b, ErrorCode::corrupt_data, "mip count 0");
  b = good;
  put_u32(b, 48, 0xFFFFFFF0u);
  expect_pvr_error(b, ErrorCode::corrupt_data, "metadata size");
}

TEST(Pvr3, LegacyV2IsRecognisedAndRejected) {
  Bytes v2(52 + 32, 0);
  put_u32(v2, 0, 52);
  put_u32(v2, 44, 0x21525650u);  // "PVR!"
  EXPECT_EQ(detect_container(v2), ContainerFormat::pvr3);
  Result<CompressedTexture> r = parse_texture(v2, "old.pvr");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code, ErrorCode::unsupported);
  EXPECT_NE(r.status().message.find("legacy PVR v2"), std::string::npos) << r.status().message;
}

TEST(Pvr3, UnknownMetadataIsSkipped) {
  CompressedTexture t = fake_texture(pvrtc::Format::pvrtc1_2bpp, 32, 8, 1, true, false);
  Bytes b = pvr_bytes(t);
  // Insert an unknown 4-byte entry after the orientation block.
  const std::uint8_t extra[16] = {'A', 'B', 'C', 'D', 9, 0, 0, 0, 4, 0, 0, 0, 1, 2, 3, 4};
  b.insert(b.begin() + 67, extra, extra + 16);
  put_u32(b, 48, 31);
  Result<CompressedTexture> back = parse_pvr3(b, "mem");
  ASSERT_TRUE(back.ok()) << back.status().message;
  expect_same(t, *back);
}

// ---------------------------------------------------------------------------------------------
// KTX 1.1
// ---------------------------------------------------------------------------------------------

TEST(Ktx1, RoundTripsEveryVariant) {
  for (pvrtc::Format f : {pvrtc::Format::pvrtc1_4bpp, pvrtc::Format::pvrtc1_2bpp}) {
    for (bool alpha : {false, true}) {
      for (bool srgb : {false, true}) {
        for (auto [w, h] : {std::pair{4, 4}, {64, 16}, {8, 128}}) {
          for (int levels : {1, mip_level_count(w, h)}) {
            CompressedTexture t = fake_texture(f, w, h, levels, alpha, srgb);
            Result<CompressedTexture> back = parse_ktx1(ktx_bytes(t), "mem");
            ASSERT_TRUE(back.ok()) << back.status().message;
            expect_same(t, *back);
          }
        }
      }
    }
  }
}

TEST(Ktx1, HeaderFieldsAndFormats) {
  struct Case {
    pvrtc::Format f;
    bool alpha, srgb;
    std::uint32_t internal;
  };
  const Case cases[] = {
      {pvrtc::Format::pvrtc1_4bpp, false, false, 0x8C00},
      {pvrtc::Format::pvrtc1_2bpp, false, false, 0x8C01},
      {pvrtc::Format::pvrtc1_4bpp, true, false, 0x8C02},
      {pvrtc::Format::pvrtc1_2bpp, true, false, 0x8C03},
      {pvrtc::Format::pvrtc1_2bpp, false, true, 0x8A54},
      {pvrtc::Format::pvrtc1_4bpp, false, true, 0x8A55},
      {pvrtc::Format::pvrtc1_2bpp, true, true, 0x8A56},
      {pvrtc::Format::pvrtc1_4bpp, true, true, 0x8A57},
  };
  for (const Case& c : cases) {
    const Bytes b = ktx_bytes(fake_texture(c.f, 32, 16, 2, c.alpha, c.srgb));
    EXPECT_EQ(get_u32(b, 12), 0x04030201u);
    EXPECT_EQ(get_u32(b, 16), 0u);  // glType
    EXPECT_EQ(get_u32(b, 20), 1u);  // glTypeSize
    EXPECT_EQ(get_u32(b, 24), 0u);  // glFormat
    EXPECT_EQ(get_u32(b, 28), c.internal);
    EXPECT_EQ(get_u32(b, 32), c.alpha ? 0x1908u : 0x1907u);
    EXPECT_EQ(get_u32(b, 36), 32u);
    EXPECT_EQ(get_u32(b, 40), 16u);
    EXPECT_EQ(get_u32(b, 44), 0u);
    EXPECT_EQ(get_u32(b, 48), 0u);
    EXPECT_EQ(get_u32(b, 52), 1u);
    EXPECT_EQ(get_u32(b, 56), 2u);
    const std::uint32_t kv = get_u32(b, 60);
    EXPECT_EQ(kv % 4, 0u);
    const std::string key(reinterpret_cast<const char*>(b.data() + 68));
    EXPECT_EQ(key, "KTXorientation");
    EXPECT_EQ(std::string(reinterpret_cast<const char*>(b.data() + 68 + key.size() + 1)),
              "S=r,T=d");
    const std::size_t level0 = 64 + kv;
    EXPECT_EQ(get_u32(b, level0), pvrtc::level_size(c.f, 32, 16));
  }
}

TEST(Ktx1, BigEndianFilesAreRead) {
  CompressedTexture t = fake_texture(pvrtc::Format::pvrtc1_4bpp, 16, 16, 3, true, false);
  Bytes b = ktx_bytes(t);
  const std::uint32_t kv = get_u32(b, 60);
  auto swap_at = [&](std::size_t at) {
    std::swap(b[at], b[at + 3]);
    std::swap(b[at + 1], b[at + 2]);
  };
  for (std::size_t at = 12; at < 64; at += 4) swap_at(at);
  swap_at(64);  // the one key/value entry's size
  std::size_t at = 64 + kv;
  for (const Bytes& l : t.levels) {
    swap_at(at);
    at += 4 + l.size();
  }
  Result<CompressedTexture> back = parse_ktx1(b, "mem");
  ASSERT_TRUE(back.ok()) << back.status().message;
  expect_same(t, *back);
}

TEST(Ktx1, EveryTruncationIsRejected) {
  const Bytes good = ktx_bytes(fake_texture(pvrtc::Format::pvrtc1_2bpp, 16, 8, 2, false, true));
  for (std::size_t n = 0; n < good.size(); ++n) {
    Result<CompressedTexture> r = parse_ktx1(std::span(good.data(), n), "f.ktx");
    ASSERT_FALSE(r.ok()) << "prefix of " << n << " bytes accepted";
    EXPECT_EQ(r.status().code, ErrorCode::corrupt_data) << r.status().message;
  }
}

TEST(Ktx1, HeaderLiesAreRejected) {
  const Bytes good = ktx_bytes(fake_texture(pvrtc::Format::pvrtc1_4bpp, 16, 16, 1, false, false));
  Bytes b = good;
  b[1] = 'X';
  expect_ktx_error(b, ErrorCode::corrupt_data, "bad identifier");
  b = good;
  put_u32(b, 12, 0x12345678);
  expect_ktx_error(b, ErrorCode::corrupt_data, "endianness");
  b = good;
  put_u32(b, 16, 0x1401);
  expect_ktx_error(b, ErrorCode::unsupported, "uncompressed");
  b = good;
  put_u32(b, 28, 0x83F0);
  expect_ktx_error(b, ErrorCode::unsupported, "0x000083F0");
  b = good;
  put_u32(b, 44, 2);
  expect_ktx_error(b, ErrorCode::unsupported, "3D");
  b = good;
  put_u32(b, 48, 4);
  expect_ktx_error(b, ErrorCode::unsupported, "arrays");
  b = good;
  put_u32(b, 52, 6);
  expect_ktx_error(b, ErrorCode::unsupported, "cube maps");
  b = good;
  put_u32(b, 40, 0);
  expect_ktx_error(b, ErrorCode::unsupported, "1D");
  b = good;
  put_u32(b, 36, 12);
  expect_ktx_error(b, ErrorCode::invalid_argument, "power");
  b = good;
  put_u32(b, 36, 0xFFFFFFFFu);
  expect_ktx_error(b, ErrorCode::too_large, "");
  b = good;
  put_u32(b, 56, 9);
  expect_ktx_error(b, ErrorCode::corrupt_data, "mip count 9");
  b = good;
  put_u32(b, 60, 0x7FFFFFFF);
  expect_ktx_error(b, ErrorCode::corrupt_data, "key/value");
  b = good;
  put_u32(b, 64, 1000);  // key/value entry overruns its block
  expect_ktx_error(b, ErrorCode::corrupt_data, "overruns");
  b = good;
  put_u32(b, 64 + get_u32(good, 60), 64);
  expect_ktx_error(b, ErrorCode::corrupt_data, "imageSize 64");
  b = good;
  b.push_back(0);
  expect_ktx_error(b, ErrorCode::corrupt_data, "unexpected data");
}

TEST(Ktx1, ZeroMipLevelsMeansOne) {
  Bytes b = ktx_bytes(fake_texture(pvrtc::Format::pvrtc1_4bpp, 16, 16, 1, false, false));
  put_u32(b, 56, 0);
  Result<CompressedTexture> r = parse_ktx1(b, "mem");
  ASSERT_TRUE(r.ok()) << r.status().message;
  EXPECT_EQ(r->level_count(), 1);
}

// ---------------------------------------------------------------------------------------------
// Detection, validation and files
// ---------------------------------------------------------------------------------------------

TEST(TextureFile, DetectsContainers) {
  const CompressedTexture t = fake_texture(pvrtc::Format::pvrtc1_4bpp, 8, 8, 1, false, false);
  EXPECT_EQ(detect_container(pvr_bytes(t)), ContainerFormat::pvr3);
  EXPECT_EQ(detect_container(ktx_bytes(t)), ContainerFormat::ktx1);
  EXPECT_EQ(detect_container(Bytes{1, 2, 3}), ContainerFormat::unknown);
  EXPECT_EQ(container_from_extension("a/b.PVR"), ContainerFormat::pvr3);
  EXPECT_EQ(container_from_extension("x.ktx"), ContainerFormat::ktx1);
  EXPECT_EQ(container_from_extension("x.ktx2"), ContainerFormat::unknown);
  EXPECT_EQ(container_from_extension("dir.pvr/x"), ContainerFormat::unknown);
  Result<CompressedTexture> r = parse_texture(Bytes{1, 2, 3, 4, 5}, "junk.bin");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().message, "junk.bin: not a PVR v3 or KTX 1.1 texture (unrecognised magic)");
}

TEST(TextureFile, ValidateRejectsInconsistentTextures) {
  CompressedTexture t = fake_texture(pvrtc::Format::pvrtc1_4bpp, 16, 16, 2, false, false);
  EXPECT_TRUE(validate_texture(t, "t").ok());
  t.levels[1].pop_back();
  EXPECT_FALSE(serialize_pvr3(t).ok());
  EXPECT_FALSE(serialize_ktx1(t).ok());
  t = fake_texture(pvrtc::Format::pvrtc1_4bpp, 16, 16, 5, false, false);
  t.levels.push_back(t.levels.back());
  EXPECT_FALSE(validate_texture(t, "t").ok());
  t.levels.clear();
  EXPECT_FALSE(validate_texture(t, "t").ok());
}

TEST(TextureFile, WritesAtomicallyAndReadsBack) {
  const fs::path dir = test::temp_dir("files");
  const CompressedTexture t = fake_texture(pvrtc::Format::pvrtc1_2bpp, 32, 32, 6, true, true);
  for (const char* name : {"t.pvr", "t.ktx"}) {
    const std::string path = (dir / name).string();
    ASSERT_TRUE(write_texture_file(path, t).ok());
    Result<CompressedTexture> back = read_texture_file(path);
    ASSERT_TRUE(back.ok()) << back.status().message;
    expect_same(t, *back);
  }
  // A folder in the way, an unknown extension, a missing file: errors, nothing written.
  fs::create_directories(dir / "sub.pvr");
  EXPECT_FALSE(write_texture_file((dir / "sub.pvr").string(), t).ok());
  Status s = write_texture_file((dir / "t.dds").string(), t);
  EXPECT_EQ(s.code, ErrorCode::invalid_argument);
  EXPECT_FALSE(fs::exists(dir / "t.dds"));
  Result<CompressedTexture> missing = read_texture_file((dir / "none.pvr").string());
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.status().code, ErrorCode::io_error);
}

TEST(TextureFile, DecodeLevelChecksRangeAndForcesOpaqueRgb) {
  CompressedTexture t = fake_texture(pvrtc::Format::pvrtc1_4bpp, 16, 8, 2, false, false);
  Result<ImageRGBA8> img = decode_texture_level(t, 1, 1);
  ASSERT_TRUE(img.ok()) << img.status().message;
  EXPECT_EQ(img->width, 8);
  EXPECT_EQ(img->height, 4);
  EXPECT_FALSE(img->has_alpha);
  for (std::size_t i = 3; i < img->pixels.size(); i += 4) ASSERT_EQ(img->pixels[i], 255);
  Result<ImageRGBA8> bad = decode_texture_level(t, 2, 1);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message.find("out of range"), std::string::npos);
  EXPECT_FALSE(decode_texture_level(t, -1, 1).ok());
}

// ---------------------------------------------------------------------------------------------
// Mipmaps and resizing
// ---------------------------------------------------------------------------------------------

ImageRGBA8 filled(int w, int h, std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint8_t a) {
  ImageRGBA8 img(w, h);
  for (std::size_t i = 0; i < img.pixel_count(); ++i) {
    img.pixels[i * 4 + 0] = r;
    img.pixels[i * 4 + 1] = g;
    img.pixels[i * 4 + 2] = b;
    img.pixels[i * 4 + 3] = a;
  }
  return img;
}

TEST(Mipmap, ChainSizesGoDownToOneByOneForNonSquare) {
  const ImageRGBA8 img = make_procedural(Procedural::noise, 32, 4);
  Result<std::vector<ImageRGBA8>> chain = generate_mipmaps(img);
  ASSERT_TRUE(chain.ok());
  ASSERT_EQ(chain->size(), 6u);
  const int expect[6][2] = {{32, 4}, {16, 2}, {8, 1}, {4, 1}, {2, 1}, {1, 1}};
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ((*chain)[std::size_t(i)].width, expect[i][0]);
    EXPECT_EQ((*chain)[std::size_t(i)].height, expect[i][1]);
  }
  EXPECT_EQ((*chain)[0].pixels, img.pixels);
  EXPECT_EQ(mip_level_count(1, 1), 1);
  EXPECT_EQ(mip_level_count(256, 64), 9);
  MipmapOptions o;
  o.max_levels = 2;
  EXPECT_EQ(generate_mipmaps(img, o)->size(), 2u);
}

TEST(Mipmap, SrgbAveragesInLinearLight) {
  ImageRGBA8 img(2, 2);
  for (int i = 0; i < 4; ++i) {
    const std::uint8_t v = (i == 0 || i == 3) ? 255 : 0;
    img.pixels[std::size_t(i) * 4 + 0] = img.pixels[std::size_t(i) * 4 + 1] =
        img.pixels[std::size_t(i) * 4 + 2] = v;
    img.pixels[std::size_t(i) * 4 + 3] = 255;
  }
  MipmapOptions o;
  o.srgb = true;
  const ImageRGBA8 gamma = (*generate_mipmaps(img, o))[1];
  EXPECT_EQ(gamma.pixels[0], linear_to_srgb8(0.5f));  // 188
  EXPECT_EQ(gamma.pixels[0], 188);
  o.srgb = false;
  EXPECT_EQ((*generate_mipmaps(img, o))[1].pixels[0], 128);  // 127.5 rounded
}

TEST(Mipmap, AlphaWeightsColour) {
  // Left half transparent red, right half opaque green: the average must be pure green.
  ImageRGBA8 img = filled(2, 1, 255, 0, 0, 0);
  img.has_alpha = true;
  img.at(1, 0)[0] = 0;
  img.at(1, 0)[1] = 255;
  img.at(1, 0)[3] = 255;
  const ImageRGBA8 m = (*generate_mipmaps(img))[1];
  EXPECT_EQ(m.at(0, 0)[0], 0);
  EXPECT_EQ(m.at(0, 0)[1], 255);
  EXPECT_EQ(m.at(0, 0)[3], 128);
  // Fully transparent: the plain colour average survives (no black fringe).
  ImageRGBA8 clear = filled(4, 4, 200, 100, 50, 0);
  clear.has_alpha = true;
  const ImageRGBA8 c = (*generate_mipmaps(clear))[2];
  EXPECT_EQ(c.at(0, 0)[0], 200);
  EXPECT_EQ(c.at(0, 0)[3], 0);
  // Opaque input stays opaque.
  const ImageRGBA8 solid = filled(8, 8, 10, 20, 30, 255);
  const std::vector<ImageRGBA8> solid_chain = *generate_mipmaps(solid);
  for (const ImageRGBA8& l : solid_chain) {
    EXPECT_EQ(l.at(0, 0)[0], 10);
    EXPECT_EQ(l.at(0, 0)[3], 255);
  }
}

TEST(Mipmap, IdenticalForAnyThreadCount) {
  const ImageRGBA8 img = make_procedural(Procedural::foliage, 64, 32);
  MipmapOptions a, b;
  a.threads = 1;
  b.threads = 4;
  const std::vector<ImageRGBA8> ca = *generate_mipmaps(img, a);
  const std::vector<ImageRGBA8> cb = *generate_mipmaps(img, b);
  for (std::size_t i = 0; i < ca.size(); ++i) EXPECT_EQ(ca[i].pixels, cb[i].pixels);
  EXPECT_EQ(resize_image(img, 100, 20, a)->pixels, resize_image(img, 100, 20, b)->pixels);
}

TEST(Resize, ConstantStaysConstantAndSizesAreRight) {
  const ImageRGBA8 img = filled(127, 128, 90, 160, 220, 255);
  Result<ImageRGBA8> r = resize_image(img, 128, 128);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->width, 128);
  EXPECT_EQ(r->height, 128);
  for (std::size_t i = 0; i < r->pixel_count(); ++i) {
    ASSERT_NEAR(r->pixels[i * 4 + 0], 90, 1);
    ASSERT_NEAR(r->pixels[i * 4 + 1], 160, 1);
    ASSERT_NEAR(r->pixels[i * 4 + 2], 220, 1);
    ASSERT_EQ(r->pixels[i * 4 + 3], 255);
  }
  // A smooth image survives a small resample almost unchanged.
  const ImageRGBA8 smooth = make_procedural(Procedural::gradient, 120, 120);
  Result<ImageRGBA8> up = resize_image(smooth, 128, 128);
  Result<ImageRGBA8> back = resize_image(*up, 120, 120);
  EXPECT_GT(compare_images(smooth, *back)->psnr_rgb, 35.0);
  EXPECT_FALSE(resize_image(smooth, 0, 4).ok());
}

TEST(Resize, NearestPowerOfTwo) {
  EXPECT_EQ(nearest_power_of_two(1), 1);
  EXPECT_EQ(nearest_power_of_two(127), 128);
  EXPECT_EQ(nearest_power_of_two(128), 128);
  EXPECT_EQ(nearest_power_of_two(95), 64);
  EXPECT_EQ(nearest_power_of_two(96), 128);
  EXPECT_EQ(nearest_power_of_two(300), 256);
  EXPECT_EQ(nearest_power_of_two(1000), 1024);
}

// ---------------------------------------------------------------------------------------------
// Against the oracle (PVRTexToolCLI)
// ---------------------------------------------------------------------------------------------

/// Runs PVRTexToolCLI with `args`; true on exit status 0.
bool run_tool(const fs::path& tool, const std::string& args) {
  std::string cmd = "'";
  cmd.append(tool.string()).append("' ").append(args).append(" >/dev/null 2>&1");
  return std::system(cmd.c_str()) == 0;
}

TEST(Oracle, ReadsPvrTexToolFilesAndMatchesItsDecode) {
  const auto tool = test::pvrtextool();
  if (!tool) GTEST_SKIP() << "PVRTexToolCLI not available";
  const fs::path dir = test::temp_dir("oracle-in");
  struct Case {
    Procedural kind;
    int w, h;
    const char* format;
    bool mips;
  };
  const Case cases[] = {
      {Procedural::noise, 64, 32, "PVRTC1_4,UBN,lRGB", true},
      {Procedural::foliage, 32, 32, "PVRTC1_4,UBN,sRGB", true},
      {Procedural::bricks, 64, 64, "PVRTC1_2,UBN,lRGB", false},
      {Procedural::gradient, 16, 64, "PVRTC1_2_RGB,UBN,sRGB", true},
      {Procedural::text, 32, 32, "PVRTC1_4_RGB,UBN,lRGB", false},
  };
  int n = 0;
  for (const Case& c : cases) {
    const std::string stem = (dir / ("case" + std::to_string(n++))).string();
    ASSERT_TRUE(write_png(stem + ".png", make_procedural(c.kind, c.w, c.h)).ok());
    ASSERT_TRUE(run_tool(*tool, "-i " + stem + ".png -o " + stem + ".pvr -f " + c.format +
                                    " -q pvrtcfastest" + (c.mips ? " -m" : "") + " -d " + stem +
                                    "-dec.png -shh"));
    Result<CompressedTexture> tex = read_texture_file(stem + ".pvr");
    ASSERT_TRUE(tex.ok()) << tex.status().message;
    EXPECT_EQ(tex->width, c.w);
    EXPECT_EQ(tex->height, c.h);
    EXPECT_EQ(tex->level_count(), c.mips ? mip_level_count(c.w, c.h) : 1);
    EXPECT_EQ(tex->srgb, std::strstr(c.format, "sRGB") != nullptr);
    EXPECT_EQ(tex->has_alpha, std::strstr(c.format, "_RGB") == nullptr);
    EXPECT_EQ(tex->format, std::strstr(c.format, "PVRTC1_4") ? pvrtc::Format::pvrtc1_4bpp
                                                             : pvrtc::Format::pvrtc1_2bpp);
    // Level 0 decoded by tessera equals PVRTexTool's own decode (RGB exactly; PVRTexTool's
    // -d writes the alpha it decodes even for RGB formats, so compare alpha only for RGBA).
    Result<ImageRGBA8> ours = decode_texture_level(*tex, 0, 1);
    ASSERT_TRUE(ours.ok()) << ours.status().message;
    Result<ImageRGBA8> theirs = read_image(stem + "-dec.png");
    ASSERT_TRUE(theirs.ok()) << theirs.status().message;
    ASSERT_EQ(theirs->width, c.w);
    // PVRTexTool's -d converts an sRGB texture to linear 8-bit on output, so for those the
    // reference is srgb_to_linear(our decode), equal within one rounding step.
    int mismatches = 0;
    for (std::size_t i = 0; i < ours->pixels.size(); ++i) {
      const bool is_alpha = i % 4 == 3;
      if (is_alpha && !tex->has_alpha) continue;
      if (tex->srgb && !is_alpha) {
        const int expect = int(std::lround(srgb8_to_linear(ours->pixels[i]) * 255.0f));
        mismatches += std::abs(expect - int(theirs->pixels[i])) > 1;
      } else {
        mismatches += ours->pixels[i] != theirs->pixels[i];
      }
    }
    EXPECT_EQ(mismatches, 0) << stem;
    // And re-serialised, byte for byte the same file.
    Result<std::vector<std::uint8_t>> original = read_file(stem + ".pvr");
    Bytes again = pvr_bytes(*tex);
    EXPECT_EQ(again, *original) << stem;
    // Its KTX output of the same encode holds the same blocks (PVRTexTool labels sRGB data
    // with the linear 0x8C0x formats, so the colour space is not compared).
    ASSERT_TRUE(run_tool(*tool, "-i " + stem + ".png -o " + stem + ".ktx -f " + c.format +
                                    " -q pvrtcfastest" + (c.mips ? " -m" : "") + " -shh"));
    Result<CompressedTexture> ktx = read_texture_file(stem + ".ktx");
    ASSERT_TRUE(ktx.ok()) << ktx.status().message;
    EXPECT_EQ(ktx->width, tex->width);
    EXPECT_EQ(ktx->height, tex->height);
    EXPECT_EQ(ktx->format, tex->format);
    EXPECT_EQ(ktx->levels, tex->levels) << stem;
    // Its legacy (v2) output is recognised and rejected with a clear message.
    ASSERT_TRUE(run_tool(*tool, "-i " + stem + ".png -o " + stem + "-v2.pvr -f " + c.format +
                                    " -q pvrtcfastest -legacypvr -shh"));
    Result<CompressedTexture> v2 = read_texture_file(stem + "-v2.pvr");
    ASSERT_FALSE(v2.ok());
    EXPECT_NE(v2.status().message.find("legacy PVR v2"), std::string::npos)
        << v2.status().message;
  }
}

TEST(Oracle, PvrTexToolReadsOurFiles) {
  const auto tool = test::pvrtextool();
  if (!tool) GTEST_SKIP() << "PVRTexToolCLI not available";
  const fs::path dir = test::temp_dir("oracle-out");
  for (pvrtc::Format f : {pvrtc::Format::pvrtc1_4bpp, pvrtc::Format::pvrtc1_2bpp}) {
    for (bool alpha : {false, true}) {
      const ImageRGBA8 img = make_procedural(alpha ? Procedural::foliage : Procedural::noise, 64, 32);
      pvrtc::EncodeOptions eo;
      eo.format = f;
      eo.quality = pvrtc::Quality::fast;
      eo.force_alpha = alpha;
      Result<std::vector<ImageRGBA8>> chain = generate_mipmaps(img);
      CompressedTexture t;
      t.format = f;
      t.width = 64;
      t.height = 32;
      t.has_alpha = alpha;
      for (const ImageRGBA8& l : *chain) {
        Result<Bytes> enc = pvrtc::encode(l, eo);
        ASSERT_TRUE(enc.ok()) << enc.status().message;
        t.levels.push_back(*enc);
      }
      for (const char* ext : {".pvr", ".ktx"}) {
        const std::string stem =
            (dir / (std::string(f == pvrtc::Format::pvrtc1_4bpp ? "p4" : "p2") +
                    (alpha ? "a" : "") + (ext[1] == 'p' ? "-pvr" : "-ktx")))
                .string();
        ASSERT_TRUE(write_texture_file(stem + ext, t).ok());
        ASSERT_TRUE(run_tool(*tool, "-i " + stem + ext + " -o " + stem + "-scratch.pvr -f r8g8b8a8 -d " +
                                        stem + "-dec.png -shh"))
            << "PVRTexToolCLI rejected " << stem << ext;
        Result<ImageRGBA8> theirs = read_image(stem + "-dec.png");
        ASSERT_TRUE(theirs.ok()) << theirs.status().message;
        Result<ImageRGBA8> ours = decode_texture_level(t, 0, 1);
        ASSERT_TRUE(ours.ok());
        ASSERT_EQ(theirs->width, 64);
        ASSERT_EQ(theirs->height, 32);
        int mismatches = 0;
        for (std::size_t i = 0; i < ours->pixels.size(); ++i) {
          if (i % 4 == 3 && !alpha) continue;
          mismatches += ours->pixels[i] != theirs->pixels[i];
        }
        EXPECT_EQ(mismatches, 0) << stem << ext;
      }
    }
  }
}

}  // namespace
}  // namespace tessera
