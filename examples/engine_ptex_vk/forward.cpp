// engine_ptex_vk's forward pass (engine.h: draw): a render pass clearing an RGBA32F colour
// target to the background and a D32 depth target, one indexed draw, a copy to a host buffer.
#include <chrono>
#include <cstring>

#include "engine.h"

namespace engine {

namespace {

// The targets (colour, depth), the pass's objects (vk_pipelines.h), the command pool and fence.
struct Objects {
  VkDevice device = VK_NULL_HANDLE;
  VkImage images[2] = {VK_NULL_HANDLE, VK_NULL_HANDLE};  // colour, depth
  VkDeviceMemory memory[2] = {VK_NULL_HANDLE, VK_NULL_HANDLE};
  VkImageView views[2] = {VK_NULL_HANDLE, VK_NULL_HANDLE};
  ForwardObjects forward;
  VkCommandPool cmd_pool = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  ~Objects() {
    if (device == VK_NULL_HANDLE) return;
    vkDeviceWaitIdle(device);
    vkDestroyFence(device, fence, nullptr);
    vkDestroyCommandPool(device, cmd_pool, nullptr);
    forward.destroy(device);
    for (int i = 0; i < 2; ++i) {
      vkDestroyImageView(device, views[i], nullptr);
      vkDestroyImage(device, images[i], nullptr);
      vkFreeMemory(device, memory[i], nullptr);
    }
  }
};

void create_targets(const Device& d, Objects& o, int w, int h) {
  const VkFormat formats[2] = {VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_D32_SFLOAT};
  const VkImageUsageFlags usage[2] = {
      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
      VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT};
  const VkImageAspectFlags aspect[2] = {VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_ASPECT_DEPTH_BIT};
  for (int i = 0; i < 2; ++i) {
    create_image(d.device, d.physical, formats[i], std::uint32_t(w), std::uint32_t(h), usage[i],
                 aspect[i], &o.images[i], &o.memory[i], &o.views[i]);
  }
  // Both cleared; colour left in TRANSFER_SRC_OPTIMAL for the copy (the dependency below).
  std::vector<VkSubpassDependency> deps(2);
  deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  deps[0].dstSubpass = 0;
  deps[0].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                         VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                         VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  deps[0].dstStageMask = deps[0].srcStageMask;
  deps[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                          VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                          VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  deps[1].srcSubpass = 0;
  deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  deps[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  deps[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  deps[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  deps[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  o.forward.create_pass(d.device, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_IMAGE_LAYOUT_UNDEFINED,
                        VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, deps, o.views, w, h);
}

// The pipeline (vk_pipelines.h's forward pipeline); "" or the problem.
std::string create_pipeline(VkDevice dev, Objects& o, const Frame& in) {
  if (VkResult r = o.forward.create_pipeline(dev, ForwardPipelineDesc::of(in)); r != VK_SUCCESS) {
    return "vkCreateGraphicsPipelines: VkResult " + std::to_string(int(r));
  }
  return "";
}

// Records the frame into `cmd`: the pass (the colour cleared to the background), then the copy
// of the colour target to `out`; "" or what the caller's bind said.
std::string record(const Objects& o, const Frame& f, const Buffer& vbo, const Buffer& ibo,
                   const Buffer& out, VkCommandBuffer cmd) {
  VkClearValue clear[2]{};
  std::memcpy(clear[0].color.float32, f.background, sizeof f.background);
  clear[1].depthStencil = {1.0f, 0};
  if (f.before_pass) {
    if (std::string e = f.before_pass(cmd); !e.empty()) return e;
  }
  const std::string bound = o.forward.record(
      cmd, f.width, f.height, clear, vbo.buffer, ibo.buffer, std::uint32_t(f.indices.size()),
      [&f](VkCommandBuffer c, VkPipelineLayout l) {
        return f.bind_extra ? f.bind_extra(c, l) : std::string();
      });
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {std::uint32_t(f.width), std::uint32_t(f.height), 1};
  vkCmdCopyImageToBuffer(cmd, o.images[0], VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, out.buffer, 1,
                         &region);
  VkMemoryBarrier host{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT,
                       VK_ACCESS_HOST_READ_BIT};
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &host,
                       0, nullptr, 0, nullptr);
  return bound;
}

}  // namespace

std::vector<float> draw(Device& d, const Frame& f, double* ms, std::string& error) {
  const std::size_t texels = std::size_t(f.width) * std::size_t(f.height);
  Buffer vbo = d.buffer(f.vertices, f.vertex_bytes, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
  Buffer ibo = d.buffer(f.indices.data(), f.indices.size() * 4, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
  Buffer ubo = d.buffer(f.block.data(), f.block.size(), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
  Buffer out = d.buffer(nullptr, texels * 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  std::vector<float> pixels;
  {
    Objects o;
    o.device = d.device;
    create_targets(d, o, f.width, f.height);
    // Set 0: the frame block; 1..: the caller's layouts.
    o.forward.create_sets(d.device, f.extra_layouts, ubo.buffer);
    error = create_pipeline(d.device, o, f);
    VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, nullptr,
                               VK_COMMAND_POOL_CREATE_TRANSIENT_BIT, d.family};
    vkCreateCommandPool(d.device, &pi, nullptr, &o.cmd_pool);
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr,
                                   o.cmd_pool, VK_COMMAND_BUFFER_LEVEL_PRIMARY, 1};
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    vkAllocateCommandBuffers(d.device, &ai, &cmd);
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO, nullptr, 0};
    vkCreateFence(d.device, &fi, nullptr, &o.fence);
    if (error.empty()) {
      VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, nullptr,
                                  VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT, nullptr};
      vkBeginCommandBuffer(cmd, &bi);
      error = record(o, f, vbo, ibo, out, cmd);
      vkEndCommandBuffer(cmd);
    }
    if (error.empty()) {
      const auto t0 = std::chrono::steady_clock::now();
      VkSubmitInfo si{};
      si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
      si.commandBufferCount = 1;
      si.pCommandBuffers = &cmd;
      vkQueueSubmit(d.queue, 1, &si, o.fence);
      vkWaitForFences(d.device, 1, &o.fence, VK_TRUE, UINT64_MAX);
      *ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      pixels.resize(texels * 4);
      std::memcpy(pixels.data(), out.data, texels * 16);
    }
  }
  for (Buffer* b : {&out, &ubo, &ibo, &vbo}) d.destroy(*b);
  return pixels;
}

}  // namespace engine
