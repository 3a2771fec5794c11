// engine_aa_vk's scene targets (scene_frame.h).
#include "scene_frame.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace engine {

void setup(Device& d, int width, int height, int m, int view, Frame& f) {
  const std::uint32_t gw = std::uint32_t(width * m), gh = std::uint32_t(height * m);
  const VkImageUsageFlags rt = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  f.rt0 = d.image(VK_FORMAT_R16G16B16A16_SFLOAT, gw, gh, rt);
  f.rt1 = d.image(VK_FORMAT_R8G8B8A8_UNORM, gw, gh, rt);
  f.depth = d.image(VK_FORMAT_D32_SFLOAT, gw, gh, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                    VK_IMAGE_ASPECT_DEPTH_BIT);
  const std::vector<Vertex> verts = make_scene();
  f.vertex_count = verts.size();
  f.vertices = d.buffer(verts.size() * sizeof(Vertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, true);
  std::memcpy(f.vertices.data, verts.data(), verts.size() * sizeof(Vertex));
  f.cam = make_camera(width, height);
  if (view > 0) {  // another viewport: the camera turned about the scene's vertical axis
    const float turn = 0.9f * float(view), c = std::cos(turn), s = std::sin(turn);
    const float x = f.cam.eye[0], z = f.cam.eye[2];
    f.cam.eye[0] = c * x + s * z;
    f.cam.eye[2] = -s * x + c * z;
    const float at[3] = {0.0f, 0.4f, 0.0f};
    look_at(f.cam.eye, at, f.cam.view, f.cam.inv_view);
  }
  const float zn = 0.1f, zf = 50.0f;  // Vulkan's depth range [0, 1]
  f.cam.proj[0] = 1.0f / (f.cam.tan_half * f.cam.aspect);
  f.cam.proj[5] = 1.0f / f.cam.tan_half;
  f.cam.proj[10] = zf / (zn - zf);
  f.cam.proj[11] = -1.0f;
  f.cam.proj[14] = zn * zf / (zn - zf);
  const FrameBlock u = frame_block(f.cam, int(gw), int(gh));
  f.ubo = d.buffer(sizeof u, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
  std::memcpy(f.ubo.data, &u, sizeof u);
  // The engine's descriptor set 0 for the hook: its frame block, RT1 as a sampler.
  VkSamplerCreateInfo si{};
  si.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
  vkCreateSampler(d.device, &si, nullptr, &f.sampler);
  const VkDescriptorSetLayoutBinding b[2] = {
      {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}};
  VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO, nullptr,
                                     0, 2, b};
  vkCreateDescriptorSetLayout(d.device, &li, nullptr, &f.set_layout);
  const VkDescriptorPoolSize ps[2] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
                                      {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1}};
  VkDescriptorPoolCreateInfo pi{
      VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, nullptr, 0, 1, 2, ps};
  vkCreateDescriptorPool(d.device, &pi, nullptr, &f.pool);
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO, nullptr, f.pool, 1,
                                 &f.set_layout};
  vkAllocateDescriptorSets(d.device, &ai, &f.set);
  const VkDescriptorBufferInfo bi{f.ubo.buffer, 0, VK_WHOLE_SIZE};
  // tessera leaves the G-buffer in SHADER_READ_ONLY_OPTIMAL while its passes run.
  const VkDescriptorImageInfo ii{f.sampler, f.rt1.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkWriteDescriptorSet w[2]{};
  for (int i = 0; i < 2; ++i) {
    w[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    w[i].dstSet = f.set;
    w[i].dstBinding = std::uint32_t(i);
    w[i].descriptorCount = 1;
  }
  w[0].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  w[0].pBufferInfo = &bi;
  w[1].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  w[1].pImageInfo = &ii;
  vkUpdateDescriptorSets(d.device, 2, w, 0, nullptr);
}

void set_grid(Frame& f, std::uint32_t gw, std::uint32_t gh) {
  const FrameBlock u = frame_block(f.cam, int(gw), int(gh));
  std::memcpy(f.ubo.data, &u, sizeof u);
}

void destroy(Device& d, Frame& f) {
  vkDestroyDescriptorPool(d.device, f.pool, nullptr);
  vkDestroyDescriptorSetLayout(d.device, f.set_layout, nullptr);
  vkDestroySampler(d.device, f.sampler, nullptr);
  d.destroy(f.vertices);
  d.destroy(f.ubo);
  d.destroy(f.rt0);
  d.destroy(f.rt1);
  d.destroy(f.depth);
}

/// The geometry pass: dynamic rendering into RT0, RT1 and depth (from UNDEFINED: cleared).
void record_gbuffer(VkCommandBuffer cmd, const GeometryPipeline& gp, const Frame& f,
                    VkExtent2D area) {
  if (area.width == 0) area = {f.rt0.w, f.rt0.h};
  const VkPipelineStageFlags2 out = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
  for (const Image* rt : {&f.rt0, &f.rt1}) {
    barrier(cmd, rt->image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, 0, out, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  }
  const VkPipelineStageFlags2 tests =
      VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
  barrier(cmd, f.depth.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
          tests, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, tests,
          VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
              VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT,
          VK_IMAGE_ASPECT_DEPTH_BIT);
  VkRenderingAttachmentInfo colour[2]{};
  for (int i = 0; i < 2; ++i) {
    colour[i].sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
    colour[i].imageView = i == 0 ? f.rt0.view : f.rt1.view;
    colour[i].imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    colour[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    colour[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  }
  VkRenderingAttachmentInfo depth{};
  depth.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
  depth.imageView = f.depth.view;
  depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  depth.clearValue.depthStencil = {1.0f, 0};
  VkRenderingInfo ri{};
  ri.sType = VK_STRUCTURE_TYPE_RENDERING_INFO;
  ri.renderArea = {{0, 0}, area};
  ri.layerCount = 1;
  ri.colorAttachmentCount = 2;
  ri.pColorAttachments = colour;
  ri.pDepthAttachment = &depth;
  vkCmdBeginRendering(cmd, &ri);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, gp.pipeline);
  const VkViewport vp{0, 0, float(area.width), float(area.height), 0, 1};
  vkCmdSetViewport(cmd, 0, 1, &vp);
  vkCmdSetScissor(cmd, 0, 1, &ri.renderArea);
  float pc[32];
  std::copy(f.cam.view, f.cam.view + 16, pc);
  std::copy(f.cam.proj, f.cam.proj + 16, pc + 16);
  vkCmdPushConstants(cmd, gp.layout, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof pc, pc);
  const VkDeviceSize zero = 0;
  vkCmdBindVertexBuffers(cmd, 0, 1, &f.vertices.buffer, &zero);
  vkCmdDraw(cmd, std::uint32_t(f.vertex_count), 1, 0, 0);
  vkCmdEndRendering(cmd);
}

tessera::vk::ImageResource rendered(const Image& img) {
  tessera::vk::ImageResource r;
  r.image = img.image;
  r.view = img.view;
  r.format = img.format;
  r.extent = {img.w, img.h};
  r.usage = img.usage;
  r.layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  r.stage = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
  r.access = VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
  return r;
}
}  // namespace engine
