// Tests of tessera/mipmap.h: mip chain sizes, sRGB-correct and alpha-weighted averaging,
// thread-count independence, and resizing.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "tessera/metrics.h"
#include "tessera/mipmap.h"
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
