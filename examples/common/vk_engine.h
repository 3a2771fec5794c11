// vk_engine.h — the Vulkan examples' platform layer, the part an engine already has before it
// adopts tessera: an instance with the validation layer when it is installed (synchronization
// validation on, a messenger counting warnings and errors), the first physical device of at
// least a given API version with one graphics + compute queue family, and the memory-type
// look-up every buffer and image allocation needs, and the forward pipeline (one colour target
// and depth through a render pass) engine_ptex_vk and the tests' Vulkan engine (tests/vk) draw
// with. tessera never sees the instance: its components work on the VkDevice and queue the engine
// hands them.
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

/// What forward_pipeline builds from: two SPIR-V stages, one vertex binding, a width x height
/// target, the layout and the render pass (subpass 0, one colour attachment and depth).
struct ForwardPipelineDesc {
  const std::vector<std::uint32_t>* vertex_spirv = nullptr;
  const std::vector<std::uint32_t>* fragment_spirv = nullptr;
  std::uint32_t stride = 0;
  const std::vector<VkVertexInputAttributeDescription>* attributes = nullptr;
  int width = 0, height = 0;
  bool cull_back = true;  // counter-clockwise front faces, as the CPU renderers
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkRenderPass pass = VK_NULL_HANDLE;
};

/// Creates a forward pipeline (triangle lists, +y up viewport, depth test less with writes, the
/// colour written whole) and its two shader modules into `modules` (the caller destroys them).
inline VkResult forward_pipeline(VkDevice dev, const ForwardPipelineDesc& in,
                                 VkShaderModule modules[2], VkPipeline* pipeline) {
  VkShaderModuleCreateInfo mi{};
  mi.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  mi.codeSize = in.vertex_spirv->size() * 4;
  mi.pCode = in.vertex_spirv->data();
  vkCreateShaderModule(dev, &mi, nullptr, &modules[0]);
  mi.codeSize = in.fragment_spirv->size() * 4;
  mi.pCode = in.fragment_spirv->data();
  vkCreateShaderModule(dev, &mi, nullptr, &modules[1]);
  VkPipelineShaderStageCreateInfo st[2]{};
  for (int i = 0; i < 2; ++i) {
    st[i].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    st[i].stage = i == 0 ? VK_SHADER_STAGE_VERTEX_BIT : VK_SHADER_STAGE_FRAGMENT_BIT;
    st[i].module = modules[i];
    st[i].pName = "main";
  }
  const VkVertexInputBindingDescription vb{0, in.stride, VK_VERTEX_INPUT_RATE_VERTEX};
  VkPipelineVertexInputStateCreateInfo vin{};
  vin.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
  vin.vertexBindingDescriptionCount = 1;
  vin.pVertexBindingDescriptions = &vb;
  vin.vertexAttributeDescriptionCount = std::uint32_t(in.attributes->size());
  vin.pVertexAttributeDescriptions = in.attributes->data();
  VkPipelineInputAssemblyStateCreateInfo ia{};
  ia.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
  ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  // +y up: the viewport starts at the bottom row with a negative height (core since 1.1).
  const VkViewport vp{0.0f, float(in.height), float(in.width), -float(in.height), 0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, {std::uint32_t(in.width), std::uint32_t(in.height)}};
  VkPipelineViewportStateCreateInfo vs{};
  vs.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
  vs.viewportCount = vs.scissorCount = 1;
  vs.pViewports = &vp;
  vs.pScissors = &scissor;
  VkPipelineRasterizationStateCreateInfo rs{};
  rs.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
  rs.polygonMode = VK_POLYGON_MODE_FILL;
  rs.cullMode = in.cull_back ? VK_CULL_MODE_BACK_BIT : VK_CULL_MODE_NONE;
  rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  rs.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo ms{};
  ms.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
  ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo ds{};
  ds.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
  ds.depthTestEnable = ds.depthWriteEnable = VK_TRUE;
  ds.depthCompareOp = VK_COMPARE_OP_LESS;
  VkPipelineColorBlendAttachmentState blend{};
  blend.colorWriteMask = 0xf;
  VkPipelineColorBlendStateCreateInfo cb{};
  cb.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
  cb.attachmentCount = 1;
  cb.pAttachments = &blend;
  VkGraphicsPipelineCreateInfo pi{};
  pi.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
  pi.stageCount = 2;
  pi.pStages = st;
  pi.pVertexInputState = &vin;
  pi.pInputAssemblyState = &ia;
  pi.pViewportState = &vs;
  pi.pRasterizationState = &rs;
  pi.pMultisampleState = &ms;
  pi.pDepthStencilState = &ds;
  pi.pColorBlendState = &cb;
  pi.layout = in.layout;
  pi.renderPass = in.pass;
  return vkCreateGraphicsPipelines(dev, VK_NULL_HANDLE, 1, &pi, nullptr, pipeline);
}

/// The forward pass's set layouts: `frame` holds the engine's uniform block (binding 0, both
/// stages), `empty` none (for the set indices between the engine's and a component's).
inline void frame_set_layouts(VkDevice dev, VkDescriptorSetLayout* frame,
                              VkDescriptorSetLayout* empty) {
  const VkDescriptorSetLayoutBinding b{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1,
                                       VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                                       nullptr};
  VkDescriptorSetLayoutCreateInfo li{};
  li.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  li.bindingCount = 1;
  li.pBindings = &b;
  vkCreateDescriptorSetLayout(dev, &li, nullptr, frame);
  li.bindingCount = 0;
  vkCreateDescriptorSetLayout(dev, &li, nullptr, empty);
}

/// The pipeline layout of `layouts` (set 0 first: `frame`), a pool of one set, and that set of
/// `frame` pointing at `ubo` (the caller destroys `*layout` and `*pool`).
inline VkDescriptorSet frame_set(VkDevice dev, const std::vector<VkDescriptorSetLayout>& layouts,
                                 VkDescriptorSetLayout frame, VkBuffer ubo,
                                 VkPipelineLayout* layout, VkDescriptorPool* pool) {
  VkPipelineLayoutCreateInfo pl{};
  pl.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  pl.setLayoutCount = std::uint32_t(layouts.size());
  pl.pSetLayouts = layouts.data();
  vkCreatePipelineLayout(dev, &pl, nullptr, layout);
  const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1};
  VkDescriptorPoolCreateInfo pi{};
  pi.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  pi.maxSets = 1;
  pi.poolSizeCount = 1;
  pi.pPoolSizes = &size;
  vkCreateDescriptorPool(dev, &pi, nullptr, pool);
  VkDescriptorSetAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  ai.descriptorPool = *pool;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &frame;
  VkDescriptorSet set = VK_NULL_HANDLE;
  vkAllocateDescriptorSets(dev, &ai, &set);
  const VkDescriptorBufferInfo bi{ubo, 0, VK_WHOLE_SIZE};
  VkWriteDescriptorSet w{};
  w.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
  w.dstSet = set;
  w.descriptorCount = 1;
  w.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  w.pBufferInfo = &bi;
  vkUpdateDescriptorSets(dev, 1, &w, 0, nullptr);
  return set;
}

}  // namespace engine
