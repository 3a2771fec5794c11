// Tests of tessera/metrics.h on analytic cases.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tessera/metrics.h"
#include "tessera/procedural.h"
#include "test_support.h"

namespace tessera::metrics {
namespace {

TEST(Psnr, IdenticalImagesAreInfiniteAndSsimOne) {
  const ImageRGBA8 img = make_procedural(Procedural::noise, 64, 48);
  Result<ImageComparison> r = compare_images(img, img);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->mse_rgb, 0.0);
  EXPECT_TRUE(std::isinf(r->psnr_rgb));
  EXPECT_DOUBLE_EQ(r->ssim_gray, 1.0);
  EXPECT_EQ(r->max_abs, 0);
}

TEST(Psnr, KnownOffsetsGiveKnownMse) {
  // Offsets (+3, -6, +9) on every pixel: MSE = (9 + 36 + 81) / 3 = 42.
  const ImageRGBA8 a = test::solid_rgba8(17, 9, 100, 100, 100);
  const ImageRGBA8 b = test::solid_rgba8(17, 9, 103, 94, 109);
  Result<ImageComparison> r = compare_images(a, b);
  ASSERT_TRUE(r.ok());
  EXPECT_DOUBLE_EQ(r->mse_rgb, 42.0);
  EXPECT_NEAR(r->psnr_rgb, 10.0 * std::log10(255.0 * 255.0 / 42.0), 1e-12);
  EXPECT_EQ(r->max_abs, 9);
  EXPECT_FALSE(r->has_alpha);
  // Error on half the pixels only: MSE halves.
  ImageRGBA8 c = a;
  for (int y = 0; y < c.height; ++y) {
    for (int x = 0; x < c.width; ++x) {
      if ((x + y) % 2 == 0) c.at(x, y)[0] = 110;  // +10 on red
    }
  }
  const double n = 17.0 * 9.0, hits = 77.0;  // ceil(153 / 2) pixels with x+y even
  EXPECT_NEAR(compare_images(a, c)->mse_rgb, 100.0 * hits / (3.0 * n), 1e-12);
}

TEST(Psnr, AlphaReportedSeparately) {
  ImageRGBA8 a = test::solid_rgba8(8, 8, 10, 20, 30, 200);
  ImageRGBA8 b = test::solid_rgba8(8, 8, 10, 20, 30, 190);
  a.has_alpha = true;
  Result<ImageComparison> r = compare_images(a, b);
  ASSERT_TRUE(r.ok());
  EXPECT_TRUE(r->has_alpha);
  EXPECT_TRUE(std::isinf(r->psnr_rgb));
  EXPECT_DOUBLE_EQ(r->mse_alpha, 100.0);
  EXPECT_NEAR(r->psnr_alpha, 10.0 * std::log10(65025.0 / 100.0), 1e-12);
  EXPECT_EQ(r->max_abs, 10);
  // Without alpha on either side, alpha differences are ignored entirely.
  a.has_alpha = false;
  EXPECT_EQ(compare_images(a, b)->max_abs, 0);
}

TEST(Psnr, SizeMismatchIsAnError) {
  Result<ImageComparison> r =
      compare_images(test::solid_rgba8(4, 4, 0, 0, 0), test::solid_rgba8(4, 5, 0, 0, 0));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code, ErrorCode::size_mismatch);
}

TEST(Ssim, ConstantImagesFollowTheLuminanceTerm) {
  // Two flat images: sigma terms vanish, SSIM = (2 mu_x mu_y + C1) / (mu_x^2 + mu_y^2 + C1).
  const double c1 = (0.01 * 255) * (0.01 * 255);
  const ImageRGBA8 a = test::solid_rgba8(32, 24, 100, 100, 100);
  const ImageRGBA8 b = test::solid_rgba8(32, 24, 120, 120, 120);
  const double mx = 100.0, my = 120.0;
  const double expect = (2 * mx * my + c1) / (mx * mx + my * my + c1);
  EXPECT_NEAR(*ssim_gray(a, b), expect, 1e-5);  // luma is float: 0.2126+0.7152+0.0722 = 1
}

TEST(Ssim, LumaWeightsAreRec709) {
  ImageRGBA8 img = test::solid_rgba8(1, 1, 10, 20, 30);
  const std::vector<float> y = luma709(img);
  EXPECT_NEAR(y[0], 0.2126 * 10 + 0.7152 * 20 + 0.0722 * 30, 1e-4);
}

TEST(Ssim, NoiseLowersSsimMonotonically) {
  const ImageRGBA8 ref = make_procedural(Procedural::gradient, 64, 64);
  double last = 1.0;
  for (int amp : {2, 8, 32}) {
    ImageRGBA8 noisy = ref;
    std::uint32_t h = 12345;
    for (auto& v : noisy.pixels) {
      h = h * 1664525u + 1013904223u;
      const int d = int((h >> 16) % (2 * amp + 1)) - amp;
      v = std::uint8_t(std::clamp(int(v) + d, 0, 255));
    }
    const double s = *ssim_gray(ref, noisy);
    EXPECT_LT(s, last) << amp;
    EXPECT_GT(s, 0.0);
    last = s;
  }
}

TEST(Ssim, MapCoversTheValidRegionOnly) {
  // No padding: an 11x11 window fits (w-10) x (h-10) times.
  const ImageRGBA8 a = make_procedural(Procedural::noise, 40, 30);
  const std::vector<float> ya = luma709(a);
  EXPECT_EQ(ssim_map(ya, ya, 40, 30).size(), std::size_t(30 * 20));
  // Small images: global SSIM, still 1 for identical inputs.
  const ImageRGBA8 s = make_procedural(Procedural::noise, 8, 8);
  EXPECT_DOUBLE_EQ(*ssim_gray(s, s), 1.0);
}

TEST(Ssim, ThreadCountDoesNotChangeTheResult) {
  const ImageRGBA8 a = make_procedural(Procedural::bricks, 200, 130);
  const ImageRGBA8 b = make_procedural(Procedural::bricks, 200, 130, 9);
  const double one = *ssim_gray(a, b, {1});
  EXPECT_EQ(*ssim_gray(a, b, {2}), one);
  EXPECT_EQ(*ssim_gray(a, b, {0}), one);
}

TEST(ErrorCdf, CountsFractionAtOrAboveEachThreshold) {
  ImageRGBAF a(4, 1), b(4, 1);
  // Pixel errors (2-norms): 0, 0.1, sqrt(0.01+0.01)=0.1414, 0.5.
  b.at(1, 0)[0] = 0.1f;
  b.at(2, 0)[0] = 0.1f;
  b.at(2, 0)[1] = 0.1f;
  b.at(3, 0)[2] = 0.5f;
  a.at(3, 0)[3] = 1.0f;  // alpha ignored
  const std::vector<double> xs = {0.0, 0.05, 0.1, 0.2, 0.6};
  Result<std::vector<double>> cdf = error_cdf(a, b, xs);
  ASSERT_TRUE(cdf.ok());
  EXPECT_DOUBLE_EQ((*cdf)[0], 1.0);
  EXPECT_DOUBLE_EQ((*cdf)[1], 0.75);
  EXPECT_DOUBLE_EQ((*cdf)[2], 0.75);  // >= 0.1 includes the pixel at exactly 0.1 (float)
  EXPECT_DOUBLE_EQ((*cdf)[3], 0.25);
  EXPECT_DOUBLE_EQ((*cdf)[4], 0.0);
  // A mask restricts the counted pixels.
  const std::vector<std::uint8_t> mask = {0, 0, 1, 1};
  Result<std::vector<double>> masked = error_cdf(a, b, xs, mask);
  EXPECT_DOUBLE_EQ((*masked)[1], 1.0);
  EXPECT_DOUBLE_EQ((*masked)[3], 0.5);
}

TEST(Heatmap, ColourMapEndsAndScale) {
  std::uint8_t rgb[3];
  colour_map_rgb(ColourMap::inferno, 0.0f, rgb);
  EXPECT_EQ(rgb[0], 0);
  EXPECT_EQ(rgb[2], 4);
  colour_map_rgb(ColourMap::inferno, 1.0f, rgb);
  EXPECT_EQ(rgb[0], 252);
  colour_map_rgb(ColourMap::grey, 0.5f, rgb);
  EXPECT_EQ(rgb[1], 128);
  const ImageRGBA8 a = test::solid_rgba8(2, 1, 0, 0, 0);
  ImageRGBA8 b = a;
  b.at(1, 0)[1] = 64;
  Result<ImageRGBA8> h = difference_heatmap(a, b, 64.0f, ColourMap::grey);
  ASSERT_TRUE(h.ok());
  EXPECT_EQ(h->at(0, 0)[0], 0);
  EXPECT_EQ(h->at(1, 0)[0], 255);
  EXPECT_EQ(h->at(1, 0)[3], 255);
}

}  // namespace
}  // namespace tessera::metrics
