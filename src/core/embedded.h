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
/// tessera::vk only: the SPIR-V of vk::AdaptiveSupersampler's embedded passes, "PASS.spv"
/// (tools/vk_passes + glslangValidator at build time; empty without glslangValidator).
std::span<const EmbeddedFile> adaptive_pass_spirv();
}  // namespace embedded

}  // namespace tessera
