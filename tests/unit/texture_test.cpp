// Texture system: analytic LOD and anisotropy, tap weights, address modes, texture arrays,
// construction errors, concurrent sampling. Filtering exactness and mip chain content:
// texture_filtering_test.cpp.
#include "tessera/texture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <thread>
#include <vector>

#include "tessera/core.h"
#include "texture_test_util.h"

namespace tessera::texture {
namespace {

using namespace test;  // NOLINT(google-build-using-namespace): texture_test_util.h

// ---------------------------------------------------------------------------------------------
// LOD and anisotropy
// ---------------------------------------------------------------------------------------------

TEST(TextureLod, KnownQuadOnNonSquareTexture) {
  // 256x64 texture; a screen quad where one pixel step advances 4 texels in u and 4 in v.
  const TextureShape shape{256, 64, mip_level_count(256, 64), 1};
  ASSERT_EQ(shape.levels, 9);
  const float du = 4.0f / 256.0f;
  const float dv = 4.0f / 64.0f;
  const std::array<Uv, 4> quad = {Uv{0.25f, 0.5f}, Uv{0.25f + du, 0.5f}, Uv{0.25f, 0.5f + dv},
                                  Uv{0.25f + du, 0.5f + dv}};
  const UvGradients g = quad_gradients(quad);
  EXPECT_FLOAT_EQ(g.dudx, du);
  EXPECT_FLOAT_EQ(g.dvdx, 0.0f);
  EXPECT_FLOAT_EQ(g.dudy, 0.0f);
  EXPECT_FLOAT_EQ(g.dvdy, dv);
  SamplerState s;
  const Footprint fp = compute_footprint(s, shape, quad[0], g);
  EXPECT_NEAR(fp.lod, 2.0f, 1e-6f);
  EXPECT_EQ(fp.probes, 1);
  // Other footprints: 1 texel -> 0, 8 -> 3, 2 x 6 (isotropic takes the max) -> log2 6.
  EXPECT_NEAR(compute_footprint(s, shape, {}, texel_grad(shape, 1, 0, 0, 1)).lod, 0.0f, 1e-6f);
  EXPECT_NEAR(compute_footprint(s, shape, {}, texel_grad(shape, 8, 0, 0, 8)).lod, 3.0f, 1e-6f);
  EXPECT_NEAR(compute_footprint(s, shape, {}, texel_grad(shape, 2, 0, 0, 6)).lod, std::log2(6.0f),
              1e-5f);
  // Diagonal gradient: |(3, 4)| = 5.
  EXPECT_NEAR(isotropic_lod({3, 4, 0, 1}), std::log2(5.0f), 1e-6f);

  // The trilinear lookup at exactly lod 2 reads level 2 only (64x16).
  const Texture tex = make_texture(constant_image(256, 64, 0.5f, 0.5f, 0.5f, 1.0f));
  TapList taps;
  tex.taps(s, quad[0], g, 0, taps);
  ASSERT_EQ(taps.count, 4);
  for (const TexelTap& t : taps) EXPECT_EQ(t.level, 2);
}

TEST(TextureLod, BiasAndClamps) {
  const TextureShape shape{64, 64, 7, 1};
  SamplerState s;
  const UvGradients g = texel_grad(shape, 4, 0, 0, 4);  // lod 2
  s.lod_bias = 1.5f;
  EXPECT_NEAR(compute_footprint(s, shape, {}, g).lod, 3.5f, 1e-6f);
  s.lod_bias = 0.0f;
  s.max_lod = 1.25f;
  EXPECT_NEAR(compute_footprint(s, shape, {}, g).lod, 1.25f, 1e-6f);
  s.max_lod = 1000.0f;
  s.min_lod = 2.5f;
  EXPECT_NEAR(compute_footprint(s, shape, {}, g).lod, 2.5f, 1e-6f);
  s.min_lod = -1000.0f;
  // Magnification clamps to 0, huge footprints to the last level; zero and NaN gradients give
  // a finite LOD.
  EXPECT_EQ(compute_footprint(s, shape, {}, texel_grad(shape, 0.1f, 0, 0, 0.1f)).lod, 0.0f);
  EXPECT_EQ(compute_footprint(s, shape, {}, texel_grad(shape, 1e6f, 0, 0, 1e6f)).lod, 6.0f);
  EXPECT_EQ(compute_footprint(s, shape, {}, {}).lod, 0.0f);
  const float nan = std::nanf("");
  EXPECT_EQ(compute_footprint(s, shape, {}, {nan, nan, nan, nan}).lod, 0.0f);
  EXPECT_EQ(footprint_at_lod(s, shape, {}, 2.75f).lod, 2.75f);
  EXPECT_EQ(footprint_at_lod(s, shape, {}, -3.0f).lod, 0.0f);
}

TEST(TextureAniso, ProbeCountAndLod) {
  // 8:1 footprint along x -> 8 probes, lod log2(8 / 8) = 0.
  AnisoFootprint a = anisotropic_footprint({8, 0, 0, 1}, 16);
  EXPECT_EQ(a.probes, 8);
  EXPECT_NEAR(a.lod, 0.0f, 1e-6f);
  EXPECT_EQ(a.axis_x, 8.0f);
  EXPECT_EQ(a.axis_y, 0.0f);
  // 32:1 clamps to 16 probes, lod log2(32 / 16) = 1.
  a = anisotropic_footprint({32, 0, 0, 1}, 16);
  EXPECT_EQ(a.probes, 16);
  EXPECT_NEAR(a.lod, 1.0f, 1e-6f);
  // Major axis along y, rotated: |d/dy| = 20 * sqrt(2), |d/dx| = 4 * sqrt(2) -> ratio 5.
  a = anisotropic_footprint({4, -4, 20, 20}, 16);
  EXPECT_EQ(a.probes, 5);
  EXPECT_NEAR(a.lod, std::log2(20.0f * std::sqrt(2.0f) / 5.0f), 1e-5f);
  EXPECT_EQ(a.axis_x, 20.0f);
  EXPECT_EQ(a.axis_y, 20.0f);
  // Non-integer ratio rounds up; max_aniso limits; isotropic footprints take one probe.
  EXPECT_EQ(anisotropic_footprint({5.5f, 0, 0, 2}, 16).probes, 3);
  EXPECT_EQ(anisotropic_footprint({8, 0, 0, 1}, 4).probes, 4);
  EXPECT_NEAR(anisotropic_footprint({8, 0, 0, 1}, 4).lod, 1.0f, 1e-6f);
  EXPECT_EQ(anisotropic_footprint({3, 0, 0, 3}, 16).probes, 1);
  EXPECT_EQ(anisotropic_footprint({8, 0, 0, 1}, 99).probes, 8);   // clamped to 16, ratio 8
  EXPECT_EQ(anisotropic_footprint({8, 0, 0, 0}, 16).probes, 16);  // degenerate minor axis
  EXPECT_EQ(anisotropic_footprint({0, 0, 0, 0}, 16).probes, 1);
}

TEST(TextureAniso, ProbesSpreadAlongMajorAxisWithEqualWeights) {
  const Texture tex = make_texture(random_image(128, 128, 3));
  SamplerState s;
  s.filter = TextureFilter::anisotropic;
  s.address_u = s.address_v = AddressMode::clamp;
  // 8:1 along x at lod 1: 16 texels along x, 2 along y -> 8 probes at lod log2(16/8) = 1.
  const UvGradients g = texel_grad(tex.shape(), 16, 0, 0, 2);
  const Footprint fp = compute_footprint(s, tex.shape(), {0.5f, 0.5f}, g);
  EXPECT_EQ(fp.probes, 8);
  EXPECT_NEAR(fp.lod, 1.0f, 1e-6f);
  TapList taps;
  tex.taps(s, {0.5f, 0.5f}, g, 0, taps);
  ASSERT_EQ(taps.count, 8 * 4);  // integer lod: one level, 8 bilinear quads
  EXPECT_NEAR(taps.weight_sum(), 1.0f, 1e-5f);
  for (int p = 0; p < 8; ++p) {
    float probe_weight = 0.0f;
    for (int k = 0; k < 4; ++k) probe_weight += taps.taps[std::size_t(p * 4 + k)].weight;
    EXPECT_NEAR(probe_weight, 1.0f / 8.0f, 1e-6f);
    // Level 1 is 64 wide; probes at 32 + ((p + 0.5) / 8 - 0.5) * 8 texels of level 1, i.e.
    // texel centres 28.5 .. 35.5 -> bilinear quads start at columns 28 .. 35.
    EXPECT_EQ(taps.taps[std::size_t(p * 4)].x, 28 + p);
    EXPECT_EQ(taps.taps[std::size_t(p * 4)].y, 31);
  }
}

TEST(TextureTaps, WeightsSumToOneForEveryFilterAndRandomFootprints) {
  const Texture tex = make_texture(random_image(96, 40, 5));
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> coord(-2.0f, 3.0f);
  std::uniform_real_distribution<float> grad(-0.3f, 0.3f);
  TapList taps;
  for (TextureFilter filter : kAllFilters) {
    for (AddressMode mode : kAllModes) {
      SamplerState s;
      s.filter = filter;
      s.address_u = mode;
      s.address_v = mode;
      for (int i = 0; i < 300; ++i) {
        const Uv uv{coord(rng), coord(rng)};
        const float scale = std::exp2(float(i % 12) - 8.0f);
        const UvGradients g{grad(rng) * scale, grad(rng) * scale, grad(rng) * scale,
                            grad(rng) * scale};
        tex.taps(s, uv, g, 0, taps);
        ASSERT_GT(taps.count, 0);
        ASSERT_LE(taps.count, kMaxTexelTaps);
        EXPECT_NEAR(taps.weight_sum(), 1.0f, 2e-5f);
        for (const TexelTap& t : taps) {
          EXPECT_GE(t.weight, 0.0f);
          EXPECT_GE(t.level, 0);
          EXPECT_LT(t.level, tex.level_count());
          const int w = tex.shape().level_width(t.level);
          const int h = tex.shape().level_height(t.level);
          EXPECT_EQ(t.resolved_x, resolve_address(t.x, w, mode));
          EXPECT_EQ(t.resolved_y, resolve_address(t.y, h, mode));
          EXPECT_EQ(t.outside, t.x < 0 || t.x >= w || t.y < 0 || t.y >= h);
        }
        // The sampling driver agrees bit for bit with resolving the tap list.
        const auto a = tex.sample(s, uv, g);
        const auto b = tex.resolve(s, taps);
        for (int c = 0; c < 4; ++c) EXPECT_EQ(a[std::size_t(c)], b[std::size_t(c)]);
      }
    }
  }
}

TEST(TextureTaps, CountsPerFilter) {
  const Texture tex = make_texture(random_image(64, 64, 9));
  TapList taps;
  SamplerState s;
  const UvGradients g = texel_grad(tex.shape(), 3, 0, 0, 3);  // lod log2 3: fractional
  s.filter = TextureFilter::nearest;
  tex.taps(s, {0.3f, 0.6f}, g, 0, taps);
  EXPECT_EQ(taps.count, 1);
  EXPECT_EQ(taps.taps[0].level, 2);  // round(1.585) = 2
  s.filter = TextureFilter::bilinear;
  tex.taps(s, {0.3f, 0.6f}, g, 0, taps);
  EXPECT_EQ(taps.count, 4);
  s.filter = TextureFilter::trilinear;
  tex.taps(s, {0.3f, 0.6f}, g, 0, taps);
  EXPECT_EQ(taps.count, 8);
  s.filter = TextureFilter::anisotropic;
  tex.taps(s, {0.3f, 0.6f}, texel_grad(tex.shape(), 48, 0, 0, 1.5f), 0, taps);
  EXPECT_EQ(taps.count, kMaxTexelTaps);  // 32:1 -> 16 probes, lod log2 3 -> two levels
  EXPECT_NEAR(taps.weight_sum(), 1.0f, 1e-5f);
}

// ---------------------------------------------------------------------------------------------
// Address modes
// ---------------------------------------------------------------------------------------------

TEST(TextureAddress, ResolveAtTheEdges) {
  const int n = 5;
  // wrap: period n, negatives included.
  EXPECT_EQ(resolve_address(-1, n, AddressMode::wrap), 4);
  EXPECT_EQ(resolve_address(5, n, AddressMode::wrap), 0);
  EXPECT_EQ(resolve_address(-6, n, AddressMode::wrap), 4);
  EXPECT_EQ(resolve_address(-5, n, AddressMode::wrap), 0);
  EXPECT_EQ(resolve_address(12, n, AddressMode::wrap), 2);
  // clamp to edge.
  EXPECT_EQ(resolve_address(-3, n, AddressMode::clamp), 0);
  EXPECT_EQ(resolve_address(7, n, AddressMode::clamp), 4);
  EXPECT_EQ(resolve_address(2, n, AddressMode::clamp), 2);
  // mirror: period 2n; -1 -> 0, n -> n-1, 2n -> 0, 2n-1 -> 0, -n-1 -> n-1.
  const int expected_mirror[] = {0, 1, 2, 3, 4, 4, 3, 2, 1, 0};
  for (int x = -20; x < 20; ++x) {
    const int m = ((x % 10) + 10) % 10;
    EXPECT_EQ(resolve_address(x, n, AddressMode::mirror), expected_mirror[m]) << x;
  }
  EXPECT_EQ(resolve_address(-1, n, AddressMode::mirror), 0);
  EXPECT_EQ(resolve_address(-6, n, AddressMode::mirror), 4);
  // border.
  EXPECT_EQ(resolve_address(-1, n, AddressMode::border), -1);
  EXPECT_EQ(resolve_address(5, n, AddressMode::border), -1);
  EXPECT_EQ(resolve_address(4, n, AddressMode::border), 4);
  // Extreme coordinates do not overflow.
  EXPECT_EQ(resolve_address(INT32_MIN, n, AddressMode::wrap), ((INT32_MIN % 5) + 5) % 5);
  EXPECT_GE(resolve_address(INT32_MIN, n, AddressMode::mirror), 0);
}

TEST(TextureAddress, SamplesAtTheEdges) {
  // 4x1 texture with red = column index.
  const Texture tex = make_texture(ramp_image(4, 1), {.max_levels = 1});
  SamplerState s;
  s.filter = TextureFilter::nearest;
  auto red_at = [&](AddressMode mode, float u) {
    s.address_u = mode;
    return tex.sample_lod(s, {u, 0.5f}, 0.0f)[0];
  };
  // Texel -1 (u in [-0.25, 0)) and texel 4 (u in [1, 1.25)).
  EXPECT_EQ(red_at(AddressMode::wrap, -0.1f), 3.0f);
  EXPECT_EQ(red_at(AddressMode::wrap, 1.1f), 0.0f);
  EXPECT_EQ(red_at(AddressMode::clamp, -0.1f), 0.0f);
  EXPECT_EQ(red_at(AddressMode::clamp, 1.1f), 3.0f);
  EXPECT_EQ(red_at(AddressMode::mirror, -0.1f), 0.0f);
  EXPECT_EQ(red_at(AddressMode::mirror, -0.3f), 1.0f);
  EXPECT_EQ(red_at(AddressMode::mirror, 1.1f), 3.0f);
  EXPECT_EQ(red_at(AddressMode::mirror, 1.6f), 1.0f);  // texel 6 -> 1
  EXPECT_EQ(red_at(AddressMode::mirror, 2.1f), 0.0f);  // texel 8 = one full period
  s.border_color = {0.25f, 0.5f, 0.75f, 1.0f};
  const auto b = (s.address_u = AddressMode::border, tex.sample_lod(s, {-0.1f, 0.5f}, 0.0f));
  EXPECT_EQ(b, s.border_color);

  // Bilinear at u = 0 blends texel -1 and texel 0 half and half.
  s.filter = TextureFilter::bilinear;
  s.address_u = AddressMode::wrap;
  EXPECT_NEAR(tex.sample_lod(s, {0.0f, 0.5f}, 0.0f)[0], 1.5f, 1e-6f);  // (3 + 0) / 2
  s.address_u = AddressMode::clamp;
  EXPECT_NEAR(tex.sample_lod(s, {0.0f, 0.5f}, 0.0f)[0], 0.0f, 1e-6f);
  s.address_u = AddressMode::mirror;
  EXPECT_NEAR(tex.sample_lod(s, {1.0f, 0.5f}, 0.0f)[0], 3.0f, 1e-6f);
  s.address_u = AddressMode::border;
  s.border_color = {10.0f, 0.0f, 0.0f, 0.0f};
  EXPECT_NEAR(tex.sample_lod(s, {0.0f, 0.5f}, 0.0f)[0], 5.0f, 1e-6f);  // (10 + 0) / 2

  // The tap list marks the outside taps (what Discard drops) and the border reads.
  TapList taps;
  tex.taps(s, {0.0f, 0.5f}, {}, 0, taps);
  ASSERT_EQ(taps.count, 4);
  int outside = 0;
  for (const TexelTap& t : taps) {
    if (t.x < 0) {
      EXPECT_TRUE(t.outside);
      EXPECT_TRUE(t.is_border());
      ++outside;
    }
  }
  EXPECT_EQ(outside, 2);
}

TEST(TextureTaps, DiscardByTapsEqualsBorderZeroNormalisation) {
  // Toth 2013: with alpha = 1 inside and a zero border colour, rgb / a of a border-mode lookup
  // equals dropping the outside taps and renormalising the remaining weights.
  ImageRGBAF img = random_image(16, 8, 21);
  for (std::size_t i = 0; i < img.pixel_count(); ++i) img.pixels[i * 4 + 3] = 1.0f;
  const Texture tex = make_texture(img);
  SamplerState s;
  s.filter = TextureFilter::anisotropic;
  s.address_u = s.address_v = AddressMode::border;
  TapList taps;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> coord(-0.1f, 1.1f);
  int partial = 0;
  for (int i = 0; i < 200; ++i) {
    const Uv uv{coord(rng), coord(rng)};
    const UvGradients g{0.05f, 0.01f, -0.004f, 0.02f};
    tex.taps(s, uv, g, 0, taps);
    float inside = 0.0f;
    double rgb[3] = {0, 0, 0};
    for (const TexelTap& t : taps) {
      if (t.outside) {
        EXPECT_TRUE(t.is_border());
        continue;
      }
      const auto c = tex.fetch(s, t);
      inside += t.weight;
      for (int k = 0; k < 3; ++k) rgb[k] += double(t.weight) * c[std::size_t(k)];
    }
    const auto bordered = tex.sample(s, uv, g);
    EXPECT_NEAR(bordered[3], inside, 1e-5f);
    if (inside < 1e-3f) continue;
    if (inside < 0.999f) ++partial;
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(bordered[std::size_t(k)] / bordered[3], rgb[k] / inside, 1e-4);
    }
  }
  EXPECT_GT(partial, 20);  // the test did exercise footprints that straddle the edge
}

TEST(TextureAddress, HugeAndNonFiniteCoordinatesAreSafe) {
  const Texture tex = make_texture(random_image(7, 5, 1));
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::nanf("");
  for (TextureFilter filter : kAllFilters) {
    for (AddressMode mode : kAllModes) {
      SamplerState s;
      s.filter = filter;
      s.address_u = s.address_v = mode;
      for (float c : {inf, -inf, nan, 1e30f, -1e30f, 3e9f}) {
        const auto a = tex.sample(s, {c, 0.5f}, {0.01f, 0.0f, 0.0f, 0.5f});
        const auto b = tex.sample(s, {0.5f, c}, {c, c, c, c});
        for (int i = 0; i < 4; ++i) {
          EXPECT_TRUE(std::isfinite(a[std::size_t(i)]));
          EXPECT_TRUE(std::isfinite(b[std::size_t(i)]));
        }
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Arrays, construction errors, concurrency
// ---------------------------------------------------------------------------------------------

TEST(TextureArray, LayerSelectionAndClamping) {
  std::vector<ImageRGBAF> layers;
  for (int i = 0; i < 3; ++i) layers.push_back(constant_image(6, 4, float(i), 0, 0, 1));
  Result<Texture> r = Texture::array_from_float(layers);
  ASSERT_TRUE(r.ok()) << r.status().message;
  const Texture& tex = *r;
  EXPECT_EQ(tex.layer_count(), 3);
  SamplerState s;
  const UvGradients g = texel_grad(tex.shape(), 2.5f, 0, 0, 2.5f);
  for (int layer = -2; layer < 6; ++layer) {
    const float expected = float(std::clamp(layer, 0, 2));
    EXPECT_NEAR(tex.sample(s, {0.4f, 0.4f}, g, layer)[0], expected, 1e-6f) << layer;
  }
  TapList taps;
  tex.taps(s, {0.4f, 0.4f}, g, 7, taps);
  for (const TexelTap& t : taps) EXPECT_EQ(t.layer, 2);
  // GL's layer coordinate rule.
  EXPECT_EQ(array_layer(1.4f, 3), 1);
  EXPECT_EQ(array_layer(1.5f, 3), 2);
  EXPECT_EQ(array_layer(-0.7f, 3), 0);
  EXPECT_EQ(array_layer(9.0f, 3), 2);
  EXPECT_EQ(array_layer(std::nanf(""), 3), 0);
}

TEST(TextureConstruction, Errors) {
  EXPECT_EQ(Texture::from_float(ImageRGBAF{}).status().code, ErrorCode::invalid_argument);
  EXPECT_EQ(Texture::array_from_float({}).status().code, ErrorCode::invalid_argument);
  EXPECT_EQ(Texture::array_from_float({ImageRGBAF(4, 4), ImageRGBAF(4, 5)}).status().code,
            ErrorCode::size_mismatch);
  EXPECT_EQ(Texture::from_float(ImageRGBAF(4, 4), {.max_levels = -1}).status().code,
            ErrorCode::invalid_argument);
  EXPECT_EQ(Texture::from_float_levels({ImageRGBAF(4, 4), ImageRGBAF(3, 2)}).status().code,
            ErrorCode::size_mismatch);
  EXPECT_EQ(Texture::from_float_levels({ImageRGBAF(2, 2), ImageRGBAF(1, 1), ImageRGBAF(1, 1)})
                .status()
                .code,
            ErrorCode::invalid_argument);
  // max_levels limits the chain; an empty texture samples the border colour.
  Result<Texture> two = Texture::from_float(ImageRGBAF(16, 16), {.max_levels = 2});
  ASSERT_TRUE(two.ok());
  EXPECT_EQ(two->level_count(), 2);
  SamplerState s;
  s.border_color = {1, 2, 3, 4};
  EXPECT_EQ(Texture{}.sample_lod(s, {0.5f, 0.5f}, 0.0f), s.border_color);
}

TEST(TextureConcurrency, ConstSamplingFromManyThreads) {
  const Texture tex = make_texture(random_image(64, 64, 8));
  SamplerState s;
  s.filter = TextureFilter::anisotropic;
  auto run = [&](std::vector<float>& out) {
    for (int i = 0; i < 2000; ++i) {
      const float t = float(i) * 0.001f;
      out.push_back(tex.sample(s, {t, 1.0f - t}, {0.05f, 0.01f, -0.002f, 0.004f})[0]);
    }
  };
  std::vector<float> serial;
  run(serial);
  std::vector<std::vector<float>> results(4);
  std::vector<std::thread> threads;
  for (auto& r : results) threads.emplace_back([&run, &r] { run(r); });
  for (auto& t : threads) t.join();
  for (const auto& r : results) EXPECT_EQ(r, serial);
}

}  // namespace
}  // namespace tessera::texture
