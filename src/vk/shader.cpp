// GLSL to SPIR-V with shaderc (the hook is known only at run time, see tessera/vk_adaptive.h;
// the experiments' graphics stages are compiled the same way), and compute pipelines.
#include "vk/shader.h"

#include <shaderc/shaderc.h>

#include <memory>

namespace tessera::vk {

namespace {

Result<std::vector<std::uint32_t>> compile_spirv(const std::string& text, shaderc_shader_kind kind) {
  std::unique_ptr<std::remove_pointer_t<shaderc_compiler_t>, void (*)(shaderc_compiler_t)> compiler(
      shaderc_compiler_initialize(), shaderc_compiler_release);
  std::unique_ptr<std::remove_pointer_t<shaderc_compile_options_t>,
                  void (*)(shaderc_compile_options_t)>
      options(shaderc_compile_options_initialize(), shaderc_compile_options_release);
  if (!compiler || !options) {
    return Status::error(ErrorCode::unsupported, "shaderc: cannot initialise the compiler");
  }
  shaderc_compile_options_set_target_env(options.get(), shaderc_target_env_vulkan,
                                         shaderc_env_version_vulkan_1_0);
  shaderc_compile_options_set_optimization_level(options.get(),
                                                 shaderc_optimization_level_performance);
  std::unique_ptr<std::remove_pointer_t<shaderc_compilation_result_t>,
                  void (*)(shaderc_compilation_result_t)>
      result(shaderc_compile_into_spv(compiler.get(), text.data(), text.size(),
                                      kind, "tessera", "main", options.get()),
             shaderc_result_release);
  if (!result) return Status::error(ErrorCode::unsupported, "shaderc: no result");
  if (shaderc_result_get_compilation_status(result.get()) != shaderc_compilation_status_success) {
    return Status::error(ErrorCode::invalid_argument,
                         shaderc_result_get_error_message(result.get()));
  }
  const std::size_t bytes = shaderc_result_get_length(result.get());
  std::vector<std::uint32_t> spirv(bytes / 4);
  const char* data = shaderc_result_get_bytes(result.get());
  std::copy(data, data + spirv.size() * 4, reinterpret_cast<char*>(spirv.data()));
  return spirv;
}

}  // namespace

Result<std::vector<std::uint32_t>> compile_compute_spirv(const std::string& text) {
  return compile_spirv(text, shaderc_compute_shader);
}

Result<std::vector<std::uint32_t>> compile_graphics_spirv(const std::string& text,
                                                          glsl::Stage stage) {
  switch (stage) {
    case glsl::Stage::vertex:
      return compile_spirv(text, shaderc_vertex_shader);
    case glsl::Stage::fragment:
      return compile_spirv(text, shaderc_fragment_shader);
    default:
      return Status::error(ErrorCode::invalid_argument,
                           "shaderc: compile_graphics_spirv takes a vertex or fragment stage");
  }
}

Result<Pipeline> create_compute_pipeline(const Api& api, const std::vector<std::uint32_t>& spirv,
                                         VkPipelineLayout layout, const std::string& what,
                                         VkPipelineCache cache) {
  VkShaderModuleCreateInfo mi{};
  mi.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  mi.codeSize = spirv.size() * 4;
  mi.pCode = spirv.data();
  VkShaderModule raw_module = VK_NULL_HANDLE;
  if (VkResult r = api.CreateShaderModule(api.device(), &mi, api.alloc(), &raw_module);
      r != VK_SUCCESS) {
    return vk_error(what + ": vkCreateShaderModule", r);
  }
  ShaderModule module(api, raw_module);
  VkComputePipelineCreateInfo pi{};
  pi.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
  pi.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  pi.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  pi.stage.module = module.get();
  pi.stage.pName = "main";
  pi.layout = layout;
  VkPipeline raw = VK_NULL_HANDLE;
  if (VkResult r =
          api.CreateComputePipelines(api.device(), cache, 1, &pi, api.alloc(), &raw);
      r != VK_SUCCESS) {
    return vk_error(what + ": vkCreateComputePipelines", r);
  }
  return Pipeline(api, raw);
}

}  // namespace tessera::vk
