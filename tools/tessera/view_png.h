// tessera view: the PNG writer behind the page's images. Fast (libdeflate, one filter chosen per
// image from a sample of its rows) rather than smallest; RGB where every texel is opaque, else
// RGBA (straight alpha, as stored). The page reads the texels back exactly with its own
// decoder (view_png.js), so no canvas ever premultiplies them.
#pragma once

#include <cstdint>
#include <vector>

#include "tessera/core.h"

namespace tessera::cli {

/// libdeflate levels: the server's (an encode waits for it) and the static export's (written
/// once, kept and sent around).
constexpr int kPngLevelFast = 1;
constexpr int kPngLevelSmall = 6;

/// The 8-bit PNG of `image` (colour type 2 when every alpha is 255, else 6); with `palette`,
/// an opaque image of at most 256 colours (a heatmap) is written with a palette (type 3: a byte
/// a texel, a third of the size or less). Empty when the image is empty or the compressor
/// cannot be made. The page's texel reader (view_png.js) reads types 2 and 6 only: texels are
/// written without `palette`.
std::vector<std::uint8_t> encode_view_png(const ImageRGBA8& image, int level, bool palette = false);

}  // namespace tessera::cli
