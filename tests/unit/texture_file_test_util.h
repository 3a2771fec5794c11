// Helpers shared by the texture-file tests (texture_file_test.cpp, texture_file_io_test.cpp):
// fake textures, serialisation that expects success, field-by-field comparison.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <utility>
#include <vector>

#include "tessera/image_mipmap.h"
#include "tessera/texture_file.h"

namespace tessera::test {

using Bytes = std::vector<std::uint8_t>;

/// A texture with deterministic pseudo-random block data (not necessarily a meaningful image).
inline texture_file::CompressedTexture fake_texture(pvrtc::Format format, int w, int h, int levels,
                                                    bool alpha, bool srgb) {
  texture_file::CompressedTexture t;
  t.format = format;
  t.width = w;
  t.height = h;
  t.has_alpha = alpha;
  t.srgb = srgb;
  std::uint32_t state = 12345u + std::uint32_t(w * 31 + h);
  for (int i = 0; i < levels; ++i) {
    Bytes data(pvrtc::level_size(format, mip_dimension(w, i), mip_dimension(h, i)));
    for (auto& b : data) {
      state = state * 1664525u + 1013904223u;
      b = std::uint8_t(state >> 24);
    }
    t.levels.push_back(std::move(data));
  }
  return t;
}

inline void expect_same(const texture_file::CompressedTexture& a,
                        const texture_file::CompressedTexture& b) {
  EXPECT_EQ(a.format, b.format);
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.has_alpha, b.has_alpha);
  EXPECT_EQ(a.srgb, b.srgb);
  EXPECT_EQ(a.levels, b.levels);
}

inline Bytes pvr_bytes(const texture_file::CompressedTexture& t) {
  Result<Bytes> b = texture_file::serialise_pvr3(t);
  EXPECT_TRUE(b.ok()) << b.status().message;
  return b.ok() ? *b : Bytes{};
}
inline Bytes ktx_bytes(const texture_file::CompressedTexture& t) {
  Result<Bytes> b = texture_file::serialise_ktx1(t);
  EXPECT_TRUE(b.ok()) << b.status().message;
  return b.ok() ? *b : Bytes{};
}

}  // namespace tessera::test
