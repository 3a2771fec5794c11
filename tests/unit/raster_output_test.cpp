// Rasteriser output tests: determinism across thread counts, quad shaders, supersampling
// equivalence, resolve, culling, argument errors and many-channel G-buffers.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "raster_test_support.h"
#include "tessera/raster.h"

namespace tessera::raster {
namespace {

using namespace tessera::raster::test_util;

Mesh random_scene(int count, int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> px(-0.2 * w, 1.2 * w), py(-0.2 * h, 1.2 * h);
  std::uniform_real_distribution<double> sz(1.0, 40.0), zz(-0.2, 1.0), ww(0.3, 2.0);
  Mesh m(3);
  for (int i = 0; i < count; ++i) {
    const double cx = px(rng), cy = py(rng), s = sz(rng);
    std::uint32_t id[3];
    for (int k = 0; k < 3; ++k) {
      const double x = cx + s * (ww(rng) - 1.0), y = cy + s * (ww(rng) - 1.0);
      id[k] =
          m.add(x, y, w, h, zz(rng), ww(rng), {float(x / w), float(y / h), float(i % 7) / 7.0f});
    }
    m.tri(id[0], id[1], id[2]);
  }
  return m;
}

void shade_rgb(const ShadeInput& in, float* out) {
  out[0] = in.varyings[0] + 4.0f * in.ddx[0];
  out[1] = in.varyings[1] + 4.0f * in.ddy[1];
  out[2] = in.varyings[2];
  out[3] = 1.0f;
}

TEST(RasterDeterminism, IdenticalForAnyThreadCount) {
  constexpr int kW = 300, kH = 200;
  const Mesh m = random_scene(3000, kW, kH, 99);
  DrawCall d = m.draw(shade_rgb);
  for (int n : {1, 4}) {
    std::vector<FrameBuffer> fbs;
    std::vector<RasterStats> stats;
    for (int threads : {1, 2, 0}) {
      FrameBuffer fb = make_fb(kW, kH, n, 1, 4, true);
      Rasteriser r({.threads = threads});
      stats.push_back(render_ok(r, fb, d));
      fbs.push_back(std::move(fb));
    }
    for (std::size_t i = 1; i < fbs.size(); ++i) {
      ASSERT_EQ(
          0, std::memcmp(fbs[0].data().data(), fbs[i].data().data(), fbs[0].data().size_bytes()));
      ASSERT_EQ(0, std::memcmp(fbs[0].depth_data().data(), fbs[i].depth_data().data(),
                               fbs[0].depth_data().size_bytes()));
      ASSERT_EQ(0, std::memcmp(fbs[0].primitive_id_data().data(), fbs[i].primitive_id_data().data(),
                               fbs[0].primitive_id_data().size_bytes()));
      EXPECT_EQ(stats[0].samples_written, stats[i].samples_written);
      EXPECT_EQ(stats[0].quads, stats[i].quads);
    }
    EXPECT_GT(stats[0].triangles_clipped, 0u);
    EXPECT_GT(stats[0].samples_written, std::uint64_t(kW * kH));
  }
}

// A QuadShadeFn sees exactly what the per-pixel ShadeFn sees (centroid included) and produces
// the same frame buffer, at every MSAA rate (the 1x, 2x and 4x/8x/16x coverage paths differ).
TEST(RasterShading, QuadShaderMatchesPixelShader) {
  constexpr int kW = 157, kH = 93;  // odd sizes: quads on the last row/column are partial
  const Mesh m = random_scene(1500, kW, kH, 7);
  for (int n : {1, 2, 4, 8, 16}) {
    for (bool centroid : {false, true}) {
      DrawCall pixel = m.draw(shade_rgb);
      pixel.centroid = centroid;
      DrawCall quad = m.draw();
      quad.centroid = centroid;
      quad.quad_shader = [](const ShadeInput* lanes, std::uint32_t active, float* out) {
        for (int lane = 0; lane < 4; ++lane) {
          if (!(active >> lane & 1u)) continue;
          EXPECT_EQ(lanes[lane].lane, lane);
          shade_rgb(lanes[lane], out + lane * kMaxChannels);
        }
      };
      FrameBuffer a = make_fb(kW, kH, n, 1, 4, true);
      FrameBuffer b = make_fb(kW, kH, n, 1, 4, true);
      Rasteriser r({.threads = 2});
      const RasterStats sa = render_ok(r, a, pixel);
      const RasterStats sb = render_ok(r, b, quad);
      ASSERT_EQ(0, std::memcmp(a.data().data(), b.data().data(), a.data().size_bytes()))
          << n << "x, centroid " << centroid;
      ASSERT_EQ(0, std::memcmp(a.depth_data().data(), b.depth_data().data(),
                               a.depth_data().size_bytes()));
      EXPECT_EQ(sa.lanes_shaded, sb.lanes_shaded);
      EXPECT_EQ(sa.samples_written, sb.samples_written);
      EXPECT_GT(sa.samples_written, 0u);
    }
  }
}

// Supersampling m x m at w x h is exactly a (m w) x (m h) render, box-downsampled.
TEST(RasterSupersampling, EqualsLargeRenderBoxDownsampled) {
  constexpr int kW = 70, kH = 50;
  const Mesh m = random_scene(400, kW, kH, 5);
  DrawCall d = m.draw(shade_rgb);
  Rasteriser r({.threads = 0});
  for (int msaa : {1, 4}) {
    FrameBuffer ss = make_fb(kW, kH, msaa, 2);
    FrameBuffer big = make_fb(2 * kW, 2 * kH, msaa, 1);
    render_ok(r, ss, d);
    render_ok(r, big, d);
    ASSERT_EQ(0, std::memcmp(ss.data().data(), big.data().data(), ss.data().size_bytes()));
    const ImageRGBAF a = resolve(ss);
    for (int y = 0; y < kH; ++y) {
      for (int x = 0; x < kW; ++x) {
        for (int c = 0; c < 4; ++c) {
          float sum = 0.0f;
          for (int j = 0; j < 2; ++j) {
            for (int i = 0; i < 2; ++i) {
              for (int s = 0; s < msaa; ++s) sum += big.data(2 * x + i, 2 * y + j, s)[c];
            }
          }
          ASSERT_NEAR(a.at(x, y)[c], sum / float(4 * msaa), 1e-6f);
        }
      }
    }
  }
}

TEST(RasterResolve, BoxFilterAndSrgb) {
  constexpr int kSize = 8;
  Mesh m(0);
  // Covers the left half of the screen exactly (x < 4).
  const auto a = m.add(-4, -4, kSize, kSize), b = m.add(4, -4, kSize, kSize);
  const auto c = m.add(4, 12, kSize, kSize), e = m.add(-4, 12, kSize, kSize);
  m.tri(a, b, c);
  m.tri(a, c, e);
  DrawCall d = m.draw([](const ShadeInput&, float* out) {
    out[0] = 1.0f;
    out[1] = 0.5f;
    out[2] = 0.25f;
    out[3] = 1.0f;
  });
  FrameBuffer fb = make_fb(kSize, kSize, 4);
  Rasteriser r({.threads = 1});
  render_ok(r, fb, d);
  const ImageRGBAF img = resolve(fb);
  EXPECT_FLOAT_EQ(img.at(1, 1)[0], 1.0f);
  EXPECT_FLOAT_EQ(img.at(1, 1)[1], 0.5f);
  EXPECT_FLOAT_EQ(img.at(6, 1)[0], 0.0f);
  const ImageRGBA8 s = resolve_srgb8(fb);
  EXPECT_EQ(s.at(1, 1)[0], 255);
  EXPECT_EQ(s.at(1, 1)[1], linear_to_srgb8(0.5f));
  // Fewer than four channels: alpha reads as 1.
  FrameBuffer one = make_fb(kSize, kSize, 1, 1, 1);
  render_ok(r, one, d);
  EXPECT_FLOAT_EQ(resolve(one).at(1, 1)[3], 1.0f);
}

// The fused sRGB resolve (table-driven encoder) equals to_srgb8(resolve(fb)) bit for bit,
// including values at and around every 8-bit threshold, out-of-range values and NaN.
TEST(RasterResolve, Srgb8MatchesExactEncoder) {
  FrameBuffer fb = make_fb(256, 64, 2);
  std::span<float> d = fb.data();
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-0.1f, 1.1f);
  std::size_t i = 0;
  // Exact thresholds: 2x MSAA averages two equal samples, so each pixel sees the value itself.
  for (int k = 0; k < 256 && i + 8 <= d.size(); ++k) {
    const float t = srgb_to_linear((float(k) + 0.5f) / 255.0f);
    for (float v : {t, std::nextafter(t, 0.0f), std::nextafter(t, 2.0f)}) {
      d[i] = d[i + 4] = v;
      i += 1;
    }
    i = (i + 7) / 8 * 8;
  }
  for (; i < d.size(); i += 8) {
    for (int c = 0; c < 4; ++c) d[i + c] = d[i + 4 + c] = u(rng);
  }
  d[0] = d[4] = NAN;
  const ImageRGBA8 fast = resolve_srgb8(fb);
  const ImageRGBA8 slow = to_srgb8(resolve(fb));
  ASSERT_EQ(fast.pixels.size(), slow.pixels.size());
  for (std::size_t k = 0; k < fast.pixels.size(); ++k) {
    ASSERT_EQ(int(fast.pixels[k]), int(slow.pixels[k])) << "byte " << k;
  }
}

TEST(RasterCulling, BackFacesAndFacingFlag) {
  constexpr int kSize = 16;
  Mesh m(0);
  // Counter-clockwise in NDC (y up) = clockwise on screen (y down): a, b, c below.
  const auto a = m.add(2, 14, kSize, kSize), b = m.add(14, 14, kSize, kSize);
  const auto c = m.add(8, 2, kSize, kSize);
  m.tri(a, b, c);  // CCW in NDC: front
  m.tri(a, c, b);  // back
  DrawCall d =
      m.draw([](const ShadeInput& in, float* out) { out[0] = in.front_facing ? 1.0f : 2.0f; });
  Rasteriser r({.threads = 1});
  const std::pair<CullMode, float> cases[] = {{CullMode::back, 1.0f}, {CullMode::front, 2.0f}};
  for (const auto& [cull, expect] : cases) {
    d.cull = cull;
    FrameBuffer fb = make_fb(kSize, kSize, 1, 1, 1);
    const RasterStats st = render_ok(r, fb, d);
    EXPECT_EQ(st.triangles_culled, 1u);
    EXPECT_EQ(fb.data(8, 10, 0)[0], expect);
  }
}

TEST(RasterErrors, InvalidArguments) {
  FrameBufferDesc desc;
  desc.width = 16;
  desc.height = 16;
  desc.msaa = 3;
  EXPECT_EQ(FrameBuffer::create(desc).status().code, ErrorCode::invalid_argument);
  desc.msaa = 4;
  desc.channels = 17;
  EXPECT_EQ(FrameBuffer::create(desc).status().code, ErrorCode::invalid_argument);
  desc.channels = 4;
  desc.ssaa = 9;
  EXPECT_EQ(FrameBuffer::create(desc).status().code, ErrorCode::invalid_argument);
  desc.ssaa = 8;
  desc.width = 20000;
  EXPECT_FALSE(FrameBuffer::create(desc).ok());
  desc.width = 0;
  EXPECT_FALSE(FrameBuffer::create(desc).ok());

  FrameBuffer fb = make_fb(16, 16);
  Mesh m(0);
  m.add(1, 1, 16, 16);
  m.add(9, 1, 16, 16);
  m.add(1, 9, 16, 16);
  m.tri(0, 1, 3);  // index 3 is out of range
  Rasteriser r;
  auto res = r.render(fb, m.draw());
  EXPECT_EQ(res.status().code, ErrorCode::invalid_argument);
  DrawCall d = m.draw();
  d.varying_count = 17;
  EXPECT_EQ(r.render(fb, d).status().code, ErrorCode::invalid_argument);
  d.varying_count = 0;
  d.index_count = 2;
  EXPECT_EQ(r.render(fb, d).status().code, ErrorCode::invalid_argument);
}

// A G-buffer: many channels per sample, written per sample; NaN/degenerate input is dropped.
TEST(RasterGBuffer, ManyChannelsAndDegenerateInput) {
  constexpr int kSize = 16;
  Mesh m(0);
  const auto a = m.add(0, 0, kSize, kSize), b = m.add(16, 0, kSize, kSize);
  const auto c = m.add(0, 16, kSize, kSize);
  m.tri(a, b, c);
  m.tri(a, a, b);  // degenerate
  m.pos.insert(m.pos.end(), {NAN, 0, 0, 1, 1, 0, 0, 1, 0, 1, 0, 1});
  m.tri(3, 4, 5);  // NaN
  DrawCall d = m.draw([](const ShadeInput& in, float* out) {
    for (int k = 0; k < 12; ++k) out[k] = float(k) + in.depth;
  });
  FrameBuffer fb = make_fb(kSize, kSize, 2, 1, 12);
  Rasteriser r({.threads = 1});
  const RasterStats st = render_ok(r, fb, d);
  EXPECT_EQ(st.triangles_in, 3u);
  EXPECT_EQ(st.triangles_culled, 2u);
  for (int k = 0; k < 12; ++k) EXPECT_FLOAT_EQ(fb.data(2, 2, 1)[k], float(k) + 0.5f);
}

}  // namespace
}  // namespace tessera::raster
