// Helpers shared by the texture tests (texture_test.cpp, texture_filtering_test.cpp): every
// filter and address mode, test images, a texture that must build, footprints in texels.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <utility>

#include "tessera/core.h"
#include "tessera/texture.h"
#include "test_support.h"

namespace tessera::test {

inline constexpr texture::TextureFilter kAllFilters[] = {
    texture::TextureFilter::nearest, texture::TextureFilter::bilinear,
    texture::TextureFilter::trilinear, texture::TextureFilter::anisotropic};
inline constexpr texture::AddressMode kAllModes[] = {
    texture::AddressMode::wrap, texture::AddressMode::clamp, texture::AddressMode::mirror,
    texture::AddressMode::border};

inline ImageRGBAF constant_image(int w, int h, float r, float g, float b, float a) {
  return solid_image<ImageRGBAF>(w, h, r, g, b, a);
}

/// Red channel = column index, green = row index: bilinear must reproduce both ramps.
inline ImageRGBAF ramp_image(int w, int h) {
  ImageRGBAF img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* p = img.at(x, y);
      p[0] = float(x);
      p[1] = float(y);
      p[2] = 0.0f;
      p[3] = 1.0f;
    }
  return img;
}

inline ImageRGBAF random_image(int w, int h, std::uint32_t seed) {
  std::mt19937 rng(seed);
  ImageRGBAF img(w, h);
  for (float& v : img.pixels) v = float(rng() % 100000) / 100000.0f;
  return img;
}

inline texture::Texture make_texture(const ImageRGBAF& img,
                                     const texture::TextureOptions& options = {}) {
  Result<texture::Texture> r = texture::Texture::from_float(img, options);
  EXPECT_TRUE(r.ok()) << r.status().message;
  return std::move(r).value();
}

/// Gradients (normalised units) of a footprint given in texels of level 0.
inline texture::UvGradients texel_grad(const texture::TextureShape& s, float dxu, float dxv,
                                       float dyu, float dyv) {
  return {dxu / float(s.width), dxv / float(s.height), dyu / float(s.width), dyv / float(s.height)};
}

}  // namespace tessera::test
