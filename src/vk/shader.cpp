// GLSL to SPIR-V through the compiler module tessera-vk-glsl.so (glsl_module.cpp, loaded here
// the first time tessera::vk compiles: the hook is known only at run time, see
// tessera/vk_adaptive.h; the experiments' graphics stages are compiled the same way), and
// compute pipelines.
#include "vk/shader.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>

#include "vk/glsl_module.h"

namespace tessera::vk {

namespace {

struct GlslModule {
  TesseraVkGlslCompile compile = nullptr;
  TesseraVkGlslFree free = nullptr;
  std::string why;  // when it could not be loaded
};

/// Where the module may be: $TESSERA_VK_GLSL; beside the program (bin/../lib/tessera/);
/// where it was installed; where it was built.
std::vector<std::string> module_candidates() {
  std::vector<std::string> c;
  if (const char* env = std::getenv("TESSERA_VK_GLSL"); env && *env) c.push_back(env);
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec)
    c.push_back((exe.parent_path() / ".." / "lib" / "tessera" / "tessera-vk-glsl.so").string());
#ifdef TESSERA_VK_GLSL_INSTALLED
  c.push_back(TESSERA_VK_GLSL_INSTALLED);
#endif
#ifdef TESSERA_VK_GLSL_BUILD
  c.push_back(TESSERA_VK_GLSL_BUILD);
#endif
  return c;
}

const GlslModule& glsl_module() {
  static GlslModule m;
  static std::once_flag once;
  std::call_once(once, [] {
    std::string tried;
    for (const std::string& path : module_candidates()) {
      std::error_code ec;
      if (!std::filesystem::exists(path, ec)) {
        tried += (tried.empty() ? "" : ", ") + path;
        continue;
      }
      void* h = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (h == nullptr) {
        m.why = path + ": " + dlerror();
        return;
      }
      m.compile = reinterpret_cast<TesseraVkGlslCompile>(dlsym(h, "tessera_vk_glsl_compile"));
      m.free = reinterpret_cast<TesseraVkGlslFree>(dlsym(h, "tessera_vk_glsl_free"));
      if (m.compile == nullptr || m.free == nullptr) {
        m.compile = nullptr;
        m.why = path + ": not tessera's GLSL compiler module";
      }
      return;  // the module stays loaded for the process
    }
    m.why = "no GLSL compiler module tessera-vk-glsl.so (looked at " + tried +
            "; set TESSERA_VK_GLSL, or give a shader binary)";
  });
  return m;
}

Result<std::vector<std::uint32_t>> compile_spirv(const std::string& text, int stage) {
  const GlslModule& m = glsl_module();
  if (m.compile == nullptr) return Status::error(ErrorCode::unsupported, m.why);
  std::uint32_t* words = nullptr;
  std::size_t count = 0;
  char* log = nullptr;
  const int r = m.compile(text.data(), text.size(), stage, &words, &count, &log);
  const std::string message = log != nullptr ? log : "";
  std::vector<std::uint32_t> spirv;
  if (r == TESSERA_VK_GLSL_OK) spirv.assign(words, words + count);
  m.free(words);
  m.free(log);
  if (r == TESSERA_VK_GLSL_ERROR) return Status::error(ErrorCode::invalid_argument, message);
  if (r != TESSERA_VK_GLSL_OK) return Status::error(ErrorCode::unsupported, message);
  return spirv;
}

}  // namespace

Result<std::vector<std::uint32_t>> compile_compute_spirv(const std::string& text) {
  return compile_spirv(text, TESSERA_VK_GLSL_COMPUTE);
}

Result<std::vector<std::uint32_t>> compile_graphics_spirv(const std::string& text,
                                                          glsl::Stage stage) {
  switch (stage) {
    case glsl::Stage::vertex:
      return compile_spirv(text, TESSERA_VK_GLSL_VERTEX);
    case glsl::Stage::fragment:
      return compile_spirv(text, TESSERA_VK_GLSL_FRAGMENT);
    default:
      return Status::error(ErrorCode::invalid_argument,
                           "shaderc: compile_graphics_spirv takes a vertex or fragment stage");
  }
}

Result<Pipeline> create_compute_pipeline(const Api& api, const std::vector<std::uint32_t>& spirv,
                                         VkPipelineLayout layout, const std::string& what,
                                         VkPipelineCache cache,
                                         const VkSpecializationInfo* specialization) {
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
  pi.stage.pSpecializationInfo = specialization;
  pi.layout = layout;
  VkPipeline raw = VK_NULL_HANDLE;
  if (VkResult r = api.CreateComputePipelines(api.device(), cache, 1, &pi, api.alloc(), &raw);
      r != VK_SUCCESS) {
    return vk_error(what + ": vkCreateComputePipelines", r);
  }
  return Pipeline(api, raw);
}

}  // namespace tessera::vk
