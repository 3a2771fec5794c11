// Tests of deferred shading with adaptive supersampling (Hollander et al. 2013) and FXAA.
#include "tessera/deferred.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <set>

#include "tessera/metrics.h"

namespace tessera::deferred {
namespace {

// --- Index matrices ---------------------------------------------------------------------------

TEST(IndexMatrix, PaperMatricesAndPermutations) {
  const std::vector<std::uint8_t> m2 = {0, 2, 3, 1};
  const std::vector<std::uint8_t> m3 = {2, 6, 3, 5, 0, 8, 1, 7, 4};
  const std::vector<std::uint8_t> m4 = {1, 8, 2, 10, 12, 4, 14, 6, 3, 11, 0, 9, 15, 7, 13, 5};
  auto vec = [](std::span<const std::uint8_t> s) {
    return std::vector<std::uint8_t>(s.begin(), s.end());
  };
  EXPECT_EQ(vec(index_matrix(2)), m2);
  EXPECT_EQ(vec(index_matrix(3)), m3);
  EXPECT_EQ(vec(index_matrix(4)), m4);
  EXPECT_TRUE(index_matrix(0).empty());
  EXPECT_TRUE(index_matrix(9).empty());
  for (int m = 1; m <= 8; ++m) {
    const auto idx = index_matrix(m);
    const auto order = sample_order(m);
    ASSERT_EQ(idx.size(), std::size_t(m * m));
    std::set<int> seen(idx.begin(), idx.end());
    EXPECT_EQ(seen.size(), std::size_t(m * m)) << "m=" << m;
    EXPECT_EQ(*seen.begin(), 0);
    EXPECT_EQ(*seen.rbegin(), m * m - 1);
    for (int p = 0; p < m * m; ++p) EXPECT_EQ(idx[order[std::size_t(p)]], p);
  }
}

TEST(IndexMatrix, PrefixesAreWellSpread) {
  for (int m = 2; m <= 8; ++m) {
    const auto order = sample_order(m);
    for (int p = 2; p <= m * m; ++p) {
      double dmin = 1e9;
      double cx = 0, cy = 0;
      for (int a = 0; a < p; ++a) {
        const int xa = order[std::size_t(a)] % m, ya = order[std::size_t(a)] / m;
        cx += xa;
        cy += ya;
        for (int b = a + 1; b < p; ++b) {
          const int xb = order[std::size_t(b)] % m, yb = order[std::size_t(b)] / m;
          dmin = std::min(dmin, std::hypot(double(xa - xb), double(ya - yb)));
        }
      }
      // Minimum distance close to that of a regular grid of p points in the window.
      EXPECT_GE(dmin, 0.5 * m / std::sqrt(double(p)) - 1e-9) << "m=" << m << " p=" << p;
      // Prefixes of four or more samples are centred on the window.
      if (p >= 4) {
        EXPECT_LE(std::hypot(cx / p - (m - 1) / 2.0, cy / p - (m - 1) / 2.0),
                  0.5 * m / std::sqrt(double(p)) + 0.26)
            << "m=" << m << " p=" << p;
      }
    }
  }
}

// --- Metrics ----------------------------------------------------------------------------------

TEST(Metrics, ZeroOnFlatWindows) {
  const std::vector<float> depth(16, 7.5f);
  EXPECT_EQ(metric_depth(depth, 200.0f), 0.0f);
  std::vector<float> normals;
  for (int i = 0; i < 16; ++i) normals.insert(normals.end(), {0.2f, 0.9f, 0.3f});
  EXPECT_EQ(metric_normal(normals, 2.0f, 16), 0.0f);
  EXPECT_EQ(metric_shading(0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.0312f, 0.125f, 4.0f, 16), 0.0f);
  // Below both thresholds: still 0.
  EXPECT_EQ(metric_shading(0.5f, 0.52f, 0.5f, 0.5f, 0.5f, 0.0312f, 0.125f, 4.0f, 16), 0.0f);
}

TEST(Metrics, PositiveOnEdges) {
  std::vector<float> depth(16, 5.0f);
  for (int i = 8; i < 16; ++i) depth[std::size_t(i)] = 10.0f;  // a depth step
  const float kd = metric_depth(depth, 200.0f);
  EXPECT_GT(kd, 15.0f);
  // Variance of d / mean: (1/3)^2 here, times c * (n - 1).
  EXPECT_NEAR(kd, 200.0f * 15.0f / 9.0f, 1e-2f);
  std::vector<float> normals;
  for (int i = 0; i < 16; ++i) {
    if (i < 8)
      normals.insert(normals.end(), {0, 1, 0});
    else
      normals.insert(normals.end(), {1, 0, 0});
  }
  const float kn = metric_normal(normals, 2.0f, 16);
  // Mean normal at 45 degrees: sqrt(1 - cos 45) * c * K.
  EXPECT_NEAR(kn, 2.0f * 15.0f * std::sqrt(1.0f - std::sqrt(0.5f)), 1e-3f);
  // Background (zero) normals are skipped.
  std::vector<float> half(normals.begin(), normals.begin() + 24);
  half.resize(48, 0.0f);
  EXPECT_EQ(metric_normal(half, 2.0f, 16), 0.0f);
  EXPECT_NEAR(metric_shading(0.2f, 0.8f, 0.2f, 0.2f, 0.2f, 0.0312f, 0.125f, 4.0f, 16),
              4.0f * 15.0f * 0.6f, 1e-4f);
}

// --- Renderer ---------------------------------------------------------------------------------

struct Fixture {
  scene::Scene sc = scene::builtin_scene();
  std::unique_ptr<DeferredRenderer> renderer;
  scene::Camera camera;
  ShadingOptions shading;

  Fixture() {
    auto r = DeferredRenderer::create(sc, {2});
    EXPECT_TRUE(r.ok());
    renderer = std::move(*r);
    camera = scene::orbit_camera(sc, 1, 8);
    shading = scene_shading(sc, 2);
    shading.threads = 2;
  }
  GBuffer gbuffer(int w, int h, int m) {
    GBuffer gb;
    const Status s = renderer->render_gbuffer(camera, w, h, m, gb);
    EXPECT_TRUE(s.ok()) << s.message;
    return gb;
  }
};

bool same_pixels(const ImageRGBAF& a, const ImageRGBAF& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
}

TEST(Deferred, GBufferReconstructsTheGroundPlane) {
  Fixture f;
  const GBuffer gb = f.gbuffer(64, 48, 2);
  int ground = 0;
  for (int gy = 0; gy < gb.fb.grid_height(); ++gy) {
    for (int gx = 0; gx < gb.fb.grid_width(); ++gx) {
      const float* s = gb.sample(gx, gy);
      if (s[kChMaterial] != 0.0f || std::fabs(s[kChNormal + 1]) < 0.999f) continue;
      ++ground;
      EXPECT_NEAR(gb.position(gx, gy).y, 0.0f, 2e-4f * s[kChDepth]);
    }
  }
  EXPECT_GT(ground, 1000);
}

TEST(Deferred, AdaptiveExtremesMatchReferenceAndDefault) {
  Fixture f;
  for (int m : {2, 3, 4}) {
    const GBuffer gb = f.gbuffer(48, 36, m);
    const ImageRGBAF ref = f.renderer->shade_reference(gb, f.shading);
    const ImageRGBAF one = f.renderer->shade_default(gb, f.shading);
    AdaptiveThresholds a;
    a.force_k = m * m - 1;
    const AdaptiveResult full = f.renderer->shade_adaptive(gb, f.shading, a);
    EXPECT_TRUE(same_pixels(full.image, ref)) << "m=" << m;
    EXPECT_EQ(full.samples_shaded, std::uint64_t(48 * 36 * m * m));
    a.force_k = 0;
    const AdaptiveResult none = f.renderer->shade_adaptive(gb, f.shading, a);
    EXPECT_TRUE(same_pixels(none.image, one)) << "m=" << m;
    EXPECT_EQ(none.samples_shaded, std::uint64_t(48 * 36));
    EXPECT_FALSE(same_pixels(ref, one));
  }
}

TEST(Deferred, HeavyModeChangesPixelsAndStillMatches) {
  Fixture f;
  f.shading.heavy = true;
  f.shading.heavy_terms = 16;
  const GBuffer gb = f.gbuffer(40, 30, 2);
  const ImageRGBAF ref = f.renderer->shade_reference(gb, f.shading);
  AdaptiveThresholds a;
  a.force_k = 3;
  EXPECT_TRUE(same_pixels(f.renderer->shade_adaptive(gb, f.shading, a).image, ref));
  ShadingOptions light = f.shading;
  light.heavy = false;
  EXPECT_FALSE(same_pixels(f.renderer->shade_reference(gb, light), ref));
}

TEST(Deferred, AdaptiveIsBetweenDefaultAndReferenceAndThreadIndependent) {
  Fixture f;
  const int m = 4;
  const GBuffer gb = f.gbuffer(128, 96, m);
  const ImageRGBA8 ref = to_srgb8(f.renderer->shade_reference(gb, f.shading));
  const ImageRGBA8 one = to_srgb8(f.renderer->shade_default(gb, f.shading));
  const AdaptiveResult ad = f.renderer->shade_adaptive(gb, f.shading, {});
  const ImageRGBA8 img = to_srgb8(ad.image);
  metrics::CompareOptions co;
  co.compute_ssim = false;
  const double p_one = metrics::compare_images(ref, one, co)->psnr_rgb;
  const double p_ad = metrics::compare_images(ref, img, co)->psnr_rgb;
  EXPECT_GT(p_ad, p_one + 6.0);
  const double frac = double(ad.samples_shaded) / double(128 * 96 * m * m);
  EXPECT_GT(frac, 1.0 / 16.0);
  EXPECT_LT(frac, 0.9);
  for (std::uint8_t s : ad.samples) {
    EXPECT_GE(s, 1);
    EXPECT_LE(s, m * m);
  }
  ShadingOptions one_thread = f.shading;
  one_thread.threads = 1;
  EXPECT_TRUE(same_pixels(f.renderer->shade_adaptive(gb, one_thread, {}).image, ad.image));
  // Ablations: each metric alone shades fewer samples than both together.
  AdaptiveThresholds geo;
  geo.use_shading = false;
  AdaptiveThresholds shd;
  shd.use_geometry = false;
  EXPECT_LE(f.renderer->shade_adaptive(gb, f.shading, geo).samples_shaded, ad.samples_shaded);
  EXPECT_LE(f.renderer->shade_adaptive(gb, f.shading, shd).samples_shaded, ad.samples_shaded);
}

TEST(Deferred, ReferenceDefaultAndFxaaAreThreadIndependent) {
  Fixture f;
  const GBuffer gb = f.gbuffer(72, 40, 3);
  ShadingOptions one = f.shading, many = f.shading;
  one.threads = 1;
  many.threads = 3;
  EXPECT_TRUE(
      same_pixels(f.renderer->shade_reference(gb, one), f.renderer->shade_reference(gb, many)));
  const ImageRGBAF a = f.renderer->shade_default(gb, one);
  EXPECT_TRUE(same_pixels(a, f.renderer->shade_default(gb, many)));
  FxaaOptions fo1, fo3;
  fo1.threads = 1;
  fo3.threads = 3;
  EXPECT_EQ(fxaa(to_srgb8(a), fo1)->pixels, fxaa(to_srgb8(a), fo3)->pixels);
}

TEST(Deferred, RejectsBadWindow) {
  Fixture f;
  GBuffer gb;
  EXPECT_EQ(f.renderer->render_gbuffer(f.camera, 16, 16, 0, gb).code, ErrorCode::invalid_argument);
  EXPECT_EQ(f.renderer->render_gbuffer(f.camera, 16, 16, 9, gb).code, ErrorCode::invalid_argument);
}

// --- FXAA -------------------------------------------------------------------------------------

TEST(Fxaa, FlatImageUnchanged) {
  ImageRGBA8 img(32, 24);
  for (std::size_t i = 0; i < img.pixel_count(); ++i) {
    img.pixels[i * 4] = 120;
    img.pixels[i * 4 + 1] = 80;
    img.pixels[i * 4 + 2] = 200;
    img.pixels[i * 4 + 3] = 255;
  }
  const Result<ImageRGBA8> out = fxaa(img);
  ASSERT_TRUE(out.ok());
  EXPECT_EQ(out->pixels, img.pixels);
}

TEST(Fxaa, SoftensAHardEdge) {
  // A slanted black/white edge (slope 1/5) at one sample per pixel, and its exact coverage.
  const int w = 64, h = 48;
  ImageRGBA8 hard(w, h), exact(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      auto inside = [](double px, double py) { return py > 0.2 * px + 10.0; };
      const std::uint8_t v = inside(x + 0.5, y + 0.5) ? 255 : 0;
      int cover = 0;
      for (int j = 0; j < 16; ++j) {
        for (int i = 0; i < 16; ++i) cover += inside(x + (i + 0.5) / 16, y + (j + 0.5) / 16);
      }
      const std::uint8_t e = linear_to_srgb8(float(cover) / 256.0f);
      for (int c = 0; c < 3; ++c) {
        hard.at(x, y)[c] = v;
        exact.at(x, y)[c] = e;
      }
      hard.at(x, y)[3] = exact.at(x, y)[3] = 255;
    }
  }
  const Result<ImageRGBA8> out = fxaa(hard);
  ASSERT_TRUE(out.ok());
  int intermediate = 0;
  for (std::size_t i = 0; i < out->pixel_count(); ++i) {
    intermediate += out->pixels[i * 4] > 8 && out->pixels[i * 4] < 247;
  }
  EXPECT_GT(intermediate, w / 2);
  metrics::CompareOptions co;
  co.compute_ssim = false;
  EXPECT_LT(metrics::compare_images(exact, *out, co)->mse_rgb,
            0.7 * metrics::compare_images(exact, hard, co)->mse_rgb);
  // Far from the edge nothing changes.
  EXPECT_EQ(out->at(5, 40)[0], 255);
  EXPECT_EQ(out->at(60, 2)[0], 0);
  FxaaOptions bad;
  bad.preset = 17;
  EXPECT_FALSE(fxaa(hard, bad).ok());
  EXPECT_FALSE(valid_fxaa_preset(30));
  EXPECT_TRUE(valid_fxaa_preset(12));
}

}  // namespace
}  // namespace tessera::deferred
