// Tests of tessera/texture_file.h's containers (PVR v3 and KTX 1.1): round trips, exact header
// bytes, every malformed-header path, truncation at every offset. Detection, files and the
// exchange with PVRTexToolCLI: texture_file_io_test.cpp; tessera/image_mipmap.h: mipmap_test.cpp.
#include "tessera/texture_file.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <utility>

#include "tessera/image_mipmap.h"
#include "texture_file_test_util.h"

namespace tessera::texture_file {
namespace {

using test::Bytes;
using test::expect_same;
using test::fake_texture;
using test::ktx_bytes;
using test::pvr_bytes;

void put_u32(Bytes& b, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b[at + std::size_t(i)] = std::uint8_t(v >> (8 * i));
}
std::uint32_t get_u32(const Bytes& b, std::size_t at) {
  return std::uint32_t(b[at]) | std::uint32_t(b[at + 1]) << 8 | std::uint32_t(b[at + 2]) << 16 |
         std::uint32_t(b[at + 3]) << 24;
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
  EXPECT_EQ(get_u32(b, 4), 0u);     // flags
  EXPECT_EQ(get_u32(b, 8), 3u);     // PVRTC1 4bpp RGBA
  EXPECT_EQ(get_u32(b, 12), 0u);    // pixel format high word
  EXPECT_EQ(get_u32(b, 16), 1u);    // sRGB
  EXPECT_EQ(get_u32(b, 20), 0u);    // channel type
  EXPECT_EQ(get_u32(b, 24), 128u);  // height
  EXPECT_EQ(get_u32(b, 28), 256u);  // width
  EXPECT_EQ(get_u32(b, 32), 1u);    // depth
  EXPECT_EQ(get_u32(b, 36), 1u);    // surfaces
  EXPECT_EQ(get_u32(b, 40), 1u);    // faces
  EXPECT_EQ(get_u32(b, 44), 3u);    // mip count
  EXPECT_EQ(get_u32(b, 48), 15u);   // metadata size
  const std::uint8_t meta[15] = {'P', 'V', 'R', 3, 3, 0, 0, 0, 3, 0, 0, 0, 0, 0, 0};
  EXPECT_EQ(std::memcmp(b.data() + 52, meta, 15), 0);
  EXPECT_EQ(b.size(), 67u + 256 * 128 / 2 + 128 * 64 / 2 + 64 * 32 / 2);
  // 2bpp RGB code is 0, 4bpp RGB 2, 2bpp RGBA 1.
  EXPECT_EQ(
      get_u32(pvr_bytes(fake_texture(pvrtc::Format::pvrtc1_2bpp, 16, 16, 1, false, false)), 8), 0u);
  EXPECT_EQ(
      get_u32(pvr_bytes(fake_texture(pvrtc::Format::pvrtc1_4bpp, 16, 16, 1, false, false)), 8), 2u);
  EXPECT_EQ(get_u32(pvr_bytes(fake_texture(pvrtc::Format::pvrtc1_2bpp, 16, 16, 1, true, false)), 8),
            1u);
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
  put_u32(b, 36, 6);  // six surfaces (an array) promised, one present
  expect_pvr_error(b, ErrorCode::corrupt_data, "truncated: 1 level(s) need 768 bytes");
  b = good;
  put_u32(b, 40, 3);
  expect_pvr_error(b, ErrorCode::unsupported, "3 faces are not supported");
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
  put_u32(b, 48, 4);  // an array of 4: imageSize must be the whole level
  expect_ktx_error(b, ErrorCode::corrupt_data, "(512 bytes per level)");
  b = good;
  put_u32(b, 52, 6);  // a cube map: six faces of 128 bytes, one present
  expect_ktx_error(b, ErrorCode::corrupt_data, "level 0 face 1 needs 128 bytes");
  b = good;
  put_u32(b, 52, 2);
  expect_ktx_error(b, ErrorCode::unsupported, "2 faces are not supported");
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

}  // namespace
}  // namespace tessera::texture_file
