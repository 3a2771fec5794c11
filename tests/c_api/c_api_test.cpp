// The C API (tessera/tessera_c.h) against the C++ API, byte for byte: encodes under every kind
// of option (the same files as texture_file::compress_images + serialise_texture), raw blocks,
// decoding into padded buffers, the three containers from memory and files, metrics, progress
// and cancellation. Bad input: c_api_bad_input_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "c_api_test_util.h"
#include "tessera/io.h"
#include "tessera/metrics.h"
#include "tessera/texture_file.h"
#include "test_support.h"

namespace tessera::c_api_test {
namespace {

namespace tf = texture_file;

struct Case {
  const char* name;
  tessera_encode_options c;  // the C options
  tf::CompressOptions cxx;   // the same in C++
  tf::TextureShape shape;
  int images = 1;
  bool alpha = true;
  int size = 32;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  const auto add = [&](const char* name, auto&& set) {
    Case k{name, {}, {}, {}, 1, true, 32};
    tessera_encode_options_init(&k.c);
    set(k);
    out.push_back(k);
  };
  add("defaults", [](Case&) {});
  add("rgb_fast", [](Case& k) {
    k.alpha = false;
    k.c.quality = TESSERA_QUALITY_FAST;
    k.cxx.encode.quality = pvrtc::Quality::fast;
  });
  add("2bpp_high_mips_kaiser", [](Case& k) {
    k.c.format = TESSERA_FORMAT_PVRTC1_2BPP;
    k.c.quality = TESSERA_QUALITY_HIGH;
    k.c.flags = TESSERA_FLAG_MIPMAPS;
    k.c.mip_filter = TESSERA_MIP_FILTER_KAISER;
    k.cxx.encode.format = pvrtc::Format::pvrtc1_2bpp;
    k.cxx.encode.quality = pvrtc::Quality::high;
    k.cxx.mipmaps = true;
    k.cxx.mip_filter = image::MipFilter::kaiser;
  });
  add("srgb_bleed_weighted_3_levels", [](Case& k) {
    k.c.flags = TESSERA_FLAG_SRGB | TESSERA_FLAG_ALPHA_BLEED | TESSERA_FLAG_ALPHA_WEIGHTED;
    k.c.mip_levels = 3;
    k.cxx.srgb = k.cxx.alpha_bleed = k.cxx.encode.alpha_weighted = true;
    k.cxx.mipmaps = true;
    k.cxx.mip_levels = 3;
  });
  add("premultiply_flip_lanczos", [](Case& k) {
    k.c.flags = TESSERA_FLAG_PREMULTIPLY | TESSERA_FLAG_FLIP_Y | TESSERA_FLAG_MIPMAPS;
    k.c.mip_filter = TESSERA_MIP_FILTER_LANCZOS;
    k.cxx.premultiply = k.cxx.flip_y = k.cxx.mipmaps = true;
    k.cxx.mip_filter = image::MipFilter::lanczos;
  });
  add("normal_map_schedule", [](Case& k) {
    k.alpha = false;
    k.c.flags = TESSERA_FLAG_NORMAL_MAP;
    k.c.iterations = 2;
    k.c.exact_search_rounds = 1;
    k.cxx.normal_map = true;
    k.cxx.encode.iterations = 2;
    k.cxx.encode.exact_search_rounds = 1;
  });
  add("resize_pot", [](Case& k) {
    k.size = 24;
    k.c.flags = TESSERA_FLAG_RESIZE_POT;
    k.cxx.resize_pot = true;
  });
  add("cube_mips", [](Case& k) {
    k.images = 6;
    k.c.faces = 6;
    k.c.flags = TESSERA_FLAG_MIPMAPS;
    k.shape.faces = 6;
    k.cxx.mipmaps = true;
  });
  add("array_of_3", [](Case& k) {
    k.images = 3;
    k.c.array = 1;
    k.shape.array = true;
  });
  return out;
}

TEST(CApi, EncodeEqualsCxxInEveryContainer) {
  Context context = make_context(2);
  for (const Case& k : cases()) {
    SCOPED_TRACE(k.name);
    std::vector<ImageRGBA8> images;
    std::vector<tessera_image> views;
    std::vector<std::string> names;
    for (int i = 0; i < k.images; ++i) {
      images.push_back(test_image(k.size, k.size, i, k.alpha));
      names.push_back("images[" + std::to_string(i) + "]");
    }
    for (const ImageRGBA8& im : images) views.push_back(c_image(im));
    tessera_texture* raw = nullptr;
    ASSERT_EQ(tessera_encode(context.get(), views.data(), std::uint32_t(views.size()), &k.c, &raw),
              TESSERA_SUCCESS)
        << tessera_context_last_error(context.get());
    Texture texture(raw);
    tf::CompressOptions cxx = k.cxx;
    cxx.encode.threads = 2;
    Result<tf::CompressedImage> want = tf::compress_images(images, k.shape, cxx, names);
    ASSERT_TRUE(want.ok()) << want.status().message;
    EXPECT_EQ(c_file(context.get(), raw, TESSERA_CONTAINER_PVR3),
              *tf::serialise_pvr3(want->texture));
    EXPECT_EQ(c_file(context.get(), raw, TESSERA_CONTAINER_KTX1),
              *tf::serialise_ktx1(want->texture));
    EXPECT_EQ(c_file(context.get(), raw, TESSERA_CONTAINER_KTX2, 3),
              *tf::serialise_ktx2(want->texture, tf::Ktx2Options{3}));
    tessera_texture_info info{};
    info.struct_size = sizeof info;
    ASSERT_EQ(tessera_texture_get_info(raw, &info), TESSERA_SUCCESS);
    EXPECT_EQ(int(info.levels), want->texture.level_count());
    EXPECT_EQ(int(info.faces), want->texture.faces);
    EXPECT_EQ(int(info.layers), want->texture.layers);
    EXPECT_EQ(info.has_alpha != 0, want->texture.has_alpha);
    EXPECT_EQ(int(info.width), want->texture.width);
  }
}

TEST(CApi, DifferentOptionsGiveDifferentBytes) {  // the control of the test above
  Context context = make_context();
  const ImageRGBA8 im = test_image(32, 32, 0, true);
  const tessera_image view = c_image(im);
  std::vector<std::vector<std::uint8_t>> files;
  for (tessera_quality q : {TESSERA_QUALITY_FAST, TESSERA_QUALITY_HIGH}) {
    tessera_encode_options o;
    tessera_encode_options_init(&o);
    o.quality = q;
    tessera_texture* raw = nullptr;
    ASSERT_EQ(tessera_encode(context.get(), &view, 1, &o, &raw), TESSERA_SUCCESS);
    Texture texture(raw);
    files.push_back(c_file(context.get(), raw, TESSERA_CONTAINER_PVR3));
  }
  EXPECT_NE(files[0], files[1]);
}

TEST(CApi, PaddedRowsAndThreadCountsGiveTheSameBytes) {
  const ImageRGBA8 im = test_image(64, 32, 3, true);
  const std::size_t pitch = 64 * 4 + 20;
  std::vector<std::uint8_t> padded(pitch * 32, 0x5a);  // the padding must never be read
  for (int y = 0; y < 32; ++y) std::memcpy(&padded[y * pitch], im.at(0, y), 64 * 4);
  tessera_image view = c_image(im);
  std::vector<std::vector<std::uint8_t>> files;
  for (int threads : {1, 2}) {
    Context context = make_context(threads);
    for (bool pad : {false, true}) {
      if (pad) {
        view.pixels = padded.data();
        view.row_pitch = pitch;
      }
      tessera_texture* raw = nullptr;
      ASSERT_EQ(tessera_encode(context.get(), &view, 1, nullptr, &raw), TESSERA_SUCCESS);
      Texture texture(raw);
      files.push_back(c_file(context.get(), raw, TESSERA_CONTAINER_KTX2));
    }
  }
  for (const auto& f : files) EXPECT_EQ(f, files[0]);
}

TEST(CApi, RawBlocksEncodeAndDecodeAsTheCxxCodec) {
  Context context = make_context();
  const ImageRGBA8 im = test_image(32, 16, 1, true);
  const tessera_image view = c_image(im);
  for (tessera_format format : {TESSERA_FORMAT_PVRTC1_4BPP, TESSERA_FORMAT_PVRTC1_2BPP}) {
    tessera_encode_options o;
    tessera_encode_options_init(&o);
    o.format = format;
    std::size_t size = 0;
    ASSERT_EQ(tessera_pvrtc_encode(context.get(), &view, &o, nullptr, 0, &size), TESSERA_SUCCESS);
    std::size_t level = 0;
    ASSERT_EQ(tessera_pvrtc_level_size(format, 32, 16, &level), TESSERA_SUCCESS);
    EXPECT_EQ(size, level);
    std::vector<std::uint8_t> blocks(size);
    ASSERT_EQ(tessera_pvrtc_encode(context.get(), &view, &o, blocks.data(), blocks.size(), &size),
              TESSERA_SUCCESS);
    tf::CompressOptions cxx;
    cxx.encode.format = format == TESSERA_FORMAT_PVRTC1_2BPP ? pvrtc::Format::pvrtc1_2bpp
                                                             : pvrtc::Format::pvrtc1_4bpp;
    Result<tf::CompressedImage> want = tf::compress_image(im, cxx, "image");
    ASSERT_TRUE(want.ok());
    EXPECT_EQ(blocks, want->texture.levels[0]);

    const std::size_t pitch = 32 * 4 + 8;
    std::vector<std::uint8_t> rgba(pitch * 16, 0xee);
    ASSERT_EQ(tessera_pvrtc_decode(context.get(), format, 32, 16, blocks.data(), blocks.size(),
                                   rgba.data(), pitch, rgba.size()),
              TESSERA_SUCCESS);
    Result<ImageRGBA8> decoded = pvrtc::decode(blocks, cxx.encode.format, 32, 16);
    ASSERT_TRUE(decoded.ok());
    for (int y = 0; y < 16; ++y) {
      EXPECT_EQ(0, std::memcmp(&rgba[y * pitch], decoded->at(0, y), 32 * 4)) << "row " << y;
      for (std::size_t x = 32 * 4; x < pitch; ++x) ASSERT_EQ(rgba[y * pitch + x], 0xee);
    }
  }
}

TEST(CApi, ReadsEveryContainerFromMemoryAndFiles) {
  Context context = make_context();
  std::vector<ImageRGBA8> faces;
  for (int i = 0; i < 6; ++i) faces.push_back(test_image(16, 16, i, i % 2 == 0));
  tf::CompressOptions cxx;
  cxx.mipmaps = true;
  cxx.srgb = true;
  const std::vector<std::string> names(6, "face");
  Result<tf::CompressedImage> made = tf::compress_images(faces, {6, false}, cxx, names);
  ASSERT_TRUE(made.ok()) << made.status().message;
  const tf::CompressedTexture& want = made->texture;
  const std::filesystem::path dir = test::temp_dir("c_api_read");
  for (const char* ext : {".pvr", ".ktx", ".ktx2"}) {
    SCOPED_TRACE(ext);
    const std::string path = (dir / (std::string("cube") + ext)).string();
    ASSERT_TRUE(tf::write_texture_file(path, want).ok());
    Result<std::vector<std::uint8_t>> bytes =
        tf::serialise_texture(want, tf::container_from_extension(path));
    ASSERT_TRUE(bytes.ok());
    tessera_texture* from_memory = nullptr;
    tessera_texture* from_file = nullptr;
    ASSERT_EQ(
        tessera_texture_read_memory(context.get(), bytes->data(), bytes->size(), &from_memory),
        TESSERA_SUCCESS)
        << tessera_context_last_error(context.get());
    ASSERT_EQ(tessera_texture_read_file(context.get(), path.c_str(), &from_file), TESSERA_SUCCESS);
    Texture a(from_memory), b(from_file);
    tessera_texture_info info{};
    info.struct_size = sizeof info;
    ASSERT_EQ(tessera_texture_get_info(from_memory, &info), TESSERA_SUCCESS);
    EXPECT_EQ(info.faces, 6u);
    EXPECT_EQ(int(info.levels), want.level_count());
    EXPECT_EQ(info.srgb, 1);
    for (std::uint32_t level = 0; level < info.levels; ++level) {
      for (std::uint32_t face = 0; face < 6; ++face) {
        const std::uint8_t* blocks = nullptr;
        std::size_t size = 0;
        ASSERT_EQ(tessera_texture_get_blocks(from_file, level, 0, face, &blocks, &size),
                  TESSERA_SUCCESS);
        const auto image = want.image(int(level), 0, int(face));
        ASSERT_EQ(std::vector<std::uint8_t>(blocks, blocks + size),
                  std::vector<std::uint8_t>(image.begin(), image.end()));
      }
    }
    // Written back through the C API: the same file.
    const std::string again = (dir / (std::string("again") + ext)).string();
    ASSERT_EQ(tessera_texture_write_file(context.get(), from_memory, again.c_str(), 0),
              TESSERA_SUCCESS);
    Result<std::vector<std::uint8_t>> written = io::read_file(again);
    ASSERT_TRUE(written.ok());
    EXPECT_EQ(*written, *bytes);
    // Level 1 of face 3 decoded into a padded buffer: decode_texture_image's texels.
    const int w = want.level_width(1), h = want.level_height(1);
    const std::size_t pitch = std::size_t(w) * 4 + 4;
    std::vector<std::uint8_t> rgba(pitch * h);
    ASSERT_EQ(
        tessera_texture_decode(context.get(), from_file, 1, 0, 3, rgba.data(), pitch, rgba.size()),
        TESSERA_SUCCESS);
    Result<ImageRGBA8> decoded = tf::decode_texture_image(want, 1, 0, 3);
    ASSERT_TRUE(decoded.ok());
    for (int y = 0; y < h; ++y) {
      EXPECT_EQ(0, std::memcmp(&rgba[y * pitch], decoded->at(0, y), std::size_t(w) * 4));
    }
  }
}

TEST(CApi, MetricsEqualCompareImages) {
  Context context = make_context();
  const ImageRGBA8 a = test_image(48, 40, 0, true);
  const ImageRGBA8 b = test_image(48, 40, 2, true);
  const tessera_image va = c_image(a), vb = c_image(b);
  tessera_metrics m{};
  m.struct_size = sizeof m;
  ASSERT_EQ(tessera_compare(context.get(), &va, &vb, 1, &m), TESSERA_SUCCESS);
  Result<metrics::ImageComparison> want = metrics::compare_images(a, b);
  ASSERT_TRUE(want.ok());
  EXPECT_EQ(m.psnr_rgb, want->psnr_rgb);
  EXPECT_EQ(m.mse_rgb, want->mse_rgb);
  EXPECT_EQ(m.psnr_alpha, want->psnr_alpha);
  EXPECT_EQ(m.ssim, want->ssim_gray);
  EXPECT_EQ(m.max_abs, want->max_abs);
  EXPECT_EQ(m.has_alpha, 1);
  EXPECT_LT(m.ssim, 1.0);
  ASSERT_EQ(tessera_compare(context.get(), &va, &va, 1, &m), TESSERA_SUCCESS);
  EXPECT_TRUE(std::isinf(m.psnr_rgb));
  EXPECT_EQ(m.ssim, 1.0);
}

struct ProgressLog {
  std::vector<double> fractions;
  int cancel_after = -1;  // cancel on this call (0-based); -1 never
};

int log_progress(void* user, double fraction) {
  auto* log = static_cast<ProgressLog*>(user);
  log->fractions.push_back(fraction);
  return log->cancel_after >= 0 && int(log->fractions.size()) > log->cancel_after ? 1 : 0;
}

TEST(CApi, ProgressRisesToOneAndCancelStopsTheEncode) {
  const ImageRGBA8 im = test_image(64, 64, 0, true);
  const tessera_image view = c_image(im);
  tessera_encode_options o;
  tessera_encode_options_init(&o);
  o.quality = TESSERA_QUALITY_HIGH;
  o.flags = TESSERA_FLAG_MIPMAPS;
  ProgressLog log;
  Context context = make_context(0, log_progress, &log);
  tessera_texture* raw = nullptr;
  ASSERT_EQ(tessera_encode(context.get(), &view, 1, &o, &raw), TESSERA_SUCCESS);
  Texture done(raw);
  ASSERT_GE(log.fractions.size(), 3u);
  for (std::size_t i = 1; i < log.fractions.size(); ++i) {
    EXPECT_GE(log.fractions[i], log.fractions[i - 1]);
  }
  EXPECT_EQ(log.fractions.back(), 1.0);

  ProgressLog stop;
  stop.cancel_after = 1;
  Context cancelling = make_context(0, log_progress, &stop);
  raw = reinterpret_cast<tessera_texture*>(&stop);  // must be reset to NULL
  EXPECT_EQ(tessera_encode(cancelling.get(), &view, 1, &o, &raw), TESSERA_ERROR_CANCELLED);
  EXPECT_EQ(raw, nullptr);
  EXPECT_EQ(stop.fractions.size(), 2u);  // no call after the one that cancelled
  EXPECT_STRNE(tessera_context_last_error(cancelling.get()), "");
  // The context is usable again, and a success clears the message.
  stop.cancel_after = -1;
  ASSERT_EQ(tessera_encode(cancelling.get(), &view, 1, &o, &raw), TESSERA_SUCCESS);
  Texture again(raw);
  EXPECT_STREQ(tessera_context_last_error(cancelling.get()), "");
  EXPECT_EQ(c_file(cancelling.get(), raw, TESSERA_CONTAINER_PVR3),
            c_file(context.get(), done.get(), TESSERA_CONTAINER_PVR3));
}

TEST(CApi, CancellingAtEveryProgressPointOfACubeMapLeavesNothing) {
  std::vector<ImageRGBA8> faces;
  std::vector<tessera_image> views;
  for (int i = 0; i < 6; ++i) faces.push_back(test_image(16, 16, i, true));
  for (const ImageRGBA8& f : faces) views.push_back(c_image(f));
  tessera_encode_options o;
  tessera_encode_options_init(&o);
  o.faces = 6;
  o.quality = TESSERA_QUALITY_FAST;
  o.flags = TESSERA_FLAG_MIPMAPS;
  ProgressLog count;
  Context counting = make_context(2, log_progress, &count);
  tessera_texture* raw = nullptr;
  ASSERT_EQ(tessera_encode(counting.get(), views.data(), 6, &o, &raw), TESSERA_SUCCESS);
  tessera_texture_free(raw);
  ASSERT_GE(count.fractions.size(), 6u);  // at least one point per face
  for (std::size_t stop_at = 0; stop_at < count.fractions.size(); ++stop_at) {
    ProgressLog stop;
    stop.cancel_after = int(stop_at);
    Context cancelling = make_context(2, log_progress, &stop);
    raw = nullptr;
    ASSERT_EQ(tessera_encode(cancelling.get(), views.data(), 6, &o, &raw), TESSERA_ERROR_CANCELLED)
        << "cancelled at call " << stop_at;
    EXPECT_EQ(raw, nullptr);
    EXPECT_EQ(stop.fractions.size(), stop_at + 1);
  }
}

TEST(CApi, ErrorStringsAndVersion) {
  EXPECT_STREQ(tessera_error_string(TESSERA_SUCCESS), "success");
  EXPECT_STREQ(tessera_error_string(TESSERA_ERROR_BUFFER_TOO_SMALL), "buffer too small");
  EXPECT_STREQ(tessera_error_string(static_cast<tessera_error>(999)), "unknown error");
  std::vector<std::string> seen;
  for (int c = TESSERA_SUCCESS; c <= TESSERA_ERROR_INTERNAL; ++c) {
    const std::string s = tessera_error_string(static_cast<tessera_error>(c));
    EXPECT_NE(s, "unknown error") << c;
    EXPECT_EQ(std::count(seen.begin(), seen.end(), s), 0) << s;
    seen.push_back(s);
  }
  EXPECT_GT(std::strlen(tessera_version()), 4u);
}

}  // namespace
}  // namespace tessera::c_api_test
