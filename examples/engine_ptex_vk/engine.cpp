// engine_ptex_vk's own Vulkan plumbing (engine.h).
#include "engine.h"

#include <shaderc/shaderc.h>

#include <chrono>
#include <cstring>

namespace engine {

namespace {

constexpr const char* kValidation = "VK_LAYER_KHRONOS_validation";

VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                          VkDebugUtilsMessageTypeFlagsEXT,
                                          const VkDebugUtilsMessengerCallbackDataEXT* data,
                                          void* user) {
  auto* d = static_cast<Device*>(user);
  if (d->messages++ == 0) d->first_message = data->pMessage ? data->pMessage : "?";
  return VK_FALSE;
}

bool has_layer() {
  std::uint32_t n = 0;
  vkEnumerateInstanceLayerProperties(&n, nullptr);
  std::vector<VkLayerProperties> layers(n);
  vkEnumerateInstanceLayerProperties(&n, layers.data());
  for (const VkLayerProperties& l : layers) {
    if (std::strcmp(l.layerName, kValidation) == 0) return true;
  }
  return false;
}

std::uint32_t memory_type(VkPhysicalDevice pd, std::uint32_t bits, VkMemoryPropertyFlags want) {
  VkPhysicalDeviceMemoryProperties mp{};
  vkGetPhysicalDeviceMemoryProperties(pd, &mp);
  for (std::uint32_t i = 0; i < mp.memoryTypeCount; ++i) {
    if ((bits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & want) == want) return i;
  }
  return 0;
}

}  // namespace

std::string Device::create(bool want_validation) {
  validation = want_validation && has_layer();
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO,
                        nullptr,
                        "engine_ptex_vk",
                        1,
                        nullptr,
                        0,
                        VK_API_VERSION_1_1};
  VkDebugUtilsMessengerCreateInfoEXT mi{};
  mi.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
  mi.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  mi.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                   VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                   VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  mi.pfnUserCallback = &on_message;
  mi.pUserData = this;
  const VkValidationFeatureEnableEXT sync =
      VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  VkValidationFeaturesEXT vf{};
  vf.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT;
  vf.pNext = &mi;
  vf.enabledValidationFeatureCount = 1;
  vf.pEnabledValidationFeatures = &sync;
  const char* ext = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
  VkInstanceCreateInfo ii{};
  ii.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  ii.pApplicationInfo = &app;
  if (validation) {
    ii.pNext = &vf;
    ii.enabledLayerCount = 1;
    ii.ppEnabledLayerNames = &kValidation;
    ii.enabledExtensionCount = 1;
    ii.ppEnabledExtensionNames = &ext;
  }
  if (vkCreateInstance(&ii, nullptr, &instance) != VK_SUCCESS) return "no Vulkan instance";
  if (validation) {
    auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    if (create_messenger) create_messenger(instance, &mi, nullptr, &messenger_);
  }
  std::uint32_t n = 0;
  vkEnumeratePhysicalDevices(instance, &n, nullptr);
  std::vector<VkPhysicalDevice> devs(n);
  vkEnumeratePhysicalDevices(instance, &n, devs.data());
  for (VkPhysicalDevice p : devs) {
    VkPhysicalDeviceProperties props{};
    vkGetPhysicalDeviceProperties(p, &props);
    if (props.apiVersion < VK_API_VERSION_1_1 || physical != VK_NULL_HANDLE) continue;
    std::uint32_t nf = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(p, &nf, nullptr);
    std::vector<VkQueueFamilyProperties> fams(nf);
    vkGetPhysicalDeviceQueueFamilyProperties(p, &nf, fams.data());
    const VkQueueFlags want = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    for (std::uint32_t f = 0; f < nf && physical == VK_NULL_HANDLE; ++f) {
      if ((fams[f].queueFlags & want) == want) {
        physical = p;
        family = f;
        name = props.deviceName;
        api_version = props.apiVersion < VK_API_VERSION_1_3 ? props.apiVersion : VK_API_VERSION_1_3;
      }
    }
  }
  if (physical == VK_NULL_HANDLE) return "no Vulkan 1.1 device with a graphics + compute queue";
  const float prio = 1.0f;
  VkDeviceQueueCreateInfo qi{
      VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO, nullptr, 0, family, 1, &prio};
  VkDeviceCreateInfo di{};
  di.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  di.queueCreateInfoCount = 1;
  di.pQueueCreateInfos = &qi;
  di.pEnabledFeatures = &features;
  if (vkCreateDevice(physical, &di, nullptr, &device) != VK_SUCCESS) return "vkCreateDevice failed";
  vkGetDeviceQueue(device, family, 0, &queue);
  return "";
}

void Device::destroy() {
  if (device) {
    vkDeviceWaitIdle(device);
    vkDestroyDevice(device, nullptr);
    device = VK_NULL_HANDLE;
  }
  if (instance) {
    auto destroy_messenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy_messenger && messenger_) destroy_messenger(instance, messenger_, nullptr);
    vkDestroyInstance(instance, nullptr);
    instance = VK_NULL_HANDLE;
  }
}

Buffer Device::buffer(const void* data, VkDeviceSize bytes, VkBufferUsageFlags usage) {
  Buffer b;
  VkBufferCreateInfo bi{};
  bi.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  bi.size = bytes;
  bi.usage = usage;
  vkCreateBuffer(device, &bi, nullptr, &b.buffer);
  VkMemoryRequirements req{};
  vkGetBufferMemoryRequirements(device, b.buffer, &req);
  VkMemoryAllocateInfo ai{
      VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, req.size,
      memory_type(physical, req.memoryTypeBits,
                  VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT)};
  vkAllocateMemory(device, &ai, nullptr, &b.memory);
  vkBindBufferMemory(device, b.buffer, b.memory, 0);
  vkMapMemory(device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.data);
  if (data != nullptr) std::memcpy(b.data, data, bytes);
  return b;
}

void Device::destroy(Buffer& b) {
  vkDestroyBuffer(device, b.buffer, nullptr);
  vkFreeMemory(device, b.memory, nullptr);
  b = Buffer{};
}

std::vector<std::uint32_t> compile(const std::string& glsl, bool vertex, const std::string& name,
                                   std::string& log) {
  shaderc_compiler_t compiler = shaderc_compiler_initialize();
  shaderc_compile_options_t options = shaderc_compile_options_initialize();
  shaderc_compile_options_set_target_env(options, shaderc_target_env_vulkan,
                                         shaderc_env_version_vulkan_1_1);
  shaderc_compilation_result_t r = shaderc_compile_into_spv(
      compiler, glsl.data(), glsl.size(), vertex ? shaderc_vertex_shader : shaderc_fragment_shader,
      name.c_str(), "main", options);
  std::vector<std::uint32_t> spirv;
  if (r != nullptr &&
      shaderc_result_get_compilation_status(r) == shaderc_compilation_status_success) {
    spirv.resize(shaderc_result_get_length(r) / 4);
    std::memcpy(spirv.data(), shaderc_result_get_bytes(r), spirv.size() * 4);
  } else {
    log = r != nullptr ? shaderc_result_get_error_message(r) : "shaderc: no result";
  }
  if (r != nullptr) shaderc_result_release(r);
  shaderc_compile_options_release(options);
  shaderc_compiler_release(compiler);
  return spirv;
}

}  // namespace engine
