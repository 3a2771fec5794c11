// Tests of tessera/metrics.h on analytic cases.
#include "tessera/metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

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

TEST(Premultiplied, ColourTimesAlphaHandComputed) {
  // Texel 0: red differs by 10 under alpha 128; texel 1: every colour differs, alpha 0 in both.
  ImageRGBA8 a(2, 1), b(2, 1);
  a.has_alpha = b.has_alpha = true;
  const std::uint8_t ta[2][4] = {{200, 100, 50, 128}, {10, 20, 30, 0}};
  const std::uint8_t tb[2][4] = {{190, 100, 50, 128}, {250, 250, 250, 0}};
  for (int i = 0; i < 2; ++i) {
    for (int c = 0; c < 4; ++c) {
      a.at(i, 0)[c] = ta[i][c];
      b.at(i, 0)[c] = tb[i][c];
    }
  }
  CompareOptions o;
  o.premultiplied = true;
  Result<ImageComparison> r = compare_images(a, b, o);
  ASSERT_TRUE(r.ok());
  ASSERT_TRUE(r->has_premultiplied);
  EXPECT_FALSE(r->has_normal);
  // (10 * 128 / 255)^2 over 2 texels x 3 channels; the transparent texel adds nothing.
  const double mse = std::pow(10.0 * 128.0 / 255.0, 2) / 6.0;  // 4.1995
  EXPECT_NEAR(r->mse_premultiplied, mse, 1e-12);
  EXPECT_NEAR(r->psnr_premultiplied, 10.0 * std::log10(65025.0 / mse), 1e-9);
  EXPECT_GT(r->mse_rgb, 10000.0);  // the plain error is dominated by the invisible texel
  // Colour under alpha 0 on both sides never counts: identical colour x alpha is infinite.
  b.at(0, 0)[0] = 200;
  r = compare_images(a, b, o);
  EXPECT_EQ(r->mse_premultiplied, 0.0);
  EXPECT_TRUE(std::isinf(r->psnr_premultiplied));
  EXPECT_GT(r->mse_rgb, 0.0);
  // Alpha itself matters: 100 under alpha 255 against the same under alpha 0 is 100 of error.
  a.at(1, 0)[0] = 100;
  a.at(1, 0)[3] = 255;
  r = compare_images(a, b, o);
  EXPECT_NEAR(r->mse_premultiplied, (100.0 * 100 + 20.0 * 20 + 30.0 * 30) / 6.0, 1e-12);
  // Not asked for: not computed.
  EXPECT_FALSE(compare_images(a, b)->has_premultiplied);
}

TEST(Premultiplied, ImagesWithoutAlphaCountAsOpaque) {
  // Alpha bytes of images without alpha are ignored: premultiplied MSE is the plain MSE.
  const ImageRGBA8 a = test::solid_rgba8(5, 3, 100, 100, 100, 0);
  const ImageRGBA8 b = test::solid_rgba8(5, 3, 103, 94, 109, 7);
  CompareOptions o;
  o.premultiplied = true;
  Result<ImageComparison> r = compare_images(a, b, o);
  EXPECT_DOUBLE_EQ(r->mse_premultiplied, 42.0);
  EXPECT_DOUBLE_EQ(r->mse_premultiplied, r->mse_rgb);
  // Deterministic for any thread count, on an image larger than one chunk.
  const ImageRGBA8 c = make_procedural(Procedural::foliage, 300, 200);
  const ImageRGBA8 d = make_procedural(Procedural::foliage, 300, 200, 5);
  o.threads = 1;
  const double one = compare_images(c, d, o)->mse_premultiplied;
  o.threads = 4;
  EXPECT_EQ(compare_images(c, d, o)->mse_premultiplied, one);
  EXPECT_GT(one, 0.0);
}

/// A w x h image of one normal (8-bit RGB), alpha 255.
ImageRGBA8 normal_image(int w, int h, std::uint8_t x, std::uint8_t y, std::uint8_t z) {
  return test::solid_rgba8(w, h, x, y, z);
}

TEST(AngularError, HandComputedAngles) {
  CompareOptions o;
  o.normal = true;
  o.compute_ssim = false;
  // 8-bit normals cannot hold 0: +X is (1, e, e) and +Z (e, e, 1) with e = 1/255, so their
  // angle is acos((2e + e^2) / (1 + 2e^2)) = 89.5498 degrees, not quite 90.
  const double e = 1.0 / 255.0;
  const double x_to_z = std::acos((2 * e + e * e) / (1 + 2 * e * e)) * 180.0 / std::numbers::pi;
  Result<ImageComparison> r =
      compare_images(normal_image(1, 1, 255, 128, 128), normal_image(1, 1, 128, 128, 255), o);
  ASSERT_TRUE(r.ok());
  ASSERT_TRUE(r->has_normal);
  EXPECT_FALSE(r->has_premultiplied);
  EXPECT_NEAR(r->angular_error_mean_deg, x_to_z, 1e-9);
  EXPECT_NEAR(r->angular_error_mean_deg, 89.5498, 1e-4);
  EXPECT_EQ(r->angular_error_max_deg, r->angular_error_mean_deg);
  EXPECT_EQ(r->angular_error_p99_deg, r->angular_error_mean_deg);
  // (1, e, e) against (-1, -e, -e): exactly opposite.
  r = compare_images(normal_image(1, 1, 255, 128, 128), normal_image(1, 1, 0, 127, 127), o);
  EXPECT_DOUBLE_EQ(r->angular_error_mean_deg, 180.0);
  // Length does not matter: (1, 1, e) is 45 degrees from (1, e, e) up to the e terms.
  r = compare_images(normal_image(1, 1, 255, 128, 128), normal_image(1, 1, 255, 255, 128), o);
  EXPECT_NEAR(r->angular_error_mean_deg, 45.0, 0.3);
  // Identical normals: exactly 0.
  const ImageRGBA8 n = make_procedural(Procedural::noise, 20, 20);
  r = compare_images(n, n, o);
  EXPECT_EQ(r->angular_error_max_deg, 0.0);
  EXPECT_EQ(r->angular_error_mean_deg, 0.0);
}

TEST(AngularError, P99IsTheNearestRank) {
  CompareOptions o;
  o.normal = true;
  const double theta =
      compare_images(normal_image(1, 1, 255, 128, 128), normal_image(1, 1, 128, 128, 255), o)
          ->angular_error_max_deg;
  // n texels of +X, `wrong` of them +Z: the p99 is the ceil(0.99 n)-th smallest angle, 0 while
  // at least that many are right. 200 texels: rank 198, theta from 3 wrong on; 150 texels:
  // rank ceil(148.5) = 149, theta from 2 wrong on.
  for (const auto& [w, first_theta] : {std::pair{20, 3}, std::pair{15, 2}}) {
    const ImageRGBA8 a = normal_image(w, 10, 255, 128, 128);
    const double n = w * 10.0;
    for (const int wrong : {1, 2, 3, 4}) {
      ImageRGBA8 b = a;
      for (int i = 0; i < wrong; ++i) {
        b.at(3 * i, 5)[0] = 128;
        b.at(3 * i, 5)[2] = 255;
      }
      Result<ImageComparison> r = compare_images(a, b, o);
      ASSERT_TRUE(r.ok());
      EXPECT_EQ(r->angular_error_p99_deg, wrong >= first_theta ? theta : 0.0) << n << " " << wrong;
      EXPECT_NEAR(r->angular_error_mean_deg, wrong * theta / n, 1e-12) << wrong;
      EXPECT_EQ(r->angular_error_max_deg, theta);
    }
  }
  // Deterministic for any thread count.
  const ImageRGBA8 c = make_procedural(Procedural::noise, 300, 200);
  const ImageRGBA8 d = make_procedural(Procedural::noise, 300, 200, 3);
  o.threads = 1;
  const ImageComparison one = *compare_images(c, d, o);
  o.threads = 4;
  const ImageComparison four = *compare_images(c, d, o);
  EXPECT_EQ(one.angular_error_mean_deg, four.angular_error_mean_deg);
  EXPECT_EQ(one.angular_error_p99_deg, four.angular_error_p99_deg);
  EXPECT_GT(one.angular_error_mean_deg, 0.0);
  EXPECT_LE(one.angular_error_p99_deg, one.angular_error_max_deg);
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
