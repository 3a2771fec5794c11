// engine_ptex_vk --frame-loop (frame_loop.h).
#include "frame_loop.h"

#include <algorithm>
#include <cstring>

#include "vk_window.h"  // examples/common: the GLFW window and swapchain

namespace engine {

int render_scale(int frame) {
  static const int kScales[3] = {100, 70, 85};
  return kScales[frame % 3];
}

VkExtent2D render_size(int w, int h, int scale) {
  auto side = [scale](int n) { return std::uint32_t(std::max(2, 2 * ((n * scale + 100) / 200))); };
  return {side(w), side(h)};
}

namespace {

/// One view of one frame slot: its max-size colour and depth targets and their framebuffer,
/// the uniform buffer the host writes its frame block into and the frame set pointing at it,
/// and the buffer its image is read back into.
struct Target {
  VkImage images[2] = {VK_NULL_HANDLE, VK_NULL_HANDLE};  // colour, depth
  VkDeviceMemory memory[2] = {VK_NULL_HANDLE, VK_NULL_HANDLE};
  VkImageView views[2] = {VK_NULL_HANDLE, VK_NULL_HANDLE};
  VkFramebuffer framebuffer = VK_NULL_HANDLE;
  Buffer ubo, read_back;
  VkDescriptorSet set = VK_NULL_HANDLE;
};

/// One frame slot: its fence, its command buffer, its views' targets, and the frame in flight.
struct Slot {
  VkFence fence = VK_NULL_HANDLE;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  bool in_flight = false, read_back = false;
  std::vector<Target> views;
  FrameResult pending;
};

/// What every frame shares: the render pass, set layouts, pipeline and its layout, the pool of
/// the frame sets, the command pool, the mesh's buffers.
struct Shared {
  VkRenderPass pass = VK_NULL_HANDLE;
  VkDescriptorSetLayout frame_layout = VK_NULL_HANDLE, empty_layout = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkShaderModule modules[2] = {VK_NULL_HANDLE, VK_NULL_HANDLE};
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VkCommandPool cmd_pool = VK_NULL_HANDLE;
  Buffer vbo, ibo;
  VkFilter blit_filter = VK_FILTER_LINEAR;
};

// The render pass: colour cleared (from UNDEFINED: its last frame's contents are not needed)
// and left in TRANSFER_SRC_OPTIMAL for the read-back copy and the window's blit. Before it: the
// slot's last frame's attachment writes and transfer reads of the same targets (that frame's
// fence was waited for, but the engine states the hazards); after it: the transfer reads.
VkRenderPass make_pass(VkDevice dev) {
  std::vector<VkSubpassDependency> deps(2);
  deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  deps[0].dstSubpass = 0;
  const VkPipelineStageFlags attachments = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                           VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                           VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  deps[0].srcStageMask = attachments | VK_PIPELINE_STAGE_TRANSFER_BIT;
  deps[0].srcAccessMask =
      VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  deps[0].dstStageMask = attachments;
  deps[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                          VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                          VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  deps[1].srcSubpass = 0;
  deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  deps[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  deps[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  deps[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  deps[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  return forward_render_pass(dev, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_IMAGE_LAYOUT_UNDEFINED,
                             VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, deps);
}

// Everything but the slots; "" or the problem.
std::string create_shared(Device& d, const Frame& scene, const FrameLoopOptions& o, Shared& s) {
  s.pass = make_pass(d.device);
  frame_set_layouts(d.device, &s.frame_layout, &s.empty_layout);
  std::vector<VkDescriptorSetLayout> layouts{s.frame_layout};
  for (VkDescriptorSetLayout l : scene.extra_layouts) {
    layouts.push_back(l != VK_NULL_HANDLE ? l : s.empty_layout);
  }
  VkPipelineLayoutCreateInfo pl{};
  pl.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  pl.setLayoutCount = std::uint32_t(layouts.size());
  pl.pSetLayouts = layouts.data();
  vkCreatePipelineLayout(d.device, &pl, nullptr, &s.layout);
  ForwardPipelineDesc desc = ForwardPipelineDesc::of(scene);
  desc.dynamic_viewport = true;  // a render size per frame
  desc.layout = s.layout;
  desc.pass = s.pass;
  if (VkResult r = forward_pipeline(d.device, desc, s.modules, &s.pipeline); r != VK_SUCCESS) {
    return "vkCreateGraphicsPipelines: VkResult " + std::to_string(int(r));
  }
  const std::uint32_t sets = o.frames_in_flight * std::uint32_t(o.views);
  const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, sets};
  VkDescriptorPoolCreateInfo pi{};
  pi.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  pi.maxSets = sets;
  pi.poolSizeCount = 1;
  pi.pPoolSizes = &size;
  vkCreateDescriptorPool(d.device, &pi, nullptr, &s.pool);
  VkCommandPoolCreateInfo ci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, nullptr,
                             VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT, d.family};
  vkCreateCommandPool(d.device, &ci, nullptr, &s.cmd_pool);
  s.vbo = d.buffer(scene.vertices, scene.vertex_bytes, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
  s.ibo =
      d.buffer(scene.indices.data(), scene.indices.size() * 4, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
  if (o.window != nullptr) {
    VkFormatProperties fp{};
    vkGetPhysicalDeviceFormatProperties(d.physical, VK_FORMAT_R32G32B32A32_SFLOAT, &fp);
    if ((fp.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_SRC_BIT) == 0) {
      return "the device cannot blit from R32G32B32A32_SFLOAT to the window";
    }
    if ((fp.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) == 0) {
      s.blit_filter = VK_FILTER_NEAREST;
    }
  }
  return "";
}

void create_slot(Device& d, const Frame& scene, const FrameLoopOptions& o, const Shared& sh,
                 Slot& s) {
  VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO, nullptr, 0};
  vkCreateFence(d.device, &fi, nullptr, &s.fence);
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr,
                                 sh.cmd_pool, VK_COMMAND_BUFFER_LEVEL_PRIMARY, 1};
  vkAllocateCommandBuffers(d.device, &ai, &s.cmd);
  const VkFormat formats[2] = {VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_D32_SFLOAT};
  const VkImageUsageFlags usage[2] = {
      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
      VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT};
  const VkImageAspectFlags aspect[2] = {VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_ASPECT_DEPTH_BIT};
  s.views.resize(std::size_t(o.views));
  for (Target& t : s.views) {
    for (int i = 0; i < 2; ++i) {
      create_image(d.device, d.physical, formats[i], std::uint32_t(o.w), std::uint32_t(o.h),
                   usage[i], aspect[i], &t.images[i], &t.memory[i], &t.views[i]);
    }
    t.framebuffer = forward_framebuffer(d.device, sh.pass, t.views, o.w, o.h);
    t.ubo = d.buffer(nullptr, scene.block.size(), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    t.read_back = d.buffer(nullptr, VkDeviceSize(o.w) * VkDeviceSize(o.h) * 16,
                           VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    VkDescriptorSetAllocateInfo si{};
    si.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    si.descriptorPool = sh.pool;
    si.descriptorSetCount = 1;
    si.pSetLayouts = &sh.frame_layout;
    vkAllocateDescriptorSets(d.device, &si, &t.set);
    write_uniform_buffer(d.device, t.set, t.ubo.buffer);
  }
}

void destroy(Device& d, Shared& sh, std::vector<Slot>& slots) {
  for (Slot& s : slots) {
    for (Target& t : s.views) {
      vkDestroyFramebuffer(d.device, t.framebuffer, nullptr);
      for (int i = 0; i < 2; ++i) {
        vkDestroyImageView(d.device, t.views[i], nullptr);
        vkDestroyImage(d.device, t.images[i], nullptr);
        vkFreeMemory(d.device, t.memory[i], nullptr);
      }
      d.destroy(t.ubo);
      d.destroy(t.read_back);
    }
    vkDestroyFence(d.device, s.fence, nullptr);
  }
  vkDestroyCommandPool(d.device, sh.cmd_pool, nullptr);  // and the slots' command buffers
  vkDestroyDescriptorPool(d.device, sh.pool, nullptr);
  vkDestroyPipeline(d.device, sh.pipeline, nullptr);
  for (VkShaderModule m : sh.modules) vkDestroyShaderModule(d.device, m, nullptr);
  vkDestroyPipelineLayout(d.device, sh.layout, nullptr);
  vkDestroyDescriptorSetLayout(d.device, sh.empty_layout, nullptr);
  vkDestroyDescriptorSetLayout(d.device, sh.frame_layout, nullptr);
  vkDestroyRenderPass(d.device, sh.pass, nullptr);
  d.destroy(sh.vbo);
  d.destroy(sh.ibo);
}

/// The slot's frame, once its fence signalled: its read-back images, and the texture set's
/// staging released after the first frame.
std::string collect(Device& d, const FrameLoopOptions& o, Slot& s, std::vector<FrameResult>& out) {
  vkWaitForFences(d.device, 1, &s.fence, VK_TRUE, UINT64_MAX);
  vkResetFences(d.device, 1, &s.fence);
  s.in_flight = false;
  if (s.read_back) {
    for (ViewResult& v : s.pending.views) {
      const float* px = static_cast<const float*>(s.views[std::size_t(v.view)].read_back.data);
      v.image.assign(px, px + std::size_t(v.w) * v.h * 4);
    }
  }
  std::string err;
  if (s.pending.frame == 0 && o.first_frame_completed) err = o.first_frame_completed();
  out.push_back(std::move(s.pending));
  s.pending = FrameResult{};
  return err;
}

// Records view `t`'s pass at render size `size` into the top-left of its targets: the colour
// cleared to the background, the viewport (+y up: negative height) and scissor set here.
std::string record_view(VkCommandBuffer cmd, const Frame& scene, const Shared& sh, const Target& t,
                        VkExtent2D size) {
  VkClearValue clear[2]{};
  std::memcpy(clear[0].color.float32, scene.background, sizeof scene.background);
  clear[1].depthStencil = {1.0f, 0};
  VkRenderPassBeginInfo rb{};
  rb.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
  rb.renderPass = sh.pass;
  rb.framebuffer = t.framebuffer;
  rb.renderArea = {{0, 0}, size};
  rb.clearValueCount = 2;
  rb.pClearValues = clear;
  vkCmdBeginRenderPass(cmd, &rb, VK_SUBPASS_CONTENTS_INLINE);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, sh.pipeline);
  const VkViewport viewport{0.0f, float(size.height), float(size.width), -float(size.height), 0.0f,
                            1.0f};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  const VkRect2D scissor{{0, 0}, size};
  vkCmdSetScissor(cmd, 0, 1, &scissor);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, sh.layout, 0, 1, &t.set, 0,
                          nullptr);
  const std::string bound = scene.bind_extra ? scene.bind_extra(cmd, sh.layout) : "";
  const VkDeviceSize zero = 0;
  vkCmdBindVertexBuffers(cmd, 0, 1, &sh.vbo.buffer, &zero);
  vkCmdBindIndexBuffer(cmd, sh.ibo.buffer, 0, VK_INDEX_TYPE_UINT32);
  vkCmdDrawIndexed(cmd, std::uint32_t(scene.indices.size()), 1, 0, 0, 0);
  vkCmdEndRenderPass(cmd);
  return bound;
}

}  // namespace

std::string run_frame_loop(Device& d, const Frame& scene, const FrameLoopOptions& o,
                           std::vector<FrameResult>& out) {
  Shared sh;
  std::vector<Slot> slots(o.frames_in_flight);
  std::string err = create_shared(d, scene, o, sh);
  for (Slot& s : slots) create_slot(d, scene, o, sh, s);
  for (int i = 0; i < o.frames && err.empty(); ++i) {
    const std::uint32_t slot = std::uint32_t(i) % o.frames_in_flight;
    Slot& s = slots[slot];
    // ---- the engine's frame start: wait for this slot's last frame, then reuse its objects ----
    if (s.in_flight) err = collect(d, o, s, out);
    if (!err.empty()) break;
    const int scale = render_scale(i);
    const VkExtent2D size = render_size(o.w, o.h, scale);
    s.pending.frame = i;
    s.pending.slot = slot;
    s.pending.scale_percent = scale;
    s.read_back = i >= o.read_back_from;
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, nullptr,
                                VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT, nullptr};
    vkBeginCommandBuffer(s.cmd, &bi);  // resets it (the pool's RESET_COMMAND_BUFFER)
    // ---- tessera: the texture set's upload, recorded into the first frame (before_pass) ----
    if (scene.before_pass) err = scene.before_pass(s.cmd);
    for (int v = 0; v < o.views && err.empty(); ++v) {
      Target& t = s.views[std::size_t(v)];
      // The slot's fence was waited for: its uniform buffer is the host's to write.
      const std::vector<std::uint8_t> block = o.frame_block(i, v, size);
      std::memcpy(t.ubo.data, block.data(), std::min(block.size(), scene.block.size()));
      // ---- tessera: bind_extra binds the texture set at the engine's set index ----
      err = record_view(s.cmd, scene, sh, t, size);
      if (!err.empty()) break;
      if (s.read_back) {
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {size.width, size.height, 1};
        vkCmdCopyImageToBuffer(s.cmd, t.images[0], VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               t.read_back.buffer, 1, &region);
      }
      // The view's image (TRANSFER_SRC_OPTIMAL, top-left `size` texels) is the engine's until
      // the slot comes round again: view 0 goes to the window.
      if (v == 0 && o.window != nullptr) {
        err = o.window->acquire(d, slot);
        if (err.empty()) o.window->record_blit(s.cmd, t.images[0], size, sh.blit_filter);
      }
      s.pending.views.push_back({v, size.width, size.height, {}});
    }
    if (s.read_back) {
      VkMemoryBarrier host{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT,
                           VK_ACCESS_HOST_READ_BIT};
      vkCmdPipelineBarrier(s.cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1,
                           &host, 0, nullptr, 0, nullptr);
    }
    vkEndCommandBuffer(s.cmd);
    if (!err.empty()) break;
    // No wait: the next frame starts at once.
    const VkSemaphore wait = o.window != nullptr ? o.window->acquired(slot) : VK_NULL_HANDLE;
    const VkSemaphore signal = o.window != nullptr ? o.window->rendered() : VK_NULL_HANDLE;
    const VkPipelineStageFlags wait_stage = Window::kWaitStage;
    VkSubmitInfo si{};
    si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    si.waitSemaphoreCount = wait != VK_NULL_HANDLE ? 1 : 0;
    si.pWaitSemaphores = &wait;
    si.pWaitDstStageMask = &wait_stage;
    si.commandBufferCount = 1;
    si.pCommandBuffers = &s.cmd;
    si.signalSemaphoreCount = signal != VK_NULL_HANDLE ? 1 : 0;
    si.pSignalSemaphores = &signal;
    if (VkResult r = vkQueueSubmit(d.queue, 1, &si, s.fence); r != VK_SUCCESS) {
      err = "vkQueueSubmit: VkResult " + std::to_string(int(r));
      break;
    }
    s.in_flight = true;
    if (o.window != nullptr) err = o.window->present(d);
  }
  for (std::uint32_t k = 0; k < o.frames_in_flight; ++k) {  // drain, oldest first
    Slot& s = slots[std::uint32_t(o.frames + int(k)) % o.frames_in_flight];
    if (!s.in_flight) continue;
    const std::string e = collect(d, o, s, out);
    if (err.empty()) err = e;
  }
  vkDeviceWaitIdle(d.device);  // after the loop: a failed frame may have left work queued
  destroy(d, sh, slots);
  return err;
}

}  // namespace engine
