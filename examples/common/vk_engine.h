// vk_engine.h — the Vulkan examples' platform layer, the part an engine already has before it
// adopts tessera: an instance with the validation layer when it is installed (synchronization
// validation on, a messenger counting warnings and errors), the first physical device of at
// least a given API version with one graphics + compute queue family, and the memory-type
// look-up, buffers and device-local images every allocation needs (the pipelines and the
// forward pass are vk_pipelines.h). tessera never sees the instance: its components work on the
// VkDevice and queue the engine hands them.
//
// Header-only, shared by examples/engine_aa_vk and examples/engine_ptex_vk (each adds
// examples/common to its include path, as the GL examples do for engine_context.h) and
// tests/vk's harness.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace engine {

inline constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

/// Whether the instance layer `name` is installed.
inline bool has_layer(const char* name) {
  std::uint32_t n = 0;
  vkEnumerateInstanceLayerProperties(&n, nullptr);
  std::vector<VkLayerProperties> layers(n);
  vkEnumerateInstanceLayerProperties(&n, layers.data());
  for (const VkLayerProperties& l : layers) {
    if (std::strcmp(l.layerName, name) == 0) return true;
  }
  return false;
}

/// The validation set-up of an engine's instance: warnings and errors to `callback` (with
/// `user`), synchronization validation on. `features` goes into VkInstanceCreateInfo::pNext (it
/// chains `messenger`), and `messenger` makes the messenger once the instance exists. Not
/// copyable: `features` points at the members.
struct ValidationChain {
  VkDebugUtilsMessengerCreateInfoEXT messenger{};
  VkValidationFeatureEnableEXT sync = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  VkValidationFeaturesEXT features{};

  ValidationChain(PFN_vkDebugUtilsMessengerCallbackEXT callback, void* user) {
    messenger.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
    messenger.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                            VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                            VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messenger.pfnUserCallback = callback;
    messenger.pUserData = user;
    features.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT;
    features.pNext = &messenger;
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = &sync;
  }
  ValidationChain(const ValidationChain&) = delete;
  ValidationChain& operator=(const ValidationChain&) = delete;
};

/// Writes `buffer` (from 0, `range` bytes) as the uniform buffer at binding 0 of `set`.
inline void write_uniform_buffer(VkDevice dev, VkDescriptorSet set, VkBuffer buffer,
                                 VkDeviceSize range = VK_WHOLE_SIZE) {
  const VkDescriptorBufferInfo bi{buffer, 0, range};
  VkWriteDescriptorSet w{};
  w.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
  w.dstSet = set;
  w.descriptorCount = 1;
  w.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  w.pBufferInfo = &bi;
  vkUpdateDescriptorSets(dev, 1, &w, 0, nullptr);
}

/// The engine's instance and its validation messenger. Each engine's Device derives from it; it
/// must stay where it is between create_instance and destroy_instance (the messenger holds its
/// address).
class Instance {
 public:
  VkInstance instance = VK_NULL_HANDLE;
  bool validation = false;  // the layer was asked for and is installed
  int messages = 0;         // validation warnings + errors
  std::string first_message;

  /// Makes the instance (with the layer when `want_validation` and installed, and the instance
  /// `extensions`, e.g. a window system's surface ones); "" or the reason.
  std::string create_instance(const char* app_name, std::uint32_t api_version, bool want_validation,
                              std::vector<const char*> extensions = {}) {
    validation = want_validation && has_layer(kValidationLayer);
    VkApplicationInfo app{
        VK_STRUCTURE_TYPE_APPLICATION_INFO, nullptr, app_name, 1, nullptr, 0, api_version};
    const ValidationChain chain(&on_message, this);
    const char* layer = kValidationLayer;
    VkInstanceCreateInfo ii{};
    ii.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
    ii.pApplicationInfo = &app;
    if (validation) {
      ii.pNext = &chain.features;
      ii.enabledLayerCount = 1;
      ii.ppEnabledLayerNames = &layer;
      extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }
    ii.enabledExtensionCount = std::uint32_t(extensions.size());
    ii.ppEnabledExtensionNames = extensions.data();
    if (vkCreateInstance(&ii, nullptr, &instance) != VK_SUCCESS) return "no Vulkan instance";
    if (validation) {
      auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
          vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
      if (create_messenger) create_messenger(instance, &chain.messenger, nullptr, &messenger_);
    }
    return "";
  }

  /// The first physical device of at least `min_api` with a graphics + compute queue family:
  /// false when there is none, else `physical`, `family` and `props` are set.
  bool pick_device(std::uint32_t min_api, VkPhysicalDevice& physical, std::uint32_t& family,
                   VkPhysicalDeviceProperties& props) const {
    std::uint32_t n = 0;
    vkEnumeratePhysicalDevices(instance, &n, nullptr);
    std::vector<VkPhysicalDevice> devs(n);
    vkEnumeratePhysicalDevices(instance, &n, devs.data());
    const VkQueueFlags want = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    for (VkPhysicalDevice p : devs) {
      VkPhysicalDeviceProperties pp{};
      vkGetPhysicalDeviceProperties(p, &pp);
      if (pp.apiVersion < min_api) continue;
      std::uint32_t nf = 0;
      vkGetPhysicalDeviceQueueFamilyProperties(p, &nf, nullptr);
      std::vector<VkQueueFamilyProperties> fams(nf);
      vkGetPhysicalDeviceQueueFamilyProperties(p, &nf, fams.data());
      for (std::uint32_t f = 0; f < nf; ++f) {
        if ((fams[f].queueFlags & want) == want) {
          physical = p;
          family = f;
          props = pp;
          return true;
        }
      }
    }
    return false;
  }

  /// Destroys the messenger and the instance (after the engine destroyed its device).
  void destroy_instance() {
    if (!instance) return;
    auto destroy_messenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy_messenger && messenger_) destroy_messenger(instance, messenger_, nullptr);
    messenger_ = VK_NULL_HANDLE;
    vkDestroyInstance(instance, nullptr);
    instance = VK_NULL_HANDLE;
  }

 private:
  static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                   VkDebugUtilsMessageTypeFlagsEXT,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                   void* user) {
    auto* self = static_cast<Instance*>(user);
    if (self->messages++ == 0) self->first_message = data->pMessage ? data->pMessage : "?";
    return VK_FALSE;
  }

  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
};

/// The first memory type of `physical` allowed by `bits` with all of `want` (0 when none).
inline std::uint32_t memory_type(VkPhysicalDevice physical, std::uint32_t bits,
                                 VkMemoryPropertyFlags want) {
  VkPhysicalDeviceMemoryProperties mp{};
  vkGetPhysicalDeviceMemoryProperties(physical, &mp);
  for (std::uint32_t i = 0; i < mp.memoryTypeCount; ++i) {
    if ((bits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & want) == want) return i;
  }
  return 0;
}

/// A buffer and its memory; `data` is its mapping when host-visible (coherent).
struct Buffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* data = nullptr;
};

/// The engine's device on its instance: the first physical device of at least an API version
/// with a graphics + compute queue family, one queue of it, the features it enabled. Each
/// engine's Device derives from it and adds its own resources.
class DeviceBase : public Instance {
 public:
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  std::uint32_t family = 0;
  VkQueue queue = VK_NULL_HANDLE;
  VkPhysicalDeviceFeatures features{};  // what was enabled
  std::string name;

  /// A buffer of `bytes` for `usage`: host-visible, coherent and mapped when `host`, else
  /// device-local.
  Buffer buffer(VkDeviceSize bytes, VkBufferUsageFlags usage, bool host) {
    Buffer b;
    VkBufferCreateInfo bi{};
    bi.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    bi.size = bytes;
    bi.usage = usage;
    vkCreateBuffer(device, &bi, nullptr, &b.buffer);
    VkMemoryRequirements req{};
    vkGetBufferMemoryRequirements(device, b.buffer, &req);
    const VkMemoryPropertyFlags want =
        host ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
             : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, req.size,
                            memory_type(physical, req.memoryTypeBits, want)};
    vkAllocateMemory(device, &ai, nullptr, &b.memory);
    vkBindBufferMemory(device, b.buffer, b.memory, 0);
    if (host) vkMapMemory(device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.data);
    return b;
  }

  void destroy(Buffer& b) {
    if (b.data) vkUnmapMemory(device, b.memory);
    vkDestroyBuffer(device, b.buffer, nullptr);
    vkFreeMemory(device, b.memory, nullptr);
    b = Buffer{};
  }

 protected:
  /// The instance (`app_name`, `api_version`, the layer when `want_validation` and installed)
  /// and the physical device (`props`, `name`); "" or the reason.
  std::string create_instance_and_pick(const char* app_name, std::uint32_t api_version,
                                       bool want_validation, VkPhysicalDeviceProperties& props,
                                       const std::vector<const char*>& extensions = {}) {
    const std::string why = create_instance(app_name, api_version, want_validation, extensions);
    if (!why.empty()) return why;
    if (!pick_device(api_version, physical, family, props)) {
      return std::string("no Vulkan ") + std::to_string(VK_API_VERSION_MAJOR(api_version)) + "." +
             std::to_string(VK_API_VERSION_MINOR(api_version)) +
             " device with a graphics + compute queue";
    }
    name = props.deviceName;
    return "";
  }

  /// The device with one queue of `family`, `features` and the `next` chain; "" or the reason.
  std::string create_device(const void* next, const std::vector<const char*>& extensions = {}) {
    const float prio = 1.0f;
    VkDeviceQueueCreateInfo qi{
        VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO, nullptr, 0, family, 1, &prio};
    VkDeviceCreateInfo di{};
    di.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
    di.pNext = next;
    di.enabledExtensionCount = std::uint32_t(extensions.size());
    di.ppEnabledExtensionNames = extensions.data();
    di.queueCreateInfoCount = 1;
    di.pQueueCreateInfos = &qi;
    di.pEnabledFeatures = &features;
    if (vkCreateDevice(physical, &di, nullptr, &device) != VK_SUCCESS) {
      return "vkCreateDevice failed";
    }
    vkGetDeviceQueue(device, family, 0, &queue);
    return "";
  }

  /// Destroys the device (idle first), then the instance.
  void destroy_device_and_instance() {
    if (device) {
      vkDeviceWaitIdle(device);
      vkDestroyDevice(device, nullptr);
      device = VK_NULL_HANDLE;
    }
    destroy_instance();
  }
};

/// A 2D image of one mip level and layer in device-local memory, and its view of `aspect`.
inline void create_image(VkDevice dev, VkPhysicalDevice physical, VkFormat format, std::uint32_t w,
                         std::uint32_t h, VkImageUsageFlags usage, VkImageAspectFlags aspect,
                         VkImage* image, VkDeviceMemory* memory, VkImageView* view) {
  VkImageCreateInfo ci{};
  ci.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
  ci.imageType = VK_IMAGE_TYPE_2D;
  ci.format = format;
  ci.extent = {w, h, 1};
  ci.mipLevels = ci.arrayLayers = 1;
  ci.samples = VK_SAMPLE_COUNT_1_BIT;
  ci.tiling = VK_IMAGE_TILING_OPTIMAL;
  ci.usage = usage;
  vkCreateImage(dev, &ci, nullptr, image);
  VkMemoryRequirements req{};
  vkGetImageMemoryRequirements(dev, *image, &req);
  VkMemoryAllocateInfo ai{
      VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, req.size,
      memory_type(physical, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT)};
  vkAllocateMemory(dev, &ai, nullptr, memory);
  vkBindImageMemory(dev, *image, *memory, 0);
  VkImageViewCreateInfo vi{};
  vi.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
  vi.image = *image;
  vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
  vi.format = format;
  vi.subresourceRange = {aspect, 0, 1, 0, 1};
  vkCreateImageView(dev, &vi, nullptr, view);
}

}  // namespace engine
