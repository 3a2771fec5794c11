// Internal: files embedded into the library at build time by cmake/embed_files.cmake (the
// shipped GLSL, share/tessera/glsl). Each list is sorted by name; the bytes live for the
// program's lifetime.
#pragma once

#include <span>
#include <string_view>

namespace tessera {

struct EmbeddedFile {
  std::string_view name;  ///< Path relative to the embedded folder, e.g. "seams.glsl".
  std::string_view data;  ///< The file's bytes.
};

namespace embedded {
/// share/tessera/glsl: every shipped GLSL file (src/glsl/glsl_files.cpp, generated).
std::span<const EmbeddedFile> glsl_files();
}  // namespace embedded

}  // namespace tessera
