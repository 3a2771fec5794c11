// Per-face textures on Vulkan (tessera/vk_faces.h): the shared GPU layout (tessera/faces_gpu.h)
// uploaded through the engine's queue, every mip level from the CPU chains, so Vulkan, GL and
// the CPU filter the same texels; samplers and a descriptor set as seams.glsl reads them.
#include <algorithm>
#include <cstring>
#include <utility>

#include "tessera/faces.h"
#include "tessera/vk_faces.h"
#include "vk/vk_api.h"

namespace tessera::vk {

namespace {

constexpr int kMaxClasses = 16;  // seams.glsl's TESSERA_SEAMS_CLASSES range

Status invalid(const std::string& msg) {
  return Status::error(ErrorCode::invalid_argument, "vk::FaceTextureSet: " + msg);
}

VkFormat vk_format(faces::TexelFormat f) {
  switch (f) {
    case faces::TexelFormat::rgba32f:
      return VK_FORMAT_R32G32B32A32_SFLOAT;
    case faces::TexelFormat::rgba16f:
      return VK_FORMAT_R16G16B16A16_SFLOAT;
    case faces::TexelFormat::rgba8_unorm:
      return VK_FORMAT_R8G8B8A8_UNORM;
    case faces::TexelFormat::rgba8_srgb:
      return VK_FORMAT_R8G8B8A8_SRGB;
  }
  return VK_FORMAT_R32G32B32A32_SFLOAT;
}

const char* format_name(faces::TexelFormat f) {
  switch (f) {
    case faces::TexelFormat::rgba32f:
      return "R32G32B32A32_SFLOAT";
    case faces::TexelFormat::rgba16f:
      return "R16G16B16A16_SFLOAT";
    case faces::TexelFormat::rgba8_unorm:
      return "R8G8B8A8_UNORM";
    case faces::TexelFormat::rgba8_srgb:
      return "R8G8B8A8_SRGB";
  }
  return "?";
}

// The staging buffer's contents: per class, per level, per layer the level's texels (tight
// rows), then the face records. `regions[c]` are the class's copies.
struct Staging {
  std::vector<std::vector<VkBufferImageCopy>> regions;
  VkDeviceSize records_offset = 0, bytes = 0;
};

}  // namespace

struct detail::FaceTextureSetState {
  Api api;
  faces::PackedFaces layout;
  FaceTextureSetBindings bindings;
  std::vector<Memory> memories;  // destroyed after the images bound to them
  std::vector<RawImage> images;
  std::vector<ImageView> views;
  Buffer records;
  Sampler border, clamp;
  SetLayout set_layout;
  DescriptorPool pool;
  VkDescriptorSet set = VK_NULL_HANDLE;
  float anisotropy = 1.0f;
  std::uint64_t texture_bytes = 0;
  faces::TexelFormat format = faces::TexelFormat::rgba32f;
  // FaceUpload::engine_command_buffer: the filled staging buffer until release_staging.
  FaceUpload upload = FaceUpload::queue_submit;
  Buffer staging;
  Staging plan;
  bool recorded = false;
};

namespace {

Status check_bindings(const FaceTextureSetBindings& b) {
  if (b.faces == b.border || b.faces == b.clamp || b.border == b.clamp) {
    return invalid("bindings collide (faces " + std::to_string(b.faces) + ", border " +
                   std::to_string(b.border) + ", clamp " + std::to_string(b.clamp) +
                   "): the storage buffer and the two sampler arrays need three binding numbers");
  }
  if (b.stages == 0) return invalid("bindings.stages is empty");
  return Status::success();
}

Status check_format(const Api& api, faces::TexelFormat format) {
  VkFormatProperties fp{};
  api.GetPhysicalDeviceFormatProperties(api.ctx.physical_device, vk_format(format), &fp);
  const VkFormatFeatureFlags need = VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT |
                                    VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT |
                                    VK_FORMAT_FEATURE_TRANSFER_DST_BIT;
  if ((fp.optimalTilingFeatures & need) != need) {
    return Status::error(ErrorCode::unsupported,
                         std::string("vk::FaceTextureSet: the device does not sample ") +
                             format_name(format) +
                             " optimal-tiling images with linear filtering (options.format)");
  }
  return Status::success();
}

// One 2D-array image per class with its memory and an array view of every level and layer.
Status create_images(detail::FaceTextureSetState& s) {
  const Api& api = s.api;
  for (const faces::FaceClass& c : s.layout.classes) {
    const std::string what = "vk::FaceTextureSet: " + std::to_string(c.faces.size()) +
                             " faces of " + std::to_string(c.width) + "x" +
                             std::to_string(c.height);
    VkImageCreateInfo ci{};
    ci.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
    ci.imageType = VK_IMAGE_TYPE_2D;
    ci.format = vk_format(s.format);
    ci.extent = {std::uint32_t(c.width), std::uint32_t(c.height), 1};
    ci.mipLevels = std::uint32_t(c.levels);
    ci.arrayLayers = std::uint32_t(c.faces.size());
    ci.samples = VK_SAMPLE_COUNT_1_BIT;
    ci.tiling = VK_IMAGE_TILING_OPTIMAL;
    ci.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImage image = VK_NULL_HANDLE;
    if (VkResult r = api.CreateImage(api.device(), &ci, api.alloc(), &image); r != VK_SUCCESS) {
      return vk_error(what + ": vkCreateImage", r);
    }
    s.images.emplace_back(api, image);
    VkMemoryRequirements req{};
    api.GetImageMemoryRequirements(api.device(), image, &req);
    bool local = false;
    Result<VkDeviceMemory> mem =
        allocate(api, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0, what, &local);
    if (!mem) return mem.status();
    s.memories.emplace_back(api, *mem);
    if (VkResult r = api.BindImageMemory(api.device(), image, *mem, 0); r != VK_SUCCESS) {
      return vk_error(what + ": vkBindImageMemory", r);
    }
    VkImageViewCreateInfo vi{};
    vi.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
    vi.image = image;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D_ARRAY;
    vi.format = vk_format(s.format);
    vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, ci.mipLevels, 0, ci.arrayLayers};
    VkImageView view = VK_NULL_HANDLE;
    if (VkResult r = api.CreateImageView(api.device(), &vi, api.alloc(), &view); r != VK_SUCCESS) {
      return vk_error(what + ": vkCreateImageView", r);
    }
    s.views.emplace_back(api, view);
  }
  return Status::success();
}

Staging plan_staging(detail::FaceTextureSetState& s, const faces::FaceTextureSet& set) {
  Staging st;
  VkDeviceSize at = 0;
  for (const faces::FaceClass& c : s.layout.classes) {
    std::vector<VkBufferImageCopy> regions;
    const texture::Texture& t0 = set.texture(c.faces[0]);
    for (int level = 0; level < c.levels; ++level) {
      const texture::TextureLevelView v = t0.level(0, level);
      VkBufferImageCopy r{};
      r.bufferOffset = at;
      r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, std::uint32_t(level), 0,
                            std::uint32_t(c.faces.size())};
      r.imageExtent = {std::uint32_t(v.width), std::uint32_t(v.height), 1};
      regions.push_back(r);
      const VkDeviceSize bytes = VkDeviceSize(v.width) * VkDeviceSize(v.height) * c.faces.size() *
                                 faces::texel_bytes(s.format);
      at += bytes;
      s.texture_bytes += bytes;
    }
    st.regions.push_back(std::move(regions));
  }
  st.records_offset = at;
  st.bytes = at + s.layout.records.size() * sizeof(faces::FaceRecord);
  return st;
}

void fill_staging(const detail::FaceTextureSetState& s, const faces::FaceTextureSet& set,
                  const Staging& st, std::uint8_t* dst) {
  for (std::size_t ci = 0; ci < s.layout.classes.size(); ++ci) {
    const faces::FaceClass& c = s.layout.classes[ci];
    for (int level = 0; level < c.levels; ++level) {
      std::uint8_t* at = dst + st.regions[ci][std::size_t(level)].bufferOffset;
      for (int face : c.faces) {
        const texture::TextureLevelView v = set.texture(face).level(0, level);
        const std::size_t texels = std::size_t(v.width) * std::size_t(v.height);
        faces::convert_texels(v.texels, texels, s.format, at);
        at += texels * faces::texel_bytes(s.format);
      }
    }
  }
  std::memcpy(dst + st.records_offset, s.layout.records.data(),
              s.layout.records.size() * sizeof(faces::FaceRecord));
}

void image_barrier(const Api& api, VkCommandBuffer cmd, VkImage image, const faces::FaceClass& c,
                   bool to_read) {
  VkImageMemoryBarrier b{};
  b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
  b.srcAccessMask = to_read ? VK_ACCESS_TRANSFER_WRITE_BIT : 0;
  b.dstAccessMask = to_read ? VK_ACCESS_SHADER_READ_BIT : VK_ACCESS_TRANSFER_WRITE_BIT;
  b.oldLayout = to_read ? VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL : VK_IMAGE_LAYOUT_UNDEFINED;
  b.newLayout =
      to_read ? VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL : VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, std::uint32_t(c.levels), 0,
                        std::uint32_t(c.faces.size())};
  api.CmdPipelineBarrier(
      cmd, to_read ? VK_PIPELINE_STAGE_TRANSFER_BIT : VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
      to_read ? VK_PIPELINE_STAGE_ALL_COMMANDS_BIT : VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr,
      0, nullptr, 1, &b);
}

}  // namespace

// The copies of the staging buffer into the images and the record buffer.
void record_upload_commands(const detail::FaceTextureSetState& s, const Staging& st,
                            VkBuffer staging, VkCommandBuffer cmd) {
  const Api& api = s.api;
  for (std::size_t c = 0; c < s.images.size(); ++c) {
    image_barrier(api, cmd, s.images[c].get(), s.layout.classes[c], false);
    api.CmdCopyBufferToImage(cmd, staging, s.images[c].get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                             std::uint32_t(st.regions[c].size()), st.regions[c].data());
    image_barrier(api, cmd, s.images[c].get(), s.layout.classes[c], true);
  }
  VkBufferCopy copy{st.records_offset, 0, s.records.size()};
  api.CmdCopyBuffer(cmd, staging, s.records.get(), 1, &copy);
  VkBufferMemoryBarrier bb{};
  bb.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER;
  bb.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  bb.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
  bb.srcQueueFamilyIndex = bb.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  bb.buffer = s.records.get();
  bb.size = VK_WHOLE_SIZE;
  api.CmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0,
                         0, nullptr, 1, &bb, 0, nullptr);
}

namespace {

// The staging buffer, planned and filled (kept in the state).
Status stage(detail::FaceTextureSetState& s, const faces::FaceTextureSet& set) {
  s.plan = plan_staging(s, set);
  Result<Buffer> staging = Buffer::create(s.api, s.plan.bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                          true, "vk::FaceTextureSet: staging buffer");
  if (!staging) return staging.status();
  s.staging = std::move(*staging);
  fill_staging(s, set, s.plan, static_cast<std::uint8_t*>(s.staging.mapped()));
  s.staging.flush();
  return Status::success();
}

// FaceUpload::queue_submit: one command buffer on the engine's queue, one submit, one fence
// waited on; the staging buffer freed.
Status upload(detail::FaceTextureSetState& s) {
  const Api& api = s.api;
  const Staging& st = s.plan;
  const Buffer* staging = &s.staging;
  VkCommandPoolCreateInfo pi{};
  pi.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  pi.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  pi.queueFamilyIndex = api.ctx.queue_family;
  VkCommandPool pool_handle = VK_NULL_HANDLE;
  if (VkResult r = api.CreateCommandPool(api.device(), &pi, api.alloc(), &pool_handle);
      r != VK_SUCCESS) {
    return vk_error("vk::FaceTextureSet: vkCreateCommandPool", r);
  }
  const CommandPool pool(api, pool_handle);
  VkCommandBufferAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  ai.commandPool = pool.get();
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;  // freed with the pool
  if (VkResult r = api.AllocateCommandBuffers(api.device(), &ai, &cmd); r != VK_SUCCESS) {
    return vk_error("vk::FaceTextureSet: vkAllocateCommandBuffers", r);
  }
  VkCommandBufferBeginInfo bi{};
  bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  if (VkResult r = api.BeginCommandBuffer(cmd, &bi); r != VK_SUCCESS) {
    return vk_error("vk::FaceTextureSet: vkBeginCommandBuffer", r);
  }
  record_upload_commands(s, st, staging->get(), cmd);
  if (VkResult r = api.EndCommandBuffer(cmd); r != VK_SUCCESS) {
    return vk_error("vk::FaceTextureSet: vkEndCommandBuffer", r);
  }
  VkFenceCreateInfo fi{};
  fi.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
  VkFence fence_handle = VK_NULL_HANDLE;
  if (VkResult r = api.CreateFence(api.device(), &fi, api.alloc(), &fence_handle);
      r != VK_SUCCESS) {
    return vk_error("vk::FaceTextureSet: vkCreateFence", r);
  }
  const Fence fence(api, fence_handle);
  VkSubmitInfo si{};
  si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  if (VkResult r = api.QueueSubmit(api.ctx.queue, 1, &si, fence.get()); r != VK_SUCCESS) {
    return vk_error("vk::FaceTextureSet: vkQueueSubmit", r);
  }
  if (VkResult r = api.WaitForFences(api.device(), 1, &fence_handle, VK_TRUE, UINT64_MAX);
      r != VK_SUCCESS) {
    return vk_error("vk::FaceTextureSet: vkWaitForFences", r);
  }
  s.staging.reset();
  s.recorded = true;
  return Status::success();
}

Status create_samplers(detail::FaceTextureSetState& s, float max_anisotropy) {
  const Api& api = s.api;
  const bool aniso_on = api.ctx.enabled_features.samplerAnisotropy == VK_TRUE;
  s.anisotropy = aniso_on ? std::clamp(max_anisotropy, 1.0f,
                                       std::max(1.0f, api.properties.limits.maxSamplerAnisotropy))
                          : 1.0f;
  for (Sampler* out : {&s.border, &s.clamp}) {
    const VkSamplerAddressMode mode = out == &s.border ? VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER
                                                       : VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    VkSamplerCreateInfo ci{};
    ci.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
    ci.magFilter = VK_FILTER_LINEAR;
    ci.minFilter = VK_FILTER_LINEAR;
    ci.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    ci.addressModeU = ci.addressModeV = ci.addressModeW = mode;
    ci.anisotropyEnable = s.anisotropy > 1.0f ? VK_TRUE : VK_FALSE;
    ci.maxAnisotropy = s.anisotropy;
    ci.minLod = 0.0f;
    ci.maxLod = VK_LOD_CLAMP_NONE;
    ci.borderColor = VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;
    VkSampler h = VK_NULL_HANDLE;
    if (VkResult r = api.CreateSampler(api.device(), &ci, api.alloc(), &h); r != VK_SUCCESS) {
      return vk_error("vk::FaceTextureSet: vkCreateSampler", r);
    }
    *out = Sampler(api, h);
  }
  return Status::success();
}

// The set layout, a pool of one set, the set, written.
Status create_descriptors(detail::FaceTextureSetState& s) {
  const Api& api = s.api;
  const auto n = std::uint32_t(s.layout.classes.size());
  const FaceTextureSetBindings& b = s.bindings;
  const VkDescriptorSetLayoutBinding lb[3] = {
      {b.faces, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, b.stages, nullptr},
      {b.border, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, n, b.stages, nullptr},
      {b.clamp, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, n, b.stages, nullptr}};
  VkDescriptorSetLayoutCreateInfo li{};
  li.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  li.bindingCount = 3;
  li.pBindings = lb;
  VkDescriptorSetLayout layout = VK_NULL_HANDLE;
  if (VkResult r = api.CreateDescriptorSetLayout(api.device(), &li, api.alloc(), &layout);
      r != VK_SUCCESS) {
    return vk_error("vk::FaceTextureSet: vkCreateDescriptorSetLayout", r);
  }
  s.set_layout = SetLayout(api, layout);
  const VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1},
                                         {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2 * n}};
  VkDescriptorPoolCreateInfo pi{};
  pi.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  pi.maxSets = 1;
  pi.poolSizeCount = 2;
  pi.pPoolSizes = sizes;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  if (VkResult r = api.CreateDescriptorPool(api.device(), &pi, api.alloc(), &pool);
      r != VK_SUCCESS) {
    return vk_error("vk::FaceTextureSet: vkCreateDescriptorPool", r);
  }
  s.pool = DescriptorPool(api, pool);
  VkDescriptorSetAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  ai.descriptorPool = pool;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &layout;
  if (VkResult r = api.AllocateDescriptorSets(api.device(), &ai, &s.set); r != VK_SUCCESS) {
    return vk_error("vk::FaceTextureSet: vkAllocateDescriptorSets", r);
  }
  const VkDescriptorBufferInfo records{s.records.get(), 0, VK_WHOLE_SIZE};
  std::vector<VkDescriptorImageInfo> border, clamp;
  for (const ImageView& v : s.views) {
    border.push_back({s.border.get(), v.get(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
    clamp.push_back({s.clamp.get(), v.get(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
  }
  VkWriteDescriptorSet w[3]{};
  for (int i = 0; i < 3; ++i) {
    w[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    w[i].dstSet = s.set;
    w[i].dstBinding = lb[i].binding;
    w[i].descriptorCount = lb[i].descriptorCount;
    w[i].descriptorType = lb[i].descriptorType;
  }
  w[0].pBufferInfo = &records;
  w[1].pImageInfo = border.data();
  w[2].pImageInfo = clamp.data();
  api.UpdateDescriptorSets(api.device(), 3, w, 0, nullptr);
  return Status::success();
}

}  // namespace

Result<std::unique_ptr<FaceTextureSet>> FaceTextureSet::create(
    const DeviceContext& device, const faces::FaceTextureSet& set,
    const FaceTextureSetOptions& options) {
  if (set.face_count() == 0) return invalid("the face set has no faces");
  if (Status st = check_bindings(options.bindings); !st.ok()) return st;
  Result<Api> api = load_api(device);
  if (!api) return api.status();
  if (device.queue == VK_NULL_HANDLE && options.upload == FaceUpload::queue_submit)
    return invalid(
        "DeviceContext::queue is null (create uploads; or FaceUpload::engine_command_buffer)");
  auto s = std::make_unique<detail::FaceTextureSetState>();
  s->api = std::move(*api);
  s->bindings = options.bindings;
  s->format = options.format;
  s->upload = options.upload;
  if (Status st = check_format(s->api, s->format); !st.ok()) return st;
  const VkPhysicalDeviceLimits& lim = s->api.properties.limits;
  faces::PackLimits limits;
  limits.max_texture_size = int(std::min<std::uint32_t>(lim.maxImageDimension2D, 1u << 30));
  limits.max_array_layers = int(std::min<std::uint32_t>(lim.maxImageArrayLayers, 1u << 30));
  limits.max_classes = std::min<int>(
      kMaxClasses,
      int(std::min<std::uint32_t>(lim.maxPerStageDescriptorSamplers, 2 * kMaxClasses) / 2));
  limits.max_ssbo_bytes = std::int64_t(lim.maxStorageBufferRange);
  faces::PackLimitNames names;
  names.texture_size = "maxImageDimension2D";
  names.array_layers = "maxImageArrayLayers";
  names.ssbo_bytes = "maxStorageBufferRange";
  Result<faces::PackedFaces> packed = faces::pack_faces(set, limits, names);
  if (!packed) {
    return Status::error(packed.status().code, "vk::FaceTextureSet: " + packed.status().message);
  }
  s->layout = std::move(*packed);
  Result<Buffer> records =
      Buffer::create(s->api, s->layout.records.size() * sizeof(faces::FaceRecord),
                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false,
                     "vk::FaceTextureSet: face records");
  if (!records) return records.status();
  s->records = std::move(*records);
  if (Status st = create_images(*s); !st.ok()) return st;
  if (Status st = stage(*s, set); !st.ok()) return st;
  if (s->upload == FaceUpload::queue_submit) {
    if (Status st = upload(*s); !st.ok()) return st;
  }
  if (Status st = create_samplers(*s, options.max_anisotropy); !st.ok()) return st;
  if (Status st = create_descriptors(*s); !st.ok()) return st;
  return std::unique_ptr<FaceTextureSet>(new FaceTextureSet(std::move(s)));
}

FaceTextureSet::FaceTextureSet(std::unique_ptr<detail::FaceTextureSetState> s) : s_(std::move(s)) {}
FaceTextureSet::~FaceTextureSet() = default;

const faces::PackedFaces& FaceTextureSet::layout() const { return s_->layout; }
int FaceTextureSet::class_count() const { return int(s_->layout.classes.size()); }
const FaceTextureSetBindings& FaceTextureSet::bindings() const { return s_->bindings; }
VkDescriptorSetLayout FaceTextureSet::set_layout() const { return s_->set_layout.get(); }
VkDescriptorSet FaceTextureSet::descriptor_set() const { return s_->set; }
VkImage FaceTextureSet::image(int cls) const { return s_->images.at(std::size_t(cls)).get(); }
VkImageView FaceTextureSet::image_view(int cls) const {
  return s_->views.at(std::size_t(cls)).get();
}
VkBuffer FaceTextureSet::record_buffer() const { return s_->records.get(); }
VkSampler FaceTextureSet::border_sampler() const { return s_->border.get(); }
VkSampler FaceTextureSet::clamp_sampler() const { return s_->clamp.get(); }
float FaceTextureSet::anisotropy() const { return s_->anisotropy; }
std::uint64_t FaceTextureSet::texture_bytes() const { return s_->texture_bytes; }
faces::TexelFormat FaceTextureSet::format() const { return s_->format; }
bool FaceTextureSet::upload_recorded() const { return s_->recorded; }

Status FaceTextureSet::record_upload(VkCommandBuffer cmd) {
  if (s_->upload != FaceUpload::engine_command_buffer) {
    return invalid("record_upload: create uploaded already (options.upload = queue_submit)");
  }
  if (s_->recorded) return invalid("record_upload: the upload is recorded already");
  if (cmd == VK_NULL_HANDLE) return invalid("record_upload: no VkCommandBuffer");
  record_upload_commands(*s_, s_->plan, s_->staging.get(), cmd);
  s_->recorded = true;
  return Status::success();
}

Status FaceTextureSet::release_staging() {
  if (!s_->recorded) return invalid("release_staging before record_upload");
  s_->staging.reset();
  return Status::success();
}

Status FaceTextureSet::bind(VkCommandBuffer cmd, VkPipelineBindPoint bind_point,
                            VkPipelineLayout pipeline_layout, std::uint32_t set) const {
  if (cmd == VK_NULL_HANDLE || pipeline_layout == VK_NULL_HANDLE) {
    return invalid("bind: null command buffer or pipeline layout");
  }
  const std::uint32_t max_sets = s_->api.properties.limits.maxBoundDescriptorSets;
  if (set >= max_sets) {
    return invalid("bind: set " + std::to_string(set) +
                   " >= maxBoundDescriptorSets = " + std::to_string(max_sets));
  }
  s_->api.CmdBindDescriptorSets(cmd, bind_point, pipeline_layout, set, 1, &s_->set, 0, nullptr);
  return Status::success();
}

std::vector<std::string> FaceTextureSet::glsl_defines(std::uint32_t set) const {
  return {"#define TESSERA_SEAMS_CLASSES " + std::to_string(class_count()),
          "#define TESSERA_SEAMS_SET " + std::to_string(set),
          "#define TESSERA_SEAMS_FACES_BINDING " + std::to_string(s_->bindings.faces),
          "#define TESSERA_SEAMS_BORDER_BINDING " + std::to_string(s_->bindings.border),
          "#define TESSERA_SEAMS_CLAMP_BINDING " + std::to_string(s_->bindings.clamp)};
}

}  // namespace tessera::vk
