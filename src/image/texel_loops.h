// Internal: the per-texel loops of the image system (image_ops.cpp, mipmap.cpp): rows in
// parallel, 16 a chunk, each texel on its own, so results never depend on the thread count.
#pragma once

#include <cstdint>

#include "tessera/core.h"

namespace tessera::image::detail {

/// Calls `texel(s, d)` for every pixel: `s` the pixel of `src`, `d` the same pixel of `dst`
/// (an image of the same size, or `src` itself).
template <class Src, class Dst, class Texel>
void map_texels(const Src& src, Dst& dst, const Parallel& parallel, Texel texel) {
  parallel_for(
      0, src.height, 16,
      [&](std::int64_t y0, std::int64_t y1) {
        for (std::int64_t y = y0; y < y1; ++y) {
          for (int x = 0; x < src.width; ++x) texel(src.at(x, int(y)), dst.at(x, int(y)));
        }
      },
      parallel);
}

/// Calls `texel(p)` on every pixel of `image`, in place.
template <class Image, class Texel>
void for_each_texel(Image& image, const Parallel& parallel, Texel texel) {
  map_texels(image, image, parallel, [&](const auto*, auto* p) { texel(p); });
}

}  // namespace tessera::image::detail
