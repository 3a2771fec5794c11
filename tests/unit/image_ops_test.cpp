// Tests of tessera/image_ops.h: flips, premultiplication (against exhaustive references),
// alpha bleeding (against a brute-force nearest-texel search) and normal renormalisation.
#include "tessera/image_ops.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "tessera/procedural.h"
#include "test_support.h"

namespace tessera::image {
namespace {

// ---------------------------------------------------------------------------------------------
// flip_y
// ---------------------------------------------------------------------------------------------

TEST(FlipY, ReversesRowsAndIsItsOwnInverse) {
  for (const int h : {1, 2, 3, 6}) {
    const ImageRGBA8 img = make_procedural(Procedural::noise, 5, h);
    ImageRGBA8 f = img;
    flip_y(f);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < 5; ++x) {
        for (int c = 0; c < 4; ++c) ASSERT_EQ(f.at(x, y)[c], img.at(x, h - 1 - y)[c]);
      }
    }
    flip_y(f);
    EXPECT_EQ(f.pixels, img.pixels);
  }
  ImageRGBA8 empty;
  flip_y(empty);  // nothing to do, nothing to crash on
  EXPECT_TRUE(empty.empty());
}

// ---------------------------------------------------------------------------------------------
// premultiply_alpha
// ---------------------------------------------------------------------------------------------

/// Every (colour, alpha) pair once: texel (c, a) has colour c in R, 255 - c in G, c in B.
ImageRGBA8 all_pairs() {
  ImageRGBA8 img(256, 256);
  img.has_alpha = true;
  for (int a = 0; a < 256; ++a) {
    for (int c = 0; c < 256; ++c) {
      std::uint8_t* p = img.at(c, a);
      p[0] = std::uint8_t(c);
      p[1] = std::uint8_t(255 - c);
      p[2] = std::uint8_t(c);
      p[3] = std::uint8_t(a);
    }
  }
  return img;
}

TEST(Premultiply, LinearIsRoundedToNearestExhaustively) {
  ImageRGBA8 img = all_pairs();
  premultiply_alpha(img, false);
  for (int a = 0; a < 256; ++a) {
    for (int c = 0; c < 256; ++c) {
      const std::uint8_t* p = img.at(c, a);
      ASSERT_EQ(p[0], std::lround(c * a / 255.0)) << "c " << c << " a " << a;
      ASSERT_EQ(p[1], std::lround((255 - c) * a / 255.0)) << "c " << 255 - c << " a " << a;
      ASSERT_EQ(p[3], a);
    }
  }
  // Hand-computed: 100 * 128 / 255 = 50.196 -> 50; 255 * 1 / 255 = 1; 1 * 128 / 255 -> 1.
  EXPECT_EQ(img.at(100, 128)[0], 50);
  EXPECT_EQ(img.at(255, 1)[0], 1);
  EXPECT_EQ(img.at(1, 128)[0], 1);
  EXPECT_EQ(img.at(1, 127)[0], 0);
}

/// Exact sRGB curves in double precision.
double srgb_decode(double v) {
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}
double srgb_encode(double v) {
  return v <= 0.0031308 ? v * 12.92 : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

TEST(Premultiply, SrgbMultipliesInLinearLight) {
  ImageRGBA8 img = all_pairs();
  premultiply_alpha(img, true);
  int off_by_one = 0;
  for (int a = 0; a < 256; ++a) {
    for (int c = 0; c < 256; ++c) {
      const std::uint8_t* p = img.at(c, a);
      const double exact = 255.0 * srgb_encode(srgb_decode(c / 255.0) * a / 255.0);
      // Single-precision curves may land on the other side of a .5 only right at it.
      const double miss = std::abs(p[0] - exact);
      ASSERT_LT(miss, 0.5 + 1e-3) << "c " << c << " a " << a << " exact " << exact;
      if (miss > 0.5) ++off_by_one;
      ASSERT_EQ(p[3], a);
    }
    EXPECT_EQ(img.at(a, 255)[0], a) << "alpha 255 keeps the colour";
    EXPECT_EQ(img.at(a, 0)[0], 0) << "alpha 0 is black";
  }
  EXPECT_LE(off_by_one, 2);
  // Half coverage of white is half the light: sRGB 188, not 128.
  EXPECT_EQ(img.at(255, 128)[0], 188);
}

TEST(Premultiply, ImageWithoutAlphaIsUnchanged) {
  ImageRGBA8 img = all_pairs();
  img.has_alpha = false;
  const ImageRGBA8 before = img;
  premultiply_alpha(img, false);
  EXPECT_EQ(img.pixels, before.pixels);
  premultiply_alpha(img, true);
  EXPECT_EQ(img.pixels, before.pixels);
}

// ---------------------------------------------------------------------------------------------
// bleed_alpha
// ---------------------------------------------------------------------------------------------

/// The definition, by brute force: for each transparent texel, every visible texel in row-major
/// order, keeping the first of the smallest wrapped Euclidean distance.
ImageRGBA8 bleed_reference(const ImageRGBA8& img) {
  ImageRGBA8 out = img;
  const int w = img.width, h = img.height;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (img.at(x, y)[3] != 0) continue;
      long best = -1;
      int bx = -1, by = -1;
      for (int sy = 0; sy < h; ++sy) {
        for (int sx = 0; sx < w; ++sx) {
          if (img.at(sx, sy)[3] == 0) continue;
          const int dx = std::min(std::abs(x - sx), w - std::abs(x - sx));
          const int dy = std::min(std::abs(y - sy), h - std::abs(y - sy));
          const long d = long(dx) * dx + long(dy) * dy;
          if (best < 0 || d < best) {
            best = d;
            bx = sx;
            by = sy;
          }
        }
      }
      if (best < 0) return img;  // nothing visible
      for (int c = 0; c < 3; ++c) out.at(x, y)[c] = img.at(bx, by)[c];
    }
  }
  return out;
}

/// A w x h image whose texels all have distinct colours (so that a wrong site shows), visible
/// with probability `density`.
ImageRGBA8 random_sites(int w, int h, double density, std::mt19937& rng) {
  ImageRGBA8 img(w, h);
  img.has_alpha = true;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::uniform_int_distribution<int> byte(1, 255);
  for (int i = 0; i < w * h; ++i) {
    std::uint8_t* p = &img.pixels[std::size_t(i) * 4];
    p[0] = std::uint8_t(i & 0xff);
    p[1] = std::uint8_t(i >> 8);
    p[2] = std::uint8_t(byte(rng));
    p[3] = u(rng) < density ? std::uint8_t(byte(rng)) : 0;
  }
  return img;
}

TEST(BleedAlpha, MatchesBruteForceOnRandomImages) {
  std::mt19937 rng(20240611);
  int compared = 0;
  for (int h = 1; h <= 17; ++h) {
    for (int w = 1; w <= 17; ++w) {
      for (const double density : {0.02, 0.1, 0.3, 0.7}) {
        const ImageRGBA8 img = random_sites(w, h, density, rng);
        const ImageRGBA8 expect = bleed_reference(img);
        for (const int threads : {1, 3}) {
          ImageRGBA8 got = img;
          bleed_alpha(got, {threads});
          ASSERT_EQ(got.pixels, expect.pixels)
              << w << "x" << h << " density " << density << " threads " << threads;
        }
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 17 * 17 * 4);
}

TEST(BleedAlpha, LargerImagesMatchBruteForce) {
  // Wider than one column block of the first pass, sparse and clustered sites.
  std::mt19937 rng(7);
  for (const auto& [w, h, density] :
       {std::tuple{70, 33, 0.003}, std::tuple{45, 64, 0.05}, std::tuple{64, 64, 0.0005}}) {
    const ImageRGBA8 img = random_sites(w, h, density, rng);
    ImageRGBA8 got = img;
    bleed_alpha(got, {4});
    EXPECT_EQ(got.pixels, bleed_reference(img).pixels) << w << "x" << h;
  }
}

/// A w x h transparent image (colour 9, 9, 9) with visible texels `sites` of distinct colours.
ImageRGBA8 with_sites(int w, int h, std::initializer_list<std::pair<int, int>> sites) {
  ImageRGBA8 img = test::solid_rgba8(w, h, 9, 9, 9, 0);
  img.has_alpha = true;
  std::uint8_t colour = 100;
  for (const auto& [x, y] : sites) {
    std::uint8_t* p = img.at(x, y);
    p[0] = colour;
    p[1] = std::uint8_t(colour + 1);
    p[2] = std::uint8_t(colour + 2);
    p[3] = 255;
    colour = std::uint8_t(colour + 10);
  }
  return img;
}

TEST(BleedAlpha, TiesGoToTheFirstInRowMajorOrder) {
  // (1, 0) and (0, 1) are both 1 from (1, 1): (1, 0) comes first.
  ImageRGBA8 img = with_sites(5, 5, {{0, 1}, {1, 0}});
  bleed_alpha(img);
  EXPECT_EQ(img.at(1, 1)[0], 110);
  // (2, 0) [index 2] and (0, 2) [index 10] are both sqrt(2) from (1, 1): the row-major index
  // decides, not the column (a column-first rule would pick (0, 2)).
  img = with_sites(5, 5, {{0, 2}, {2, 0}});
  bleed_alpha(img);
  EXPECT_EQ(img.at(1, 1)[0], 110);
  EXPECT_EQ(img.at(0, 0)[0], 110) << "(0, 2) and (2, 0) are both 2 away: index 2 < 10";
  // Equal distances in one column, up and down: the smaller row.
  img = with_sites(1, 7, {{0, 5}, {0, 1}});
  bleed_alpha(img);
  EXPECT_EQ(img.at(0, 3)[0], 110);
  EXPECT_EQ(img.at(0, 0)[0], 110);
  // ... also across the edge: row 7 of 8 is 2 from row 5 and (wrapped) from row 1.
  img = with_sites(1, 8, {{0, 5}, {0, 1}});
  bleed_alpha(img);
  EXPECT_EQ(img.at(0, 7)[0], 110);
  EXPECT_EQ(img.at(0, 3)[0], 110);
  EXPECT_EQ(img.at(0, 6)[0], 100);
}

TEST(BleedAlpha, DistancesWrapAroundTheEdges) {
  // In a row of 8, (7, 0) is 1 from (0, 0) across the edge; (3, 0) is 3 away.
  ImageRGBA8 img = with_sites(8, 1, {{3, 0}, {7, 0}});
  bleed_alpha(img);
  EXPECT_EQ(img.at(0, 0)[0], 110);
  EXPECT_EQ(img.at(1, 0)[0], 100) << "1 is 2 from 3 and from 7 (wrapped): 3 comes first";
  EXPECT_EQ(img.at(5, 0)[0], 100) << "5 is 2 from 3 and from 7: 3 comes first";
  EXPECT_EQ(img.at(6, 0)[0], 110);
  // Vertically too: row 0 takes the site in the last row.
  img = with_sites(3, 10, {{1, 9}, {1, 4}});
  bleed_alpha(img);
  EXPECT_EQ(img.at(1, 0)[0], 100);
  EXPECT_EQ(img.at(0, 1)[0], 100);
  EXPECT_EQ(img.at(1, 2)[0], 110);
}

TEST(BleedAlpha, KeepsAlphaAndVisibleTexels) {
  const ImageRGBA8 img = make_procedural(Procedural::foliage, 48, 40);
  ASSERT_TRUE(img.has_alpha);
  ImageRGBA8 b = img;
  bleed_alpha(b);
  int changed = 0;
  for (std::size_t i = 0; i < img.pixel_count(); ++i) {
    ASSERT_EQ(b.pixels[i * 4 + 3], img.pixels[i * 4 + 3]);
    if (img.pixels[i * 4 + 3] != 0) {
      for (int c = 0; c < 3; ++c) ASSERT_EQ(b.pixels[i * 4 + c], img.pixels[i * 4 + c]);
    } else {
      changed += b.pixels[i * 4] != img.pixels[i * 4];
    }
  }
  EXPECT_GT(changed, 0);
  EXPECT_EQ(b.pixels, bleed_reference(img).pixels);
  ImageRGBA8 one_thread = img;
  bleed_alpha(one_thread, {1});
  EXPECT_EQ(one_thread.pixels, b.pixels);
}

TEST(BleedAlpha, NothingVisibleOrNoAlphaIsUnchanged) {
  ImageRGBA8 clear = test::solid_rgba8(6, 4, 1, 2, 3, 0);
  clear.has_alpha = true;
  clear.at(2, 2)[0] = 200;
  const ImageRGBA8 before = clear;
  bleed_alpha(clear);
  EXPECT_EQ(clear.pixels, before.pixels);
  // Alpha 0 texels in an image without alpha are not transparent.
  ImageRGBA8 rgb = with_sites(4, 4, {{1, 1}});
  rgb.has_alpha = false;
  const ImageRGBA8 rgb_before = rgb;
  bleed_alpha(rgb);
  EXPECT_EQ(rgb.pixels, rgb_before.pixels);
  // One visible texel colours everything.
  ImageRGBA8 one = with_sites(9, 5, {{4, 3}});
  bleed_alpha(one);
  for (std::size_t i = 0; i < one.pixel_count(); ++i) ASSERT_EQ(one.pixels[i * 4 + 0], 100);
}

// ---------------------------------------------------------------------------------------------
// normalise_normals
// ---------------------------------------------------------------------------------------------

double length_of(const std::uint8_t* p) {
  double s = 0;
  for (int c = 0; c < 3; ++c) s += std::pow(2.0 * p[c] / 255.0 - 1.0, 2);
  return std::sqrt(s);
}

TEST(NormaliseNormals, ScalesToUnitLengthAndKeepsAlpha) {
  ImageRGBA8 img = test::solid_rgba8(3, 1, 200, 200, 128, 77);
  img.at(1, 0)[0] = 0;  // (-1, 0.004, 0.004)
  img.at(1, 0)[1] = 128;
  img.at(1, 0)[2] = 128;
  img.at(2, 0)[0] = 128;  // already +Z
  img.at(2, 0)[1] = 128;
  img.at(2, 0)[2] = 255;
  normalise_normals(img);
  // (0.569, 0.569, 0.004) / 0.804 -> (0.7071, 0.7071, 0.0049) -> 217.66, 217.66, 128.12.
  EXPECT_EQ(img.at(0, 0)[0], 218);
  EXPECT_EQ(img.at(0, 0)[1], 218);
  EXPECT_EQ(img.at(0, 0)[2], 128);
  EXPECT_EQ(img.at(0, 0)[3], 77);
  EXPECT_EQ(img.at(1, 0)[0], 0);
  EXPECT_EQ(img.at(1, 0)[1], 128);
  EXPECT_EQ(img.at(2, 0)[0], 128);
  EXPECT_EQ(img.at(2, 0)[2], 255);
  // Random vectors come out unit length within the 8-bit quantisation (1/255 per component).
  ImageRGBA8 noise = make_procedural(Procedural::noise, 64, 64);
  ImageRGBA8 n4 = noise;
  normalise_normals(noise, {1});
  normalise_normals(n4, {4});
  EXPECT_EQ(noise.pixels, n4.pixels);
  for (std::size_t i = 0; i < noise.pixel_count(); ++i) {
    ASSERT_NEAR(length_of(&noise.pixels[i * 4]), 1.0, std::sqrt(3.0) / 255.0);
  }
}

}  // namespace
}  // namespace tessera::image
