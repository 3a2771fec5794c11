// engine_aa_vk's own Vulkan plumbing (nothing here is tessera's): instance with the validation
// layer when it is installed (synchronization validation on, a messenger counting warnings and
// errors), a device with one graphics + compute queue, buffers, images, the geometry pipeline
// (dynamic rendering into the enlarged G-buffer), submit-and-wait, read-back.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

#include "vk_pipelines.h"  // examples/common: instance, device (vk_engine.h), pipelines

namespace engine {

struct Image {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkImageUsageFlags usage = 0;
  std::uint32_t w = 0, h = 0;
};

/// A Vulkan 1.3 device (vk_engine.h's DeviceBase) with synchronization2, dynamic rendering,
/// shaderFloat64 where the device has it, and a command pool.
class Device : public DeviceBase {
 public:
  /// Creates everything; "" on success, else the reason (no device, no Vulkan 1.3, ...). The
  /// extensions: a window's surface (instance) and swapchain (device), for --window.
  std::string create(bool validation, const std::vector<const char*>& instance_extensions = {},
                     const std::vector<const char*>& device_extensions = {});
  void destroy();

  using DeviceBase::destroy;  // buffers (vk_engine.h)
  Image image(VkFormat format, std::uint32_t w, std::uint32_t h, VkImageUsageFlags usage,
              VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT);
  void destroy(Image& i);
  VkCommandBuffer begin();
  void submit_and_wait(VkCommandBuffer cmd);
  /// The frame loop's: a fence, a submission of `cmd` (ended here) signalling it (waiting for
  /// `wait` at the transfer stage and signalling `signal` where given: the window's acquire and
  /// present), the wait for it (then reset), freeing a command buffer once its fence signalled.
  VkFence fence();
  void submit(VkCommandBuffer cmd, VkFence fence, VkSemaphore wait = VK_NULL_HANDLE,
              VkSemaphore signal = VK_NULL_HANDLE);
  void wait(VkFence fence);
  void free(VkCommandBuffer cmd);
  /// Reads an RGBA16F / R8_UINT image left in `layout` after (stage, access) (synchronization2).
  std::vector<std::uint8_t> read(const Image& img, std::size_t texel_bytes, VkImageLayout layout,
                                 VkPipelineStageFlags2 stage, VkAccessFlags2 access);

 private:
  VkCommandPool pool_ = VK_NULL_HANDLE;
};

/// A whole file's bytes ("" or the problem; a missing file reads as empty), and a file written
/// through a temporary and a rename ("" or the problem).
std::string read_file(const std::string& path, std::vector<std::uint8_t>& bytes);
std::string write_file(const std::string& path, const std::vector<std::uint8_t>& bytes);

/// One image barrier (synchronization2).
void barrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
             VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
             VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access,
             VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT);

/// The geometry pipeline: vertex (p, n, albedo, id), push constants view + proj, two colour
/// attachments (RGBA16F, RGBA8) and D32 depth, dynamic rendering.
struct GeometryPipeline {
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkPipeline pipeline = VK_NULL_HANDLE;
};
GeometryPipeline geometry_pipeline(Device& d);
void destroy(Device& d, GeometryPipeline& p);

}  // namespace engine
