// Internal to src/vk: the state of tessera::vk::AdaptiveSupersampler, shared by
// adaptive_supersampler.cpp (Vulkan's checks, SPIR-V), adaptive_objects.cpp (the objects, the
// descriptor sets) and adaptive_record.cpp (the frame checks, the recorded passes); the
// backend-neutral part is src/adaptive/.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "adaptive/adaptive_host.h"
#include "tessera/vk_adaptive.h"
#include "vk/vk_api.h"

namespace tessera::vk {

/// The component's bindings in its descriptor set.
inline constexpr std::uint32_t kBindParams = 0, kBindWork = 1, kBindList = 2, kBindColour = 3,
                               kBindCounts = 4, kBindGBuffer = 5;

using AdaptiveMode = adaptive::Mode;

struct AdaptiveSupersampler::State {
  AdaptiveSupersamplerOptions options;
  Api api;
  adaptive::Derived derived;  // n, sample order, slots, list capacity
  std::uint32_t set_index = 0;
  std::map<std::string, std::vector<std::uint32_t>> spirv;  // by pass, until the pipelines exist

  Sampler sampler;
  SetLayout set_layout;
  PipelineLayout pipeline_layout;
  std::map<std::string, Pipeline> pipelines;  // by pass name
  Buffer params, work, list, readback;
  Image colour, counts;
  DescriptorPool pool;
  struct Set {
    VkDescriptorSet set = VK_NULL_HANDLE;
    std::array<VkImageView, 4> views{};
    std::array<VkImageLayout, 4> layouts{};  // the layout each view is read in
    std::uint64_t used = 0;                  // record counter when last used; 0 = never
  };
  std::vector<Set> sets;
  std::uint64_t records = 0;
  QueryPool queries;
  bool timestamps = false;  // profile and the queue family has timestamps
  std::uint32_t query_capacity = 0;
  // What the last record measures (profile).
  std::vector<std::string> last_passes;
  AdaptiveMode last_mode = AdaptiveMode::adaptive;
  bool recorded = false;
};

/// Checks the frame (nothing recorded); see vk_adaptive.h, 4.
Status check_adaptive_frame(const AdaptiveSupersampler::State& st, VkCommandBuffer cmd,
                            const AdaptiveFrame& f);
/// The layout a G-buffer image given in `layout` is read in.
VkImageLayout adaptive_read_layout(VkImageLayout layout);
/// The component descriptor set for the frame's G-buffer views (written when new).
VkDescriptorSet acquire_adaptive_set(AdaptiveSupersampler::State& st, const AdaptiveFrame& f);
/// Records one frame (checked first).
Result<AdaptiveRecord> record_adaptive(AdaptiveSupersampler::State& st, VkCommandBuffer cmd,
                                       const AdaptiveFrame& f, AdaptiveMode mode);

}  // namespace tessera::vk
