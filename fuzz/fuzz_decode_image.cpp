// libFuzzer target: tessera::io::decode_image (PNG via libspng; JPEG, TGA, BMP via stb_image) on
// arbitrary bytes. Must fail cleanly or return an image whose buffer matches its size.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "tessera/io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  tessera::Result<tessera::ImageRGBA8> img =
      tessera::io::decode_image(std::span<const std::uint8_t>(data, size), "fuzz");
  if (img) {
    if (img->pixels.size() != img->pixel_count() * 4) std::abort();
  } else if (img.status().message.empty()) {
    std::abort();
  }
  return 0;
}
