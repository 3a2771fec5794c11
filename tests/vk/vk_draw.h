// The Vulkan test engine's forward pass (vk_harness.h's Engine): GLSL stages compiled at run time
// with shaderc (as an engine that builds its shaders at load would), one indexed draw into an
// RGBA32F colour target with D32 depth through a classic render pass, and the image read back.
// The engine's frame uniform block is set 0, binding 0; a component's descriptor set goes at
// the set index the test chooses (bound by the component's own `bind` through a callback).
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "tessera/core.h"
#include "vk_harness.h"

namespace tessera::vk_test {

/// GLSL (already include-expanded) to SPIR-V for Vulkan 1.1 (VULKAN defined); the status is
/// shaderc's log on failure.
Result<std::vector<std::uint32_t>> compile_glsl(VkShaderStageFlagBits stage,
                                                const std::string& text, const std::string& name);

struct DrawInput {
  int width = 0, height = 0;
  std::vector<float> background;  ///< RGBA, width * height * 4 (the target's contents first).
  const void* vertices = nullptr;
  std::size_t vertex_bytes = 0;
  std::uint32_t stride = 0;
  std::vector<VkVertexInputAttributeDescription> attributes;  ///< binding 0
  std::vector<std::uint32_t> indices;
  std::vector<std::uint8_t> frame;  ///< The set-0 uniform block's bytes.
  std::vector<std::uint32_t> vertex_spirv, fragment_spirv;
  /// The component's set layout, at `component_set` (>= 1; holes get an empty layout).
  VkDescriptorSetLayout component_layout = VK_NULL_HANDLE;
  std::uint32_t component_set = 1;
  std::function<Status(VkCommandBuffer, VkPipelineLayout)> bind_component;
  /// Recorded into the frame's command buffer before its render pass (an upload); optional.
  std::function<Status(VkCommandBuffer)> before_pass;
  bool cull_back = true;  ///< Counter-clockwise front faces, as the CPU renderers.
};

/// Draws `in` (negative viewport height: +y up as GL, so GL's matrices and winding apply;
/// the vertex shader maps GL's z to Vulkan's 0..1) and returns the RGBA pixels, top row first.
Result<std::vector<float>> draw(Engine& engine, const DrawInput& in);

}  // namespace tessera::vk_test
