// vk_engine.h — the Vulkan examples' platform layer, the part an engine already has before it
// adopts tessera: an instance with the validation layer when it is installed (synchronization
// validation on, a messenger counting warnings and errors), the first physical device of at
// least a given API version with one graphics + compute queue family, and the memory-type
// look-up every buffer and image allocation needs. tessera never sees the instance: its
// components work on the VkDevice and queue the engine hands them.
//
// Header-only, shared by examples/engine_aa_vk and examples/engine_ptex_vk (each adds
// examples/common to its include path, as the GL examples do for engine_context.h).
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace engine {

/// The engine's instance and its validation messenger. Each engine's Device derives from it; it
/// must stay where it is between create_instance and destroy_instance (the messenger holds its
/// address).
class Instance {
 public:
  VkInstance instance = VK_NULL_HANDLE;
  bool validation = false;  // the layer was asked for and is installed
  int messages = 0;         // validation warnings + errors
  std::string first_message;

  /// Makes the instance (with the layer when `want_validation` and installed); "" or the reason.
  std::string create_instance(const char* app_name, std::uint32_t api_version,
                              bool want_validation) {
    validation = want_validation && has_layer();
    VkApplicationInfo app{
        VK_STRUCTURE_TYPE_APPLICATION_INFO, nullptr, app_name, 1, nullptr, 0, api_version};
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
    const char* layer = kValidation;
    VkInstanceCreateInfo ii{};
    ii.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
    ii.pApplicationInfo = &app;
    if (validation) {
      ii.pNext = &vf;
      ii.enabledLayerCount = 1;
      ii.ppEnabledLayerNames = &layer;
      ii.enabledExtensionCount = 1;
      ii.ppEnabledExtensionNames = &ext;
    }
    if (vkCreateInstance(&ii, nullptr, &instance) != VK_SUCCESS) return "no Vulkan instance";
    if (validation) {
      auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
          vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
      if (create_messenger) create_messenger(instance, &mi, nullptr, &messenger_);
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
  static constexpr const char* kValidation = "VK_LAYER_KHRONOS_validation";

  static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                   VkDebugUtilsMessageTypeFlagsEXT,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                   void* user) {
    auto* self = static_cast<Instance*>(user);
    if (self->messages++ == 0) self->first_message = data->pMessage ? data->pMessage : "?";
    return VK_FALSE;
  }

  static bool has_layer() {
    std::uint32_t n = 0;
    vkEnumerateInstanceLayerProperties(&n, nullptr);
    std::vector<VkLayerProperties> layers(n);
    vkEnumerateInstanceLayerProperties(&n, layers.data());
    for (const VkLayerProperties& l : layers) {
      if (std::strcmp(l.layerName, kValidation) == 0) return true;
    }
    return false;
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

}  // namespace engine
