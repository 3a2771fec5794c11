// tessera/vk.h — the Vulkan runtime's hand-off (tessera::vk): how an engine gives tessera's
// Vulkan components its device, its images and its command buffers.
//
// The model is FidelityFX FSR2's Vulkan backend. The engine keeps its instance, device, queues,
// frame graph and command buffers; a component (vk::AdaptiveSupersampler in vk_adaptive.h,
// vk::FaceTextureSet in vk_faces.h) is created once on the engine's `DeviceContext`, owns its
// own pipelines, descriptor pool, buffers and images, and records its passes into the engine's
// VkCommandBuffer. tessera calls no Vulkan loader symbol: every entry point comes from
// the engine's vkGetInstanceProcAddr / vkGetDeviceProcAddr (the library is compiled with
// VK_NO_PROTOTYPES and links no libvulkan), so it runs on whatever loader, layer stack or
// volk-style table the engine uses. Images cross the boundary as `ImageResource`: image, view,
// format, extent, usage, the layout they are in and the stage/access of their last write, so the
// component can record the one barrier that makes them readable and say in which state it
// leaves them. Not thread-safe: one thread records a component at a time (the engine's rules
// for its command buffer apply).
//
// Frames in flight (the contract of every component that records per frame): the engine keeps
// F frames in flight, a ring of F frame slots each guarded by its own fence, and creates the
// component with `frames_in_flight = F`. Once per frame, before recording it, the engine calls
// `begin_frame(i)` with the frame's slot i < F, after waiting for the fence of the last
// submission that recorded the component in slot i (nothing to wait for the first F frames).
// Everything the GPU may still read or write after a submission and the host touches
// (descriptor sets, output images, query pools, read-back buffers) belongs to one (slot, view)
// pair: a record never rewrites what a submitted command buffer still uses, and no record waits
// for the GPU. Any number of records (views) per frame: the first frame that records more views
// than any before grows the slot's resources (allocations once; none after). The component's
// scratch buffers are shared by all records and ordered by the barrier each record begins with,
// so command buffers that record a component are submitted to one queue (or ordered across
// queues by the engine's semaphores). Results that come back to the host (read_profile) are
// read per (slot, view), once that frame's fence has signalled. Errors keep Vulkan's meaning:
// `result_code` below. Tests: tests/vk/vk_frames_test.cpp.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

#include "tessera/core.h"

namespace tessera::vk {

/// The engine's device, as FSR2's VkDeviceContext: everything below is owned by the engine and
/// must outlive every component created on it.
struct DeviceContext {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  /// The queue family of the command buffers the engine records components into (must
  /// support VK_QUEUE_COMPUTE_BIT), and one queue of it (used only by components that upload
  /// data at creation, e.g. the per-face textures; vk::AdaptiveSupersampler never submits).
  std::uint32_t queue_family = 0;
  VkQueue queue = VK_NULL_HANDLE;
  PFN_vkGetInstanceProcAddr get_instance_proc_addr = nullptr;
  PFN_vkGetDeviceProcAddr get_device_proc_addr = nullptr;
  /// The Vulkan version the engine's device runs at: min(VkApplicationInfo::apiVersion, the
  /// physical device's apiVersion). 1.3 makes vkCmdPipelineBarrier2 core.
  std::uint32_t api_version = VK_API_VERSION_1_0;
  /// The engine enabled VkPhysicalDeviceVulkan13Features::synchronization2 (or
  /// VK_KHR_synchronization2's feature): barriers are then recorded with vkCmdPipelineBarrier2
  /// (vkCmdPipelineBarrier2KHR below 1.3), else with vkCmdPipelineBarrier.
  bool synchronization2 = false;
  /// The core features the engine enabled in VkDeviceCreateInfo (a component names the one it
  /// lacks; Vulkan cannot be asked which features a VkDevice was created with).
  VkPhysicalDeviceFeatures enabled_features{};
  /// Host allocator for every object tessera creates (nullptr = the driver's).
  const VkAllocationCallbacks* allocator = nullptr;
};

/// One image the engine hands over (or a component hands back). The component reads it
/// through `view` (a 2D view of mip level 0, layer 0, colour aspect); `layout` is the layout it
/// is in when the recorded commands run; `stage`/`access` are the pipeline stage and access of
/// its last write before them (the source scope of the component's barrier). Values of the
/// synchronization2 flags; for a device without synchronization2 the component maps them to
/// the VkPipelineStageFlags/VkAccessFlags of vkCmdPipelineBarrier.
struct ImageResource {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkExtent2D extent{0, 0};
  VkImageUsageFlags usage = 0;  ///< The usage the image was created with.
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkPipelineStageFlags2 stage = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
  VkAccessFlags2 access = VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
};

/// Checks a DeviceContext before a component uses it: non-null handles and entry points, a
/// queue family that exists and supports compute, and every core entry point tessera records
/// with (invalid_argument / unsupported naming the first thing missing). Creates nothing.
Status check_device(const DeviceContext& device);

/// Vulkan's name of `result` ("VK_ERROR_OUT_OF_DEVICE_MEMORY", ...), for messages.
const char* result_name(VkResult result);
/// The error code every tessera::vk call returns for a failed `result`: out_of_memory for
/// VK_ERROR_OUT_OF_HOST_MEMORY / _DEVICE_MEMORY / _POOL_MEMORY, VK_ERROR_FRAGMENTED_POOL and
/// VK_ERROR_TOO_MANY_OBJECTS; device_lost for VK_ERROR_DEVICE_LOST; unsupported for the rest
/// (feature, format, extension, driver); ok for VK_SUCCESS. The message names the result.
ErrorCode result_code(VkResult result);

}  // namespace tessera::vk
