// engine_aa_vk's own Vulkan plumbing (engine.h).
#include "engine.h"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace engine {

namespace {

const std::uint32_t kVertSpirv[] = {
#include "geometry.vert.inc"
};
const std::uint32_t kFragSpirv[] = {
#include "geometry.frag.inc"
};

}  // namespace

std::string Device::create(bool want_validation,
                           const std::vector<const char*>& instance_extensions,
                           const std::vector<const char*>& device_extensions) {
  VkPhysicalDeviceProperties props{};
  const std::string why = create_instance_and_pick("engine_aa_vk", VK_API_VERSION_1_3,
                                                   want_validation, props, instance_extensions);
  if (!why.empty()) return why;
  VkPhysicalDeviceFeatures supported{};
  vkGetPhysicalDeviceFeatures(physical, &supported);
  // tessera's depth metric runs in double where the device has fp64, else in float.
  features.shaderFloat64 = supported.shaderFloat64;
  features.shaderStorageImageExtendedFormats = supported.shaderStorageImageExtendedFormats;
  VkPhysicalDeviceVulkan13Features f13{};
  f13.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES;
  f13.synchronization2 = VK_TRUE;
  f13.dynamicRendering = VK_TRUE;
  if (std::string no = create_device(&f13, device_extensions); !no.empty()) return no;
  VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, nullptr, 0, family};
  vkCreateCommandPool(device, &pi, nullptr, &pool_);
  return "";
}

void Device::destroy() {
  if (device) {
    vkDeviceWaitIdle(device);
    vkDestroyCommandPool(device, pool_, nullptr);
  }
  destroy_device_and_instance();
}

Image Device::image(VkFormat format, std::uint32_t w, std::uint32_t h, VkImageUsageFlags usage,
                    VkImageAspectFlags aspect) {
  Image img;
  img.format = format;
  img.usage = usage;
  img.w = w;
  img.h = h;
  create_image(device, physical, format, w, h, usage, aspect, &img.image, &img.memory, &img.view);
  return img;
}

void Device::destroy(Image& i) {
  vkDestroyImageView(device, i.view, nullptr);
  vkDestroyImage(device, i.image, nullptr);
  vkFreeMemory(device, i.memory, nullptr);
  i = Image{};
}

VkCommandBuffer Device::begin() {
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr, pool_,
                                 VK_COMMAND_BUFFER_LEVEL_PRIMARY, 1};
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  vkAllocateCommandBuffers(device, &ai, &cmd);
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, nullptr,
                              VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT, nullptr};
  vkBeginCommandBuffer(cmd, &bi);
  return cmd;
}

void Device::submit_and_wait(VkCommandBuffer cmd) {
  vkEndCommandBuffer(cmd);
  VkSubmitInfo si{};
  si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  vkQueueSubmit(queue, 1, &si, VK_NULL_HANDLE);
  vkQueueWaitIdle(queue);
  vkFreeCommandBuffers(device, pool_, 1, &cmd);
}

std::string read_file(const std::string& path, std::vector<std::uint8_t>& bytes) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return "";
  std::ifstream in(path, std::ios::binary);
  if (!in) return path + ": cannot open";
  bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return in.bad() ? path + ": cannot read" : "";
}

std::string write_file(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    if (!out) return tmp + ": cannot write";
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  return ec ? path + ": " + ec.message() : "";
}

VkFence Device::fence() {
  VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO, nullptr, 0};
  VkFence f = VK_NULL_HANDLE;
  vkCreateFence(device, &fi, nullptr, &f);
  return f;
}

void Device::submit(VkCommandBuffer cmd, VkFence fence, VkSemaphore wait, VkSemaphore signal) {
  vkEndCommandBuffer(cmd);
  const VkPipelineStageFlags stage = VK_PIPELINE_STAGE_TRANSFER_BIT;  // the blit to the window
  VkSubmitInfo si{};
  si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  si.waitSemaphoreCount = wait != VK_NULL_HANDLE ? 1 : 0;
  si.pWaitSemaphores = &wait;
  si.pWaitDstStageMask = &stage;
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  si.signalSemaphoreCount = signal != VK_NULL_HANDLE ? 1 : 0;
  si.pSignalSemaphores = &signal;
  vkQueueSubmit(queue, 1, &si, fence);
}

void Device::wait(VkFence fence) {
  vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX);
  vkResetFences(device, 1, &fence);
}

void Device::free(VkCommandBuffer cmd) { vkFreeCommandBuffers(device, pool_, 1, &cmd); }

void barrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
             VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
             VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access,
             VkImageAspectFlags aspect) {
  VkImageMemoryBarrier2 b{};
  b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2;
  b.srcStageMask = src_stage;
  b.srcAccessMask = src_access;
  b.dstStageMask = dst_stage;
  b.dstAccessMask = dst_access;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {aspect, 0, 1, 0, 1};
  VkDependencyInfo dep{};
  dep.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO;
  dep.imageMemoryBarrierCount = 1;
  dep.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dep);
}

std::vector<std::uint8_t> Device::read(const Image& img, std::size_t texel_bytes,
                                       VkImageLayout layout, VkPipelineStageFlags2 stage,
                                       VkAccessFlags2 access) {
  const std::size_t bytes = std::size_t(img.w) * img.h * texel_bytes;
  Buffer b = buffer(bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
  VkCommandBuffer cmd = begin();
  barrier(cmd, img.image, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, stage, access,
          VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {img.w, img.h, 1};
  vkCmdCopyImageToBuffer(cmd, img.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, b.buffer, 1,
                         &region);
  VkMemoryBarrier2 host{};
  host.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2;
  host.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
  host.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
  host.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
  host.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
  VkDependencyInfo dep{};
  dep.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO;
  dep.memoryBarrierCount = 1;
  dep.pMemoryBarriers = &host;
  vkCmdPipelineBarrier2(cmd, &dep);
  submit_and_wait(cmd);
  std::vector<std::uint8_t> out(bytes);
  std::memcpy(out.data(), b.data, bytes);
  destroy(b);
  return out;
}

GeometryPipeline geometry_pipeline(Device& d) {
  GeometryPipeline g;
  VkPushConstantRange pc{VK_SHADER_STAGE_VERTEX_BIT, 0, 128};
  VkPipelineLayoutCreateInfo li{};
  li.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  li.pushConstantRangeCount = 1;
  li.pPushConstantRanges = &pc;
  vkCreatePipelineLayout(d.device, &li, nullptr, &g.layout);
  VkShaderModule mods[2];
  const std::pair<const std::uint32_t*, std::size_t> code[2] = {{kVertSpirv, sizeof kVertSpirv},
                                                                {kFragSpirv, sizeof kFragSpirv}};
  for (int i = 0; i < 2; ++i) {
    VkShaderModuleCreateInfo mi{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, nullptr, 0,
                                code[i].second, code[i].first};
    vkCreateShaderModule(d.device, &mi, nullptr, &mods[i]);
  }
  const VkVertexInputAttributeDescription va[4] = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0},
                                                   {1, 0, VK_FORMAT_R32G32B32_SFLOAT, 12},
                                                   {2, 0, VK_FORMAT_R32G32B32_SFLOAT, 24},
                                                   {3, 0, VK_FORMAT_R32_SFLOAT, 36}};
  const VkFormat colour[2] = {VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R8G8B8A8_UNORM};
  VkPipelineRenderingCreateInfo ri{};
  ri.sType = VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO;
  ri.colorAttachmentCount = 2;
  ri.pColorAttachmentFormats = colour;
  ri.depthAttachmentFormat = VK_FORMAT_D32_SFLOAT;
  // vk_pipelines.h's pipeline state (triangles, depth test less with writes, no blending): no
  // culling, the viewport set per pass, dynamic rendering into two colour targets and depth.
  GraphicsPipelineDesc desc;
  desc.vertex = mods[0];
  desc.fragment = mods[1];
  desc.stride = 40;
  desc.attributes = va;
  desc.attribute_count = 4;
  desc.dynamic_viewport = true;
  desc.cull = VK_CULL_MODE_NONE;
  desc.colour_attachments = 2;
  desc.layout = g.layout;
  desc.next = &ri;
  graphics_pipeline(d.device, desc, &g.pipeline);
  for (VkShaderModule m : mods) vkDestroyShaderModule(d.device, m, nullptr);
  return g;
}

void destroy(Device& d, GeometryPipeline& p) {
  vkDestroyPipeline(d.device, p.pipeline, nullptr);
  vkDestroyPipelineLayout(d.device, p.layout, nullptr);
  p = GeometryPipeline{};
}

}  // namespace engine
