// engine_ptex_vk's own Vulkan plumbing (engine.h).
#include "engine.h"

#include <shaderc/shaderc.h>

#include <chrono>
#include <cstring>

namespace engine {

std::string Device::create(bool want_validation,
                           const std::vector<const char*>& instance_extensions,
                           const std::vector<const char*>& device_extensions) {
  VkPhysicalDeviceProperties props{};
  const std::string why = create_instance_and_pick("engine_ptex_vk", VK_API_VERSION_1_1,
                                                   want_validation, props, instance_extensions);
  if (!why.empty()) return why;
  api_version = props.apiVersion < VK_API_VERSION_1_3 ? props.apiVersion : VK_API_VERSION_1_3;
  return create_device(nullptr, device_extensions);
}

std::vector<std::uint32_t> compile(const std::string& glsl, bool vertex, const std::string& name,
                                   std::string& log) {
  shaderc_compiler_t compiler = shaderc_compiler_initialize();
  shaderc_compile_options_t options = shaderc_compile_options_initialize();
  shaderc_compile_options_set_target_env(options, shaderc_target_env_vulkan,
                                         shaderc_env_version_vulkan_1_1);
  shaderc_compilation_result_t r = shaderc_compile_into_spv(
      compiler, glsl.data(), glsl.size(), vertex ? shaderc_vertex_shader : shaderc_fragment_shader,
      name.c_str(), "main", options);
  std::vector<std::uint32_t> spirv;
  if (r != nullptr &&
      shaderc_result_get_compilation_status(r) == shaderc_compilation_status_success) {
    spirv.resize(shaderc_result_get_length(r) / 4);
    std::memcpy(spirv.data(), shaderc_result_get_bytes(r), spirv.size() * 4);
  } else {
    log = r != nullptr ? shaderc_result_get_error_message(r) : "shaderc: no result";
  }
  if (r != nullptr) shaderc_result_release(r);
  shaderc_compile_options_release(options);
  shaderc_compiler_release(compiler);
  return spirv;
}

}  // namespace engine
