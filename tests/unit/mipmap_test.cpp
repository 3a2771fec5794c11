// Tests of tessera/image_mipmap.h: mip chain sizes, sRGB-correct and alpha-weighted averaging,
// thread-count independence, the Lanczos and Kaiser filters, normal-map chains, and resizing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "tessera/image_mipmap.h"
#include "tessera/image_ops.h"
#include "tessera/metrics.h"
#include "tessera/procedural.h"
#include "test_support.h"

namespace tessera::image {
namespace {

// ---------------------------------------------------------------------------------------------
// Mipmaps and resizing
// ---------------------------------------------------------------------------------------------

TEST(Mipmap, ChainSizesGoDownToOneByOneForNonSquare) {
  const ImageRGBA8 img = make_procedural(Procedural::noise, 32, 4);
  Result<std::vector<ImageRGBA8>> chain = generate_mipmaps(img);
  ASSERT_TRUE(chain.ok());
  ASSERT_EQ(chain->size(), 6u);
  const int expect[6][2] = {{32, 4}, {16, 2}, {8, 1}, {4, 1}, {2, 1}, {1, 1}};
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ((*chain)[std::size_t(i)].width, expect[i][0]);
    EXPECT_EQ((*chain)[std::size_t(i)].height, expect[i][1]);
  }
  EXPECT_EQ((*chain)[0].pixels, img.pixels);
  EXPECT_EQ(mip_level_count(1, 1), 1);
  EXPECT_EQ(mip_level_count(256, 64), 9);
  MipmapOptions o;
  o.max_levels = 2;
  EXPECT_EQ(generate_mipmaps(img, o)->size(), 2u);
}

TEST(Mipmap, SrgbAveragesInLinearLight) {
  ImageRGBA8 img(2, 2);
  for (int i = 0; i < 4; ++i) {
    const std::uint8_t v = (i == 0 || i == 3) ? 255 : 0;
    img.pixels[std::size_t(i) * 4 + 0] = img.pixels[std::size_t(i) * 4 + 1] =
        img.pixels[std::size_t(i) * 4 + 2] = v;
    img.pixels[std::size_t(i) * 4 + 3] = 255;
  }
  MipmapOptions o;
  o.srgb = true;
  const ImageRGBA8 gamma = (*generate_mipmaps(img, o))[1];
  EXPECT_EQ(gamma.pixels[0], linear_to_srgb8(0.5f));  // 188
  EXPECT_EQ(gamma.pixels[0], 188);
  o.srgb = false;
  EXPECT_EQ((*generate_mipmaps(img, o))[1].pixels[0], 128);  // 127.5 rounded
}

TEST(Mipmap, AlphaWeightsColour) {
  // Left half transparent red, right half opaque green: the average must be pure green.
  ImageRGBA8 img = test::solid_rgba8(2, 1, 255, 0, 0, 0);
  img.has_alpha = true;
  img.at(1, 0)[0] = 0;
  img.at(1, 0)[1] = 255;
  img.at(1, 0)[3] = 255;
  const ImageRGBA8 m = (*generate_mipmaps(img))[1];
  EXPECT_EQ(m.at(0, 0)[0], 0);
  EXPECT_EQ(m.at(0, 0)[1], 255);
  EXPECT_EQ(m.at(0, 0)[3], 128);
  // Fully transparent: the plain colour average survives (no black fringe).
  ImageRGBA8 clear = test::solid_rgba8(4, 4, 200, 100, 50, 0);
  clear.has_alpha = true;
  const ImageRGBA8 c = (*generate_mipmaps(clear))[2];
  EXPECT_EQ(c.at(0, 0)[0], 200);
  EXPECT_EQ(c.at(0, 0)[3], 0);
  // Opaque input stays opaque.
  const ImageRGBA8 solid = test::solid_rgba8(8, 8, 10, 20, 30, 255);
  const std::vector<ImageRGBA8> solid_chain = *generate_mipmaps(solid);
  for (const ImageRGBA8& l : solid_chain) {
    EXPECT_EQ(l.at(0, 0)[0], 10);
    EXPECT_EQ(l.at(0, 0)[3], 255);
  }
}

TEST(Mipmap, IdenticalForAnyThreadCount) {
  const ImageRGBA8 img = make_procedural(Procedural::foliage, 64, 32);
  MipmapOptions a, b;
  a.threads = 1;
  b.threads = 4;
  const std::vector<ImageRGBA8> ca = *generate_mipmaps(img, a);
  const std::vector<ImageRGBA8> cb = *generate_mipmaps(img, b);
  for (std::size_t i = 0; i < ca.size(); ++i) EXPECT_EQ(ca[i].pixels, cb[i].pixels);
  EXPECT_EQ(resize_image(img, 100, 20, a)->pixels, resize_image(img, 100, 20, b)->pixels);
}

// ---------------------------------------------------------------------------------------------
// Lanczos and Kaiser mip filters
// ---------------------------------------------------------------------------------------------

constexpr MipFilter kSincFilters[] = {MipFilter::lanczos, MipFilter::kaiser};
constexpr MipFilter kAllFilters[] = {MipFilter::box, MipFilter::lanczos, MipFilter::kaiser};

MipmapOptions with_filter(MipFilter filter, bool srgb = false) {
  MipmapOptions o;
  o.filter = filter;
  o.srgb = srgb;
  return o;
}

TEST(MipFilter, Names) {
  EXPECT_STREQ(mip_filter_name(MipFilter::box), "box");
  EXPECT_STREQ(mip_filter_name(MipFilter::lanczos), "lanczos");
  EXPECT_STREQ(mip_filter_name(MipFilter::kaiser), "kaiser");
  EXPECT_EQ(MipmapOptions{}.filter, MipFilter::box);
  EXPECT_FALSE(MipmapOptions{}.normal_map);
}

TEST(MipFilter, ConstantImageStaysConstantAtEveryLevelWithGlSizes) {
  for (const MipFilter f : kSincFilters) {
    for (const auto& [w, h] : {std::pair{16, 16}, {32, 4}, {5, 3}, {1, 9}, {12, 1}}) {
      for (const bool srgb : {false, true}) {
        ImageRGBA8 img = test::solid_rgba8(w, h, 90, 160, 220, 77);
        img.has_alpha = true;
        Result<std::vector<ImageRGBA8>> chain = generate_mipmaps(img, with_filter(f, srgb));
        ASSERT_TRUE(chain.ok());
        ASSERT_EQ(int(chain->size()), mip_level_count(w, h));
        for (int level = 0; level < int(chain->size()); ++level) {
          const ImageRGBA8& l = (*chain)[std::size_t(level)];
          ASSERT_EQ(l.width, mip_dimension(w, level));
          ASSERT_EQ(l.height, mip_dimension(h, level));
          ASSERT_TRUE(l.has_alpha);
          for (std::size_t i = 0; i < l.pixel_count(); ++i) {
            ASSERT_EQ(l.pixels[i * 4 + 0], 90) << mip_filter_name(f) << " " << w << "x" << h;
            ASSERT_EQ(l.pixels[i * 4 + 1], 160);
            ASSERT_EQ(l.pixels[i * 4 + 2], 220);
            ASSERT_EQ(l.pixels[i * 4 + 3], 77);
          }
        }
      }
    }
  }
}

TEST(MipFilter, IdenticalForAnyThreadCount) {
  const ImageRGBA8 img = make_procedural(Procedural::foliage, 64, 48);
  for (const MipFilter f : kAllFilters) {
    for (const bool normal : {false, true}) {
      MipmapOptions a = with_filter(f, true), b = a;
      a.normal_map = b.normal_map = normal;
      a.threads = 1;
      b.threads = 3;
      const std::vector<ImageRGBA8> ca = *generate_mipmaps(img, a);
      const std::vector<ImageRGBA8> cb = *generate_mipmaps(img, b);
      ASSERT_EQ(ca.size(), 7u);
      for (std::size_t i = 0; i < ca.size(); ++i) EXPECT_EQ(ca[i].pixels, cb[i].pixels) << i;
    }
  }
}

TEST(MipFilter, CheckerboardGoesToMidGrey) {
  // Symmetric kernels give the two texel parities equal total weight: exactly the mean.
  ImageRGBA8 img(16, 16);
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) {
      std::uint8_t* p = img.at(x, y);
      p[0] = p[1] = p[2] = (x + y) % 2 ? 255 : 0;
      p[3] = 255;
    }
  }
  for (const MipFilter f : kSincFilters) {
    for (const bool srgb : {false, true}) {
      const std::vector<ImageRGBA8> chain = *generate_mipmaps(img, with_filter(f, srgb));
      for (std::size_t level = 1; level < chain.size(); ++level) {
        for (std::size_t i = 0; i < chain[level].pixel_count(); ++i) {
          // Linear: 127.5 rounds to 128; sRGB: half the light is 188.
          ASSERT_EQ(chain[level].pixels[i * 4], srgb ? 188 : 128) << mip_filter_name(f);
        }
      }
    }
  }
}

/// Modified Bessel function I0 by its power series.
double bessel_i0(double x) {
  double sum = 1, term = 1;
  for (int k = 1; k < 60; ++k) {
    term *= x / (2.0 * k);
    sum += term * term;
  }
  return sum;
}

/// The documented kernels, in texels of the level below.
double kernel(MipFilter f, double x) {
  if (std::abs(x) >= 3) return 0;
  const auto sinc = [](double v) {
    return v == 0 ? 1.0 : std::sin(std::numbers::pi * v) / (std::numbers::pi * v);
  };
  if (f == MipFilter::lanczos) return sinc(x) * sinc(x / 3);
  return sinc(x) * bessel_i0(4 * std::sqrt(1 - x * x / 9)) / bessel_i0(4);
}

TEST(MipFilter, ImpulseResponseIsTheNormalisedKernelWrapped) {
  // A 32-texel line of 100 with 255 at texel 1: output i (centred on 2i + 1) sees the impulse
  // at d = 1.5 - (2i + 1) texels, wrapped to the nearest copy, with weight k(d / 2) / sum, the
  // sum over the 12 taps d = +-0.5 .. +-5.5. The same along a column.
  for (const MipFilter f : kSincFilters) {
    double sum = 0;
    for (int t = 0; t < 12; ++t) sum += kernel(f, (t - 5.5) / 2);
    for (const bool vertical : {false, true}) {
      ImageRGBA8 img = vertical ? test::solid_rgba8(1, 32, 100, 100, 100)
                                : test::solid_rgba8(32, 1, 100, 100, 100);
      img.pixels[4] = 255;
      const ImageRGBA8 l1 = (*generate_mipmaps(img, with_filter(f)))[1];
      ASSERT_EQ(l1.pixel_count(), 16u);
      for (int i = 0; i < 16; ++i) {
        double d = 1.5 - (2 * i + 1);
        if (d < -16) d += 32;
        const double expect = 100 + 155 * kernel(f, d / 2) / sum;
        EXPECT_LT(std::abs(l1.pixels[std::size_t(i) * 4] - expect), 0.5 + 1e-3)
            << mip_filter_name(f) << " output " << i << " expect " << expect;
      }
      // The negative lobes show: some outputs dip below the background.
      int below = 0;
      for (int i = 0; i < 16; ++i) below += l1.pixels[std::size_t(i) * 4] < 100;
      EXPECT_GE(below, 2);
    }
  }
}

TEST(MipFilter, KaiserRingsLessThanLanczosOnAStep) {
  // Left half 10, right half 245 (so two edges on the wrapped line): total over- and
  // undershoot of level 1. Box does not ring at all.
  ImageRGBA8 img = test::solid_rgba8(64, 4, 10, 10, 10);
  for (int y = 0; y < 4; ++y) {
    for (int x = 32; x < 64; ++x) img.at(x, y)[0] = img.at(x, y)[1] = img.at(x, y)[2] = 245;
  }
  int ringing[3] = {0, 0, 0};
  for (const MipFilter f : kAllFilters) {
    const ImageRGBA8 l1 = (*generate_mipmaps(img, with_filter(f)))[1];
    for (std::size_t i = 0; i < l1.pixel_count(); ++i) {
      const int v = l1.pixels[i * 4];
      ringing[int(f)] += std::max(v - 245, 0) + std::max(10 - v, 0);
    }
  }
  EXPECT_EQ(ringing[int(MipFilter::box)], 0);
  EXPECT_GT(ringing[int(MipFilter::kaiser)], 0);
  EXPECT_LT(ringing[int(MipFilter::kaiser)], ringing[int(MipFilter::lanczos)]);
}

TEST(MipFilter, AlphaWeightsColourAsBoxDoes) {
  // Transparent red beside opaque green: no red reaches any level.
  ImageRGBA8 img = test::solid_rgba8(16, 16, 255, 0, 0, 0);
  img.has_alpha = true;
  for (int y = 0; y < 16; ++y) {
    for (int x = 4; x < 12; ++x) {
      std::uint8_t* p = img.at(x, y);
      p[0] = 0;
      p[1] = 255;
      p[3] = 255;
    }
  }
  for (const MipFilter f : kSincFilters) {
    const std::vector<ImageRGBA8> chain = *generate_mipmaps(img, with_filter(f, true));
    for (std::size_t level = 1; level < chain.size(); ++level) {
      for (std::size_t i = 0; i < chain[level].pixel_count(); ++i) {
        if (chain[level].pixels[i * 4 + 3] == 0) continue;
        ASSERT_EQ(chain[level].pixels[i * 4 + 0], 0) << mip_filter_name(f) << " " << level;
      }
    }
    EXPECT_EQ(chain.back().pixels[3], 128) << "alpha averages to one half";
  }
}

// ---------------------------------------------------------------------------------------------
// Normal maps
// ---------------------------------------------------------------------------------------------

double normal_length(const std::uint8_t* p) {
  double s = 0;
  for (int c = 0; c < 3; ++c) s += std::pow(2.0 * p[c] / 255.0 - 1.0, 2);
  return std::sqrt(s);
}

TEST(MipNormalMap, LevelsHoldUnitVectors) {
  ImageRGBA8 img = make_procedural(Procedural::noise, 64, 32);
  normalise_normals(img);
  for (const MipFilter f : kAllFilters) {
    MipmapOptions o = with_filter(f);
    o.normal_map = true;
    const std::vector<ImageRGBA8> chain = *generate_mipmaps(img, o);
    ASSERT_EQ(chain.size(), 7u);
    for (std::size_t level = 1; level < chain.size(); ++level) {
      for (std::size_t i = 0; i < chain[level].pixel_count(); ++i) {
        // Each component is within 1/255 of the unit vector's.
        ASSERT_NEAR(normal_length(&chain[level].pixels[i * 4]), 1.0, std::sqrt(3.0) / 255.0)
            << mip_filter_name(f) << " level " << level;
      }
    }
  }
}

TEST(MipNormalMap, SymmetricPatternAveragesToPlusZ) {
  // (+-t, +-t, z) alternating by column and by row: the tilts cancel, +Z remains at every level.
  ImageRGBA8 img(8, 8);
  img.has_alpha = true;
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 8; ++x) {
      std::uint8_t* p = img.at(x, y);
      p[0] = x % 2 ? 200 : 55;  // 2 c / 255 - 1 = +-0.5686
      p[1] = y % 2 ? 200 : 55;
      p[2] = 200;
      p[3] = 200;
    }
  }
  for (const MipFilter f : kAllFilters) {
    MipmapOptions o = with_filter(f);
    o.normal_map = true;
    const std::vector<ImageRGBA8> chain = *generate_mipmaps(img, o);
    for (std::size_t level = 1; level < chain.size(); ++level) {
      for (std::size_t i = 0; i < chain[level].pixel_count(); ++i) {
        const std::uint8_t* p = &chain[level].pixels[i * 4];
        ASSERT_EQ(p[0], 128) << mip_filter_name(f) << " level " << level;
        ASSERT_EQ(p[1], 128);
        ASSERT_EQ(p[2], 255);
        ASSERT_EQ(p[3], 200);  // alpha filtered as usual
      }
    }
  }
  // Opposite vectors average to zero, which becomes +Z.
  ImageRGBA8 pair = test::solid_rgba8(2, 1, 255, 128, 128);
  pair.at(1, 0)[0] = 0;  // (1, e, e) and (-1, -e, -e)
  pair.at(1, 0)[1] = 127;
  pair.at(1, 0)[2] = 127;
  for (const MipFilter f : kAllFilters) {
    MipmapOptions o = with_filter(f);
    o.normal_map = true;
    const ImageRGBA8 l1 = (*generate_mipmaps(pair, o))[1];
    EXPECT_EQ(l1.pixels[0], 128) << mip_filter_name(f);
    EXPECT_EQ(l1.pixels[1], 128);
    EXPECT_EQ(l1.pixels[2], 255);
    EXPECT_EQ(l1.pixels[3], 255);
  }
}

TEST(MipNormalMap, SrgbAndPremultiplyDoNotApplyToVectors) {
  ImageRGBA8 img = make_procedural(Procedural::foliage, 32, 32);  // varying alpha
  ASSERT_TRUE(img.has_alpha);
  for (const MipFilter f : kAllFilters) {
    MipmapOptions plain = with_filter(f, false), fancy = with_filter(f, true);
    plain.premultiply = false;
    fancy.premultiply = true;
    plain.normal_map = fancy.normal_map = true;
    const std::vector<ImageRGBA8> a = *generate_mipmaps(img, plain);
    const std::vector<ImageRGBA8> b = *generate_mipmaps(img, fancy);
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].pixels, b[i].pixels) << i;
    // ... whereas as colour the same options differ.
    plain.normal_map = fancy.normal_map = false;
    EXPECT_NE((*generate_mipmaps(img, plain))[1].pixels, (*generate_mipmaps(img, fancy))[1].pixels);
  }
}

TEST(Resize, ConstantStaysConstantAndSizesAreRight) {
  const ImageRGBA8 img = test::solid_rgba8(127, 128, 90, 160, 220, 255);
  Result<ImageRGBA8> r = resize_image(img, 128, 128);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->width, 128);
  EXPECT_EQ(r->height, 128);
  for (std::size_t i = 0; i < r->pixel_count(); ++i) {
    ASSERT_NEAR(r->pixels[i * 4 + 0], 90, 1);
    ASSERT_NEAR(r->pixels[i * 4 + 1], 160, 1);
    ASSERT_NEAR(r->pixels[i * 4 + 2], 220, 1);
    ASSERT_EQ(r->pixels[i * 4 + 3], 255);
  }
  // A smooth image survives a small resample almost unchanged.
  const ImageRGBA8 smooth = make_procedural(Procedural::gradient, 120, 120);
  Result<ImageRGBA8> up = resize_image(smooth, 128, 128);
  Result<ImageRGBA8> back = resize_image(*up, 120, 120);
  EXPECT_GT(metrics::compare_images(smooth, *back)->psnr_rgb, 35.0);
  EXPECT_FALSE(resize_image(smooth, 0, 4).ok());
}

TEST(Resize, NearestPowerOfTwo) {
  EXPECT_EQ(nearest_power_of_two(1), 1);
  EXPECT_EQ(nearest_power_of_two(127), 128);
  EXPECT_EQ(nearest_power_of_two(128), 128);
  EXPECT_EQ(nearest_power_of_two(95), 64);
  EXPECT_EQ(nearest_power_of_two(96), 128);
  EXPECT_EQ(nearest_power_of_two(300), 256);
  EXPECT_EQ(nearest_power_of_two(1000), 1024);
}

}  // namespace
}  // namespace tessera::image
