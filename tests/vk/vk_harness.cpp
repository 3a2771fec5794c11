// The Vulkan tests' engine (vk_harness.h).
#include "vk_harness.h"

#include <cmath>
#include <cstring>
#include <limits>

#include "vk_engine.h"  // examples/common: the validation layer look-up

namespace tessera::vk_test {

namespace {

// The layer and its look-up: examples/common/vk_engine.h's, as the example engines'.
constexpr const char* kValidation = engine::kValidationLayer;
using engine::has_layer;

float half_to_float(std::uint16_t h) {
  const int e = (h >> 10) & 31, m = h & 1023;
  const float s = (h & 0x8000) ? -1.0f : 1.0f;
  if (e == 0) return s * std::ldexp(float(m), -24);
  if (e == 31) return m ? std::nanf("") : s * std::numeric_limits<float>::infinity();
  return s * std::ldexp(float(m | 1024), e - 25);
}

/// Synchronization2 stage/access to Vulkan 1.0 (the bits the tests use).
VkPipelineStageFlags stage1(VkPipelineStageFlags2 s) {
  VkPipelineStageFlags out = VkPipelineStageFlags(s & 0xffffffffull);
  if (s & (VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_CLEAR_BIT)) {
    out |= VK_PIPELINE_STAGE_TRANSFER_BIT;
  }
  return out != 0 ? out : VkPipelineStageFlags(VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT);
}
VkAccessFlags access1(VkAccessFlags2 a) {
  VkAccessFlags out = VkAccessFlags(a & 0xffffffffull);
  if (a & (VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT)) {
    out |= VK_ACCESS_SHADER_READ_BIT;
  }
  if (a & VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT) out |= VK_ACCESS_SHADER_WRITE_BIT;
  return out;
}

}  // namespace

VKAPI_ATTR VkBool32 VKAPI_CALL Engine::on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                  VkDebugUtilsMessageTypeFlagsEXT,
                                                  const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                  void* self) {
  auto* e = static_cast<Engine*>(self);
  if (severity & (VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                  VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT)) {
    e->messages_.fetch_add(1);
    if (e->texts_.size() < 4) e->texts_.push_back(data->pMessage ? data->pMessage : "?");
  }
  return VK_FALSE;
}

std::string Engine::first_messages() const {
  std::string out;
  for (const std::string& t : texts_) out += "\n  " + t;
  return out;
}

Result<std::unique_ptr<Engine>> Engine::create(const EngineOptions& options, std::string* missing) {
  std::unique_ptr<Engine> e(new Engine());
  *missing = "vulkan-validation";
  if (options.validation && !has_layer(kValidation)) {
    return Status::error(ErrorCode::unsupported,
                         "no VK_LAYER_KHRONOS_validation (Debian: vulkan-validationlayers)");
  }
  *missing = "vulkan";
  VkApplicationInfo app{};
  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = "tessera vk tests";
  app.apiVersion = VK_API_VERSION_1_3;
  const engine::ValidationChain chain(&Engine::on_message, e.get());
  const char* ext = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
  VkInstanceCreateInfo ii{};
  ii.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  ii.pApplicationInfo = &app;
  ii.enabledExtensionCount = 1;
  ii.ppEnabledExtensionNames = &ext;
  if (options.validation) {
    ii.enabledLayerCount = 1;
    ii.ppEnabledLayerNames = &kValidation;
    ii.pNext = &chain.features;
  }
  if (VkResult r = vkCreateInstance(&ii, nullptr, &e->ctx_.instance); r != VK_SUCCESS) {
    return Status::error(ErrorCode::unsupported,
                         std::string("vkCreateInstance: ") + vk::result_name(r));
  }
  auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
      vkGetInstanceProcAddr(e->ctx_.instance, "vkCreateDebugUtilsMessengerEXT"));
  if (create_messenger) {
    create_messenger(e->ctx_.instance, &chain.messenger, nullptr, &e->messenger_);
  }
  std::uint32_t n = 0;
  vkEnumeratePhysicalDevices(e->ctx_.instance, &n, nullptr);
  std::vector<VkPhysicalDevice> devices(n);
  vkEnumeratePhysicalDevices(e->ctx_.instance, &n, devices.data());
  for (VkPhysicalDevice d : devices) {
    std::uint32_t nf = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(d, &nf, nullptr);
    std::vector<VkQueueFamilyProperties> fams(nf);
    vkGetPhysicalDeviceQueueFamilyProperties(d, &nf, fams.data());
    for (std::uint32_t f = 0; f < nf; ++f) {
      const VkQueueFlags want = VK_QUEUE_COMPUTE_BIT | VK_QUEUE_GRAPHICS_BIT;
      if ((fams[f].queueFlags & want) == want && e->ctx_.physical_device == VK_NULL_HANDLE) {
        e->ctx_.physical_device = d;
        e->ctx_.queue_family = f;
      }
    }
  }
  if (e->ctx_.physical_device == VK_NULL_HANDLE) {
    return Status::error(ErrorCode::unsupported,
                         "no Vulkan device with a graphics + compute queue (Debian: "
                         "mesa-vulkan-drivers for lavapipe)");
  }
  VkPhysicalDeviceProperties props{};
  vkGetPhysicalDeviceProperties(e->ctx_.physical_device, &props);
  e->ctx_.api_version = std::min<std::uint32_t>(props.apiVersion, VK_API_VERSION_1_3);
  VkPhysicalDeviceFeatures supported{};
  vkGetPhysicalDeviceFeatures(e->ctx_.physical_device, &supported);
  e->ctx_.enabled_features.shaderStorageImageExtendedFormats =
      options.extended_formats ? supported.shaderStorageImageExtendedFormats : VK_FALSE;
  e->ctx_.enabled_features.shaderFloat64 = options.float64 ? supported.shaderFloat64 : VK_FALSE;
  VkPhysicalDeviceVulkan13Features f13{};
  f13.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES;
  f13.synchronization2 = VK_TRUE;
  // Timeline semaphores (core 1.2): the frames-in-flight tests hold the GPU behind with one.
  VkPhysicalDeviceVulkan12Features f12{};
  f12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
  f12.timelineSemaphore = VK_TRUE;
  e->ctx_.synchronization2 = options.synchronization2 && e->ctx_.api_version >= VK_API_VERSION_1_3;
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo qi{};
  qi.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
  qi.queueFamilyIndex = e->ctx_.queue_family;
  qi.queueCount = 1;
  qi.pQueuePriorities = &priority;
  VkDeviceCreateInfo di{};
  di.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  f12.pNext = e->ctx_.synchronization2 ? &f13 : nullptr;
  di.pNext = &f12;
  di.queueCreateInfoCount = 1;
  di.pQueueCreateInfos = &qi;
  di.pEnabledFeatures = &e->ctx_.enabled_features;
  if (VkResult r = vkCreateDevice(e->ctx_.physical_device, &di, nullptr, &e->ctx_.device);
      r != VK_SUCCESS) {
    return Status::error(ErrorCode::unsupported,
                         std::string("vkCreateDevice: ") + vk::result_name(r));
  }
  vkGetDeviceQueue(e->ctx_.device, e->ctx_.queue_family, 0, &e->ctx_.queue);
  e->ctx_.get_instance_proc_addr = vkGetInstanceProcAddr;
  e->ctx_.get_device_proc_addr = vkGetDeviceProcAddr;
  VkCommandPoolCreateInfo pi{};
  pi.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  pi.queueFamilyIndex = e->ctx_.queue_family;
  vkCreateCommandPool(e->ctx_.device, &pi, nullptr, &e->pool_);
  return e;
}

std::string Engine::device_name() const {
  VkPhysicalDeviceProperties props{};
  vkGetPhysicalDeviceProperties(ctx_.physical_device, &props);
  return props.deviceName;
}

void Engine::shutdown() {
  if (ctx_.device != VK_NULL_HANDLE) {
    vkDeviceWaitIdle(ctx_.device);
    vkDestroyCommandPool(ctx_.device, pool_, nullptr);
    vkDestroyDevice(ctx_.device, nullptr);
    ctx_.device = VK_NULL_HANDLE;
  }
  if (ctx_.instance != VK_NULL_HANDLE) {
    auto destroy_messenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(ctx_.instance, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy_messenger && messenger_) destroy_messenger(ctx_.instance, messenger_, nullptr);
    vkDestroyInstance(ctx_.instance, nullptr);
    ctx_.instance = VK_NULL_HANDLE;
  }
}

Engine::~Engine() { shutdown(); }

VkCommandBuffer Engine::idle_command_buffer() {
  VkCommandBufferAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  ai.commandPool = pool_;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  vkAllocateCommandBuffers(ctx_.device, &ai, &cmd);
  return cmd;
}

VkCommandBuffer Engine::begin() {
  VkCommandBuffer cmd = idle_command_buffer();
  VkCommandBufferBeginInfo bi{};
  bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkBeginCommandBuffer(cmd, &bi);
  return cmd;
}

void Engine::submit_and_wait(VkCommandBuffer cmd) {
  vkEndCommandBuffer(cmd);
  VkSubmitInfo si{};
  si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  vkQueueSubmit(ctx_.queue, 1, &si, VK_NULL_HANDLE);
  vkQueueWaitIdle(ctx_.queue);
  vkFreeCommandBuffers(ctx_.device, pool_, 1, &cmd);
}

std::uint32_t Engine::memory_type(std::uint32_t bits, VkMemoryPropertyFlags want) const {
  VkPhysicalDeviceMemoryProperties mp{};
  vkGetPhysicalDeviceMemoryProperties(ctx_.physical_device, &mp);
  for (std::uint32_t i = 0; i < mp.memoryTypeCount; ++i) {
    if ((bits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & want) == want) return i;
  }
  return 0;
}

using HostBuffer = EngineBuffer;

EngineImage Engine::upload_rgba(VkFormat format, int w, int h, const std::vector<float>& texels,
                                VkImageUsageFlags extra_usage) {
  EngineImage img;
  VkImageCreateInfo ci{};
  ci.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
  ci.imageType = VK_IMAGE_TYPE_2D;
  ci.format = format;
  ci.extent = {std::uint32_t(w), std::uint32_t(h), 1};
  ci.mipLevels = 1;
  ci.arrayLayers = 1;
  ci.samples = VK_SAMPLE_COUNT_1_BIT;
  ci.tiling = VK_IMAGE_TILING_OPTIMAL;
  ci.usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | extra_usage;
  ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  vkCreateImage(ctx_.device, &ci, nullptr, &img.image);
  VkMemoryRequirements req{};
  vkGetImageMemoryRequirements(ctx_.device, img.image, &req);
  VkMemoryAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  vkAllocateMemory(ctx_.device, &ai, nullptr, &img.memory);
  vkBindImageMemory(ctx_.device, img.image, img.memory, 0);
  VkImageViewCreateInfo vi{};
  vi.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
  vi.image = img.image;
  vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
  vi.format = format;
  vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCreateImageView(ctx_.device, &vi, nullptr, &img.view);

  // A staging buffer, one copy (zeros when no texels are given), image left in TRANSFER_DST.
  const std::size_t bytes = std::size_t(w) * std::size_t(h) * 16;
  HostBuffer hb;
  VkBufferCreateInfo bi{};
  bi.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  bi.size = bytes;
  bi.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
  vkCreateBuffer(ctx_.device, &bi, nullptr, &hb.buffer);
  vkGetBufferMemoryRequirements(ctx_.device, hb.buffer, &req);
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                           VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  vkAllocateMemory(ctx_.device, &ai, nullptr, &hb.memory);
  vkBindBufferMemory(ctx_.device, hb.buffer, hb.memory, 0);
  vkMapMemory(ctx_.device, hb.memory, 0, VK_WHOLE_SIZE, 0, &hb.data);
  std::memset(hb.data, 0, bytes);
  if (format == VK_FORMAT_R32G32B32A32_SFLOAT && !texels.empty()) {
    std::memcpy(hb.data, texels.data(), bytes);
  }
  VkCommandBuffer cmd = begin();
  VkImageMemoryBarrier b{};
  b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
  b.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = img.image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0,
                       nullptr, 0, nullptr, 1, &b);
  if (format == VK_FORMAT_R32G32B32A32_SFLOAT) {
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {std::uint32_t(w), std::uint32_t(h), 1};
    vkCmdCopyBufferToImage(cmd, hb.buffer, img.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                           &region);
  }
  submit_and_wait(cmd);
  vkDestroyBuffer(ctx_.device, hb.buffer, nullptr);
  vkFreeMemory(ctx_.device, hb.memory, nullptr);
  img.resource.image = img.image;
  img.resource.view = img.view;
  img.resource.format = format;
  img.resource.extent = {std::uint32_t(w), std::uint32_t(h)};
  img.resource.usage = ci.usage;
  img.resource.layout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  img.resource.stage = VK_PIPELINE_STAGE_2_TRANSFER_BIT;
  img.resource.access = VK_ACCESS_2_TRANSFER_WRITE_BIT;
  return img;
}

void Engine::destroy(EngineImage& img) {
  if (ctx_.device == VK_NULL_HANDLE) return;
  vkDeviceWaitIdle(ctx_.device);
  vkDestroyImageView(ctx_.device, img.view, nullptr);
  vkDestroyImage(ctx_.device, img.image, nullptr);
  vkFreeMemory(ctx_.device, img.memory, nullptr);
  img = EngineImage{};
}

EngineBuffer Engine::host_buffer(VkDeviceSize bytes, VkBufferUsageFlags usage) {
  EngineBuffer b;
  VkBufferCreateInfo bi{};
  bi.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  bi.size = bytes;
  bi.usage = usage;
  vkCreateBuffer(ctx_.device, &bi, nullptr, &b.buffer);
  VkMemoryRequirements req{};
  vkGetBufferMemoryRequirements(ctx_.device, b.buffer, &req);
  VkMemoryAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                           VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  vkAllocateMemory(ctx_.device, &ai, nullptr, &b.memory);
  vkBindBufferMemory(ctx_.device, b.buffer, b.memory, 0);
  vkMapMemory(ctx_.device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.data);
  return b;
}

void Engine::destroy(EngineBuffer& buf) {
  if (ctx_.device == VK_NULL_HANDLE) return;
  vkDeviceWaitIdle(ctx_.device);
  vkDestroyBuffer(ctx_.device, buf.buffer, nullptr);
  vkFreeMemory(ctx_.device, buf.memory, nullptr);
  buf = EngineBuffer{};
}

PendingRead Engine::record_read(VkCommandBuffer cmd, const vk::ImageResource& from,
                                VkExtent2D region) {
  if (region.width == 0) region = from.extent;
  PendingRead pr;
  pr.texels = std::size_t(region.width) * region.height;
  pr.texel_bytes = from.format == VK_FORMAT_R32G32B32A32_SFLOAT   ? 16
                   : from.format == VK_FORMAT_R16G16B16A16_SFLOAT ? 8
                                                                  : 1;
  HostBuffer& hb = pr.buffer;
  VkBufferCreateInfo bi{};
  bi.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  bi.size = pr.texels * pr.texel_bytes;
  bi.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  vkCreateBuffer(ctx_.device, &bi, nullptr, &hb.buffer);
  VkMemoryRequirements req{};
  vkGetBufferMemoryRequirements(ctx_.device, hb.buffer, &req);
  VkMemoryAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                           VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  vkAllocateMemory(ctx_.device, &ai, nullptr, &hb.memory);
  vkBindBufferMemory(ctx_.device, hb.buffer, hb.memory, 0);
  VkImageMemoryBarrier b{};
  b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
  b.srcAccessMask = access1(from.access);
  b.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  b.oldLayout = from.layout;
  b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = from.image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdPipelineBarrier(cmd, stage1(from.stage), VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                       nullptr, 1, &b);
  VkBufferImageCopy copy{};
  copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  copy.imageExtent = {region.width, region.height, 1};
  vkCmdCopyImageToBuffer(cmd, from.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, hb.buffer, 1,
                         &copy);
  VkMemoryBarrier host{};
  host.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
  host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &host,
                       0, nullptr, 0, nullptr);
  return pr;
}

std::vector<float> Engine::finish_read(PendingRead& pr) {
  HostBuffer& hb = pr.buffer;
  vkMapMemory(ctx_.device, hb.memory, 0, VK_WHOLE_SIZE, 0, &hb.data);
  std::vector<float> out;
  if (pr.texel_bytes == 16) {
    out.resize(pr.texels * 4);
    std::memcpy(out.data(), hb.data, pr.texels * 16);
  } else if (pr.texel_bytes == 8) {
    const auto* h = static_cast<const std::uint16_t*>(hb.data);
    for (std::size_t i = 0; i < pr.texels * 4; ++i) out.push_back(half_to_float(h[i]));
  } else {
    const auto* u = static_cast<const std::uint8_t*>(hb.data);
    for (std::size_t i = 0; i < pr.texels; ++i) out.push_back(float(u[i]));
  }
  vkUnmapMemory(ctx_.device, hb.memory);
  // Its copy completed (no device wait: later frames may still be held behind a semaphore).
  vkDestroyBuffer(ctx_.device, hb.buffer, nullptr);
  vkFreeMemory(ctx_.device, hb.memory, nullptr);
  hb = EngineBuffer{};
  return out;
}

std::vector<float> Engine::read_back(const vk::ImageResource& from, VkExtent2D region) {
  VkCommandBuffer cmd = begin();
  PendingRead pr = record_read(cmd, from, region);
  submit_and_wait(cmd);
  return finish_read(pr);
}

VkSemaphore Engine::timeline_semaphore() {
  VkSemaphoreTypeCreateInfo ti{};
  ti.sType = VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO;
  ti.semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE;
  VkSemaphoreCreateInfo si{};
  si.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO;
  si.pNext = &ti;
  VkSemaphore s = VK_NULL_HANDLE;
  vkCreateSemaphore(ctx_.device, &si, nullptr, &s);
  return s;
}

void Engine::signal(VkSemaphore timeline, std::uint64_t value) {
  VkSemaphoreSignalInfo si{};
  si.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SIGNAL_INFO;
  si.semaphore = timeline;
  si.value = value;
  vkSignalSemaphore(ctx_.device, &si);
}

VkFence Engine::fence() {
  VkFenceCreateInfo fi{};
  fi.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
  VkFence f = VK_NULL_HANDLE;
  vkCreateFence(ctx_.device, &fi, nullptr, &f);
  return f;
}

void Engine::submit(VkCommandBuffer cmd, VkSemaphore timeline, std::uint64_t wait_value,
                    VkFence fence) {
  vkEndCommandBuffer(cmd);
  VkTimelineSemaphoreSubmitInfo ti{};
  ti.sType = VK_STRUCTURE_TYPE_TIMELINE_SEMAPHORE_SUBMIT_INFO;
  ti.waitSemaphoreValueCount = 1;
  ti.pWaitSemaphoreValues = &wait_value;
  const VkPipelineStageFlags stage = VK_PIPELINE_STAGE_ALL_COMMANDS_BIT;
  VkSubmitInfo si{};
  si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  si.pNext = &ti;
  si.waitSemaphoreCount = 1;
  si.pWaitSemaphores = &timeline;
  si.pWaitDstStageMask = &stage;
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  vkQueueSubmit(ctx_.queue, 1, &si, fence);
}

void Engine::wait_and_reset(VkFence fence) {
  vkWaitForFences(ctx_.device, 1, &fence, VK_TRUE, UINT64_MAX);
  vkResetFences(ctx_.device, 1, &fence);
}

void Engine::free(VkCommandBuffer cmd) { vkFreeCommandBuffers(ctx_.device, pool_, 1, &cmd); }

}  // namespace tessera::vk_test
