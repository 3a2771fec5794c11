// stb_image_write (Debian libstb-dev) compiled into tessera for BMP, TGA and JPEG output, to
// memory only, every stbi_* function static (see stb_encoder.h). PNG output goes through
// libspng (image_io.cpp). src/CMakeLists.txt builds this file without the sanitizers, as it
// does the other third-party *_impl.cpp files.
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO
#include <stb_image_write.h>

#include "io/stb_encoder.h"

namespace tessera::io::detail {

namespace {
void append(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(context);
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  out->insert(out->end(), bytes, bytes + size);
}
}  // namespace

bool stb_encode(StbFormat format, int width, int height, int components, const std::uint8_t* pixels,
                std::vector<std::uint8_t>& out) {
  out.clear();
  switch (format) {
    case StbFormat::bmp:
      return stbi_write_bmp_to_func(append, &out, width, height, components, pixels) != 0;
    case StbFormat::tga:
      return stbi_write_tga_to_func(append, &out, width, height, components, pixels) != 0;
    case StbFormat::jpeg:
      return stbi_write_jpg_to_func(append, &out, width, height, components, pixels, 95) != 0;
  }
  return false;
}

}  // namespace tessera::io::detail
