// Texture system: bilinear/trilinear/anisotropic exactness, sample4 against per-lane sample,
// NPOT box mip chains, gamma-correct and alpha-weighted chains. (LOD, taps, address modes,
// arrays: texture_test.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <utility>
#include <vector>

#include "tessera/core.h"
#include "tessera/procedural.h"
#include "tessera/texture.h"
#include "texture_test_util.h"

namespace tessera::texture {
namespace {

using namespace test;  // NOLINT(google-build-using-namespace): texture_test_util.h

double channel_mean(const ImageRGBAF& img, int c) {
  double sum = 0;
  for (std::size_t i = 0; i < img.pixel_count(); ++i) sum += img.pixels[i * 4 + std::size_t(c)];
  return sum / double(img.pixel_count());
}

// ---------------------------------------------------------------------------------------------
// Filtering exactness
// ---------------------------------------------------------------------------------------------

TEST(TextureFiltering, BilinearReproducesLinearRamp) {
  const Texture tex = make_texture(ramp_image(16, 8), {.max_levels = 1});
  SamplerState s;
  s.filter = TextureFilter::bilinear;
  s.address_u = s.address_v = AddressMode::clamp;
  for (float x = 0.0f; x <= 15.0f; x += 0.125f) {
    for (float y = 0.0f; y <= 7.0f; y += 0.25f) {
      // Texel-space position x (texel centres at integers) is u = (x + 0.5) / 16.
      const auto c = tex.sample_lod(s, {(x + 0.5f) / 16.0f, (y + 0.5f) / 8.0f}, 0.0f);
      EXPECT_NEAR(c[0], x, 1e-5f);
      EXPECT_NEAR(c[1], y, 1e-5f);
    }
  }
}

TEST(TextureFiltering, TrilinearBlendsLevelsByFractionalLod) {
  // Hand-made chain: level 0 all 0, level 1 all 1, level 2 all 2.
  std::vector<ImageRGBAF> levels = {constant_image(8, 4, 0, 0, 0, 1),
                                    constant_image(4, 2, 1, 1, 1, 1),
                                    constant_image(2, 1, 2, 2, 2, 1)};
  Result<Texture> r = Texture::from_float_levels(levels);
  ASSERT_TRUE(r.ok()) << r.status().message;
  const Texture& tex = *r;
  SamplerState s;
  for (float lod : {0.0f, 0.3f, 0.5f, 1.0f, 1.25f, 1.9f, 2.0f, 5.0f}) {
    const float expected = lod > 2.0f ? 2.0f : lod;
    EXPECT_NEAR(tex.sample_lod(s, {0.37f, 0.61f}, lod)[0], expected, 1e-6f) << lod;
  }
  // Through gradients: footprint 2^1.25 texels.
  const float f = std::exp2(1.25f);
  EXPECT_NEAR(tex.sample(s, {0.5f, 0.5f}, texel_grad(tex.shape(), f, 0, 0, f))[0], 1.25f, 1e-5f);
  // Nearest-level filters round: lod 0.5 -> level 0, 0.6 -> level 1, 1.5 -> 1, 1.6 -> 2.
  s.filter = TextureFilter::bilinear;
  EXPECT_EQ(tex.sample_lod(s, {0.5f, 0.5f}, 0.5f)[0], 0.0f);
  EXPECT_EQ(tex.sample_lod(s, {0.5f, 0.5f}, 0.6f)[0], 1.0f);
  EXPECT_EQ(tex.sample_lod(s, {0.5f, 0.5f}, 1.5f)[0], 1.0f);
  EXPECT_EQ(tex.sample_lod(s, {0.5f, 0.5f}, 1.6f)[0], 2.0f);
  // max_lod = 0 disables mipmapping.
  s.filter = TextureFilter::trilinear;
  s.max_lod = 0.0f;
  EXPECT_EQ(tex.sample_lod(s, {0.5f, 0.5f}, 1.6f)[0], 0.0f);
}

TEST(TextureFiltering, AnisotropicOfRampAlongMajorAxisIsCentreValue) {
  // The probes are symmetric about the centre, so on a linear ramp the average is exact.
  const Texture tex = make_texture(ramp_image(64, 64), {.max_levels = 1});
  SamplerState s;
  s.filter = TextureFilter::anisotropic;
  s.address_u = s.address_v = AddressMode::clamp;
  const auto c = tex.sample(s, {0.5f, 0.5f}, texel_grad(tex.shape(), 8, 4, 0.5f, -1));
  EXPECT_NEAR(c[0], 31.5f, 1e-4f);
  EXPECT_NEAR(c[1], 31.5f, 1e-4f);
}

TEST(TextureFiltering, SampleQuadUsesSharedCoarseGradients) {
  const Texture tex = make_texture(random_image(32, 32, 4));
  SamplerState s;
  const std::array<Uv, 4> quad = {Uv{0.1f, 0.2f}, Uv{0.16f, 0.21f}, Uv{0.12f, 0.27f},
                                  Uv{0.19f, 0.3f}};
  const auto out = tex.sample_quad(s, quad);
  const UvGradients g = quad_gradients(quad);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(out[i], tex.sample(s, quad[i], g));
}

TEST(TextureFiltering, Sample4IsBitIdenticalToPerLaneSample) {
  // Power-of-two (vector addressing for wrap), NPOT, non-square and one-level textures; every
  // filter (bilinear/trilinear take the four-lane path), address mode, LOD setting and lane mask.
  const Texture textures[] = {
      make_texture(random_image(64, 64, 21)), make_texture(random_image(37, 20, 22)),
      make_texture(random_image(128, 8, 23)),
      make_texture(random_image(16, 16, 24), TextureOptions{true, false, 1, 0})};
  std::mt19937 rng(31);
  std::uniform_real_distribution<float> coord(-3.0f, 4.0f);
  std::uniform_real_distribution<float> grad(-1.0f, 1.0f);
  std::uniform_int_distribution<int> special(0, 40);
  const float kSpecial[] = {0.0f, -0.0f, 1.0f, std::nanf(""), INFINITY, -INFINITY, 1e-30f, 1e30f};
  auto value = [&](float v) { return special(rng) == 0 ? kSpecial[rng() % 8] : v; };
  for (const Texture& tex : textures) {
    for (TextureFilter filter : kAllFilters) {
      for (AddressMode mu : kAllModes) {
        for (AddressMode mv : {AddressMode::wrap, AddressMode::clamp, AddressMode::border}) {
          SamplerState s;
          s.filter = filter;
          s.address_u = mu;
          s.address_v = mv;
          s.border_color = {0.25f, 0.5f, 0.75f, 1.0f};
          for (int i = 0; i < 120; ++i) {
            s.lod_bias = i % 5 == 1 ? 0.7f : (i % 5 == 2 ? -1.3f : 0.0f);
            s.min_lod = i % 7 == 3 ? 1.5f : (i % 7 == 4 ? -0.0f : -1000.0f);
            s.max_lod = i % 11 == 5 ? 0.0f : (i % 11 == 6 ? 2.25f : 1000.0f);
            std::array<Uv, 4> uv;
            std::array<UvGradients, 4> g;
            const float scale = std::exp2(float(i % 14) - 9.0f);
            for (std::size_t lane = 0; lane < 4; ++lane) {
              uv[lane] = {value(coord(rng)), value(coord(rng))};
              g[lane] = {value(grad(rng) * scale), value(grad(rng) * scale),
                         value(grad(rng) * scale), value(grad(rng) * scale)};
            }
            const std::uint32_t active = i % 16 == 0 ? 15u : std::uint32_t(i % 16);
            std::array<std::array<float, 4>, 4> out;
            const std::array<float, 4> untouched = {-7.0f, -7.0f, -7.0f, -7.0f};
            out.fill(untouched);
            tex.sample4(s, uv, g, active, out, i % 3);
            for (std::size_t lane = 0; lane < 4; ++lane) {
              if (!(active >> lane & 1u)) {
                EXPECT_EQ(out[lane], untouched);
                continue;
              }
              const auto want = tex.sample(s, uv[lane], g[lane], i % 3);
              for (std::size_t c = 0; c < 4; ++c) {
                // Bitwise: also catches -0 vs +0 (NaN texels do not occur here).
                std::uint32_t a, b;
                std::memcpy(&a, &out[lane][c], 4);
                std::memcpy(&b, &want[c], 4);
                ASSERT_EQ(a, b) << "filter " << int(filter) << " modes " << int(mu) << int(mv)
                                << " i " << i << " lane " << lane << " c " << c;
              }
            }
          }
        }
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Mip chains
// ---------------------------------------------------------------------------------------------

TEST(TextureMips, ConstantTextureStaysConstantIncludingNpot) {
  for (auto [w, h] : {std::pair{5, 3}, std::pair{7, 7}, std::pair{6, 5}, std::pair{1, 9},
                      std::pair{64, 16}, std::pair{33, 1}}) {
    const Texture tex = make_texture(constant_image(w, h, 0.3f, 0.6f, 0.9f, 0.7f));
    ASSERT_EQ(tex.level_count(), mip_level_count(w, h));
    for (int l = 0; l < tex.level_count(); ++l) {
      const TextureLevelView v = tex.level(0, l);
      EXPECT_EQ(v.width, std::max(1, w >> l));
      EXPECT_EQ(v.height, std::max(1, h >> l));
      for (int i = 0; i < v.width * v.height * 4; i += 4) {
        EXPECT_NEAR(v.texels[i + 0], 0.3f, 1e-6f);
        EXPECT_NEAR(v.texels[i + 1], 0.6f, 1e-6f);
        EXPECT_NEAR(v.texels[i + 2], 0.9f, 1e-6f);
        EXPECT_NEAR(v.texels[i + 3], 0.7f, 1e-6f);
      }
    }
  }
  // The GL size rule: 5x3 -> 2x1 -> 1x1.
  const Texture t = make_texture(constant_image(5, 3, 1, 1, 1, 1));
  ASSERT_EQ(t.level_count(), 3);
  EXPECT_EQ(t.level(0, 1).width, 2);
  EXPECT_EQ(t.level(0, 1).height, 1);
  EXPECT_EQ(t.level(0, 2).width, 1);
  EXPECT_EQ(t.level(0, 2).height, 1);
}

TEST(TextureMips, BoxDownsamplePreservesTheMean) {
  for (auto [w, h] :
       {std::pair{5, 3}, std::pair{7, 9}, std::pair{3, 3}, std::pair{16, 6}, std::pair{11, 1}}) {
    const ImageRGBAF img = random_image(w, h, std::uint32_t(w * 100 + h));
    const ImageRGBAF half = downsample_box(img);
    for (int c = 0; c < 4; ++c) {
      EXPECT_NEAR(channel_mean(half, c), channel_mean(img, c), 1e-6) << w << "x" << h;
    }
  }
  // 3 -> 1 averages all three texels; 5 -> 2 weighs texel 2 half to each side.
  ImageRGBAF row(5, 1);
  for (int x = 0; x < 5; ++x) row.at(x, 0)[0] = float(x * x);  // 0 1 4 9 16
  const ImageRGBAF d = downsample_box(row);
  ASSERT_EQ(d.width, 2);
  EXPECT_NEAR(d.at(0, 0)[0], (0.0f + 1.0f + 0.5f * 4.0f) / 2.5f, 1e-6f);
  EXPECT_NEAR(d.at(1, 0)[0], (0.5f * 4.0f + 9.0f + 16.0f) / 2.5f, 1e-6f);
}

TEST(TextureMips, SrgbAwareChainDiffersFromNaive) {
  ImageRGBA8 checker(2, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) {
      std::uint8_t* p = checker.at(x, y);
      p[0] = p[1] = p[2] = (x + y) % 2 ? 255 : 0;
      p[3] = 255;
    }
  Result<Texture> correct = Texture::from_rgba8(checker, {.srgb = true});
  Result<Texture> naive = Texture::from_rgba8(checker, {.srgb = false});
  ASSERT_TRUE(correct.ok() && naive.ok());
  const float lin = correct->level(0, 1).texels[0];
  EXPECT_NEAR(lin, 0.5f, 1e-6f);
  EXPECT_EQ(linear_to_srgb8(lin), 188);
  // The naive chain averages the encoded values: 0.5 stored as-is, i.e. byte 128 (127.5).
  const float raw = naive->level(0, 1).texels[0];
  EXPECT_NEAR(raw, 0.5f, 1e-6f);
  EXPECT_EQ(int(std::lround(raw * 255.0f)), 128);
  EXPECT_NE(linear_to_srgb8(lin), int(std::lround(raw * 255.0f)));
  // sRGB level 0 is decoded: byte 255 -> 1, byte 0 -> 0; alpha stays linear.
  EXPECT_EQ(correct->level(0, 0).at(1, 0)[0], 1.0f);
  EXPECT_EQ(correct->level(0, 0).at(1, 0)[3], 1.0f);
}

TEST(TextureMips, AlphaWeightedDoesNotBleedTransparentColour) {
  ImageRGBAF img(2, 1);
  const float opaque_red[4] = {1, 0, 0, 1};
  const float clear_green[4] = {0, 1, 0, 0};
  std::copy(opaque_red, opaque_red + 4, img.at(0, 0));
  std::copy(clear_green, clear_green + 4, img.at(1, 0));
  const ImageRGBAF weighted = downsample_box(img, {.alpha_weighted = true});
  EXPECT_NEAR(weighted.at(0, 0)[0], 1.0f, 1e-6f);
  EXPECT_NEAR(weighted.at(0, 0)[1], 0.0f, 1e-6f);
  EXPECT_NEAR(weighted.at(0, 0)[3], 0.5f, 1e-6f);
  const ImageRGBAF plain = downsample_box(img, {.alpha_weighted = false});
  EXPECT_NEAR(plain.at(0, 0)[0], 0.5f, 1e-6f);
  EXPECT_NEAR(plain.at(0, 0)[1], 0.5f, 1e-6f);
  // Fully transparent footprint keeps the plain average.
  img.at(0, 0)[3] = 0.0f;
  EXPECT_NEAR(downsample_box(img, {.alpha_weighted = true}).at(0, 0)[0], 0.5f, 1e-6f);
}

TEST(TextureMips, DeterministicForAnyThreadCount) {
  const ImageRGBA8 src = make_procedural(Procedural::noise, 97, 61, 3);
  Result<Texture> a = Texture::from_rgba8(src, {.threads = 1});
  Result<Texture> b = Texture::from_rgba8(src, {.threads = 4});
  ASSERT_TRUE(a.ok() && b.ok());
  ASSERT_EQ(a->level_count(), b->level_count());
  for (int l = 0; l < a->level_count(); ++l) {
    EXPECT_EQ(a->level_image(0, l).pixels, b->level_image(0, l).pixels) << l;
  }
}

}  // namespace
}  // namespace tessera::texture
