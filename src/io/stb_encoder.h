// stb_encoder.h — tessera's private entry point into stb_image_write (BMP, TGA and JPEG output).
//
// Like stb_image (stb_decoder.h), stb_image_write is compiled into the library with internal
// linkage (stb_image_write_impl.cpp); this wrapper is the only way in.
#pragma once

#include <cstdint>
#include <vector>

namespace tessera::io::detail {

/// Output formats of `stb_encode`.
enum class StbFormat { bmp, tga, jpeg };

/// Encodes `width` x `height` 8-bit pixels of `components` (3 = RGB, 4 = RGBA) channels, rows
/// top to bottom, into `out`. JPEG is written at quality 95 (it has no alpha: RGBA drops it).
/// Returns false when stb_image_write fails.
bool stb_encode(StbFormat format, int width, int height, int components, const std::uint8_t* pixels,
                std::vector<std::uint8_t>& out);

}  // namespace tessera::io::detail
