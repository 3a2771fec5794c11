// Pipeline barriers in synchronization2 terms, recorded with or without synchronization2.
#include "vk/barriers.h"

namespace tessera::vk {

VkPipelineStageFlags legacy_stages(VkPipelineStageFlags2 stages, VkPipelineStageFlags none) {
  // The stages below bit 32 have the same bits in both APIs; the copy/blit/clear/resolve stages
  // of synchronization2 (bits 32..) are parts of TRANSFER.
  VkPipelineStageFlags out = VkPipelineStageFlags(stages & 0xffffffffull);
  const VkPipelineStageFlags2 transfer_parts =
      VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_RESOLVE_BIT |
      VK_PIPELINE_STAGE_2_BLIT_BIT | VK_PIPELINE_STAGE_2_CLEAR_BIT;
  if ((stages & transfer_parts) != 0) out |= VK_PIPELINE_STAGE_TRANSFER_BIT;
  return out == 0 ? none : out;
}

VkAccessFlags legacy_access(VkAccessFlags2 access) {
  VkAccessFlags out = VkAccessFlags(access & 0xffffffffull);
  if ((access & (VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT)) != 0) {
    out |= VK_ACCESS_SHADER_READ_BIT;
  }
  if ((access & VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT) != 0) out |= VK_ACCESS_SHADER_WRITE_BIT;
  return out;
}

void Barrier::memory(VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                     VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access) {
  VkMemoryBarrier2 b{};
  b.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2;
  b.srcStageMask = src_stage;
  b.srcAccessMask = src_access;
  b.dstStageMask = dst_stage;
  b.dstAccessMask = dst_access;
  memory_.push_back(b);
}

void Barrier::image(VkImage image, VkImageLayout from, VkImageLayout to,
                    VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                    VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access,
                    std::uint32_t levels, std::uint32_t layers) {
  VkImageMemoryBarrier2 b{};
  b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2;
  b.srcStageMask = src_stage;
  b.srcAccessMask = src_access;
  b.dstStageMask = dst_stage;
  b.dstAccessMask = dst_access;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, levels, 0, layers};
  images_.push_back(b);
}

void Barrier::record(const Api& api, VkCommandBuffer cmd) const {
  if (empty()) return;
  if (api.CmdPipelineBarrier2 != nullptr) {
    VkDependencyInfo dep{};
    dep.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO;
    dep.memoryBarrierCount = std::uint32_t(memory_.size());
    dep.pMemoryBarriers = memory_.data();
    dep.imageMemoryBarrierCount = std::uint32_t(images_.size());
    dep.pImageMemoryBarriers = images_.data();
    api.CmdPipelineBarrier2(cmd, &dep);
    return;
  }
  VkPipelineStageFlags2 src = 0, dst = 0;
  std::vector<VkMemoryBarrier> mem;
  for (const VkMemoryBarrier2& b : memory_) {
    src |= b.srcStageMask;
    dst |= b.dstStageMask;
    VkMemoryBarrier m{};
    m.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    m.srcAccessMask = legacy_access(b.srcAccessMask);
    m.dstAccessMask = legacy_access(b.dstAccessMask);
    mem.push_back(m);
  }
  std::vector<VkImageMemoryBarrier> img;
  for (const VkImageMemoryBarrier2& b : images_) {
    src |= b.srcStageMask;
    dst |= b.dstStageMask;
    VkImageMemoryBarrier m{};
    m.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
    m.srcAccessMask = legacy_access(b.srcAccessMask);
    m.dstAccessMask = legacy_access(b.dstAccessMask);
    m.oldLayout = b.oldLayout;
    m.newLayout = b.newLayout;
    m.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    m.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    m.image = b.image;
    m.subresourceRange = b.subresourceRange;
    img.push_back(m);
  }
  api.CmdPipelineBarrier(cmd, legacy_stages(src, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT),
                         legacy_stages(dst, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT), 0,
                         std::uint32_t(mem.size()), mem.data(), 0, nullptr,
                         std::uint32_t(img.size()), img.data());
}

void write_timestamp(const Api& api, VkCommandBuffer cmd, VkQueryPool pool, std::uint32_t query) {
  if (api.CmdWriteTimestamp2 != nullptr) {
    api.CmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool, query);
  } else {
    api.CmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool, query);
  }
}

}  // namespace tessera::vk
