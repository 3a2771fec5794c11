// Internal to src/vk: the Vulkan entry points tessera records with, loaded from the engine's
// vkGetInstanceProcAddr / vkGetDeviceProcAddr (tessera links no loader symbol: the library is
// compiled with VK_NO_PROTOTYPES), the device facts components check, and RAII owners of the
// objects they create.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "tessera/vk.h"

namespace tessera::vk {

// Instance-level entry points (vkGetInstanceProcAddr).
#define TESSERA_VK_INSTANCE_FUNCTIONS(X)    \
  X(GetPhysicalDeviceProperties)            \
  X(GetPhysicalDeviceMemoryProperties)      \
  X(GetPhysicalDeviceQueueFamilyProperties) \
  X(GetPhysicalDeviceFormatProperties)      \
  X(GetPhysicalDeviceFeatures)              \
  X(GetPhysicalDeviceImageFormatProperties)

// Device-level core 1.0 entry points (vkGetDeviceProcAddr).
#define TESSERA_VK_DEVICE_FUNCTIONS(X) \
  X(CreateBuffer)                      \
  X(DestroyBuffer)                     \
  X(GetBufferMemoryRequirements)       \
  X(BindBufferMemory)                  \
  X(CreateImage)                       \
  X(DestroyImage)                      \
  X(GetImageMemoryRequirements)        \
  X(BindImageMemory)                   \
  X(CreateImageView)                   \
  X(DestroyImageView)                  \
  X(AllocateMemory)                    \
  X(FreeMemory)                        \
  X(MapMemory)                         \
  X(UnmapMemory)                       \
  X(InvalidateMappedMemoryRanges)      \
  X(CreateSampler)                     \
  X(DestroySampler)                    \
  X(CreateDescriptorSetLayout)         \
  X(DestroyDescriptorSetLayout)        \
  X(CreatePipelineLayout)              \
  X(DestroyPipelineLayout)             \
  X(CreateShaderModule)                \
  X(DestroyShaderModule)               \
  X(CreateComputePipelines)            \
  X(DestroyPipeline)                   \
  X(CreateDescriptorPool)              \
  X(DestroyDescriptorPool)             \
  X(AllocateDescriptorSets)            \
  X(UpdateDescriptorSets)              \
  X(CreateQueryPool)                   \
  X(DestroyQueryPool)                  \
  X(GetQueryPoolResults)               \
  X(CmdBindPipeline)                   \
  X(CmdBindDescriptorSets)             \
  X(CmdDispatch)                       \
  X(CmdDispatchIndirect)               \
  X(CmdPipelineBarrier)                \
  X(CmdUpdateBuffer)                   \
  X(CmdFillBuffer)                     \
  X(CmdCopyBuffer)                     \
  X(CmdWriteTimestamp)                 \
  X(CmdResetQueryPool)                 \
  X(CmdCopyQueryPoolResults)           \
  X(CmdCopyBufferToImage)              \
  X(FlushMappedMemoryRanges)           \
  X(CreateCommandPool)                 \
  X(DestroyCommandPool)                \
  X(AllocateCommandBuffers)            \
  X(BeginCommandBuffer)                \
  X(EndCommandBuffer)                  \
  X(QueueSubmit)                       \
  X(CreateFence)                       \
  X(DestroyFence)                      \
  X(WaitForFences)                     \
  TESSERA_VK_GRAPHICS_FUNCTIONS(X)

// Device-level core 1.0 entry points of drawing and read-back: what the experiments' Vulkan
// backends (a device of their own, headless_device.h) record besides the components'.
#define TESSERA_VK_GRAPHICS_FUNCTIONS(X) \
  X(CreateGraphicsPipelines)             \
  X(CreateRenderPass)                    \
  X(DestroyRenderPass)                   \
  X(CreateFramebuffer)                   \
  X(DestroyFramebuffer)                  \
  X(CmdBeginRenderPass)                  \
  X(CmdEndRenderPass)                    \
  X(CmdBindVertexBuffers)                \
  X(CmdBindIndexBuffer)                  \
  X(CmdDraw)                             \
  X(CmdDrawIndexed)                      \
  X(CmdSetViewport)                      \
  X(CmdSetScissor)                       \
  X(CmdPushConstants)                    \
  X(CmdCopyImageToBuffer)                \
  X(CmdCopyImage)                        \
  X(CmdResolveImage)                     \
  X(CmdClearColorImage)                  \
  X(CmdBlitImage)                        \
  X(FreeCommandBuffers)                  \
  X(ResetCommandPool)                    \
  X(ResetFences)                         \
  X(QueueWaitIdle)                       \
  X(DeviceWaitIdle)

/// The loaded table plus what components check about the device.
struct Api {
  DeviceContext ctx;
#define TESSERA_VK_MEMBER(name) PFN_vk##name name = nullptr;
  TESSERA_VK_INSTANCE_FUNCTIONS(TESSERA_VK_MEMBER)
  TESSERA_VK_DEVICE_FUNCTIONS(TESSERA_VK_MEMBER)
#undef TESSERA_VK_MEMBER
  /// vkCmdPipelineBarrier2 (or ...KHR); null unless ctx.synchronization2.
  PFN_vkCmdPipelineBarrier2 CmdPipelineBarrier2 = nullptr;
  PFN_vkCmdWriteTimestamp2 CmdWriteTimestamp2 = nullptr;
  VkPhysicalDeviceProperties properties{};
  VkPhysicalDeviceMemoryProperties memory{};
  VkQueueFamilyProperties queue_family{};

  const VkAllocationCallbacks* alloc() const { return ctx.allocator; }
  VkDevice device() const { return ctx.device; }
};

/// Checks `ctx` (as check_device) and loads the table.
Result<Api> load_api(const DeviceContext& ctx);

/// A failed Vulkan call as an error status: unsupported, "what: VK_ERROR_...".
Status vk_error(const std::string& what, VkResult r);

/// Device memory for `req`: a type with all of `want`, else one with all of `fallback`
/// (`*got_want` says which); unsupported naming `what` when none fits or the allocation fails.
Result<VkDeviceMemory> allocate(const Api& api, const VkMemoryRequirements& req,
                                VkMemoryPropertyFlags want, VkMemoryPropertyFlags fallback,
                                const std::string& what, bool* got_want);

/// A buffer and its memory, destroyed together.
class Buffer {
 public:
  Buffer() = default;
  Buffer(Buffer&& o) noexcept { *this = std::move(o); }
  Buffer& operator=(Buffer&& o) noexcept;
  ~Buffer() { reset(); }
  static Result<Buffer> create(const Api& api, VkDeviceSize bytes, VkBufferUsageFlags usage,
                               bool host_visible, const std::string& what);
  void reset();
  VkBuffer get() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  /// Host-visible buffers: the mapped pointer (coherent or invalidated by `invalidate`).
  void* mapped() const { return mapped_; }
  void invalidate() const;
  /// Host-visible buffers: makes host writes through `mapped()` visible to the device.
  void flush() const;

 private:
  const Api* api_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkDeviceSize size_ = 0;
  void* mapped_ = nullptr;
  bool coherent_ = true;
};

/// A 2D device-local image, its memory and a view (of the depth aspect for D32_SFLOAT and
/// D16_UNORM, else of the colour aspect).
class Image {
 public:
  Image() = default;
  Image(Image&& o) noexcept { *this = std::move(o); }
  Image& operator=(Image&& o) noexcept;
  ~Image() { reset(); }
  static Result<Image> create(const Api& api, VkFormat format, VkExtent2D extent,
                              VkImageUsageFlags usage, const std::string& what);
  void reset();
  VkImage get() const { return image_; }
  VkImageView view() const { return view_; }
  VkFormat format() const { return format_; }
  VkExtent2D extent() const { return extent_; }
  VkImageUsageFlags usage() const { return usage_; }

 private:
  const Api* api_ = nullptr;
  VkImage image_ = VK_NULL_HANDLE;
  VkImageView view_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkExtent2D extent_{0, 0};
  VkImageUsageFlags usage_ = 0;
};

/// Any other device object destroyed with `vkDestroyX(device, handle, allocator)`.
template <class Handle, auto Api::*Destroy>
class Owned {
 public:
  Owned() = default;
  Owned(const Api& api, Handle h) : api_(&api), h_(h) {}
  Owned(Owned&& o) noexcept : api_(o.api_), h_(std::exchange(o.h_, Handle(VK_NULL_HANDLE))) {}
  Owned& operator=(Owned&& o) noexcept {
    if (this != &o) {
      reset();
      api_ = o.api_;
      h_ = std::exchange(o.h_, Handle(VK_NULL_HANDLE));
    }
    return *this;
  }
  ~Owned() { reset(); }
  void reset() {
    if (h_ != VK_NULL_HANDLE) (api_->*Destroy)(api_->device(), h_, api_->alloc());
    h_ = VK_NULL_HANDLE;
  }
  Handle get() const { return h_; }

 private:
  const Api* api_ = nullptr;
  Handle h_ = VK_NULL_HANDLE;
};
using Sampler = Owned<VkSampler, &Api::DestroySampler>;
using SetLayout = Owned<VkDescriptorSetLayout, &Api::DestroyDescriptorSetLayout>;
using PipelineLayout = Owned<VkPipelineLayout, &Api::DestroyPipelineLayout>;
using ShaderModule = Owned<VkShaderModule, &Api::DestroyShaderModule>;
using Pipeline = Owned<VkPipeline, &Api::DestroyPipeline>;
using DescriptorPool = Owned<VkDescriptorPool, &Api::DestroyDescriptorPool>;
using QueryPool = Owned<VkQueryPool, &Api::DestroyQueryPool>;
using RawImage = Owned<VkImage, &Api::DestroyImage>;
using ImageView = Owned<VkImageView, &Api::DestroyImageView>;
using Memory = Owned<VkDeviceMemory, &Api::FreeMemory>;
using CommandPool = Owned<VkCommandPool, &Api::DestroyCommandPool>;
using Fence = Owned<VkFence, &Api::DestroyFence>;
using RenderPass = Owned<VkRenderPass, &Api::DestroyRenderPass>;
using Framebuffer = Owned<VkFramebuffer, &Api::DestroyFramebuffer>;

}  // namespace tessera::vk
