// The CPU engine baseline (deferred::classify_edge_per_sample / shade_edge_per_sample):
// synthetic G-buffers with known answers, and the renderer's images on the built-in scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tessera/deferred.h"
#include "tessera/scene.h"

namespace tessera {
namespace {

namespace d = deferred;

// A w x h output, window m, camera at the origin looking down -z (inv_view = identity), every
// grid pixel on the plane z = -depth_at(gx, gy) with normal (0, 0, 1).
d::GBuffer flat_gbuffer(int w, int h, int m, float depth) {
  d::GBuffer gb;
  raster::FrameBufferDesc desc;
  desc.width = w;
  desc.height = h;
  desc.ssaa = m;
  desc.channels = d::kGBufferChannels;
  Result<raster::FrameBuffer> fb = raster::FrameBuffer::create(desc);
  EXPECT_TRUE(fb.ok());
  gb.fb = std::move(*fb);
  gb.m = m;
  gb.tan_half_fov_y = 0.5f;
  gb.aspect = float(w) / float(h);
  for (int y = 0; y < h * m; ++y) {
    for (int x = 0; x < w * m; ++x) {
      float* s = gb.fb.data(x, y, 0);
      s[d::kChDepth] = depth;
      s[d::kChNormal + 2] = 1.0f;
      s[d::kChMaterial] = 0.0f;
    }
  }
  return gb;
}

TEST(EdgePerSample, FlatFacingPlaneIsSimple) {
  const d::GBuffer gb = flat_gbuffer(8, 6, 4, 5.0f);
  const std::vector<std::uint8_t> c = d::classify_edge_per_sample(gb);
  ASSERT_EQ(c.size(), 48u);
  EXPECT_EQ(std::count(c.begin(), c.end(), 1), 0);
}

TEST(EdgePerSample, TiltedPlaneWithinItsDerivativesIsSimple) {
  // A plane tilted about the y axis: depth changes linearly in x by exactly what its normal
  // predicts, so no pixel is complex although depths differ within every window.
  const int w = 8, h = 6, m = 2;
  d::GBuffer gb = flat_gbuffer(w, h, m, 5.0f);
  const float gw = float(w * m), t = gb.tan_half_fov_y, aspect = gb.aspect;
  // Plane through (0, 0, -5) with normal n = (sin a, 0, cos a): n . X = -5 cos a.
  const float a = 0.5f, nx = std::sin(a), nz = std::cos(a);
  for (int y = 0; y < h * m; ++y) {
    for (int x = 0; x < w * m; ++x) {
      const float px = (2.0f * (float(x) + 0.5f) / gw - 1.0f) * t * aspect;
      // Ray (px, py, -1) * d: nx * px * d - nz * d = -5 nz  =>  d = 5 nz / (nz - nx px).
      float* s = gb.fb.data(x, y, 0);
      s[d::kChDepth] = 5.0f * nz / (nz - nx * px);
      s[d::kChNormal] = nx;
      s[d::kChNormal + 2] = nz;
    }
  }
  const std::vector<std::uint8_t> c = d::classify_edge_per_sample(gb);
  EXPECT_EQ(std::count(c.begin(), c.end(), 1), 0);
  // With depth_slack 0 the same depths count as different (only the 1e-4 relative slack).
  d::EdgePerSampleOptions strict;
  strict.depth_slack = 0.0f;
  const std::vector<std::uint8_t> s = d::classify_edge_per_sample(gb, strict);
  EXPECT_EQ(std::count(s.begin(), s.end(), 1), std::ptrdiff_t(c.size()));
}

TEST(EdgePerSample, DepthStepNormalChangeAndBackgroundAreComplex) {
  const int w = 8, h = 6, m = 4;
  d::GBuffer gb = flat_gbuffer(w, h, m, 5.0f);
  // Pixel (1, 1): one sample further away (an occlusion edge).
  gb.fb.data(m * 1 + 3, m * 1 + 3, 0)[d::kChDepth] = 6.0f;
  // Pixel (3, 2): one sample's normal turned by ~11 degrees (dot 0.98 < 0.99).
  float* n = gb.fb.data(m * 3 + 1, m * 2 + 0, 0);
  n[d::kChNormal] = std::sqrt(1.0f - 0.98f * 0.98f);
  n[d::kChNormal + 2] = 0.98f;
  // Pixel (5, 4): one background sample.
  gb.fb.data(m * 5, m * 4, 0)[d::kChMaterial] = -1.0f;
  gb.fb.data(m * 5, m * 4, 0)[d::kChNormal + 2] = 0.0f;
  // Pixel (7, 5): all background -> simple.
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) gb.fb.data(m * 7 + i, m * 5 + j, 0)[d::kChMaterial] = -1.0f;
  const std::vector<std::uint8_t> c = d::classify_edge_per_sample(gb);
  EXPECT_EQ(c[1 * w + 1], 1);
  EXPECT_EQ(c[2 * w + 3], 1);
  EXPECT_EQ(c[4 * w + 5], 1);
  EXPECT_EQ(c[5 * w + 7], 0);
  EXPECT_EQ(std::count(c.begin(), c.end(), 1), 3);
  // A looser normal threshold accepts the 11-degree normal.
  d::EdgePerSampleOptions loose;
  loose.min_normal_dot = 0.97f;
  EXPECT_EQ(d::classify_edge_per_sample(gb, loose)[2 * w + 3], 0);
}

TEST(EdgePerSample, ImageIsDefaultOrReferencePerPixel) {
  const scene::Scene sc = scene::builtin_scene();
  const scene::Camera cam = scene::orbit_camera(sc, 1, 8);
  auto r = d::DeferredRenderer::create(sc);
  ASSERT_TRUE(r.ok());
  d::GBuffer gb;
  ASSERT_TRUE((*r)->render_gbuffer(cam, 48, 32, 3, gb).ok());
  const d::ShadingOptions so = d::scene_shading(sc, 4, &cam);
  const d::AdaptiveResult e = d::shade_edge_per_sample(**r, gb, so);
  const ImageRGBAF ref = (*r)->shade_reference(gb, so);
  const ImageRGBAF one = (*r)->shade_default(gb, so);
  const std::vector<std::uint8_t> c = d::classify_edge_per_sample(gb);
  std::size_t complex = 0;
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 48; ++x) {
      const std::size_t i = std::size_t(y) * 48 + std::size_t(x);
      const ImageRGBAF& want = c[i] ? ref : one;
      for (int k = 0; k < 4; ++k) ASSERT_EQ(e.image.at(x, y)[k], want.at(x, y)[k]) << x << "," << y;
      EXPECT_EQ(e.samples[i], c[i] ? 9 : 1);
      complex += c[i];
    }
  }
  EXPECT_GT(complex, 0u);         // the scene has edges
  EXPECT_LT(complex, 48u * 32u);  // and flat regions
  EXPECT_EQ(e.samples_shaded, 48u * 32u + complex * 8u);
}

}  // namespace
}  // namespace tessera
