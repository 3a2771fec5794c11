// libFuzzer target: pvrtc::decode with arbitrary sizes and data. Input layout: byte 0 selects
// the format (bit 0: 2 bpp), bytes 1-4 and 5-8 are the width and height as little-endian
// int32 (so zero, negative, non-power-of-two and huge sizes all occur), the rest is block data.
// Decoding must either fail cleanly (too little data, bad size) or produce the requested image.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <span>

#include "tessera/pvrtc.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 9) return 0;
  const auto format =
      (data[0] & 1) ? tessera::pvrtc::Format::pvrtc1_2bpp : tessera::pvrtc::Format::pvrtc1_4bpp;
  std::int32_t width = 0, height = 0;
  std::memcpy(&width, data + 1, 4);
  std::memcpy(&height, data + 5, 4);
  const std::span<const std::uint8_t> blocks(data + 9, size - 9);
  const int threads = (data[0] & 2) ? 2 : 1;
  tessera::Result<tessera::ImageRGBA8> img =
      tessera::pvrtc::decode(blocks, format, width, height, {threads});
  if (img) {
    if (img->width != width || img->height != height ||
        img->pixels.size() != std::size_t(width) * std::size_t(height) * 4) {
      std::abort();
    }
    if (blocks.size() < tessera::pvrtc::level_size(format, width, height)) std::abort();
  } else if (img.status().message.empty()) {
    std::abort();
  }
  return 0;
}
