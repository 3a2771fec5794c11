// Internal to src/vk: one pipeline barrier, written in synchronization2 terms and recorded with
// vkCmdPipelineBarrier2 where the engine enabled synchronization2, else with
// vkCmdPipelineBarrier (the same scopes, stage and access bits mapped to their Vulkan 1.0
// equivalents).
#pragma once

#include <vector>

#include "vk/vk_api.h"

namespace tessera::vk {

/// The Vulkan 1.0 stage mask of synchronization2 stages (0 = `none`).
VkPipelineStageFlags legacy_stages(VkPipelineStageFlags2 stages, VkPipelineStageFlags none);
/// The Vulkan 1.0 access mask of synchronization2 accesses.
VkAccessFlags legacy_access(VkAccessFlags2 access);

class Barrier {
 public:
  /// A global memory dependency.
  void memory(VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
              VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access);
  /// An image dependency with a layout transition (colour aspect, levels 0 .. levels-1, layers
  /// 0 .. layers-1).
  void image(VkImage image, VkImageLayout from, VkImageLayout to, VkPipelineStageFlags2 src_stage,
             VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access,
             std::uint32_t levels = 1, std::uint32_t layers = 1);
  bool empty() const { return memory_.empty() && images_.empty(); }
  /// Records it into `cmd` (nothing when empty).
  void record(const Api& api, VkCommandBuffer cmd) const;

 private:
  std::vector<VkMemoryBarrier2> memory_;
  std::vector<VkImageMemoryBarrier2> images_;
};

/// A timestamp after the work recorded so far (vkCmdWriteTimestamp2 where available).
void write_timestamp(const Api& api, VkCommandBuffer cmd, VkQueryPool pool, std::uint32_t query);

}  // namespace tessera::vk
