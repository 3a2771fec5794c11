// vk::DeferredRenderer (deferred_renderer.h): the geometry pass — deferred_gbuffer.vert/.frag
// compiled with VULKAN into a graphics pipeline, the G-buffer images and framebuffer, and the
// timed draw of the scene with the CPU's clip positions (z remapped to Vulkan's [0, w]).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "tessera/glsl.h"
#include "vk/deferred_renderer.h"
#include "vk/graphics_pipeline.h"

// Vulkan's create-infos are written with designated initializers: the members left out are
// zero-initialised, which is what Vulkan asks of them (null pNext, no flags).
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace tessera::vk {

namespace {

using State = DeferredRenderer::State;

constexpr const char* kWho = "deferred VK";

/// Vertex input: binding 0 = clip xyzw + linear depth (per frame), binding 1 = normal + uv.
struct VertexInput {
  std::array<VkVertexInputBindingDescription, 2> bindings{
      {{0, 20, VK_VERTEX_INPUT_RATE_VERTEX}, {1, 20, VK_VERTEX_INPUT_RATE_VERTEX}}};
  std::array<VkVertexInputAttributeDescription, 4> attributes{
      {{0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 0},
       {1, 0, VK_FORMAT_R32_SFLOAT, 16},
       {2, 1, VK_FORMAT_R32G32B32_SFLOAT, 0},
       {3, 1, VK_FORMAT_R32G32_SFLOAT, 12}}};
};

Status create_pipeline_layout(State& st) {
  const VkPushConstantRange push{VK_SHADER_STAGE_FRAGMENT_BIT, 0, 4};  // TesseraGbufferPush
  const VkPipelineLayoutCreateInfo info{.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
                                        .pushConstantRangeCount = 1,
                                        .pPushConstantRanges = &push};
  return assign(st.gbuffer_layout, make_owned<PipelineLayout>(*st.api, &Api::CreatePipelineLayout,
                                                              info, "vkCreatePipelineLayout"));
}

}  // namespace

Status create_gbuffer_pipeline(State& st) {
  if (Status s = create_pipeline_layout(st); !s.ok()) return s;
  Result<std::vector<std::uint32_t>> vs =
      compile_shipped_stage(glsl::Stage::vertex, "deferred_gbuffer.vert", {}, kWho);
  if (!vs) return vs.status();
  Result<std::vector<std::uint32_t>> fs =
      compile_shipped_stage(glsl::Stage::fragment, "deferred_gbuffer.frag", {}, kWho);
  if (!fs) return fs.status();
  const VertexInput input;
  GraphicsPipelineDesc d;
  d.vertex_spirv = &*vs;
  d.fragment_spirv = &*fs;
  d.bindings.assign(input.bindings.begin(), input.bindings.end());
  d.attributes.assign(input.attributes.begin(), input.attributes.end());
  d.layout = st.gbuffer_layout.get();
  d.render_pass = st.render_pass.get();
  d.colour_attachments = 3;              // RGBA each, no blending
  d.cull = VK_CULL_MODE_NONE;            // the CPU draws both sides
  d.depth_compare = VK_COMPARE_OP_LESS;  // glDepthFunc(GL_LESS)
  // With VK_EXT_depth_clip_control the clip depth stays OpenGL's, as in the GL backend.
  d.gl_depth = st.device->depth_clip_control();
  Result<Pipeline> p = create_graphics_pipeline(*st.api, d, kWho);
  if (!p) return p.status();
  st.gbuffer_pipeline = std::move(*p);
  return Status::success();
}

namespace {

/// The G-buffer images and framebuffer for (m*w) x (m*h); the old ones are released first.
Status allocate_gbuffer(State& st, int width, int height, int m) {
  const Api& api = *st.api;
  st.framebuffer.reset();
  st.component.reset();  // it may hold descriptor sets naming the old views
  const VkExtent2D extent{std::uint32_t(width * m), std::uint32_t(height * m)};
  for (Image& img : st.g) {
    Result<Image> i =
        Image::create(api, VK_FORMAT_R32G32B32A32_SFLOAT, extent,
                      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                      std::string(kWho) + ": G-buffer");
    if (!i) return i.status();
    img = std::move(*i);
  }
  Result<Image> d =
      Image::create(api, VK_FORMAT_D32_SFLOAT, extent, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                    std::string(kWho) + ": G-buffer depth");
  if (!d) return d.status();
  st.depth = std::move(*d);
  const VkImageView views[4] = {st.g[0].view(), st.g[1].view(), st.g[2].view(), st.depth.view()};
  const VkFramebufferCreateInfo info{.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO,
                                     .renderPass = st.render_pass.get(),
                                     .attachmentCount = 4,
                                     .pAttachments = views,
                                     .width = extent.width,
                                     .height = extent.height,
                                     .layers = 1};
  if (Status s = assign(st.framebuffer, make_owned<Framebuffer>(api, &Api::CreateFramebuffer, info,
                                                                "vkCreateFramebuffer"));
      !s.ok()) {
    return s;
  }
  st.g_layout = VK_IMAGE_LAYOUT_UNDEFINED;
  st.set_written = false;  // the set names the G-buffer views
  st.w = width;
  st.h = height;
  st.m = m;
  return Status::success();
}

/// Camera data and vertices exactly as DeferredRenderer::render_gbuffer; clip z from OpenGL's
/// [-w, w] to Vulkan's [0, w] unless the pipeline keeps OpenGL's (VK_EXT_depth_clip_control:
/// then the depth test sees GL's window depths, bit for bit; the remap's rounding flips the
/// test where two surfaces meet).
void write_vertices(State& st, const scene::Camera& camera, int width, int height) {
  const deferred::GBufferCamera cam = deferred::gbuffer_camera(camera, width, height);
  st.camera = deferred::gpu_camera(cam, camera.far_z);
  for (std::size_t mi = 0; mi < st.scene->meshes.size(); ++mi) {
    const scene::Mesh& mesh = st.scene->meshes[mi];
    st.scratch.resize(mesh.positions.size() * 5);
    deferred::transform_gbuffer_vertices(cam, mesh.positions, st.scratch.data(), 5,
                                         st.scratch.data() + 4, 5, {});
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      float* v = &st.scratch[i * 5];
      if (!st.device->depth_clip_control()) v[2] = 0.5f * (v[2] + v[3]);
    }
    if (st.scratch.empty()) continue;
    std::memcpy(st.meshes[mi].dynamic.mapped(), st.scratch.data(), st.scratch.size() * 4);
    st.meshes[mi].dynamic.flush();
  }
}

void record_draws(State& st, VkCommandBuffer cmd, float far_z) {
  const Api& api = *st.api;
  const std::uint32_t gw = std::uint32_t(st.w * st.m), gh = std::uint32_t(st.h * st.m);
  std::array<VkClearValue, 4> clear{};
  clear[0].color = {{far_z, 0, 0, 0}};
  clear[1].color = {{-1, 0, 0, 0}};
  clear[2].color = {{0, 0, 0, 0}};
  clear[3].depthStencil = {1.0f, 0};
  VkRenderPassBeginInfo bi{};
  bi.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
  bi.renderPass = st.render_pass.get();
  bi.framebuffer = st.framebuffer.get();
  bi.renderArea = {{0, 0}, {gw, gh}};
  bi.clearValueCount = std::uint32_t(clear.size());
  bi.pClearValues = clear.data();
  api.CmdBeginRenderPass(cmd, &bi, VK_SUBPASS_CONTENTS_INLINE);
  const VkViewport viewport{0, 0, float(gw), float(gh), 0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, {gw, gh}};
  api.CmdSetViewport(cmd, 0, 1, &viewport);
  api.CmdSetScissor(cmd, 0, 1, &scissor);
  api.CmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, st.gbuffer_pipeline.get());
  for (const DeferredMesh& g : st.meshes) {
    if (g.index_count == 0) continue;
    const std::int32_t material = g.material;
    api.CmdPushConstants(cmd, st.gbuffer_layout.get(), VK_SHADER_STAGE_FRAGMENT_BIT, 0, 4,
                         &material);
    const VkBuffer buffers[2] = {g.dynamic.get(), g.statics.get()};
    const VkDeviceSize offsets[2] = {0, 0};
    api.CmdBindVertexBuffers(cmd, 0, 2, buffers, offsets);
    api.CmdBindIndexBuffer(cmd, g.indices.get(), 0, VK_INDEX_TYPE_UINT32);
    api.CmdDrawIndexed(cmd, std::uint32_t(g.index_count), 1, 0, 0, 0);
  }
  api.CmdEndRenderPass(cmd);
}

}  // namespace

Result<PassTime> DeferredRenderer::render_gbuffer(const scene::Camera& camera, int width,
                                                  int height, int m) {
  if (Status s = check_size(width, height, m); !s.ok()) return s;
  State& st = *state_;
  if (st.w != width || st.h != height || st.m != m || st.framebuffer.get() == VK_NULL_HANDLE) {
    if (Status s = allocate_gbuffer(st, width, height, m); !s.ok()) {
      st.framebuffer.reset();
      st.w = st.h = st.m = 0;
      return s;
    }
  }
  write_vertices(st, camera, width, height);
  Result<VkCommandBuffer> cmd = st.device->begin();
  if (!cmd) return cmd.status();
  const Api& api = *st.api;
  record_full_barrier(api, *cmd);
  record_timestamp(st, *cmd, 0);
  record_draws(st, *cmd, camera.far_z);
  record_timestamp(st, *cmd, 1);
  const auto wall0 = std::chrono::steady_clock::now();
  if (Status s = st.device->submit_and_wait(*cmd); !s.ok()) return s;
  const double wall =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wall0).count();
  st.g_layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  return PassTime{"gbuffer", wall, timestamp_ms(st)};
}

}  // namespace tessera::vk
