// The seam experiment drawn with Vulkan (face_renderer.h): creation (textures, mesh buffers,
// pipeline layout, timestamps), one pipeline per shader variant and sample count, the frame
// (class-grouped draws, resolve, timestamps) and the tiled reference.
#include <algorithm>
#include <chrono>
#include <cstring>
#include <string>

#include "vk/barriers.h"
#include "vk/face_renderer_internal.h"
#include "vk/graphics_pipeline.h"

namespace tessera::vk {

namespace {

constexpr const char* kWho = "vk face renderer";

Status unsupported(const std::string& what) {
  return Status::error(ErrorCode::unsupported, std::string(kWho) + ": " + what);
}
Status invalid(const std::string& what) {
  return Status::error(ErrorCode::invalid_argument, std::string(kWho) + ": " + what);
}

/// The sample counts every target of a frame can have: the framebuffer limits and what the
/// two formats allow as optimal-tiling attachments.
VkSampleCountFlags attachment_sample_counts(const Api& api) {
  const VkPhysicalDeviceLimits& lim = api.properties.limits;
  VkSampleCountFlags counts = lim.framebufferColorSampleCounts & lim.framebufferDepthSampleCounts;
  const struct {
    VkFormat format;
    VkImageUsageFlags usage;
  } formats[2] = {
      {kColourFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT},
      {kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT}};
  for (const auto& f : formats) {
    VkImageFormatProperties p{};
    if (api.GetPhysicalDeviceImageFormatProperties(api.ctx.physical_device, f.format,
                                                   VK_IMAGE_TYPE_2D, VK_IMAGE_TILING_OPTIMAL,
                                                   f.usage, 0, &p) != VK_SUCCESS) {
      return 0;
    }
    counts &= p.sampleCounts;
  }
  return counts;
}

/// What the frame needs of the device, named when missing.
Status check_device_support(const HeadlessDevice& device) {
  const Api& api = device.api();
  if (device.timestamp_ms_per_tick() <= 0.0) {
    return unsupported("the queue family has no timestamps (timestampValidBits = 0)");
  }
  VkFormatProperties colour{}, depth{};
  api.GetPhysicalDeviceFormatProperties(api.ctx.physical_device, kColourFormat, &colour);
  api.GetPhysicalDeviceFormatProperties(api.ctx.physical_device, kDepthFormat, &depth);
  const VkFormatFeatureFlags want_colour = VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT |
                                           VK_FORMAT_FEATURE_TRANSFER_SRC_BIT |
                                           VK_FORMAT_FEATURE_TRANSFER_DST_BIT;
  if ((colour.optimalTilingFeatures & want_colour) != want_colour) {
    return unsupported("R32G32B32A32_SFLOAT is no colour attachment with transfers here");
  }
  if (!(depth.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT)) {
    return unsupported("D32_SFLOAT is no depth attachment here");
  }
  return Status::success();
}

/// A host-visible buffer holding `bytes` bytes of `data` (null: left for later writes).
Result<Buffer> host_buffer(const Api& api, const void* data, std::size_t bytes,
                           VkBufferUsageFlags usage, const char* what) {
  Result<Buffer> b =
      Buffer::create(api, VkDeviceSize(bytes), usage, true, std::string(kWho) + ": " + what);
  if (!b) return b.status();
  if (data != nullptr) {
    std::memcpy(b->mapped(), data, bytes);
    b->flush();
  }
  return b;
}

Status create_mesh(FaceRenderer::State& s) {
  const faces::QuadMesh& m = s.scene->mesh;
  std::vector<float> normals;
  normals.reserve(std::size_t(m.face_count()) * 12);
  for (const Vec3& n : faces::smooth_face_normals(m)) {
    normals.insert(normals.end(), {n.x, n.y, n.z});
  }
  std::vector<std::uint32_t> indices;
  indices.reserve(std::size_t(m.face_count()) * 6);
  s.draws = faces::class_grouped_indices(s.textures->layout(), false, indices);
  s.clip_host.assign(std::size_t(m.face_count()) * 16, 0.0f);
  Result<Buffer> clip = host_buffer(*s.api, nullptr, s.clip_host.size() * 4,
                                    VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "clip positions");
  if (!clip) return clip.status();
  Result<Buffer> nb = host_buffer(*s.api, normals.data(), normals.size() * 4,
                                  VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "normals");
  if (!nb) return nb.status();
  Result<Buffer> ib = host_buffer(*s.api, indices.data(), indices.size() * 4,
                                  VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "indices");
  if (!ib) return ib.status();
  s.clip = std::move(*clip);
  s.normals = std::move(*nb);
  s.indices = std::move(*ib);
  return Status::success();
}

Status create_layout_and_queries(FaceRenderer::State& s) {
  const Api& api = *s.api;
  const VkDescriptorSetLayout set_layout = s.textures->set_layout();
  const VkPushConstantRange push{VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(std::int32_t)};
  const VkPipelineLayoutCreateInfo li{
      VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO, nullptr, 0, 1, &set_layout, 1, &push};
  VkPipelineLayout layout = VK_NULL_HANDLE;
  if (VkResult r = api.CreatePipelineLayout(api.device(), &li, api.alloc(), &layout);
      r != VK_SUCCESS) {
    return vk_error(std::string(kWho) + ": vkCreatePipelineLayout", r);
  }
  s.layout = PipelineLayout(api, layout);
  const VkQueryPoolCreateInfo qi{
      VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO, nullptr, 0, VK_QUERY_TYPE_TIMESTAMP, 3, 0};
  VkQueryPool pool = VK_NULL_HANDLE;
  if (VkResult r = api.CreateQueryPool(api.device(), &qi, api.alloc(), &pool); r != VK_SUCCESS) {
    return vk_error(std::string(kWho) + ": vkCreateQueryPool", r);
  }
  s.timestamps = QueryPool(api, pool);
  const std::uint32_t bits = api.queue_family.timestampValidBits;
  s.timestamp_mask = bits >= 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << bits) - 1;
  return Status::success();
}

Status check_frame(const FaceFrameOptions& o) {
  if (o.width < 1 || o.height < 1 || o.width > 16384 || o.height > 16384) {
    return invalid("bad frame size " + std::to_string(o.width) + "x" + std::to_string(o.height));
  }
  if (o.msaa != 1 && o.msaa != 2 && o.msaa != 4 && o.msaa != 8 && o.msaa != 16) {
    return invalid("MSAA " + std::to_string(o.msaa) + " not in 1,2,4,8,16");
  }
  if (o.filter != texture::TextureFilter::trilinear &&
      o.filter != texture::TextureFilter::anisotropic) {
    return invalid("the filter must be trilinear or anisotropic");
  }
  if (o.shading_only) return unsupported("no shading-only pass");
  if (!o.sample_pattern.empty()) {
    return unsupported(
        "frames are drawn at the device's sample locations, not at an explicit "
        "pattern");
  }
  return Status::success();
}

}  // namespace

Result<VkPipeline> FaceRenderer::State::pipeline(const FaceVariant& v) {
  if (auto it = pipelines.find(v.key()); it != pipelines.end()) return it->second.get();
  const auto shader_key = std::tuple(v.method, v.fallback, v.output);
  auto fs = fragment_spirv.find(shader_key);
  if (fs == fragment_spirv.end()) {
    std::vector<std::string> preamble = textures->glsl_defines(0);
    preamble.push_back("#define TESSERA_RENDER_METHOD " + std::to_string(v.method));
    preamble.push_back("#define TESSERA_RENDER_FALLBACK " + std::to_string(v.fallback));
    preamble.push_back("#define TESSERA_RENDER_OUTPUT " + std::to_string(v.output));
    if (class_constant) preamble.push_back("#define TESSERA_RENDER_CLASS_CONSTANT 1");
    Result<std::vector<std::uint32_t>> spirv =
        compile_shipped_stage(glsl::Stage::fragment, "seams_render.frag", preamble, kWho);
    if (!spirv) return spirv.status();
    fs = fragment_spirv.emplace(shader_key, std::move(*spirv)).first;
  }
  Result<VkRenderPass> pass = render_pass(v.samples);
  if (!pass) return pass.status();
  GraphicsPipelineDesc d;
  d.vertex_spirv = &vertex_spirv;
  d.fragment_spirv = &fs->second;
  d.bindings = {{0, 16, VK_VERTEX_INPUT_RATE_VERTEX}, {1, 12, VK_VERTEX_INPUT_RATE_VERTEX}};
  d.attributes = {{0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 0}, {1, 1, VK_FORMAT_R32G32B32_SFLOAT, 0}};
  d.layout = layout.get();
  d.render_pass = *pass;
  d.samples = VkSampleCountFlagBits(v.samples);
  const std::int32_t cls = v.cls;
  const VkSpecializationMapEntry entry{0, 0, sizeof cls};
  const VkSpecializationInfo spec{1, &entry, sizeof cls, &cls};
  if (v.cls >= 0) d.fragment_specialization = &spec;
  Result<Pipeline> p = create_graphics_pipeline(*api, d, kWho);
  if (!p) return p.status();
  return pipelines.emplace(v.key(), std::move(*p)).first->second.get();
}

Result<std::unique_ptr<FaceRenderer>> FaceRenderer::create(HeadlessDevice& device,
                                                           const faces::FaceScene& scene,
                                                           const faces::FaceTextureSet& set) {
  if (scene.mesh.face_count() != set.face_count()) {
    return Status::error(ErrorCode::size_mismatch,
                         scene.name + ": " + std::to_string(scene.mesh.face_count()) +
                             " faces but " + std::to_string(set.face_count()) + " face textures");
  }
  if (Status st = check_device_support(device); !st.ok()) return st;
  std::unique_ptr<FaceRenderer> r(new FaceRenderer());
  r->s_ = std::make_unique<State>();
  State& s = *r->s_;
  s.device = &device;
  s.api = &device.api();
  s.scene = &scene;
  s.set = &set;
  s.ms_per_tick = device.timestamp_ms_per_tick();
  s.sample_counts = attachment_sample_counts(*s.api);
  s.class_constant = device.features().shaderSampledImageArrayDynamicIndexing != VK_TRUE;
  FaceTextureSetOptions to;
  to.max_anisotropy = 16.0f;  // the paper's filter; trilinear frames get a set of their own
  Result<std::unique_ptr<FaceTextureSet>> tex = FaceTextureSet::create(device.context(), set, to);
  if (!tex) return tex.status();
  s.textures = std::move(*tex);
  if (Status st = create_mesh(s); !st.ok()) return st;
  if (Status st = create_layout_and_queries(s); !st.ok()) return st;
  Result<std::vector<std::uint32_t>> vs =
      compile_shipped_stage(glsl::Stage::vertex, "seams_render.vert", {}, kWho);
  if (!vs) return vs.status();
  s.vertex_spirv = std::move(*vs);
  return r;
}

FaceRenderer::~FaceRenderer() = default;

bool FaceRenderer::msaa_supported(int samples) const {
  if (samples != 1 && samples != 2 && samples != 4 && samples != 8 && samples != 16) return false;
  return (s_->sample_counts & VkSampleCountFlags(samples)) != 0;
}

bool FaceRenderer::standard_sample_locations() const {
  return s_->api->properties.limits.standardSampleLocations == VK_TRUE;
}

int FaceRenderer::class_count() const { return s_->textures->class_count(); }

int FaceRenderer::State::record_pass(VkCommandBuffer cmd, VkRenderPass pass,
                                     const FaceFrameOptions& o,
                                     const std::vector<VkPipeline>& class_pipelines,
                                     VkDescriptorSet textures_set) {
  api->CmdResetQueryPool(cmd, timestamps.get(), 0, 3);
  write_timestamp(*api, cmd, timestamps.get(), 0);
  const bool flags = o.output == SeamsOutput::zero_coverage;  // background 0: nothing flagged
  VkClearValue clear[2]{};
  for (std::size_t c = 0; c < 3; ++c) {
    clear[0].color.float32[c] = flags ? 0.0f : faces::kFaceBackground[c];
  }
  clear[1].depthStencil = {1.0f, 0};
  const VkExtent2D extent{std::uint32_t(o.width), std::uint32_t(o.height)};
  const VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO,
                                 nullptr,
                                 pass,
                                 targets.framebuffer.get(),
                                 {{0, 0}, extent},
                                 2,
                                 clear};
  api->CmdBeginRenderPass(cmd, &bi, VK_SUBPASS_CONTENTS_INLINE);
  const VkViewport viewport{0.0f, 0.0f, float(o.width), float(o.height), 0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, extent};
  api->CmdSetViewport(cmd, 0, 1, &viewport);
  api->CmdSetScissor(cmd, 0, 1, &scissor);
  api->CmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout.get(), 0, 1,
                             &textures_set, 0, nullptr);
  const VkBuffer vertex_buffers[2] = {clip.get(), normals.get()};
  const VkDeviceSize offsets[2] = {0, 0};
  api->CmdBindVertexBuffers(cmd, 0, 2, vertex_buffers, offsets);
  api->CmdBindIndexBuffer(cmd, indices.get(), 0, VK_INDEX_TYPE_UINT32);
  for (std::size_t i = 0; i < draws.size(); ++i) {
    const faces::FaceClassDraw& d = draws[i];
    if (i == 0 || class_constant) {
      api->CmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                           class_pipelines[class_constant ? i : 0]);
    }
    if (!class_constant) {
      const std::int32_t cls = d.cls;
      api->CmdPushConstants(cmd, layout.get(), VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof cls, &cls);
    }
    api->CmdDrawIndexed(cmd, std::uint32_t(d.count), 1, std::uint32_t(d.first), 0, 0);
  }
  api->CmdEndRenderPass(cmd);
  write_timestamp(*api, cmd, timestamps.get(), 1);
  return int(draws.size());
}

Result<ImageRGBAF> FaceRenderer::render_reference(const scene::Camera& camera, int width,
                                                  int height,
                                                  const faces::ReferenceOptions& options) {
  return faces::render_reference_with<FaceFrameOptions>(*this, camera, width, height, options);
}

Result<FaceFrame> FaceRenderer::render(const scene::Camera& camera, const FaceFrameOptions& o) {
  State& s = *s_;
  const Api& api = *s.api;
  if (Status st = check_frame(o); !st.ok()) return st;
  if (!msaa_supported(o.msaa)) {
    return unsupported("the device has no " + std::to_string(o.msaa) +
                       "x MSAA for R32G32B32A32_SFLOAT + D32_SFLOAT");
  }
  FaceVariant v;
  v.method = int(o.method);
  v.fallback = o.method == faces::SeamMethod::discard ? int(o.clamp_fallback) : 1;
  v.output = int(o.output);
  v.samples = o.msaa;
  std::vector<VkPipeline> pipelines;  // one per draw where the class is a constant, else one
  for (std::size_t i = 0; i < (s.class_constant ? s.draws.size() : 1); ++i) {
    if (s.class_constant) v.cls = s.draws[i].cls;
    Result<VkPipeline> p = s.pipeline(v);
    if (!p) return p.status();
    pipelines.push_back(*p);
  }
  const float max_aniso = std::max(1.0f, api.properties.limits.maxSamplerAnisotropy);
  const bool aniso = o.filter == texture::TextureFilter::anisotropic &&
                     api.ctx.enabled_features.samplerAnisotropy == VK_TRUE;
  Result<VkDescriptorSet> set =
      s.descriptor_set(aniso ? std::clamp(float(o.max_aniso), 1.0f, max_aniso) : 1.0f);
  if (!set) return set.status();
  if (Status st = s.ensure_targets(o.width, o.height, o.msaa); !st.ok()) return st;

  // Clip positions with the CPU renderer's arithmetic, z from [-w, w] to Vulkan's [0, w].
  faces::face_clip_positions(s.scene->mesh, camera, faces::frame_window(o), s.clip_host);
  for (std::size_t i = 0; i < s.clip_host.size(); i += 4) {
    s.clip_host[i + 2] = 0.5f * (s.clip_host[i + 2] + s.clip_host[i + 3]);
  }
  std::memcpy(s.clip.mapped(), s.clip_host.data(), s.clip_host.size() * 4);
  s.clip.flush();

  Result<VkRenderPass> pass = s.render_pass(o.msaa);  // made with the targets
  if (!pass) return pass.status();
  Result<VkCommandBuffer> cmd = s.device->begin();
  if (!cmd) return cmd.status();
  FaceFrame frame;
  frame.draw_calls = s.record_pass(*cmd, *pass, o, pipelines, *set);
  if (o.msaa > 1) s.record_resolve(*cmd);
  const auto t0 = std::chrono::steady_clock::now();
  if (Status st = s.device->submit_and_wait(*cmd); !st.ok()) return st;
  frame.wall_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::uint64_t ticks[3] = {0, 0, 0};
  const std::uint32_t stamps = o.msaa > 1 ? 3 : 2;
  if (VkResult r = api.GetQueryPoolResults(api.device(), s.timestamps.get(), 0, stamps,
                                           sizeof ticks, ticks, sizeof ticks[0],
                                           VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT);
      r != VK_SUCCESS) {
    return vk_error(std::string(kWho) + ": vkGetQueryPoolResults", r);
  }
  frame.gpu_ms_draw = double((ticks[1] - ticks[0]) & s.timestamp_mask) * s.ms_per_tick;
  if (o.msaa > 1) {
    frame.gpu_ms_resolve = double((ticks[2] - ticks[1]) & s.timestamp_mask) * s.ms_per_tick;
  }
  frame.ms = frame.gpu_ms_draw + frame.gpu_ms_resolve;
  if (o.keep_image) {
    Result<ImageRGBAF> image = s.read_back();
    if (!image) return image.status();
    frame.image = std::move(*image);
  }
  return frame;
}

}  // namespace tessera::vk
