// vk::AdaptiveSupersampler: one frame — the G-buffer images checked, then the barriers, the
// parameter upload and the passes of adaptive_component.glsl recorded into the engine's command
// buffer; the profile read back.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

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

Status check_slot(const State& st, int s, const ImageResource& img, VkExtent2D size) {
  const AdaptiveSupersamplerOptions& o = st.options;
  const std::string slot = "G-buffer slot " + std::to_string(s);
  if (img.image == VK_NULL_HANDLE || img.view == VK_NULL_HANDLE) {
    return frame_error(ErrorCode::invalid_argument,
                       slot + ": no VkImage/VkImageView (the layout reads it)");
  }
  const std::uint32_t gw = std::uint32_t(o.m) * size.width, gh = std::uint32_t(o.m) * size.height;
  if (img.extent.width < gw || img.extent.height < gh) {
    return frame_error(ErrorCode::size_mismatch,
                       slot + ": image is " + std::to_string(img.extent.width) + "x" +
                           std::to_string(img.extent.height) + ", smaller than the G-buffer " +
                           std::to_string(gw) + "x" + std::to_string(gh) +
                           " (m = " + std::to_string(o.m) + ", render size " +
                           std::to_string(size.width) + "x" + std::to_string(size.height) + ")");
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

/// The engine's own colour output: handles, format, storage usage, extent.
Status check_output(const State& st, const ImageResource& out, VkExtent2D size) {
  const std::string what = "output image: ";
  if (out.view == VK_NULL_HANDLE) {
    return frame_error(ErrorCode::invalid_argument, what + "no VkImageView");
  }
  const VkFormat want = adaptive_output_format(st.options);
  if (out.format != want) {
    return frame_error(ErrorCode::invalid_argument,
                       what + "VkFormat " + std::to_string(int(out.format)) + ", the options' " +
                           "output is VkFormat " + std::to_string(int(want)));
  }
  if ((out.usage & VK_IMAGE_USAGE_STORAGE_BIT) == 0) {
    return frame_error(ErrorCode::invalid_argument,
                       what + "usage " + hex(out.usage) + " lacks VK_IMAGE_USAGE_STORAGE_BIT");
  }
  if (out.extent.width < size.width || out.extent.height < size.height) {
    return frame_error(ErrorCode::size_mismatch,
                       what + std::to_string(out.extent.width) + "x" +
                           std::to_string(out.extent.height) + ", smaller than the render size " +
                           std::to_string(size.width) + "x" + std::to_string(size.height));
  }
  if (out.layout == VK_IMAGE_LAYOUT_PREINITIALIZED) {
    return frame_error(ErrorCode::invalid_argument, what + "layout PREINITIALIZED");
  }
  return Status::success();
}

}  // namespace

Status check_adaptive_frame(const State& st, VkCommandBuffer cmd, const AdaptiveFrame& f,
                            VkExtent2D size) {
  if (cmd == VK_NULL_HANDLE) {
    return frame_error(ErrorCode::invalid_argument, "no VkCommandBuffer");
  }
  if (!st.frame_open) {
    return frame_error(ErrorCode::invalid_argument,
                       "record before begin_frame (which frame slot the record belongs to)");
  }
  const AdaptiveSupersamplerOptions& o = st.options;
  if (size.width == 0 || size.height == 0 || size.width > std::uint32_t(o.width) ||
      size.height > std::uint32_t(o.height)) {
    return frame_error(ErrorCode::too_large, "render size " + std::to_string(f.render_size.width) +
                                                 "x" + std::to_string(f.render_size.height) +
                                                 " (1.." + std::to_string(o.width) + " x 1.." +
                                                 std::to_string(o.height) +
                                                 ", the largest size of the options)");
  }
  if (f.output.image != VK_NULL_HANDLE) {
    if (Status s = check_output(st, f.output, size); !s.ok()) return s;
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
    if (Status e = check_slot(st, s, f.gbuffer[std::size_t(s)], size); !e.ok()) return e;
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

/// One record's view, size and mode, as the recording steps below see it.
struct Target {
  State::View& view;
  VkExtent2D size;
  const AdaptiveFrame& frame;
};

/// Records the passes, one barrier between each two, timestamps when profiling.
class Recorder {
 public:
  Recorder(State& st, VkCommandBuffer cmd, const Target& t) : st_(st), cmd_(cmd), t_(t) {}

  void pass(const std::string& name, const std::string& program, std::uint32_t groups_x = 0,
            bool indirect = false, const char* then = nullptr) {
    between();
    dispatch(program, groups_x, indirect);
    if (then != nullptr) {
      between();
      dispatch(then, 1, false);
    }
    if (st_.options.profile) {
      t_.view.passes.push_back(name);
      if (st_.timestamps) {
        write_timestamp(st_.api, cmd_, t_.view.queries.get(), std::uint32_t(t_.view.passes.size()));
      }
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
      st_.api.CmdDispatch(cmd_, (t_.size.width + 7) / 8, (t_.size.height + 7) / 8, 1);
    }
  }
  State& st_;
  VkCommandBuffer cmd_;
  const Target& t_;
  bool first_ = true;
};

/// The first barrier (G-buffer in, outputs to GENERAL, the shared buffers after every earlier
/// record) and the parameter and work-header uploads.
void record_prologue(State& st, VkCommandBuffer cmd, const Target& t) {
  const Api& api = st.api;
  const AdaptiveFrame& f = t.frame;
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
  // The transition writes the image: after every earlier write (the view's previous record, or
  // whatever the engine did with it), not only after earlier reads. The engine's own output
  // keeps its contents beyond the render size (from its layout, after its last use).
  if (f.output.image != VK_NULL_HANDLE) {
    in.image(f.output.image, f.output.layout, VK_IMAGE_LAYOUT_GENERAL, f.output.stage,
             f.output.access, kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  } else {
    in.image(t.view.colour.get(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
             VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT, kCompute,
             VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  }
  if (t.view.counts.get() != VK_NULL_HANDLE) {
    in.image(t.view.counts.get(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
             VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT, kCompute,
             VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  }
  in.memory(kCompute | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT,
            VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
            VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  in.record(api, cmd);
  if (st.timestamps) {
    api.CmdResetQueryPool(cmd, t.view.queries.get(), 0, st.query_capacity);
    write_timestamp(api, cmd, t.view.queries.get(), 0);
  }
  const adaptive::Params params =
      adaptive::params(st.options, st.derived, int(t.size.width), int(t.size.height));
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

/// With `profile`: the timestamps, the extra-sample counter and the frame number copied to the
/// view's host-visible buffer (read_profile's "completed" is that frame number there).
void record_epilogue(State& st, VkCommandBuffer cmd, const Target& t) {
  if (!st.options.profile) return;
  Barrier b;
  b.memory(kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
           VK_ACCESS_2_TRANSFER_READ_BIT);
  b.record(st.api, cmd);
  const VkBuffer rb = t.view.readback.get();
  if (st.timestamps) {
    st.api.CmdCopyQueryPoolResults(cmd, t.view.queries.get(), 0,
                                   std::uint32_t(t.view.passes.size()) + 1, rb, kReadbackTicks, 8,
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT);
  }
  const VkBufferCopy copy{4, 0, 4};
  st.api.CmdCopyBuffer(cmd, st.work.get(), rb, 1, &copy);
  const std::uint64_t frame = st.frame_count;
  st.api.CmdUpdateBuffer(cmd, rb, 8, 8, &frame);
  Barrier h;
  h.memory(VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
           VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
  h.record(st.api, cmd);
}

ImageResource output_resource(VkImage image, VkImageView view, VkFormat format, VkExtent2D extent,
                              VkImageUsageFlags usage) {
  ImageResource o;
  o.image = image;
  o.view = view;
  o.format = format;
  o.extent = extent;
  o.usage = usage;
  o.layout = VK_IMAGE_LAYOUT_GENERAL;
  o.stage = kCompute;
  o.access = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
  return o;
}
ImageResource output_resource(const Image& img) {
  return output_resource(img.get(), img.view(), img.format(), img.extent(), img.usage());
}

}  // namespace

Result<AdaptiveOutput> record_adaptive(State& st, VkCommandBuffer cmd, const AdaptiveFrame& f,
                                       AdaptiveMode mode) {
  const AdaptiveSupersamplerOptions& o = st.options;
  const bool largest = f.render_size.width == 0 && f.render_size.height == 0;
  const VkExtent2D size =
      largest ? VkExtent2D{std::uint32_t(o.width), std::uint32_t(o.height)} : f.render_size;
  if (Status s = check_adaptive_frame(st, cmd, f, size); !s.ok()) return s;
  Result<State::View*> acquired = acquire_adaptive_view(st, f);
  if (!acquired) return acquired.status();
  State::View& view = **acquired;
  view.passes.clear();
  view.mode = mode;
  view.size = size;
  view.frame = st.frame_count;
  const Target t{view, size, f};
  record_prologue(st, cmd, t);
  std::vector<VkDescriptorSet> sets = f.hook_sets;
  sets.push_back(view.set);
  st.api.CmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, st.pipeline_layout.get(), 0,
                               std::uint32_t(sets.size()), sets.data(), 0, nullptr);
  Recorder run(st, cmd, t);
  for (const adaptive::Step& step : adaptive::frame_steps(mode, o.schedule, f.budget.has_value())) {
    run.pass(step.name, step.program, step.groups_x, step.indirect, step.then);
  }
  record_epilogue(st, cmd, t);

  AdaptiveOutput r;
  r.colour = f.output.image != VK_NULL_HANDLE
                 ? output_resource(f.output.image, f.output.view, f.output.format, f.output.extent,
                                   f.output.usage)
                 : output_resource(view.colour);
  if (view.counts.get() != VK_NULL_HANDLE) r.sample_counts = output_resource(view.counts);
  for (std::size_t s = 0; s < 4; ++s) {
    r.gbuffer_layout[s] =
        st.derived.slot_used[s] ? adaptive_read_layout(f.gbuffer[s].layout) : f.gbuffer[s].layout;
  }
  r.render_size = size;
  r.frame_slot = st.slot;
  r.view = st.views++;
  return r;
}

Status AdaptiveSupersampler::begin_frame(std::uint32_t frame_slot) {
  State& st = *state_;
  if (frame_slot >= st.options.frames_in_flight) {
    return frame_error(ErrorCode::invalid_argument,
                       "begin_frame(" + std::to_string(frame_slot) + "): frame slots are 0.." +
                           std::to_string(st.options.frames_in_flight - 1) +
                           " (frames_in_flight = " + std::to_string(st.options.frames_in_flight) +
                           ")");
  }
  st.frame_open = true;
  st.slot = frame_slot;
  st.views = 0;
  ++st.frame_count;
  return Status::success();
}

Result<AdaptiveOutput> AdaptiveSupersampler::record(VkCommandBuffer cmd,
                                                    const AdaptiveFrame& frame) {
  return record_adaptive(*state_, cmd, frame, AdaptiveMode::adaptive);
}
Result<AdaptiveOutput> AdaptiveSupersampler::record_reference(VkCommandBuffer cmd,
                                                              const AdaptiveFrame& frame) {
  return record_adaptive(*state_, cmd, frame, AdaptiveMode::reference);
}
Result<AdaptiveOutput> AdaptiveSupersampler::record_first_sample(VkCommandBuffer cmd,
                                                                 const AdaptiveFrame& frame) {
  return record_adaptive(*state_, cmd, frame, AdaptiveMode::first);
}

Result<AdaptiveProfile> AdaptiveSupersampler::read_profile(std::uint32_t frame_slot,
                                                           std::uint32_t view) const {
  const State& st = *state_;
  if (!st.options.profile) {
    return frame_error(ErrorCode::unsupported, "read_profile needs options.profile");
  }
  const std::string which =
      "read_profile(" + std::to_string(frame_slot) + ", " + std::to_string(view) + ")";
  if (frame_slot >= st.frames.size() || view >= st.frames[frame_slot].size() ||
      st.frames[frame_slot][view].frame == 0) {
    return frame_error(ErrorCode::invalid_argument, which + ": nothing recorded there");
  }
  const State::View& v = st.frames[frame_slot][view];
  const std::string pending =
      which + ": the command buffer of frame " + std::to_string(v.frame) + " has not completed";
  v.readback.invalidate();
  const auto* bytes = static_cast<const unsigned char*>(v.readback.mapped());
  std::uint32_t counter = 0;
  std::uint64_t written = 0;
  std::memcpy(&counter, bytes, 4);
  std::memcpy(&written, bytes + 8, 8);
  if (written != v.frame) return frame_error(ErrorCode::invalid_argument, pending);
  AdaptiveProfile p;
  p.frame = v.frame;
  p.frame_slot = frame_slot;
  p.view = view;
  p.render_size = v.size;
  p.extra_samples = adaptive::extra_samples(st.options, v.mode, counter,
                                            std::uint64_t(v.size.width) * v.size.height);
  if (!st.timestamps) {
    for (const std::string& name : v.passes) p.passes.push_back({name});  // times NaN
    return p;
  }
  std::vector<std::uint64_t> ticks(v.passes.size() + 1);
  std::memcpy(ticks.data(), bytes + kReadbackTicks, ticks.size() * 8);
  const std::uint32_t bits = st.api.queue_family.timestampValidBits;
  const double period = double(st.api.properties.limits.timestampPeriod);
  const std::uint64_t mask = bits >= 64 ? ~0ull : (1ull << bits) - 1;
  for (std::size_t i = 1; i < ticks.size(); ++i) {
    PassTime t;
    t.pass = v.passes[i - 1];
    t.gpu_ms = double((ticks[i] - ticks[i - 1]) & mask) * period * 1e-6;
    p.passes.push_back(std::move(t));
  }
  return p;
}

}  // namespace tessera::vk
