// The engine's device checked and its entry points loaded (tessera/vk.h), and the buffers and
// images components own.
#include "vk/vk_api.h"

namespace tessera::vk {

const char* result_name(VkResult r) {
  switch (r) {
#define TESSERA_VK_CASE(x) \
  case x:                  \
    return #x;
    TESSERA_VK_CASE(VK_SUCCESS)
    TESSERA_VK_CASE(VK_NOT_READY)
    TESSERA_VK_CASE(VK_TIMEOUT)
    TESSERA_VK_CASE(VK_INCOMPLETE)
    TESSERA_VK_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    TESSERA_VK_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    TESSERA_VK_CASE(VK_ERROR_INITIALIZATION_FAILED)
    TESSERA_VK_CASE(VK_ERROR_DEVICE_LOST)
    TESSERA_VK_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    TESSERA_VK_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    TESSERA_VK_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    TESSERA_VK_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    TESSERA_VK_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    TESSERA_VK_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    TESSERA_VK_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    TESSERA_VK_CASE(VK_ERROR_FRAGMENTED_POOL)
    TESSERA_VK_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
    TESSERA_VK_CASE(VK_ERROR_INVALID_SHADER_NV)
#undef TESSERA_VK_CASE
    default:
      return "VK_ERROR_UNKNOWN";
  }
}

ErrorCode result_code(VkResult result) {
  switch (result) {
    case VK_SUCCESS:
      return ErrorCode::ok;
    case VK_ERROR_OUT_OF_HOST_MEMORY:
    case VK_ERROR_OUT_OF_DEVICE_MEMORY:
    case VK_ERROR_OUT_OF_POOL_MEMORY:
    case VK_ERROR_FRAGMENTED_POOL:
    case VK_ERROR_TOO_MANY_OBJECTS:
      return ErrorCode::out_of_memory;
    case VK_ERROR_DEVICE_LOST:
      return ErrorCode::device_lost;
    default:
      return ErrorCode::unsupported;
  }
}

Status vk_error(const std::string& what, VkResult r) {
  return Status::error(result_code(r), what + ": " + result_name(r));
}

namespace {

Status invalid(const std::string& what) {
  return Status::error(ErrorCode::invalid_argument, "vulkan device: " + what);
}

}  // namespace

Result<Api> load_api(const DeviceContext& ctx) {
  if (ctx.instance == VK_NULL_HANDLE) return invalid("no VkInstance");
  if (ctx.physical_device == VK_NULL_HANDLE) return invalid("no VkPhysicalDevice");
  if (ctx.device == VK_NULL_HANDLE) return invalid("no VkDevice");
  if (ctx.get_instance_proc_addr == nullptr) return invalid("no vkGetInstanceProcAddr");
  if (ctx.get_device_proc_addr == nullptr) return invalid("no vkGetDeviceProcAddr");
  Api api;
  api.ctx = ctx;
  std::string missing;
#define TESSERA_VK_LOAD_INSTANCE(name)                                                             \
  api.name = reinterpret_cast<PFN_vk##name>(ctx.get_instance_proc_addr(ctx.instance, "vk" #name)); \
  if (api.name == nullptr && missing.empty()) missing = "vk" #name;
#define TESSERA_VK_LOAD_DEVICE(name)                                                           \
  api.name = reinterpret_cast<PFN_vk##name>(ctx.get_device_proc_addr(ctx.device, "vk" #name)); \
  if (api.name == nullptr && missing.empty()) missing = "vk" #name;
  TESSERA_VK_INSTANCE_FUNCTIONS(TESSERA_VK_LOAD_INSTANCE)
  TESSERA_VK_DEVICE_FUNCTIONS(TESSERA_VK_LOAD_DEVICE)
#undef TESSERA_VK_LOAD_INSTANCE
#undef TESSERA_VK_LOAD_DEVICE
  if (!missing.empty()) {
    return Status::error(ErrorCode::unsupported, "vulkan device: no entry point " + missing);
  }
  if (ctx.synchronization2) {
    const bool core = ctx.api_version >= VK_API_VERSION_1_3;
    api.CmdPipelineBarrier2 = reinterpret_cast<PFN_vkCmdPipelineBarrier2>(ctx.get_device_proc_addr(
        ctx.device, core ? "vkCmdPipelineBarrier2" : "vkCmdPipelineBarrier2KHR"));
    api.CmdWriteTimestamp2 = reinterpret_cast<PFN_vkCmdWriteTimestamp2>(ctx.get_device_proc_addr(
        ctx.device, core ? "vkCmdWriteTimestamp2" : "vkCmdWriteTimestamp2KHR"));
    if (api.CmdPipelineBarrier2 == nullptr || api.CmdWriteTimestamp2 == nullptr) {
      return Status::error(ErrorCode::unsupported,
                           std::string("vulkan device: synchronization2 is set but ") +
                               (core ? "vkCmdPipelineBarrier2" : "vkCmdPipelineBarrier2KHR") +
                               " is missing (enable the feature, or VK_KHR_synchronization2)");
    }
  }
  api.GetPhysicalDeviceProperties(ctx.physical_device, &api.properties);
  api.GetPhysicalDeviceMemoryProperties(ctx.physical_device, &api.memory);
  std::uint32_t families = 0;
  api.GetPhysicalDeviceQueueFamilyProperties(ctx.physical_device, &families, nullptr);
  std::vector<VkQueueFamilyProperties> props(families);
  api.GetPhysicalDeviceQueueFamilyProperties(ctx.physical_device, &families, props.data());
  if (ctx.queue_family >= families) {
    return invalid("queue_family = " + std::to_string(ctx.queue_family) + " (the device has " +
                   std::to_string(families) + ")");
  }
  api.queue_family = props[ctx.queue_family];
  if ((api.queue_family.queueFlags & VK_QUEUE_COMPUTE_BIT) == 0) {
    return Status::error(ErrorCode::unsupported, "vulkan device: queue family " +
                                                     std::to_string(ctx.queue_family) +
                                                     " has no VK_QUEUE_COMPUTE_BIT");
  }
  return api;
}

Status check_device(const DeviceContext& device) { return load_api(device).status(); }

namespace {

/// The first memory type of `bits` with all of `want`; -1 if none.
int memory_type(const Api& api, std::uint32_t bits, VkMemoryPropertyFlags want) {
  for (std::uint32_t i = 0; i < api.memory.memoryTypeCount; ++i) {
    if ((bits & (1u << i)) != 0 && (api.memory.memoryTypes[i].propertyFlags & want) == want) {
      return int(i);
    }
  }
  return -1;
}

}  // namespace

Result<VkDeviceMemory> allocate(const Api& api, const VkMemoryRequirements& req,
                                VkMemoryPropertyFlags want, VkMemoryPropertyFlags fallback,
                                const std::string& what, bool* got_want) {
  int type = memory_type(api, req.memoryTypeBits, want);
  *got_want = type >= 0;
  if (type < 0) type = memory_type(api, req.memoryTypeBits, fallback);
  if (type < 0) {
    return Status::error(ErrorCode::unsupported, what + ": no suitable memory type");
  }
  VkMemoryAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = std::uint32_t(type);
  VkDeviceMemory mem = VK_NULL_HANDLE;
  if (VkResult r = api.AllocateMemory(api.device(), &ai, api.alloc(), &mem); r != VK_SUCCESS) {
    return vk_error(what + ": vkAllocateMemory of " + std::to_string(req.size) + " bytes", r);
  }
  return mem;
}

Buffer& Buffer::operator=(Buffer&& o) noexcept {
  if (this != &o) {
    reset();
    api_ = o.api_;
    buffer_ = std::exchange(o.buffer_, VkBuffer(VK_NULL_HANDLE));
    memory_ = std::exchange(o.memory_, VkDeviceMemory(VK_NULL_HANDLE));
    size_ = std::exchange(o.size_, 0);
    mapped_ = std::exchange(o.mapped_, nullptr);
    coherent_ = o.coherent_;
  }
  return *this;
}

void Buffer::reset() {
  if (api_ == nullptr) return;
  if (mapped_ != nullptr) api_->UnmapMemory(api_->device(), memory_);
  if (buffer_ != VK_NULL_HANDLE) api_->DestroyBuffer(api_->device(), buffer_, api_->alloc());
  if (memory_ != VK_NULL_HANDLE) api_->FreeMemory(api_->device(), memory_, api_->alloc());
  buffer_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
  mapped_ = nullptr;
  size_ = 0;
}

void Buffer::invalidate() const {
  if (coherent_ || mapped_ == nullptr) return;
  VkMappedMemoryRange range{};
  range.sType = VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE;
  range.memory = memory_;
  range.size = VK_WHOLE_SIZE;
  (void)api_->InvalidateMappedMemoryRanges(api_->device(), 1, &range);  // only OOM can fail
}

void Buffer::flush() const {
  if (coherent_ || mapped_ == nullptr) return;
  VkMappedMemoryRange range{};
  range.sType = VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE;
  range.memory = memory_;
  range.size = VK_WHOLE_SIZE;
  (void)api_->FlushMappedMemoryRanges(api_->device(), 1, &range);  // only OOM can fail
}

Result<Buffer> Buffer::create(const Api& api, VkDeviceSize bytes, VkBufferUsageFlags usage,
                              bool host_visible, const std::string& what) {
  Buffer b;
  b.api_ = &api;
  b.size_ = bytes;
  VkBufferCreateInfo ci{};
  ci.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  ci.size = bytes;
  ci.usage = usage;
  ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  if (VkResult r = api.CreateBuffer(api.device(), &ci, api.alloc(), &b.buffer_); r != VK_SUCCESS) {
    return vk_error(what + ": vkCreateBuffer", r);
  }
  VkMemoryRequirements req{};
  api.GetBufferMemoryRequirements(api.device(), b.buffer_, &req);
  bool coherent = false;
  const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
  Result<VkDeviceMemory> mem =
      host_visible
          ? allocate(api, req, host | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT, host, what, &coherent)
          : allocate(api, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0, what, &coherent);
  if (!mem) return mem.status();
  b.memory_ = *mem;
  b.coherent_ = coherent || !host_visible;
  if (VkResult r = api.BindBufferMemory(api.device(), b.buffer_, b.memory_, 0); r != VK_SUCCESS) {
    return vk_error(what + ": vkBindBufferMemory", r);
  }
  if (host_visible) {
    if (VkResult r = api.MapMemory(api.device(), b.memory_, 0, VK_WHOLE_SIZE, 0, &b.mapped_);
        r != VK_SUCCESS) {
      return vk_error(what + ": vkMapMemory", r);
    }
  }
  return b;
}

Image& Image::operator=(Image&& o) noexcept {
  if (this != &o) {
    reset();
    api_ = o.api_;
    image_ = std::exchange(o.image_, VkImage(VK_NULL_HANDLE));
    view_ = std::exchange(o.view_, VkImageView(VK_NULL_HANDLE));
    memory_ = std::exchange(o.memory_, VkDeviceMemory(VK_NULL_HANDLE));
    format_ = o.format_;
    extent_ = o.extent_;
    usage_ = o.usage_;
  }
  return *this;
}

void Image::reset() {
  if (api_ == nullptr) return;
  if (view_ != VK_NULL_HANDLE) api_->DestroyImageView(api_->device(), view_, api_->alloc());
  if (image_ != VK_NULL_HANDLE) api_->DestroyImage(api_->device(), image_, api_->alloc());
  if (memory_ != VK_NULL_HANDLE) api_->FreeMemory(api_->device(), memory_, api_->alloc());
  view_ = VK_NULL_HANDLE;
  image_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
}

Result<Image> Image::create(const Api& api, VkFormat format, VkExtent2D extent,
                            VkImageUsageFlags usage, const std::string& what) {
  Image img;
  img.api_ = &api;
  img.format_ = format;
  img.extent_ = extent;
  img.usage_ = usage;
  VkImageCreateInfo ci{};
  ci.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
  ci.imageType = VK_IMAGE_TYPE_2D;
  ci.format = format;
  ci.extent = {extent.width, extent.height, 1};
  ci.mipLevels = 1;
  ci.arrayLayers = 1;
  ci.samples = VK_SAMPLE_COUNT_1_BIT;
  ci.tiling = VK_IMAGE_TILING_OPTIMAL;
  ci.usage = usage;
  ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  if (VkResult r = api.CreateImage(api.device(), &ci, api.alloc(), &img.image_); r != VK_SUCCESS) {
    return vk_error(what + ": vkCreateImage", r);
  }
  VkMemoryRequirements req{};
  api.GetImageMemoryRequirements(api.device(), img.image_, &req);
  bool local = false;
  Result<VkDeviceMemory> mem =
      allocate(api, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0, what, &local);
  if (!mem) return mem.status();
  img.memory_ = *mem;
  if (VkResult r = api.BindImageMemory(api.device(), img.image_, img.memory_, 0); r != VK_SUCCESS) {
    return vk_error(what + ": vkBindImageMemory", r);
  }
  VkImageViewCreateInfo vi{};
  vi.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
  vi.image = img.image_;
  vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
  vi.format = format;
  const bool depth = format == VK_FORMAT_D32_SFLOAT || format == VK_FORMAT_D16_UNORM;
  vi.subresourceRange = {depth ? VkImageAspectFlags(VK_IMAGE_ASPECT_DEPTH_BIT)
                               : VkImageAspectFlags(VK_IMAGE_ASPECT_COLOR_BIT),
                         0, 1, 0, 1};
  if (VkResult r = api.CreateImageView(api.device(), &vi, api.alloc(), &img.view_);
      r != VK_SUCCESS) {
    return vk_error(what + ": vkCreateImageView", r);
  }
  return img;
}

}  // namespace tessera::vk
