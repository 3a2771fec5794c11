// The Vulkan face renderer's render passes, attachments (colour, depth, resolve target, read-back
// buffer), texture sets of other anisotropies and read-back (face_renderer_internal.h).
#include <cstring>
#include <string>

#include "vk/barriers.h"
#include "vk/face_renderer_internal.h"

namespace tessera::vk {

namespace {

constexpr const char* kWho = "vk face renderer";

std::string who(const char* what) { return std::string(kWho) + ": " + what; }

/// A 2D image of `samples` samples with device-local memory and a view of `aspect` (none for
/// aspect 0: an image only copied to and from).
Result<Attachment> create_attachment(const Api& api, VkFormat format, int width, int height,
                                     int samples, VkImageUsageFlags usage,
                                     VkImageAspectFlags aspect) {
  Attachment a;
  const VkImageCreateInfo ci{.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
                             .pNext = nullptr,
                             .flags = 0,
                             .imageType = VK_IMAGE_TYPE_2D,
                             .format = format,
                             .extent = {std::uint32_t(width), std::uint32_t(height), 1},
                             .mipLevels = 1,
                             .arrayLayers = 1,
                             .samples = VkSampleCountFlagBits(samples),
                             .tiling = VK_IMAGE_TILING_OPTIMAL,
                             .usage = usage,
                             .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
                             .queueFamilyIndexCount = 0,
                             .pQueueFamilyIndices = nullptr,
                             .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED};
  VkImage image = VK_NULL_HANDLE;
  if (VkResult r = api.CreateImage(api.device(), &ci, api.alloc(), &image); r != VK_SUCCESS) {
    return vk_error(who("vkCreateImage"), r);
  }
  a.image = RawImage(api, image);
  VkMemoryRequirements req{};
  api.GetImageMemoryRequirements(api.device(), image, &req);
  bool local = false;
  Result<VkDeviceMemory> mem =
      allocate(api, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0, who("target memory"), &local);
  if (!mem) return mem.status();
  a.memory = Memory(api, *mem);
  if (VkResult r = api.BindImageMemory(api.device(), image, *mem, 0); r != VK_SUCCESS) {
    return vk_error(who("vkBindImageMemory"), r);
  }
  if (aspect == 0) return a;
  const VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
                                 nullptr,
                                 0,
                                 image,
                                 VK_IMAGE_VIEW_TYPE_2D,
                                 format,
                                 {},
                                 {aspect, 0, 1, 0, 1}};
  VkImageView view = VK_NULL_HANDLE;
  if (VkResult r = api.CreateImageView(api.device(), &vi, api.alloc(), &view); r != VK_SUCCESS) {
    return vk_error(who("vkCreateImageView"), r);
  }
  a.view = ImageView(api, view);
  return a;
}

}  // namespace

// Colour and depth of `samples` samples, both cleared; the colour ends in TRANSFER_SRC_OPTIMAL
// for the resolve or the read-back. The external dependencies order the pass after the previous
// frame's transfers (resolve, copy) and depth writes, and the copies after the pass.
Result<VkRenderPass> FaceRenderer::State::render_pass(int samples) {
  if (auto it = passes.find(samples); it != passes.end()) return it->second.get();
  const auto n = VkSampleCountFlagBits(samples);
  const VkAttachmentDescription att[2] = {
      {0, kColourFormat, n, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE,
       VK_ATTACHMENT_LOAD_OP_DONT_CARE, VK_ATTACHMENT_STORE_OP_DONT_CARE, VK_IMAGE_LAYOUT_UNDEFINED,
       VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL},
      {0, kDepthFormat, n, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_DONT_CARE,
       VK_ATTACHMENT_LOAD_OP_DONT_CARE, VK_ATTACHMENT_STORE_OP_DONT_CARE, VK_IMAGE_LAYOUT_UNDEFINED,
       VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL}};
  const VkAttachmentReference colour_ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  const VkAttachmentReference depth_ref{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  const VkSubpassDescription subpass{
      0,      VK_PIPELINE_BIND_POINT_GRAPHICS, 0, nullptr, 1, &colour_ref, nullptr, &depth_ref, 0,
      nullptr};
  const VkPipelineStageFlags tests =
      VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  const VkSubpassDependency deps[2] = {
      {VK_SUBPASS_EXTERNAL, 0, VK_PIPELINE_STAGE_TRANSFER_BIT | tests,
       VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | tests,
       VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
       VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
           VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
       0},
      {0, VK_SUBPASS_EXTERNAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
       VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
       VK_ACCESS_TRANSFER_READ_BIT, 0}};
  const VkRenderPassCreateInfo info{
      VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO, nullptr, 0, 2, att, 1, &subpass, 2, deps};
  VkRenderPass raw = VK_NULL_HANDLE;
  if (VkResult r = api->CreateRenderPass(api->device(), &info, api->alloc(), &raw);
      r != VK_SUCCESS) {
    return vk_error(who("vkCreateRenderPass"), r);
  }
  return passes.emplace(samples, RenderPass(*api, raw)).first->second.get();
}

Status FaceRenderer::State::ensure_targets(int width, int height, int samples) {
  FaceTargets& t = targets;
  if (t.framebuffer.get() != VK_NULL_HANDLE && t.width == width && t.height == height &&
      t.samples == samples) {
    return Status::success();
  }
  t = FaceTargets{};
  Result<VkRenderPass> pass = render_pass(samples);
  if (!pass) return pass.status();
  const VkImageUsageFlags colour_usage =
      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  Result<Attachment> colour = create_attachment(*api, kColourFormat, width, height, samples,
                                                colour_usage, VK_IMAGE_ASPECT_COLOR_BIT);
  if (!colour) return colour.status();
  Result<Attachment> depth =
      create_attachment(*api, kDepthFormat, width, height, samples,
                        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
  if (!depth) return depth.status();
  if (samples > 1) {
    Result<Attachment> resolved =
        create_attachment(*api, kColourFormat, width, height, 1,
                          VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, 0);
    if (!resolved) return resolved.status();
    t.resolved = std::move(*resolved);
  }
  t.colour = std::move(*colour);
  t.depth = std::move(*depth);
  const VkImageView views[2] = {t.colour.view.get(), t.depth.view.get()};
  const VkFramebufferCreateInfo fi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO,
                                   nullptr,
                                   0,
                                   *pass,
                                   2,
                                   views,
                                   std::uint32_t(width),
                                   std::uint32_t(height),
                                   1};
  VkFramebuffer fb = VK_NULL_HANDLE;
  if (VkResult r = api->CreateFramebuffer(api->device(), &fi, api->alloc(), &fb); r != VK_SUCCESS) {
    return vk_error(who("vkCreateFramebuffer"), r);
  }
  t.framebuffer = Framebuffer(*api, fb);
  Result<Buffer> rb = Buffer::create(*api, VkDeviceSize(width) * VkDeviceSize(height) * 16,
                                     VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, who("read-back"));
  if (!rb) return rb.status();
  t.read_back = std::move(*rb);
  t.width = width;
  t.height = height;
  t.samples = samples;
  return Status::success();
}

// A sampler's maxAnisotropy is fixed when it is made, so each anisotropy has a texture set of its
// own: the 16x one made with the renderer, others (trilinear frames: 1) on first use.
Result<VkDescriptorSet> FaceRenderer::State::descriptor_set(float anisotropy) {
  if (anisotropy == textures->anisotropy()) return textures->descriptor_set();
  auto it = other_textures.find(anisotropy);
  if (it == other_textures.end()) {
    FaceTextureSetOptions to;
    to.max_anisotropy = anisotropy;
    Result<std::unique_ptr<FaceTextureSet>> t = FaceTextureSet::create(device->context(), *set, to);
    if (!t) return t.status();
    it = other_textures.emplace(anisotropy, std::move(*t)).first;
  }
  return it->second->descriptor_set();
}

// The multisampled colour (TRANSFER_SRC_OPTIMAL after the pass) resolved into `resolved`, left
// in TRANSFER_SRC_OPTIMAL for the read-back, then the third timestamp.
void FaceRenderer::State::record_resolve(VkCommandBuffer cmd) {
  const VkImage resolved = targets.resolved.image.get();
  Barrier to_dst;  // after the previous frame's copy out of it
  to_dst.image(resolved, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_PIPELINE_STAGE_2_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
               VK_ACCESS_2_TRANSFER_WRITE_BIT);
  to_dst.record(*api, cmd);
  VkImageResolve region{};
  region.srcSubresource = region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.extent = {std::uint32_t(targets.width), std::uint32_t(targets.height), 1};
  api->CmdResolveImage(cmd, targets.colour.image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                       resolved, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
  Barrier to_src;  // for the read-back's copy
  to_src.image(resolved, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
               VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
               VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  to_src.record(*api, cmd);
  write_timestamp(*api, cmd, timestamps.get(), 2);
}

Result<ImageRGBAF> FaceRenderer::State::read_back() {
  FaceTargets& t = targets;
  const VkImage src = t.samples > 1 ? t.resolved.image.get() : t.colour.image.get();
  Result<VkCommandBuffer> cmd = device->begin();
  if (!cmd) return cmd.status();
  // The frame's submission left `src` in TRANSFER_SRC_OPTIMAL behind a barrier (or the render
  // pass's dependency) whose second scope is the transfer stage's reads.
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {std::uint32_t(t.width), std::uint32_t(t.height), 1};
  api->CmdCopyImageToBuffer(*cmd, src, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, t.read_back.get(), 1,
                            &region);
  Barrier to_host;
  to_host.memory(VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                 VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
  to_host.record(*api, *cmd);
  if (Status st = device->submit_and_wait(*cmd); !st.ok()) return st;
  t.read_back.invalidate();
  ImageRGBAF image(t.width, t.height);
  std::memcpy(image.pixels.data(), t.read_back.mapped(), image.pixels.size() * sizeof(float));
  return image;
}

}  // namespace tessera::vk
