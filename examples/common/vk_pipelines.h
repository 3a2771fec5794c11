// vk_pipelines.h — the Vulkan examples' drawing set-up, the part of an engine's renderer that
// exists before it adopts tessera: the graphics pipeline state both engines draw with
// (engine_aa_vk's geometry pass with dynamic rendering, the forward pass), and the forward pass
// (one colour target and depth through a render pass, the frame block at set 0) that
// engine_ptex_vk and the tests' Vulkan engine (tests/vk) draw with.
//
// Header-only, beside vk_engine.h (the instance, device, memory and images it builds on), shared
// by examples/engine_aa_vk, examples/engine_ptex_vk and tests/vk's draw.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "vk_engine.h"

namespace engine {
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
  /// The viewport and scissor set by the command buffer (a render size per frame) instead of
  /// width x height.
  bool dynamic_viewport = false;
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
  g.dynamic_viewport = in.dynamic_viewport;
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

/// The forward pass's render pass: subpass 0 drawing into an RGBA32F colour target (stored;
/// `colour_load`, from `initial` to `final` layout) and D32 depth (cleared, not stored), after
/// `deps`.
inline VkRenderPass forward_render_pass(VkDevice dev, VkAttachmentLoadOp colour_load,
                                        VkImageLayout initial, VkImageLayout final,
                                        const std::vector<VkSubpassDependency>& deps) {
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
  VkRenderPass pass = VK_NULL_HANDLE;
  vkCreateRenderPass(dev, &rp, nullptr, &pass);
  return pass;
}

/// A framebuffer of `pass` on `views` (colour, depth), `width` x `height`.
inline VkFramebuffer forward_framebuffer(VkDevice dev, VkRenderPass pass,
                                         const VkImageView views[2], int width, int height) {
  VkFramebufferCreateInfo fb{};
  fb.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
  fb.renderPass = pass;
  fb.attachmentCount = 2;
  fb.pAttachments = views;
  fb.width = std::uint32_t(width);
  fb.height = std::uint32_t(height);
  fb.layers = 1;
  VkFramebuffer framebuffer = VK_NULL_HANDLE;
  vkCreateFramebuffer(dev, &fb, nullptr, &framebuffer);
  return framebuffer;
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

  /// The render pass (forward_render_pass) and its framebuffer of `views` (colour, depth),
  /// `width` x `height`.
  void create_pass(VkDevice dev, VkAttachmentLoadOp colour_load, VkImageLayout initial,
                   VkImageLayout final, const std::vector<VkSubpassDependency>& deps,
                   const VkImageView views[2], int width, int height) {
    pass = forward_render_pass(dev, colour_load, initial, final, deps);
    framebuffer = forward_framebuffer(dev, pass, views, width, height);
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
