// tessera-vk-glsl.so: the GLSL compiler of tessera::vk as a module the Vulkan runtime loads at run
// time (src/vk/shader.cpp), only when it must compile GLSL: an engine that gives
// AdaptiveSupersamplerOptions::shader_binary never loads it, and ships without a GLSL compiler.
// shaderc, glslang and SPIRV-Tools are linked into it from Debian's static archives with every
// one of their symbols local (-Wl,--exclude-libs,ALL; hidden visibility): an engine linking its
// own glslang or shaderc, of any version, meets none of them. Two C functions leave it.
#include "vk/glsl_module.h"

#include <shaderc/shaderc.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <type_traits>

namespace {

char* copy_text(const char* s) {
  const std::size_t n = std::strlen(s);
  char* out = static_cast<char*>(std::malloc(n + 1));
  if (out != nullptr) std::memcpy(out, s, n + 1);
  return out;
}

shaderc_shader_kind kind_of(int stage) {
  return stage == TESSERA_VK_GLSL_VERTEX     ? shaderc_vertex_shader
         : stage == TESSERA_VK_GLSL_FRAGMENT ? shaderc_fragment_shader
                                             : shaderc_compute_shader;
}

}  // namespace

extern "C" __attribute__((visibility("default"))) int tessera_vk_glsl_compile(
    const char* text, std::size_t length, int stage, std::uint32_t** words, std::size_t* count,
    char** log) {
  *words = nullptr;
  *count = 0;
  *log = nullptr;
  std::unique_ptr<std::remove_pointer_t<shaderc_compiler_t>, void (*)(shaderc_compiler_t)> compiler(
      shaderc_compiler_initialize(), shaderc_compiler_release);
  std::unique_ptr<std::remove_pointer_t<shaderc_compile_options_t>,
                  void (*)(shaderc_compile_options_t)>
      options(shaderc_compile_options_initialize(), shaderc_compile_options_release);
  if (!compiler || !options) {
    *log = copy_text("shaderc: cannot initialise the compiler");
    return TESSERA_VK_GLSL_FAILED;
  }
  shaderc_compile_options_set_target_env(options.get(), shaderc_target_env_vulkan,
                                         shaderc_env_version_vulkan_1_0);
  shaderc_compile_options_set_optimization_level(options.get(),
                                                 shaderc_optimization_level_performance);
  std::unique_ptr<std::remove_pointer_t<shaderc_compilation_result_t>,
                  void (*)(shaderc_compilation_result_t)>
      result(shaderc_compile_into_spv(compiler.get(), text, length, kind_of(stage), "tessera",
                                      "main", options.get()),
             shaderc_result_release);
  if (!result) {
    *log = copy_text("shaderc: no result");
    return TESSERA_VK_GLSL_FAILED;
  }
  if (shaderc_result_get_compilation_status(result.get()) != shaderc_compilation_status_success) {
    *log = copy_text(shaderc_result_get_error_message(result.get()));
    return TESSERA_VK_GLSL_ERROR;
  }
  const std::size_t bytes = shaderc_result_get_length(result.get());
  *words = static_cast<std::uint32_t*>(std::malloc(bytes == 0 ? 4 : bytes));
  if (*words == nullptr) {
    *log = copy_text("out of memory");
    return TESSERA_VK_GLSL_FAILED;
  }
  std::memcpy(*words, shaderc_result_get_bytes(result.get()), bytes);
  *count = bytes / 4;
  return TESSERA_VK_GLSL_OK;
}

extern "C" __attribute__((visibility("default"))) void tessera_vk_glsl_free(void* p) {
  std::free(p);
}
