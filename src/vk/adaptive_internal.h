// Internal to src/vk: the state of tessera::vk::AdaptiveSupersampler, shared by
// adaptive_supersampler.cpp (Vulkan's checks, SPIR-V), adaptive_objects.cpp (the objects, the
// descriptor sets) and adaptive_record.cpp (the frame checks, the recorded passes); the
// backend-neutral part is src/adaptive/.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <vector>

#include "adaptive/adaptive_host.h"
#include "tessera/vk_adaptive.h"
#include "vk/adaptive_bindings.h"
#include "vk/vk_api.h"

namespace tessera::vk {

using AdaptiveMode = adaptive::Mode;

struct AdaptiveSupersampler::State {
  AdaptiveSupersamplerOptions options;
  Api api;
  adaptive::Derived derived;  // n, sample order, slots, list capacity, precision, tile
  std::uint32_t set_index = 0;
  std::map<std::string, std::vector<std::uint32_t>> spirv;  // by pass, until the pipelines exist
  std::vector<std::uint8_t> binary;  // every pass's SPIR-V, keyed (shader_binary.h)

  Sampler sampler;
  SetLayout set_layout;
  PipelineLayout pipeline_layout;
  std::map<std::string, Pipeline> pipelines;  // by pass name
  // Shared by every record, ordered by the barrier each record begins with (tessera/vk.h).
  Buffer params, work, list;

  /// One record's own resources, for one (frame slot, view): nothing here is written by the
  /// host while a submitted command buffer may use it (begin_frame's promise).
  struct View {
    VkDescriptorSet set = VK_NULL_HANDLE;
    Image colour, counts;  // made at the view's first record that needs them (largest size)
    // profile: uint32 [0] the extra-sample counter, uint64 [1] the frame, then the timestamps
    // (uint64 each), all written by the GPU: no query is read by the host (vkGetQueryPoolResults
    // may wait for the whole device on some drivers, e.g. lavapipe).
    Buffer readback;
    QueryPool queries;  // profile: the start, then one per pass
    // What its last record measured (profile).
    std::vector<std::string> passes;
    AdaptiveMode mode = AdaptiveMode::adaptive;
    VkExtent2D size{0, 0};
    std::uint64_t frame = 0;  // the frame of its last record; 0 = never recorded
  };
  std::vector<std::deque<View>> frames;  // [frame slot][view]
  std::vector<DescriptorPool> pools;     // kSetsPerPool sets each; grown with the views
  std::uint32_t pool_sets_left = 0;      // in pools.back()
  bool frame_open = false;
  std::uint32_t slot = 0;         // the open frame slot
  std::uint32_t views = 0;        // records made in the open frame
  std::uint64_t frame_count = 0;  // begin_frame calls
  bool timestamps = false;        // profile and the queue family has timestamps
  std::uint32_t query_capacity = 0;
};

inline constexpr std::uint32_t kSetsPerPool = 8;
/// Byte offset of the timestamps in a view's read-back buffer.
inline constexpr std::size_t kReadbackTicks = 16;

/// Checks the frame against the open frame and `size` (the resolved render size; nothing
/// recorded); see vk_adaptive.h, 4.
Status check_adaptive_frame(const AdaptiveSupersampler::State& st, VkCommandBuffer cmd,
                            const AdaptiveFrame& f, VkExtent2D size);
/// The layout a G-buffer image given in `layout` is read in.
VkImageLayout adaptive_read_layout(VkImageLayout layout);
/// The colour output's format (options.output).
VkFormat adaptive_output_format(const AdaptiveCommonOptions& o);
/// The open frame's next view, its resources made where missing (the own outputs unless the
/// frame gives its own colour image) and its descriptor set written for `f`.
Result<AdaptiveSupersampler::State::View*> acquire_adaptive_view(AdaptiveSupersampler::State& st,
                                                                 const AdaptiveFrame& f);
/// Records one frame (checked first).
Result<AdaptiveOutput> record_adaptive(AdaptiveSupersampler::State& st, VkCommandBuffer cmd,
                                       const AdaptiveFrame& f, AdaptiveMode mode);

}  // namespace tessera::vk
