// stb_decoder.h — tessera's private entry points into stb_image (JPEG, TGA and BMP input).
//
// stb_image is compiled into the library (stb_image_impl.cpp) with internal linkage instead of
// being linked from libstb.so: the CLI maps and relocates one shared library fewer at every
// start, and a program that links tessera and its own stb sees no duplicate stbi_* symbols.
// These wrappers are the only way in; they behave exactly as the stbi_* calls they name.
#pragma once

namespace tessera::io::detail {

/// stbi_info_from_memory: true when the header is readable; fills width, height, components.
bool stb_info(const unsigned char* data, int size, int* width, int* height, int* components);
/// stbi_load_from_memory with 4 requested components (RGBA8); nullptr on failure. Free the
/// result with `stb_free`.
unsigned char* stb_load_rgba(const unsigned char* data, int size, int* width, int* height,
                             int* components);
/// stbi_image_free.
void stb_free(unsigned char* pixels);
/// stbi_failure_reason: the last error of the calling thread.
const char* stb_failure_reason();

}  // namespace tessera::io::detail
