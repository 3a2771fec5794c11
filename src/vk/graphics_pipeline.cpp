// Shader modules and the graphics pipelines of the experiments' drawing passes
// (graphics_pipeline.h).
#include "vk/graphics_pipeline.h"

#include "vk/shader.h"

namespace tessera::vk {

Result<std::vector<std::uint32_t>> compile_shipped_stage(glsl::Stage stage, const char* file,
                                                         const std::vector<std::string>& preamble,
                                                         const std::string& who) {
  Result<glsl::Source> src = glsl::shipped_shader(stage, file);
  if (!src) return src.status();
  glsl::ExpandOptions eo;
  eo.preamble = preamble;
  Result<glsl::Expanded> e = glsl::expand_includes(*src, eo);
  if (!e) return e.status();
  Result<std::vector<std::uint32_t>> spirv = compile_graphics_spirv(e->text, stage);
  if (!spirv) {
    return Status::error(spirv.status().code,
                         who + ": " + glsl::format_log(spirv.status().message, e->files));
  }
  return spirv;
}

Result<ShaderModule> create_shader_module(const Api& api, const std::vector<std::uint32_t>& spirv,
                                          const std::string& what) {
  const VkShaderModuleCreateInfo info{.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
                                      .pNext = nullptr,
                                      .flags = 0,
                                      .codeSize = spirv.size() * 4,
                                      .pCode = spirv.data()};
  VkShaderModule raw = VK_NULL_HANDLE;
  if (VkResult r = api.CreateShaderModule(api.device(), &info, api.alloc(), &raw);
      r != VK_SUCCESS) {
    return vk_error(what + ": vkCreateShaderModule", r);
  }
  return ShaderModule(api, raw);
}

Result<Pipeline> create_graphics_pipeline(const Api& api, const GraphicsPipelineDesc& d,
                                          const std::string& what) {
  if (d.vertex_spirv == nullptr || d.fragment_spirv == nullptr || d.layout == VK_NULL_HANDLE ||
      d.render_pass == VK_NULL_HANDLE) {
    return Status::error(ErrorCode::invalid_argument,
                         what + ": a graphics pipeline needs both stages, a layout and a pass");
  }
  Result<ShaderModule> vs = create_shader_module(api, *d.vertex_spirv, what);
  if (!vs) return vs.status();
  Result<ShaderModule> fs = create_shader_module(api, *d.fragment_spirv, what);
  if (!fs) return fs.status();
  VkPipelineShaderStageCreateInfo stages[2]{};
  for (VkPipelineShaderStageCreateInfo& s : stages) {
    s.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    s.pName = "main";
  }
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vs->get();
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = fs->get();
  stages[1].pSpecializationInfo = d.fragment_specialization;

  const VkPipelineVertexInputStateCreateInfo input{
      .sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO,
      .pNext = nullptr,
      .flags = 0,
      .vertexBindingDescriptionCount = std::uint32_t(d.bindings.size()),
      .pVertexBindingDescriptions = d.bindings.data(),
      .vertexAttributeDescriptionCount = std::uint32_t(d.attributes.size()),
      .pVertexAttributeDescriptions = d.attributes.data()};
  VkPipelineInputAssemblyStateCreateInfo assembly{};
  assembly.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportDepthClipControlCreateInfoEXT clip_control{};
  clip_control.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_DEPTH_CLIP_CONTROL_CREATE_INFO_EXT;
  clip_control.negativeOneToOne = VK_TRUE;
  VkPipelineViewportStateCreateInfo viewport{};  // both dynamic
  viewport.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
  viewport.pNext = d.gl_depth ? &clip_control : nullptr;
  viewport.viewportCount = viewport.scissorCount = 1;
  const VkDynamicState dynamic_states[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  const VkPipelineDynamicStateCreateInfo dynamic{
      .sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO,
      .pNext = nullptr,
      .flags = 0,
      .dynamicStateCount = 2,
      .pDynamicStates = dynamic_states};
  VkPipelineRasterizationStateCreateInfo raster{};
  raster.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = d.cull;
  raster.frontFace = d.front_face;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{};
  multisample.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
  multisample.rasterizationSamples = d.samples;
  VkPipelineDepthStencilStateCreateInfo depth{};
  depth.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
  depth.depthTestEnable = depth.depthWriteEnable = d.depth_test ? VK_TRUE : VK_FALSE;
  depth.depthCompareOp = d.depth_compare;
  std::vector<VkPipelineColorBlendAttachmentState> writes(d.colour_attachments);
  for (VkPipelineColorBlendAttachmentState& w : writes) {
    w.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                       VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  }
  VkPipelineColorBlendStateCreateInfo blend{};
  blend.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
  blend.attachmentCount = d.colour_attachments;
  blend.pAttachments = writes.data();

  const VkGraphicsPipelineCreateInfo info{.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO,
                                          .pNext = nullptr,
                                          .flags = 0,
                                          .stageCount = 2,
                                          .pStages = stages,
                                          .pVertexInputState = &input,
                                          .pInputAssemblyState = &assembly,
                                          .pTessellationState = nullptr,
                                          .pViewportState = &viewport,
                                          .pRasterizationState = &raster,
                                          .pMultisampleState = &multisample,
                                          .pDepthStencilState = &depth,
                                          .pColorBlendState = &blend,
                                          .pDynamicState = &dynamic,
                                          .layout = d.layout,
                                          .renderPass = d.render_pass,
                                          .subpass = d.subpass,
                                          .basePipelineHandle = VK_NULL_HANDLE,
                                          .basePipelineIndex = -1};
  VkPipeline pipeline = VK_NULL_HANDLE;
  const VkResult r =
      api.CreateGraphicsPipelines(api.device(), VK_NULL_HANDLE, 1, &info, api.alloc(), &pipeline);
  if (r != VK_SUCCESS) return vk_error(what + ": vkCreateGraphicsPipelines", r);
  return Pipeline(api, pipeline);
}

}  // namespace tessera::vk
