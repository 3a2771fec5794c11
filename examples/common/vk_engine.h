// vk_engine.h — the Vulkan examples' platform layer, the part an engine already has before it
// adopts tessera: an instance with the validation layer when it is installed (synchronization
// validation on, a messenger counting warnings and errors), the first physical device of at
// least a given API version with one graphics + compute queue family, the memory-type look-up
// and the device-local images every allocation needs, the graphics pipeline state both engines
// draw with (engine_aa_vk's geometry pass with dynamic rendering, the forward pass), and the
// forward pass (one colour target and depth through a render pass, the frame block at set 0)
// engine_ptex_vk and the tests' Vulkan engine (tests/vk) draw with. tessera never sees the
// instance: its components work on the VkDevice and queue the engine hands them.
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

  /// Makes the instance (with the layer when `want_validation` and installed); "" or the reason.
  std::string create_instance(const char* app_name, std::uint32_t api_version,
                              bool want_validation) {
    validation = want_validation && has_layer(kValidationLayer);
    VkApplicationInfo app{
        VK_STRUCTURE_TYPE_APPLICATION_INFO, nullptr, app_name, 1, nullptr, 0, api_version};
    const ValidationChain chain(&on_message, this);
    const char* ext = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    const char* layer = kValidationLayer;
    VkInstanceCreateInfo ii{};
    ii.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
    ii.pApplicationInfo = &app;
    if (validation) {
      ii.pNext = &chain.features;
      ii.enabledLayerCount = 1;
      ii.ppEnabledLayerNames = &layer;
      ii.enabledExtensionCount = 1;
      ii.ppEnabledExtensionNames = &ext;
    }
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
                                       bool want_validation, VkPhysicalDeviceProperties& props) {
    const std::string why = create_instance(app_name, api_version, want_validation);
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
  std::string create_device(const void* next) {
    const float prio = 1.0f;
    VkDeviceQueueCreateInfo qi{
        VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO, nullptr, 0, family, 1, &prio};
    VkDeviceCreateInfo di{};
    di.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
    di.pNext = next;
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

/// What graphics_pipeline builds from: two shader modules, one vertex binding, the viewport and
/// scissor (or both dynamic), the cull mode, `colour_attachments` written whole, the
/// layout, and either a render pass (subpass 0) or, for dynamic rendering, `next` (a
/// VkPipelineRenderingCreateInfo).
struct GraphicsPipelineDesc {
  VkShaderModule vertex = VK_NULL_HANDLE, fragment = VK_NULL_HANDLE;
  std::uint32_t stride = 0;
  const VkVertexInputAttributeDescription* attributes = nullptr;
  std::uint32_t attribute_count = 0;
  VkViewport viewport{};
  VkRect2D scissor{};
  bool dynamic_viewport = false;             // set by the command buffer instead
  VkCullModeFlags cull = VK_CULL_MODE_NONE;  // counter-clockwise front faces
  std::uint32_t colour_attachments = 1;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkRenderPass pass = VK_NULL_HANDLE;
  const void* next = nullptr;
};

/// Creates a graphics pipeline: triangle lists, filled, one sample, depth test less with
/// writes, no blending.
inline VkResult graphics_pipeline(VkDevice dev, const GraphicsPipelineDesc& in,
                                  VkPipeline* pipeline) {
  VkPipelineShaderStageCreateInfo st[2]{};
  for (int i = 0; i < 2; ++i) {
    st[i].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    st[i].stage = i == 0 ? VK_SHADER_STAGE_VERTEX_BIT : VK_SHADER_STAGE_FRAGMENT_BIT;
    st[i].module = i == 0 ? in.vertex : in.fragment;
    st[i].pName = "main";
  }
  const VkVertexInputBindingDescription vb{0, in.stride, VK_VERTEX_INPUT_RATE_VERTEX};
  VkPipelineVertexInputStateCreateInfo vin{};
  vin.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
  vin.vertexBindingDescriptionCount = 1;
  vin.pVertexBindingDescriptions = &vb;
  vin.vertexAttributeDescriptionCount = in.attribute_count;
  vin.pVertexAttributeDescriptions = in.attributes;
  VkPipelineInputAssemblyStateCreateInfo ia{};
  ia.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
  ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo vs{};
  vs.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
  vs.viewportCount = vs.scissorCount = 1;
  vs.pViewports = in.dynamic_viewport ? nullptr : &in.viewport;
  vs.pScissors = in.dynamic_viewport ? nullptr : &in.scissor;
  VkPipelineRasterizationStateCreateInfo rs{};
  rs.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
  rs.polygonMode = VK_POLYGON_MODE_FILL;
  rs.cullMode = in.cull;
  rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  rs.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo ms{};
  ms.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
  ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo ds{};
  ds.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
  ds.depthTestEnable = ds.depthWriteEnable = VK_TRUE;
  ds.depthCompareOp = VK_COMPARE_OP_LESS;
  std::vector<VkPipelineColorBlendAttachmentState> blend(in.colour_attachments);
  for (auto& b : blend) b.colorWriteMask = 0xf;
  VkPipelineColorBlendStateCreateInfo cb{};
  cb.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
  cb.attachmentCount = in.colour_attachments;
  cb.pAttachments = blend.data();
  const VkDynamicState dyn[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dy{};
  dy.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO;
  dy.dynamicStateCount = 2;
  dy.pDynamicStates = dyn;
  VkGraphicsPipelineCreateInfo pi{};
  pi.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
  pi.pNext = in.next;
  pi.stageCount = 2;
  pi.pStages = st;
  pi.pVertexInputState = &vin;
  pi.pInputAssemblyState = &ia;
  pi.pViewportState = &vs;
  pi.pRasterizationState = &rs;
  pi.pMultisampleState = &ms;
  pi.pDepthStencilState = &ds;
  pi.pColorBlendState = &cb;
  pi.pDynamicState = in.dynamic_viewport ? &dy : nullptr;
  pi.layout = in.layout;
  pi.renderPass = in.pass;
  return vkCreateGraphicsPipelines(dev, VK_NULL_HANDLE, 1, &pi, nullptr, pipeline);
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

  /// The stages, vertex layout and size of a frame description `in` (members vertex_spirv,
  /// fragment_spirv, stride, attributes, width, height), culling back faces.
  template <class Frame>
  static ForwardPipelineDesc of(const Frame& in) {
    ForwardPipelineDesc d;
    d.vertex_spirv = &in.vertex_spirv;
    d.fragment_spirv = &in.fragment_spirv;
    d.stride = in.stride;
    d.attributes = &in.attributes;
    d.width = in.width;
    d.height = in.height;
    return d;
  }
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
  GraphicsPipelineDesc g;
  // +y up: the viewport starts at the bottom row with a negative height (core since 1.1).
  g.viewport = {0.0f, float(in.height), float(in.width), -float(in.height), 0.0f, 1.0f};
  g.scissor = {{0, 0}, {std::uint32_t(in.width), std::uint32_t(in.height)}};
  g.vertex = modules[0];
  g.fragment = modules[1];
  g.stride = in.stride;
  g.attributes = in.attributes->data();
  g.attribute_count = std::uint32_t(in.attributes->size());
  g.cull = in.cull_back ? VK_CULL_MODE_BACK_BIT : VK_CULL_MODE_NONE;
  g.layout = in.layout;
  g.pass = in.pass;
  return graphics_pipeline(dev, g, pipeline);
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
  write_uniform_buffer(dev, set, ubo);
  return set;
}

/// The objects of one forward pass but its targets: the render pass and framebuffer, set 0's
/// layout (the frame block) and an empty one, the pool of the frame set, the pipeline layout,
/// the pipeline and its shader modules. `destroy` destroys them (the device idle).
struct ForwardObjects {
  VkRenderPass pass = VK_NULL_HANDLE;
  VkFramebuffer framebuffer = VK_NULL_HANDLE;
  VkDescriptorSetLayout frame_layout = VK_NULL_HANDLE, empty_layout = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkShaderModule modules[2] = {VK_NULL_HANDLE, VK_NULL_HANDLE};
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkDescriptorSet frame_set = VK_NULL_HANDLE;

  /// The render pass, subpass 0 drawing into an RGBA32F colour target (stored; `colour_load`,
  /// from `initial` to `final` layout) and D32 depth (cleared, not stored), after `deps`, and
  /// its framebuffer of `views` (colour, depth), `width` x `height`.
  void create_pass(VkDevice dev, VkAttachmentLoadOp colour_load, VkImageLayout initial,
                   VkImageLayout final, const std::vector<VkSubpassDependency>& deps,
                   const VkImageView views[2], int width, int height) {
    VkAttachmentDescription att[2]{};
    for (int i = 0; i < 2; ++i) {
      att[i].samples = VK_SAMPLE_COUNT_1_BIT;
      att[i].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
      att[i].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    }
    att[0].format = VK_FORMAT_R32G32B32A32_SFLOAT;
    att[0].loadOp = colour_load;
    att[0].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    att[0].initialLayout = initial;
    att[0].finalLayout = final;
    att[1].format = VK_FORMAT_D32_SFLOAT;
    att[1].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    att[1].storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    att[1].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    att[1].finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    const VkAttachmentReference cref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    const VkAttachmentReference dref{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.colorAttachmentCount = 1;
    sub.pColorAttachments = &cref;
    sub.pDepthStencilAttachment = &dref;
    VkRenderPassCreateInfo rp{};
    rp.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
    rp.attachmentCount = 2;
    rp.pAttachments = att;
    rp.subpassCount = 1;
    rp.pSubpasses = &sub;
    rp.dependencyCount = std::uint32_t(deps.size());
    rp.pDependencies = deps.data();
    vkCreateRenderPass(dev, &rp, nullptr, &pass);
    VkFramebufferCreateInfo fb{};
    fb.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
    fb.renderPass = pass;
    fb.attachmentCount = 2;
    fb.pAttachments = views;
    fb.width = std::uint32_t(width);
    fb.height = std::uint32_t(height);
    fb.layers = 1;
    vkCreateFramebuffer(dev, &fb, nullptr, &framebuffer);
  }

  /// The set layouts, the pipeline layout of set 0 (the frame block, bound to `ubo`) and then
  /// `extra` (VK_NULL_HANDLE: an empty set), the pool and the frame set.
  void create_sets(VkDevice dev, const std::vector<VkDescriptorSetLayout>& extra, VkBuffer ubo) {
    frame_set_layouts(dev, &frame_layout, &empty_layout);
    std::vector<VkDescriptorSetLayout> layouts{frame_layout};
    for (VkDescriptorSetLayout l : extra) layouts.push_back(l != VK_NULL_HANDLE ? l : empty_layout);
    frame_set = engine::frame_set(dev, layouts, frame_layout, ubo, &layout, &pool);
  }

  /// The pipeline of `desc` on this layout and render pass.
  VkResult create_pipeline(VkDevice dev, ForwardPipelineDesc desc) {
    desc.layout = layout;
    desc.pass = pass;
    return forward_pipeline(dev, desc, modules, &pipeline);
  }

  /// Records the pass: begins it on the framebuffer (`width` x `height`, `clear`: colour then
  /// depth), binds the pipeline and the frame set, calls `bind(cmd, layout)` for the caller's
  /// sets, binds `vertices` (binding 0) and the uint32 `indices`, draws `index_count` and ends
  /// it. Returns what `bind` returned.
  template <class Bind>
  auto record(VkCommandBuffer cmd, int width, int height, const VkClearValue clear[2],
              VkBuffer vertices, VkBuffer indices, std::uint32_t index_count,
              const Bind& bind) const {
    VkRenderPassBeginInfo rb{};
    rb.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
    rb.renderPass = pass;
    rb.framebuffer = framebuffer;
    rb.renderArea = {{0, 0}, {std::uint32_t(width), std::uint32_t(height)}};
    rb.clearValueCount = 2;
    rb.pClearValues = clear;
    vkCmdBeginRenderPass(cmd, &rb, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &frame_set, 0,
                            nullptr);
    auto bound = bind(cmd, layout);
    const VkDeviceSize zero = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertices, &zero);
    vkCmdBindIndexBuffer(cmd, indices, 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(cmd, index_count, 1, 0, 0, 0);
    vkCmdEndRenderPass(cmd);
    return bound;
  }

  void destroy(VkDevice dev) {
    vkDestroyPipeline(dev, pipeline, nullptr);
    for (VkShaderModule m : modules) vkDestroyShaderModule(dev, m, nullptr);
    vkDestroyPipelineLayout(dev, layout, nullptr);
    vkDestroyDescriptorPool(dev, pool, nullptr);
    vkDestroyDescriptorSetLayout(dev, empty_layout, nullptr);
    vkDestroyDescriptorSetLayout(dev, frame_layout, nullptr);
    vkDestroyFramebuffer(dev, framebuffer, nullptr);
    vkDestroyRenderPass(dev, pass, nullptr);
    *this = ForwardObjects{};
  }
};

}  // namespace engine
