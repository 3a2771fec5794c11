// Internal to src/vk: shader modules, and graphics pipelines for the experiments' drawing
// passes (the seam backend's face renderer; the stages compiled by shader.h's
// compile_graphics_spirv): triangle lists, a dynamic viewport and scissor, one render pass
// subpass, no blending.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tessera/glsl.h"
#include "vk/vk_api.h"

namespace tessera::vk {

/// Shipped GLSL file `file` (glsl::shipped_shader: embedded, or $TESSERA_GLSL_DIR) as `stage`
/// with `preamble` after #version, its includes expanded, compiled to SPIR-V
/// (compile_graphics_spirv); a compile error is "WHO: FILE:LINE: message" (glsl::format_log).
Result<std::vector<std::uint32_t>> compile_shipped_stage(glsl::Stage stage, const char* file,
                                                         const std::vector<std::string>& preamble,
                                                         const std::string& who);

/// A shader module of `spirv`; `what` names the caller in a failure.
Result<ShaderModule> create_shader_module(const Api& api, const std::vector<std::uint32_t>& spirv,
                                          const std::string& what);

/// What `create_graphics_pipeline` builds from.
struct GraphicsPipelineDesc {
  const std::vector<std::uint32_t>* vertex_spirv = nullptr;
  const std::vector<std::uint32_t>* fragment_spirv = nullptr;
  /// The fragment stage's specialization constants (null: none).
  const VkSpecializationInfo* fragment_specialization = nullptr;
  std::vector<VkVertexInputBindingDescription> bindings;
  std::vector<VkVertexInputAttributeDescription> attributes;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkRenderPass render_pass = VK_NULL_HANDLE;
  std::uint32_t subpass = 0;
  std::uint32_t colour_attachments = 1;  ///< Each written whole (RGBA), no blending.
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
  VkCullModeFlags cull = VK_CULL_MODE_BACK_BIT;
  VkFrontFace front_face = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  bool depth_test = true;  ///< With writes, compare `depth_compare`.
  /// Clip z in OpenGL's [-w, w] (VkPipelineViewportDepthClipControlCreateInfoEXT::
  /// negativeOneToOne; only where the device enabled VK_EXT_depth_clip_control).
  bool gl_depth = false;
  VkCompareOp depth_compare = VK_COMPARE_OP_LESS;
};

/// A graphics pipeline: triangle lists, fill, the desc's vertex input, culling, samples
/// (shading once per pixel: no sample shading) and depth state, viewport and scissor dynamic
/// (vkCmdSetViewport / vkCmdSetScissor before drawing). The modules are destroyed before it
/// returns. invalid_argument for a missing stage, layout or render pass.
Result<Pipeline> create_graphics_pipeline(const Api& api, const GraphicsPipelineDesc& desc,
                                          const std::string& what);

}  // namespace tessera::vk
