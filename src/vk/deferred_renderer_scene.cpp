// vk::DeferredRenderer (deferred_renderer.h): the scene upload (the CPU's texture chains as
// RGBA32F arrays, materials, meshes), the geometry pass's render pass and pipeline
// (deferred_gbuffer.vert/.frag with VULKAN), the size check and the geometry pass.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "tessera/glsl.h"
#include "tessera/render.h"
#include "vk/barriers.h"
#include "vk/deferred_renderer.h"

// Vulkan's create-infos are written with designated initializers: the members left out are
// zero-initialised, which is what Vulkan asks of them (null pNext, no flags).
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace tessera::vk {

namespace {

using State = DeferredRenderer::State;

constexpr const char* kWho = "deferred VK";
constexpr VkFormat kGFormat = VK_FORMAT_R32G32B32A32_SFLOAT;

/// The texel data of one class: every layer's levels, tightly packed, with their copy regions.
struct ClassUpload {
  std::vector<float> texels;
  std::vector<VkBufferImageCopy> regions;
};

ClassUpload pack_class(const deferred::GpuTextureClasses::Class& c,
                       const std::vector<texture::Texture>& textures) {
  ClassUpload u;
  for (std::size_t layer = 0; layer < c.textures.size(); ++layer) {
    const texture::Texture& tex = textures[std::size_t(c.textures[layer])];
    for (int l = 0; l < c.levels; ++l) {
      const texture::TextureLevelView v = tex.level(0, l);
      VkBufferImageCopy r{};
      r.bufferOffset = u.texels.size() * sizeof(float);
      r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, std::uint32_t(l), std::uint32_t(layer), 1};
      r.imageExtent = {std::uint32_t(v.width), std::uint32_t(v.height), 1};
      u.regions.push_back(r);
      u.texels.insert(u.texels.end(), v.texels,
                      v.texels + std::size_t(v.width) * std::size_t(v.height) * 4);
    }
  }
  return u;
}

/// Creates one class's array image and view and uploads it (a submission of its own).
Status upload_class(State& st, const deferred::GpuTextureClasses::Class& c, const ClassUpload& u) {
  const Api& api = *st.api;
  TextureArray arr;
  const std::uint32_t levels = std::uint32_t(c.levels), layers = std::uint32_t(c.textures.size());
  const VkImageCreateInfo image_info{
      .sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
      .imageType = VK_IMAGE_TYPE_2D,
      .format = kGFormat,
      .extent = {std::uint32_t(c.width), std::uint32_t(c.height), 1},
      .mipLevels = levels,
      .arrayLayers = layers,
      .samples = VK_SAMPLE_COUNT_1_BIT,
      .tiling = VK_IMAGE_TILING_OPTIMAL,
      .usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
      .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED};
  if (Status s = assign(arr.image, make_owned<RawImage>(api, &Api::CreateImage, image_info,
                                                        "texture array: vkCreateImage"));
      !s.ok()) {
    return s;
  }
  const VkImage image = arr.image.get();
  VkMemoryRequirements req{};
  api.GetImageMemoryRequirements(api.device(), image, &req);
  bool local = false;
  Result<VkDeviceMemory> mem = allocate(api, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0,
                                        std::string(kWho) + ": texture array", &local);
  if (!mem) return mem.status();
  arr.memory = Memory(api, *mem);
  if (VkResult r = api.BindImageMemory(api.device(), image, *mem, 0); r != VK_SUCCESS) {
    return vk_error(std::string(kWho) + ": texture array: vkBindImageMemory", r);
  }
  const VkImageViewCreateInfo view_info{
      .sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
      .image = image,
      .viewType = VK_IMAGE_VIEW_TYPE_2D_ARRAY,  // sampler2DArray, one layer per texture
      .format = kGFormat,
      .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, levels, 0, layers}};
  if (Status s = assign(arr.view, make_owned<ImageView>(api, &Api::CreateImageView, view_info,
                                                        "texture array: vkCreateImageView"));
      !s.ok()) {
    return s;
  }

  Result<Buffer> staging =
      Buffer::create(api, u.texels.size() * sizeof(float), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true,
                     std::string(kWho) + ": texture staging");
  if (!staging) return staging.status();
  std::memcpy(staging->mapped(), u.texels.data(), u.texels.size() * sizeof(float));
  staging->flush();
  Result<VkCommandBuffer> cmd = st.device->begin();
  if (!cmd) return cmd.status();
  Barrier to_dst;
  to_dst.image(image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
               VK_ACCESS_2_TRANSFER_WRITE_BIT, levels, layers);
  to_dst.record(api, *cmd);
  api.CmdCopyBufferToImage(*cmd, staging->get(), image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           std::uint32_t(u.regions.size()), u.regions.data());
  Barrier to_read;
  to_read.image(image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, levels, layers);
  to_read.record(api, *cmd);
  if (Status s = st.device->submit_and_wait(*cmd); !s.ok()) return s;
  st.arrays.push_back(std::move(arr));
  return Status::success();
}

/// The texture classes (a 1x1 white dummy without any, so that the array binding is complete)
/// and the material buffer.
Status upload_textures(State& st) {
  Result<deferred::GpuTextureClasses> classes =
      deferred::gpu_texture_classes(st.scene->materials, st.cpu_textures, kWho);
  if (!classes) return classes.status();
  for (const deferred::GpuTextureClasses::Class& c : classes->classes) {
    if (Status s = upload_class(st, c, pack_class(c, st.cpu_textures)); !s.ok()) return s;
  }
  if (st.arrays.empty()) {
    ClassUpload dummy;
    dummy.texels = {1, 1, 1, 1};
    VkBufferImageCopy r{};
    r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    r.imageExtent = {1, 1, 1};
    dummy.regions.push_back(r);
    if (Status s = upload_class(st, {1, 1, 1, {-1}}, dummy); !s.ok()) return s;
  }
  const std::vector<deferred::GpuMaterial> mats =
      deferred::gpu_materials(st.scene->materials, st.cpu_textures, *classes);
  Result<Buffer> b =
      Buffer::create(*st.api, mats.size() * sizeof(deferred::GpuMaterial),
                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true, std::string(kWho) + ": materials");
  if (!b) return b.status();
  std::memcpy(b->mapped(), mats.data(), mats.size() * sizeof(deferred::GpuMaterial));
  b->flush();
  st.materials = std::move(*b);
  return Status::success();
}

Result<Buffer> host_buffer(const Api& api, const void* data, std::size_t bytes,
                           VkBufferUsageFlags usage, const char* what) {
  Result<Buffer> b = Buffer::create(api, std::max<std::size_t>(bytes, 16), usage, true,
                                    std::string(kWho) + ": " + what);
  if (!b) return b;
  if (data != nullptr && bytes > 0) std::memcpy(b->mapped(), data, bytes);
  b->flush();
  return b;
}

/// Per mesh: a host-visible vertex buffer rewritten per frame (clip xyzw, linear depth), a
/// static one (normal, uv) and the indices.
Status upload_meshes(State& st) {
  for (const scene::Mesh& mesh : st.scene->meshes) {
    DeferredMesh g;
    g.vertices = mesh.positions.size();
    g.index_count = mesh.indices.size();
    g.material = mesh.material;
    const std::vector<float> statics = deferred::gpu_static_vertices(mesh);
    Result<Buffer> d = host_buffer(*st.api, nullptr, g.vertices * 20,
                                   VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "vertices");
    Result<Buffer> s = host_buffer(*st.api, statics.data(), statics.size() * 4,
                                   VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "vertex attributes");
    Result<Buffer> i = host_buffer(*st.api, mesh.indices.data(), mesh.indices.size() * 4,
                                   VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "indices");
    for (const Result<Buffer>* b : {&d, &s, &i}) {
      if (!*b) return b->status();
    }
    g.dynamic = std::move(*d);
    g.statics = std::move(*s);
    g.indices = std::move(*i);
    st.meshes.push_back(std::move(g));
  }
  return Status::success();
}

Status create_samplers(State& st) {
  const Api& api = *st.api;
  // The texture arrays: trilinear, repeating, no hardware anisotropy (deferred_shading.glsl
  // builds the CPU's anisotropic filter from textureLod probes); the G-buffer: texelFetch only.
  const VkSamplerCreateInfo trilinear{.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO,
                                      .magFilter = VK_FILTER_LINEAR,
                                      .minFilter = VK_FILTER_LINEAR,
                                      .mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR,
                                      .addressModeU = VK_SAMPLER_ADDRESS_MODE_REPEAT,
                                      .addressModeV = VK_SAMPLER_ADDRESS_MODE_REPEAT,
                                      .addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT,
                                      .maxLod = VK_LOD_CLAMP_NONE};
  VkSamplerCreateInfo nearest = trilinear;
  nearest.magFilter = nearest.minFilter = VK_FILTER_NEAREST;
  nearest.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  nearest.addressModeU = nearest.addressModeV = nearest.addressModeW =
      VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  nearest.maxLod = 0.0f;
  const VkQueryPoolCreateInfo timestamps{.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
                                         .queryType = VK_QUERY_TYPE_TIMESTAMP,
                                         .queryCount = 2};
  for (Status s : {assign(st.texture_sampler, make_owned<Sampler>(api, &Api::CreateSampler,
                                                                  trilinear, "vkCreateSampler")),
                   assign(st.gbuffer_sampler, make_owned<Sampler>(api, &Api::CreateSampler, nearest,
                                                                  "vkCreateSampler")),
                   assign(st.queries, make_owned<QueryPool>(api, &Api::CreateQueryPool, timestamps,
                                                            "vkCreateQueryPool"))}) {
    if (!s.ok()) return s;
  }
  return Status::success();
}

/// Three RGBA32F colour targets and D32 depth, cleared; the colour targets end in
/// COLOR_ATTACHMENT_OPTIMAL (the readers record their own transition).
Status create_render_pass(State& st) {
  const Api& api = *st.api;
  std::array<VkAttachmentDescription, 4> att{};
  for (std::size_t i = 0; i < 4; ++i) {
    att[i].format = i < 3 ? kGFormat : VK_FORMAT_D32_SFLOAT;
    att[i].samples = VK_SAMPLE_COUNT_1_BIT;
    att[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    att[i].storeOp = i < 3 ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
    att[i].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    att[i].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    att[i].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    att[i].finalLayout = i < 3 ? VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL
                               : VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  }
  const VkAttachmentReference colour[3] = {{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
                                           {1, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
                                           {2, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL}};
  const VkAttachmentReference depth = {3, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription sub{};
  sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  sub.colorAttachmentCount = 3;
  sub.pColorAttachments = colour;
  sub.pDepthStencilAttachment = &depth;
  // The clears and the draws after the previous frame's compute reads and attachment writes.
  VkSubpassDependency dep{};
  dep.srcSubpass = VK_SUBPASS_EXTERNAL;
  dep.dstSubpass = 0;
  dep.srcStageMask = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT |
                     VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                     VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
  dep.srcAccessMask =
      VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  dep.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                     VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                     VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  dep.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                      VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                      VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  const VkRenderPassCreateInfo info{.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO,
                                    .attachmentCount = std::uint32_t(att.size()),
                                    .pAttachments = att.data(),
                                    .subpassCount = 1,
                                    .pSubpasses = &sub,
                                    .dependencyCount = 1,
                                    .pDependencies = &dep};
  return assign(st.render_pass,
                make_owned<RenderPass>(api, &Api::CreateRenderPass, info, "vkCreateRenderPass"));
}

}  // namespace

DeferredRenderer::~DeferredRenderer() = default;

Result<std::unique_ptr<DeferredRenderer>> DeferredRenderer::create(HeadlessDevice& device,
                                                                   const scene::Scene& scene) {
  std::unique_ptr<DeferredRenderer> r(new DeferredRenderer());
  r->state_ = std::make_unique<State>();
  State& st = *r->state_;
  st.device = &device;
  st.api = &device.api();
  st.scene = &scene;
  Result<std::vector<texture::Texture>> textures = render::build_scene_textures(scene, {});
  if (!textures) return textures.status();
  st.cpu_textures = std::move(*textures);
  for (Status s :
       {create_samplers(st), upload_textures(st), upload_meshes(st), create_render_pass(st)}) {
    if (!s.ok()) return s;
  }
  if (Status s = create_gbuffer_pipeline(st); !s.ok()) return s;
  if (Status s = create_deferred_set(st); !s.ok()) return s;
  return r;
}

Status DeferredRenderer::check_size(int width, int height, int m) const {
  if (m < 1 || m > 8) {
    return Status::error(
        ErrorCode::invalid_argument,
        std::string(kWho) + ": window size m must be in [1, 8], got " + std::to_string(m));
  }
  if (width < 1 || height < 1) {
    return Status::error(ErrorCode::invalid_argument, std::string(kWho) + ": bad output size " +
                                                          std::to_string(width) + "x" +
                                                          std::to_string(height));
  }
  const VkPhysicalDeviceLimits& lim = state_->api->properties.limits;
  const std::int64_t gw = std::int64_t(width) * m, gh = std::int64_t(height) * m;
  struct Limit {
    std::int64_t value;
    std::uint32_t limit;
    const char* name;
  };
  const Limit limits[] = {{std::max(gw, gh), lim.maxImageDimension2D, "maxImageDimension2D"},
                          {gw, lim.maxFramebufferWidth, "maxFramebufferWidth"},
                          {gh, lim.maxFramebufferHeight, "maxFramebufferHeight"}};
  for (const Limit& l : limits) {
    if (l.value > std::int64_t(l.limit)) {
      return Status::error(ErrorCode::too_large,
                           std::string(kWho) + ": G-buffer " + std::to_string(gw) + "x" +
                               std::to_string(gh) + " (" + std::to_string(width) + "x" +
                               std::to_string(height) + ", m = " + std::to_string(m) +
                               ") exceeds " + l.name + " = " + std::to_string(l.limit));
    }
  }
  return Status::success();
}

}  // namespace tessera::vk
