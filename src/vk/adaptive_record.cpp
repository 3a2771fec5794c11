// vk::AdaptiveSupersampler: one frame — the G-buffer images checked, then the barriers, the
// parameter upload and the passes of adaptive_component.glsl recorded into the engine's command
// buffer; the profile read back.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "vk/adaptive_internal.h"
#include "vk/barriers.h"

namespace tessera::vk {

namespace {

using State = AdaptiveSupersampler::State;

constexpr const char* kWho = "vk adaptive supersampler";

Status frame_error(ErrorCode code, const std::string& what) {
  return Status::error(code, std::string(kWho) + ": " + what);
}

/// Channel count of the float/normalised colour formats a sampler2D reads; 0 = refused.
int format_channels(VkFormat f) {
  switch (f) {
    case VK_FORMAT_R8_UNORM:
    case VK_FORMAT_R8_SNORM:
    case VK_FORMAT_R16_UNORM:
    case VK_FORMAT_R16_SNORM:
    case VK_FORMAT_R16_SFLOAT:
    case VK_FORMAT_R32_SFLOAT:
      return 1;
    case VK_FORMAT_R8G8_UNORM:
    case VK_FORMAT_R8G8_SNORM:
    case VK_FORMAT_R16G16_UNORM:
    case VK_FORMAT_R16G16_SNORM:
    case VK_FORMAT_R16G16_SFLOAT:
    case VK_FORMAT_R32G32_SFLOAT:
      return 2;
    case VK_FORMAT_B10G11R11_UFLOAT_PACK32:
    case VK_FORMAT_E5B9G9R9_UFLOAT_PACK32:
    case VK_FORMAT_R16G16B16_SFLOAT:
    case VK_FORMAT_R32G32B32_SFLOAT:
      return 3;
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SNORM:
    case VK_FORMAT_B8G8R8A8_UNORM:
    case VK_FORMAT_R16G16B16A16_UNORM:
    case VK_FORMAT_R16G16B16A16_SNORM:
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R32G32B32A32_SFLOAT:
    case VK_FORMAT_A2B10G10R10_UNORM_PACK32:
    case VK_FORMAT_A2R10G10B10_UNORM_PACK32:
      return 4;
    default:
      return 0;
  }
}

std::string hex(std::uint64_t v) {
  char b[24];
  std::snprintf(b, sizeof b, "0x%llX", static_cast<unsigned long long>(v));
  return b;
}

Status check_slot(const State& st, int s, const ImageResource& img) {
  const AdaptiveSupersamplerOptions& o = st.options;
  const std::string slot = "G-buffer slot " + std::to_string(s);
  if (img.image == VK_NULL_HANDLE || img.view == VK_NULL_HANDLE) {
    return frame_error(ErrorCode::invalid_argument,
                       slot + ": no VkImage/VkImageView (the layout reads it)");
  }
  const std::uint32_t gw = std::uint32_t(o.m * o.width), gh = std::uint32_t(o.m * o.height);
  if (img.extent.width != gw || img.extent.height != gh) {
    return frame_error(ErrorCode::size_mismatch,
                       slot + ": image is " + std::to_string(img.extent.width) + "x" +
                           std::to_string(img.extent.height) + ", the G-buffer is " +
                           std::to_string(gw) + "x" + std::to_string(gh) +
                           " (m = " + std::to_string(o.m) + ")");
  }
  const int channels = format_channels(img.format);
  if (channels == 0) {
    return frame_error(ErrorCode::invalid_argument,
                       slot + ": VkFormat " + std::to_string(int(img.format)) +
                           " is not a float or normalised colour format (integer and sRGB "
                           "formats are not read)");
  }
  if (channels < st.derived.slot_channels[s]) {
    return frame_error(ErrorCode::invalid_argument,
                       slot + ": VkFormat " + std::to_string(int(img.format)) + " has " +
                           std::to_string(channels) + " channels, the layout reads channel " +
                           std::to_string(st.derived.slot_channels[s]) + " of it");
  }
  if ((img.usage & VK_IMAGE_USAGE_SAMPLED_BIT) == 0) {
    return frame_error(ErrorCode::invalid_argument,
                       slot + ": usage " + hex(img.usage) + " lacks VK_IMAGE_USAGE_SAMPLED_BIT");
  }
  if (img.layout == VK_IMAGE_LAYOUT_UNDEFINED || img.layout == VK_IMAGE_LAYOUT_PREINITIALIZED) {
    return frame_error(ErrorCode::invalid_argument,
                       slot + ": layout " + std::to_string(int(img.layout)) +
                           " (UNDEFINED/PREINITIALIZED: the G-buffer's contents would be lost)");
  }
  VkFormatProperties fp{};
  st.api.GetPhysicalDeviceFormatProperties(st.api.ctx.physical_device, img.format, &fp);
  if ((fp.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT) == 0) {
    return frame_error(ErrorCode::unsupported, slot + ": the device cannot sample VkFormat " +
                                                   std::to_string(int(img.format)));
  }
  return Status::success();
}

}  // namespace

Status check_adaptive_frame(const State& st, VkCommandBuffer cmd, const AdaptiveFrame& f) {
  if (cmd == VK_NULL_HANDLE) {
    return frame_error(ErrorCode::invalid_argument, "no VkCommandBuffer");
  }
  if (Status s = adaptive::check_budget(f.budget, kWho); !s.ok()) return s;
  if (f.hook_sets.size() != st.options.hook_set_layouts.size()) {
    return frame_error(ErrorCode::invalid_argument,
                       std::to_string(f.hook_sets.size()) + " hook_sets for " +
                           std::to_string(st.options.hook_set_layouts.size()) +
                           " hook_set_layouts");
  }
  for (std::size_t i = 0; i < f.hook_sets.size(); ++i) {
    if (f.hook_sets[i] == VK_NULL_HANDLE) {
      return frame_error(ErrorCode::invalid_argument,
                         "hook_sets[" + std::to_string(i) + "] is VK_NULL_HANDLE");
    }
  }
  for (int s = 0; s < 4; ++s) {
    if (!st.derived.slot_used[s]) continue;
    if (Status e = check_slot(st, s, f.gbuffer[std::size_t(s)]); !e.ok()) return e;
    for (int t = 0; t < s; ++t) {
      const ImageResource &a = f.gbuffer[std::size_t(t)], &b = f.gbuffer[std::size_t(s)];
      if (st.derived.slot_used[t] && a.image == b.image && a.layout != b.layout) {
        return frame_error(ErrorCode::invalid_argument,
                           "G-buffer slots " + std::to_string(t) + " and " + std::to_string(s) +
                               " share a VkImage but give different layouts");
      }
    }
  }
  return Status::success();
}

namespace {

constexpr VkPipelineStageFlags2 kCompute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
constexpr VkAccessFlags2 kPassReads = VK_ACCESS_2_UNIFORM_READ_BIT |
                                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                                      VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;

/// Records the passes, one barrier between each two, timestamps when profiling.
class Recorder {
 public:
  Recorder(State& st, VkCommandBuffer cmd) : st_(st), cmd_(cmd) {}

  void pass(const std::string& name, const std::string& program, std::uint32_t groups_x = 0,
            bool indirect = false, const char* then = nullptr) {
    between();
    dispatch(program, groups_x, indirect);
    if (then != nullptr) {
      between();
      dispatch(then, 1, false);
    }
    if (st_.options.profile) {
      st_.last_passes.push_back(name);
      if (st_.timestamps)
        write_timestamp(st_.api, cmd_, st_.queries.get(), std::uint32_t(st_.last_passes.size()));
    }
  }

 private:
  void between() {
    if (!first_) {
      Barrier b;
      b.memory(kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
               kCompute | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
               kPassReads | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                   VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
      b.record(st_.api, cmd_);
    }
    first_ = false;
  }
  void dispatch(const std::string& program, std::uint32_t groups_x, bool indirect) {
    st_.api.CmdBindPipeline(cmd_, VK_PIPELINE_BIND_POINT_COMPUTE, st_.pipelines.at(program).get());
    if (indirect) {
      st_.api.CmdDispatchIndirect(cmd_, st_.work.get(), 2 * 4);
    } else if (groups_x > 0) {
      st_.api.CmdDispatch(cmd_, groups_x, 1, 1);
    } else {
      st_.api.CmdDispatch(cmd_, std::uint32_t((st_.options.width + 7) / 8),
                          std::uint32_t((st_.options.height + 7) / 8), 1);
    }
  }
  State& st_;
  VkCommandBuffer cmd_;
  bool first_ = true;
};

/// The first barrier (G-buffer in, outputs from UNDEFINED, the buffers after the previous
/// record) and the parameter and work-header uploads.
void record_prologue(State& st, VkCommandBuffer cmd, const AdaptiveFrame& f) {
  const Api& api = st.api;
  Barrier in;
  std::vector<VkImage> done;
  for (std::size_t s = 0; s < 4; ++s) {
    if (!st.derived.slot_used[s]) continue;
    const ImageResource& img = f.gbuffer[s];
    if (std::find(done.begin(), done.end(), img.image) != done.end()) continue;
    done.push_back(img.image);
    in.image(img.image, img.layout, adaptive_read_layout(img.layout), img.stage, img.access,
             kCompute, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  }
  const VkImage outputs[2] = {st.colour.get(), st.counts.get()};
  for (VkImage out : outputs) {
    if (out == VK_NULL_HANDLE) continue;
    // The transition writes the image: after every earlier write (the previous record's
    // passes, or whatever the engine did with it), not only after earlier reads.
    in.image(out, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
             VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT, kCompute,
             VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  }
  in.memory(kCompute | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT,
            VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
            VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  in.record(api, cmd);
  if (st.timestamps) {
    api.CmdResetQueryPool(cmd, st.queries.get(), 0, st.query_capacity);
    write_timestamp(api, cmd, st.queries.get(), 0);
  }
  const adaptive::Params params = adaptive::params(st.options, st.derived);
  api.CmdUpdateBuffer(cmd, st.params.get(), 0, sizeof params, &params);
  // The work header; histograms cleared when budgeted.
  const auto header = adaptive::work_header(f.budget);
  api.CmdUpdateBuffer(cmd, st.work.get(), 0, sizeof header, header.data());
  if (f.budget) {
    api.CmdFillBuffer(cmd, st.work.get(), sizeof header, adaptive::kHistogramUints * 4, 0u);
  }
  Barrier up;
  up.memory(
      VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
      kCompute | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
      kPassReads | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
  up.record(api, cmd);
}

/// With `profile`: the extra-sample counter copied to the host-visible buffer.
void record_epilogue(State& st, VkCommandBuffer cmd) {
  if (!st.options.profile) return;
  Barrier b;
  b.memory(kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
           VK_ACCESS_2_TRANSFER_READ_BIT);
  b.record(st.api, cmd);
  const VkBufferCopy copy{4, 0, 4};
  st.api.CmdCopyBuffer(cmd, st.work.get(), st.readback.get(), 1, &copy);
  Barrier h;
  h.memory(VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
           VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
  h.record(st.api, cmd);
}

}  // namespace

Result<AdaptiveRecord> record_adaptive(State& st, VkCommandBuffer cmd, const AdaptiveFrame& f,
                                       AdaptiveMode mode) {
  if (Status s = check_adaptive_frame(st, cmd, f); !s.ok()) return s;
  const VkDescriptorSet set = acquire_adaptive_set(st, f);
  st.last_passes.clear();
  st.last_mode = mode;
  st.recorded = true;
  record_prologue(st, cmd, f);
  std::vector<VkDescriptorSet> sets = f.hook_sets;
  sets.push_back(set);
  st.api.CmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, st.pipeline_layout.get(), 0,
                               std::uint32_t(sets.size()), sets.data(), 0, nullptr);
  Recorder run(st, cmd);
  for (const adaptive::Step& step :
       adaptive::frame_steps(mode, st.options.schedule, f.budget.has_value())) {
    run.pass(step.name, step.program, step.groups_x, step.indirect, step.then);
  }
  record_epilogue(st, cmd);

  AdaptiveRecord r;
  auto output = [](const Image& img) {
    ImageResource o;
    o.image = img.get();
    o.view = img.view();
    o.format = img.format();
    o.extent = img.extent();
    o.usage = img.usage();
    o.layout = VK_IMAGE_LAYOUT_GENERAL;
    o.stage = kCompute;
    o.access = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    return o;
  };
  r.colour = output(st.colour);
  if (st.counts.get() != VK_NULL_HANDLE) r.sample_counts = output(st.counts);
  for (std::size_t s = 0; s < 4; ++s) {
    r.gbuffer_layout[s] =
        st.derived.slot_used[s] ? adaptive_read_layout(f.gbuffer[s].layout) : f.gbuffer[s].layout;
  }
  return r;
}

Result<AdaptiveRecord> AdaptiveSupersampler::record(VkCommandBuffer cmd,
                                                    const AdaptiveFrame& frame) {
  return record_adaptive(*state_, cmd, frame, AdaptiveMode::adaptive);
}
Result<AdaptiveRecord> AdaptiveSupersampler::record_reference(VkCommandBuffer cmd,
                                                              const AdaptiveFrame& frame) {
  return record_adaptive(*state_, cmd, frame, AdaptiveMode::reference);
}
Result<AdaptiveRecord> AdaptiveSupersampler::record_first_sample(VkCommandBuffer cmd,
                                                                 const AdaptiveFrame& frame) {
  return record_adaptive(*state_, cmd, frame, AdaptiveMode::first);
}

Result<AdaptiveProfile> AdaptiveSupersampler::read_profile() const {
  const State& st = *state_;
  if (!st.options.profile) {
    return frame_error(ErrorCode::unsupported, "read_profile needs options.profile");
  }
  if (!st.recorded) return frame_error(ErrorCode::invalid_argument, "read_profile before a record");
  AdaptiveProfile p;
  st.readback.invalidate();
  const std::uint32_t extra = *static_cast<const std::uint32_t*>(st.readback.mapped());
  p.extra_samples = adaptive::extra_samples(st.options, st.last_mode, extra);
  const std::uint32_t count = std::uint32_t(st.last_passes.size()) + 1;
  std::vector<std::uint64_t> ticks(count);
  if (!st.timestamps) {
    for (const std::string& name : st.last_passes) p.passes.push_back({name, std::nan("")});
    return p;
  }
  const VkResult r = st.api.GetQueryPoolResults(st.api.device(), st.queries.get(), 0, count,
                                                count * 8, ticks.data(), 8, VK_QUERY_RESULT_64_BIT);
  if (r == VK_NOT_READY) {
    return frame_error(ErrorCode::invalid_argument,
                       "read_profile: the last recorded command buffer has not completed");
  }
  if (r != VK_SUCCESS) return vk_error("vk adaptive supersampler: vkGetQueryPoolResults", r);
  const std::uint32_t bits = st.api.queue_family.timestampValidBits;
  const double period = double(st.api.properties.limits.timestampPeriod);
  const std::uint64_t mask = bits >= 64 ? ~0ull : (1ull << bits) - 1;
  for (std::uint32_t i = 1; i < count; ++i) {
    const double ms = double((ticks[i] - ticks[i - 1]) & mask) * period * 1e-6;
    p.passes.push_back({st.last_passes[i - 1], ms});
  }
  return p;
}

}  // namespace tessera::vk
