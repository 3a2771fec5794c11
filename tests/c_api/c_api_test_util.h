// What c_api_test.cpp and c_api_bad_input_test.cpp share: generated images, a context that
// frees itself, and the C API's results as C++ values.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "tessera/core.h"
#include "tessera/tessera_c.h"

namespace tessera::c_api_test {

/// A `w` x `h` RGBA image with smooth colour, a few edges and (when `alpha`) a transparent
/// corner and a soft ramp, different for each `seed`.
inline ImageRGBA8 test_image(int w, int h, int seed, bool alpha) {
  ImageRGBA8 im(w, h);
  im.has_alpha = alpha;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = im.at(x, y);
      p[0] = std::uint8_t((x * 255) / std::max(1, w - 1) ^ (seed * 37));
      p[1] = std::uint8_t((y * 255) / std::max(1, h - 1) + seed * 11);
      p[2] = std::uint8_t(((x / 4 + y / 4) % 2) ? 200 - seed : 40 + seed);
      p[3] = !alpha ? 255 : (x < w / 4 && y < h / 4) ? 0 : std::uint8_t(128 + (x * 127) / w);
    }
  }
  return im;
}

/// The C view of `im` (packed).
inline tessera_image c_image(const ImageRGBA8& im) {
  return {im.pixels.data(), std::uint32_t(im.width), std::uint32_t(im.height), 0,
          im.has_alpha ? 1 : 0};
}

struct ContextDeleter {
  void operator()(tessera_context* c) const { tessera_context_free(c); }
};
struct TextureDeleter {
  void operator()(tessera_texture* t) const { tessera_texture_free(t); }
};
using Context = std::unique_ptr<tessera_context, ContextDeleter>;
using Texture = std::unique_ptr<tessera_texture, TextureDeleter>;

inline Context make_context(int threads = 0, tessera_progress_fn progress = nullptr,
                            void* user = nullptr) {
  tessera_context_config config;
  EXPECT_EQ(tessera_context_config_init(&config), TESSERA_SUCCESS);
  config.threads = threads;
  config.progress = progress;
  config.progress_user_data = user;
  tessera_context* c = nullptr;
  EXPECT_EQ(tessera_context_create(&config, &c), TESSERA_SUCCESS);
  return Context(c);
}

/// The file of `texture` in `container` through tessera_texture_write_alloc (empty on error).
inline std::vector<std::uint8_t> c_file(tessera_context* context, tessera_texture* texture,
                                        tessera_container container, int zstd = 0) {
  void* data = nullptr;
  std::size_t size = 0;
  const tessera_error e =
      tessera_texture_write_alloc(context, texture, container, zstd, &data, &size);
  EXPECT_EQ(e, TESSERA_SUCCESS) << tessera_context_last_error(context);
  if (e != TESSERA_SUCCESS) return {};
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  std::vector<std::uint8_t> out(bytes, bytes + size);
  tessera_free(data);
  return out;
}

}  // namespace tessera::c_api_test
