// engine_ptex_vk's own Vulkan plumbing (nothing here is tessera's): an instance with the
// validation layer when it is installed (synchronization validation on, a messenger counting
// warnings and errors), a device with one graphics queue, host-visible buffers, GLSL compiled at
// load with shaderc, and a forward pass: one render pass into an RGBA32F colour target with D32
// depth, one graphics pipeline whose layout holds the engine's frame block at set 0 and the
// sets the caller adds, submit-and-wait, read-back.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "vk_pipelines.h"  // examples/common: instance, device (vk_engine.h), forward pass

namespace engine {

/// A Vulkan 1.1 device (vk_engine.h's DeviceBase) with no optional feature.
class Device : public DeviceBase {
 public:
  /// Creates everything; "" on success, else the reason (no device, ...). The extensions: a
  /// window's surface (instance) and swapchain (device), for --frame-loop --window.
  std::string create(bool validation, const std::vector<const char*>& instance_extensions = {},
                     const std::vector<const char*>& device_extensions = {});
  void destroy() { destroy_device_and_instance(); }

  std::uint32_t api_version = VK_API_VERSION_1_1;  // the device's, at most 1.3

  /// A host-visible buffer (vk_engine.h's) holding a copy of `data` (when not null).
  Buffer buffer(const void* data, VkDeviceSize bytes, VkBufferUsageFlags usage) {
    Buffer b = DeviceBase::buffer(bytes, usage, true);
    if (data != nullptr) std::memcpy(b.data, data, bytes);
    return b;
  }
  using DeviceBase::destroy;  // buffers
};

/// GLSL to SPIR-V for Vulkan 1.1 with shaderc; "" or shaderc's log in `log`.
std::vector<std::uint32_t> compile(const std::string& glsl, bool vertex, const std::string& name,
                                   std::string& log);

/// What one forward frame needs from the engine's scene.
struct Frame {
  int width = 0, height = 0;
  float background[4] = {0, 0, 0, 0};
  const void* vertices = nullptr;
  std::size_t vertex_bytes = 0;
  std::uint32_t stride = 0;
  std::vector<VkVertexInputAttributeDescription> attributes;
  std::vector<std::uint32_t> indices;
  std::vector<std::uint8_t> block;  // set 0, binding 0: the frame's uniform block
  std::vector<std::uint32_t> vertex_spirv, fragment_spirv;
  /// Extra set layouts (index 1, 2, ...; VK_NULL_HANDLE: an empty one) and what binds them.
  std::vector<VkDescriptorSetLayout> extra_layouts;
  std::function<std::string(VkCommandBuffer, VkPipelineLayout)> bind_extra;
  /// Recorded into the frame's command buffer before its render pass (uploads); "" or why not.
  std::function<std::string(VkCommandBuffer)> before_pass;
};

/// Draws `f` (negative viewport height: +y up as GL's matrices; the vertex stage maps GL's z)
/// and reads the RGBA32F target back, top row first; "" or the problem in `error`.
std::vector<float> draw(Device& d, const Frame& f, double* gpu_ms, std::string& error);

}  // namespace engine
