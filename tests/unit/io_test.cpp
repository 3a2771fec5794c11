// Tests of tessera/io.h: PNG in all its flavours, JPEG/TGA/BMP through stb, atomic writes and
// the error paths (missing, truncated, corrupt, wrong magic, absurd sizes). The PNG fast path
// against libspng: io_png_fast_test.cpp.
#include "tessera/io.h"

#include <gtest/gtest.h>
#include <spng.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "io/png_fast.h"
#include "io_png_test_util.h"
#include "tessera/procedural.h"
#include "test_support.h"

namespace tessera::io {
namespace {

namespace fs = std::filesystem;
using test::encode_raw_png;

void append(void* ctx, void* data, int size) {
  auto* v = static_cast<std::vector<std::uint8_t>*>(ctx);
  v->insert(v->end(), static_cast<std::uint8_t*>(data), static_cast<std::uint8_t*>(data) + size);
}

TEST(Png, Rgba8RoundTripIsLossless) {
  const ImageRGBA8 img = make_procedural(Procedural::foliage, 37, 23);
  Result<std::vector<std::uint8_t>> png = encode_png(img);
  ASSERT_TRUE(png.ok());
  EXPECT_EQ(detect_image_format(*png), ImageFormat::png);
  Result<ImageRGBA8> back = decode_image(*png, "mem");
  ASSERT_TRUE(back.ok()) << back.status().message;
  EXPECT_EQ(back->width, 37);
  EXPECT_EQ(back->height, 23);
  EXPECT_TRUE(back->has_alpha);
  EXPECT_EQ(back->pixels, img.pixels);
}

TEST(Png, RgbWritesOpaqueAndReadsBackWithoutAlpha) {
  const ImageRGBA8 img = make_procedural(Procedural::bricks, 16, 16);
  Result<ImageRGBA8> back = decode_image(*encode_png(img), "mem");
  ASSERT_TRUE(back.ok());
  EXPECT_FALSE(back->has_alpha);
  EXPECT_EQ(back->pixels, img.pixels);
}

TEST(Png, SixteenBitIsRoundedNotTruncated) {
  // 2x1 RGB16: values chosen where truncation (>> 8) and rounding differ.
  const std::uint16_t px[6] = {0x0080, 0xFF7F, 0xFFFF, 0x7F80, 0x0000, 0x8080};
  // libspng takes 16-bit samples in host byte order.
  const auto png = encode_raw_png(px, sizeof px, 2, 1, SPNG_COLOR_TYPE_TRUECOLOR, 16);
  Result<ImageRGBA8> img = decode_image(png, "sixteen.png");
  ASSERT_TRUE(img.ok()) << img.status().message;
  for (int i = 0; i < 6; ++i) {
    const int expect = int((std::uint32_t(px[i]) * 255u + 32767u) / 65535u);
    EXPECT_EQ(img->pixels[(i / 3) * 4 + (i % 3)], expect) << i;
  }
  EXPECT_EQ(img->pixels[3], 255);
  Result<ImageRGBAF> f = decode_image_float(png, "sixteen.png");
  ASSERT_TRUE(f.ok());
  EXPECT_FLOAT_EQ(f->pixels[1], 0xFF7F / 65535.0f);
}

TEST(Png, GreyAndGreyAlphaExpandToRgba) {
  const std::uint8_t grey[4] = {0, 100, 200, 255};
  Result<ImageRGBA8> g =
      decode_image(encode_raw_png(grey, 4, 2, 2, SPNG_COLOR_TYPE_GRAYSCALE, 8), "g");
  ASSERT_TRUE(g.ok());
  EXPECT_FALSE(g->has_alpha);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(g->pixels[i * 4 + 0], grey[i]);
    EXPECT_EQ(g->pixels[i * 4 + 1], grey[i]);
    EXPECT_EQ(g->pixels[i * 4 + 2], grey[i]);
    EXPECT_EQ(g->pixels[i * 4 + 3], 255);
  }
  const std::uint8_t ga[4] = {10, 20, 30, 40};
  Result<ImageRGBA8> a =
      decode_image(encode_raw_png(ga, 4, 2, 1, SPNG_COLOR_TYPE_GRAYSCALE_ALPHA, 8), "ga");
  ASSERT_TRUE(a.ok());
  EXPECT_TRUE(a->has_alpha);
  EXPECT_EQ(a->pixels[0], 10);
  EXPECT_EQ(a->pixels[3], 20);
  EXPECT_EQ(a->pixels[6], 30);
  EXPECT_EQ(a->pixels[7], 40);
  // 16-bit grey+alpha.
  const std::uint16_t ga16[2] = {0xFFFF, 0x0001};  // grey 0xFFFF, alpha 1/65535 -> 0
  Result<ImageRGBA8> a16 =
      decode_image(encode_raw_png(ga16, 4, 1, 1, SPNG_COLOR_TYPE_GRAYSCALE_ALPHA, 16), "ga16");
  ASSERT_TRUE(a16.ok());
  EXPECT_EQ(a16->pixels[0], 255);
  EXPECT_EQ(a16->pixels[3], 0);
}

TEST(Png, PaletteWithTransparency) {
  spng_plte plte{};
  plte.n_entries = 2;
  plte.entries[0] = {255, 0, 0, 0};
  plte.entries[1] = {0, 0, 255, 0};
  spng_trns trns{};
  trns.n_type3_entries = 1;
  trns.type3_alpha[0] = 128;
  const std::uint8_t idx[2] = {0, 1};
  Result<ImageRGBA8> img =
      decode_image(encode_raw_png(idx, 2, 2, 1, SPNG_COLOR_TYPE_INDEXED, 8, &plte, &trns), "pal");
  ASSERT_TRUE(img.ok()) << img.status().message;
  EXPECT_TRUE(img->has_alpha);
  const std::uint8_t expect[8] = {255, 0, 0, 128, 0, 0, 255, 255};
  EXPECT_EQ(0, std::memcmp(img->pixels.data(), expect, 8));
}

TEST(Stb, TgaAndJpegAndBmpDecode) {
  const ImageRGBA8 img = make_procedural(Procedural::gradient, 32, 16);
  std::vector<std::uint8_t> tga;
  ASSERT_TRUE(stbi_write_tga_to_func(append, &tga, 32, 16, 4, img.pixels.data()));
  EXPECT_EQ(detect_image_format(tga), ImageFormat::tga);
  Result<ImageRGBA8> t = decode_image(tga, "a.tga");
  ASSERT_TRUE(t.ok()) << t.status().message;
  EXPECT_EQ(t->pixels, img.pixels);
  EXPECT_TRUE(t->has_alpha);

  std::vector<std::uint8_t> jpg;
  ASSERT_TRUE(stbi_write_jpg_to_func(append, &jpg, 32, 16, 4, img.pixels.data(), 95));
  EXPECT_EQ(detect_image_format(jpg), ImageFormat::jpeg);
  Result<ImageRGBA8> j = decode_image(jpg, "a.jpg");
  ASSERT_TRUE(j.ok()) << j.status().message;
  EXPECT_FALSE(j->has_alpha);
  int max_err = 0;
  for (std::size_t i = 0; i < img.pixel_count(); ++i) {
    for (int c = 0; c < 3; ++c) {
      max_err = std::max(max_err, std::abs(int(j->pixels[i * 4 + c]) - int(img.pixels[i * 4 + c])));
    }
  }
  EXPECT_LT(max_err, 24);  // q95 JPEG of a smooth gradient
}

TEST(Errors, MissingFileNamesThePath) {
  Result<ImageRGBA8> r = read_image("/nonexistent/dir/x.png");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code, ErrorCode::io_error);
  EXPECT_NE(r.status().message.find("/nonexistent/dir/x.png"), std::string::npos);
}

TEST(Errors, TruncatedPngAtEveryRegionIsAnError) {
  const ImageRGBA8 img = make_procedural(Procedural::noise, 64, 64);
  const std::vector<std::uint8_t> png = *encode_png(img);
  for (std::size_t cut : {std::size_t(0), std::size_t(4), std::size_t(8), std::size_t(20),
                          std::size_t(33), png.size() / 2, png.size() - 13, png.size() - 1}) {
    std::vector<std::uint8_t> part(png.begin(), png.begin() + std::ptrdiff_t(cut));
    Result<ImageRGBA8> r = decode_image(part, "cut.png");
    EXPECT_FALSE(r.ok()) << "cut at " << cut;
    if (!r.ok()) {
      EXPECT_EQ(r.status().message.rfind("cut.png: ", 0), 0u) << r.status().message;
      EXPECT_EQ(r.status().message.find('\n'), std::string::npos);
    }
  }
}

TEST(Errors, CorruptCrcAndWrongMagic) {
  std::vector<std::uint8_t> png = *encode_png(make_procedural(Procedural::text, 32, 32));
  std::vector<std::uint8_t> bad = png;
  bad[png.size() / 2] ^= 0x5A;  // inside IDAT: CRC mismatch
  EXPECT_FALSE(decode_image(bad, "crc.png").ok());
  std::vector<std::uint8_t> text = {'h', 'e', 'l', 'l', 'o', ' ', 'w', 'o', 'r', 'l', 'd'};
  Result<ImageRGBA8> r = decode_image(text, "notes.txt");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message.find("unrecognised magic"), std::string::npos);
}

TEST(Errors, AbsurdSizeRefusedBeforeAllocating) {
  // A valid 1x1 PNG whose IHDR claims 60000 x 60000 (CRC fixed up): must be refused by the
  // size limit, not by a failed 14 GB allocation.
  std::vector<std::uint8_t> png = *encode_png(make_procedural(Procedural::gradient, 1, 1));
  auto put32 = [&](std::size_t off, std::uint32_t v) {
    png[off] = std::uint8_t(v >> 24);
    png[off + 1] = std::uint8_t(v >> 16);
    png[off + 2] = std::uint8_t(v >> 8);
    png[off + 3] = std::uint8_t(v);
  };
  put32(16, 60000);
  put32(20, 60000);
  // CRC-32 over "IHDR" + 13 data bytes.
  std::uint32_t crc = 0xFFFFFFFFu;
  for (std::size_t i = 12; i < 12 + 17; ++i) {
    crc ^= png[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  put32(29, ~crc);
  Result<ImageRGBA8> r = decode_image(png, "huge.png");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code, ErrorCode::too_large) << r.status().message;
  // stb path: a TGA header claiming 65535 x 65535 with no data.
  std::vector<std::uint8_t> tga(18, 0);
  tga[2] = 2;
  tga[12] = tga[13] = tga[14] = tga[15] = 0xFF;
  tga[16] = 32;
  Result<ImageRGBA8> t = decode_image(tga, "huge.tga");
  EXPECT_FALSE(t.ok());
}

TEST(Errors, LyingHeadersAreRefusedBeforeStbAllocates) {
  // The fuzzer's finding: 23 bytes claiming a 15359 x 16392 24-bit TGA (251.8 Mpx, under the
  // size limit). stb_image would allocate ~1.7 GiB before noticing the missing data.
  std::vector<std::uint8_t> tga(23, 0);
  tga[2] = 2;
  tga[12] = 0xFF;
  tga[13] = 0x3B;  // 15359
  tga[14] = 0x08;
  tga[15] = 0x40;  // 16392
  tga[16] = 24;
  Result<ImageRGBA8> t = decode_image(tga, "lying.tga");
  ASSERT_FALSE(t.ok());
  EXPECT_NE(t.status().message.find("lying.tga: truncated image"), std::string::npos)
      << t.status().message;
  // The same for RLE TGA, BMP and JPEG headers: valid small files with enlarged dimensions.
  const ImageRGBA8 img = make_procedural(Procedural::gradient, 16, 16);
  std::vector<std::uint8_t> jpg;
  ASSERT_TRUE(stbi_write_jpg_to_func(append, &jpg, 16, 16, 4, img.pixels.data(), 90));
  for (std::size_t i = 2; i + 8 < jpg.size(); ++i) {
    if (jpg[i] == 0xFF && jpg[i + 1] == 0xC0) {  // SOF0: height at +5, width at +7 (big-endian)
      jpg[i + 5] = 0x3F;
      jpg[i + 6] = 0xFF;
      jpg[i + 7] = 0x3F;
      jpg[i + 8] = 0xFF;
      break;
    }
  }
  Result<ImageRGBA8> j = decode_image(jpg, "lying.jpg");
  ASSERT_FALSE(j.ok());
  EXPECT_NE(j.status().message.find("truncated image"), std::string::npos) << j.status().message;
}

TEST(Errors, LyingPngHeadersAreRefusedBeforeTheImageIsAllocated) {
  // The fuzzer's finding: 30 bytes (signature, an IHDR claiming 4101 x 64218 16-bit grey +
  // alpha, one byte of its CRC). libspng reads the header, and the decode allocated the whole
  // 2 GiB RGBA16 image before finding no data.
  const std::vector<std::uint8_t> png = {
      0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44,
      0x52, 0x00, 0x00, 0x10, 0x05, 0x00, 0x00, 0xfa, 0xda, 0x10, 0x04, 0x00, 0x00, 0x00, 0x08};
  Result<ImageRGBA8> r = decode_image(png, "lying.png");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code, ErrorCode::corrupt_data);
  EXPECT_EQ(r.status().message,
            "lying.png: truncated PNG: 30 bytes cannot hold the 4101x64218 image its header "
            "announces");
  // The bound is DEFLATE's largest expansion, so it never refuses a real file: a uniform
  // 1024 x 1024 RGBA image (4 MiB of pixels in a few KiB) still decodes through libspng.
  ImageRGBA8 flat;
  flat.width = flat.height = 1024;
  flat.has_alpha = true;
  flat.pixels.assign(flat.pixel_count() * 4, 0);
  const std::vector<std::uint8_t> small = *encode_png(flat);
  ASSERT_LT(small.size() * 100, flat.pixels.size());
  Result<ImageRGBA8> back = detail::decode_png_spng(small, "flat.png");
  ASSERT_TRUE(back.ok()) << back.status().message;
  EXPECT_EQ(back->pixels, flat.pixels);
}

TEST(AtomicWrite, ReplacesOnlyOnSuccess) {
  const fs::path dir = test::temp_dir("atomic");
  const std::string path = (dir / "out.png").string();
  const ImageRGBA8 img = make_procedural(Procedural::bricks, 8, 8);
  ASSERT_TRUE(write_png(path, img).ok());
  Result<ImageRGBA8> back = read_image(path);
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(back->pixels, img.pixels);
  // An unwritable destination (a folder that does not exist) leaves nothing behind.
  const Status s = write_png((dir / "missing" / "x.png").string(), img);
  EXPECT_EQ(s.code, ErrorCode::io_error);
  EXPECT_NE(s.message.find("missing/x.png"), std::string::npos);
  // A directory in the way of the rename: the old content survives, no temp file remains.
  fs::create_directories(dir / "isdir.png");
  EXPECT_FALSE(write_png((dir / "isdir.png").string(), img).ok());
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    (void)e;
    ++files;
  }
  EXPECT_EQ(files, 2);  // out.png and the isdir.png folder
}

TEST(SharedData, RealImagesDecode) {
  TESSERA_REQUIRE_SHARED_DATA(data);
  Result<ImageRGBA8> a = read_image((data / "images" / "ldr-rgba-00.png").string());
  ASSERT_TRUE(a.ok()) << a.status().message;
  EXPECT_EQ(a->width, 256);
  EXPECT_TRUE(a->has_alpha);
  Result<ImageRGBA8> npot = read_image((data / "images" / "ldr-rgb-10.png").string());
  ASSERT_TRUE(npot.ok());
  EXPECT_EQ(npot->width, 127);
  EXPECT_EQ(npot->height, 128);
}

}  // namespace
}  // namespace tessera::io
