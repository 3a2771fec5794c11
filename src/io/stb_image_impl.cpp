// stb_image (Debian libstb-dev, the same header libstb.so is built from) compiled into tessera:
// the JPEG, TGA and BMP decoders only (PNG goes through libdeflate / libspng), from memory
// only, every stbi_* function static (see stb_decoder.h). src/CMakeLists.txt builds this file
// without the sanitizers, as the shared library it replaces was.
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_JPEG
#define STBI_ONLY_BMP
#define STBI_ONLY_TGA
#define STBI_NO_STDIO
#include <stb_image.h>

#include "io/stb_decoder.h"

namespace tessera::io::detail {

bool stb_info(const unsigned char* data, int size, int* width, int* height, int* components) {
  return stbi_info_from_memory(data, size, width, height, components) != 0;
}

unsigned char* stb_load_rgba(const unsigned char* data, int size, int* width, int* height,
                             int* components) {
  return stbi_load_from_memory(data, size, width, height, components, 4);
}

void stb_free(unsigned char* pixels) { stbi_image_free(pixels); }

const char* stb_failure_reason() { return stbi_failure_reason(); }

}  // namespace tessera::io::detail
