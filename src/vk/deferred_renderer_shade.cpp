// vk::DeferredRenderer (deferred_renderer.h): the shading calls. m >= 2: adaptive, reference
// and 1 spp through vk::AdaptiveSupersampler with deferred_shading.glsl as its hook (the
// technique's one implementation, adaptive_component.glsl, as gl::DeferredRenderer does);
// FXAA, the edge-per-sample baseline and m = 1 through deferred_passes.comp (the per-pixel loop
// schedule: the same image as GL's schedules, bit for bit).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "vk/barriers.h"
#include "vk/deferred_renderer.h"

namespace tessera::vk {

namespace {

using State = DeferredRenderer::State;

// Pass buffer indices (deferred_renderer.h's `pass`).
constexpr int kBufS = 0, kBufK = 2, kBufOut = 3, kBufRgba8Out = 5;

Result<AdaptiveSupersampler*> component(State& st) {
  const std::array<int, 3> key = {st.w, st.h, st.m};
  if (st.component && st.component_key == key) return st.component.get();
  st.component.reset();
  AdaptiveSupersamplerOptions o;
  // The hook reads the deferred set (set 0); S's light terms go to deferred_passes.comp's
  // SSBO 4 (binding 9).
  deferred::gpu_component_options(o, st.w, st.h, st.m, int(st.arrays.size()),
                                  "std430, set = 0, binding = 9",
                                  "vk::DeferredRenderer's shading hook");
  o.schedule = AdaptiveSchedule::frame_list;  // gl::DeferredRenderer's default
  o.hook_set_layouts = {st.set_layout.get()};
  o.frames_in_flight = 1;  // each frame is submitted and waited for
  Result<std::unique_ptr<AdaptiveSupersampler>> c =
      AdaptiveSupersampler::create(st.device->context(), o);
  if (!c) return c.status();
  st.component = std::move(*c);
  st.component_key = key;
  return st.component.get();
}

AdaptiveFrame component_frame(const State& st) {
  AdaptiveFrame f;
  const bool drawn = st.g_layout == VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  for (std::size_t s = 0; s < 3; ++s) {
    ImageResource& r = f.gbuffer[s];
    r.image = st.g[s].get();
    r.view = st.g[s].view();
    r.format = st.g[s].format();
    r.extent = st.g[s].extent();
    r.usage = st.g[s].usage();
    r.layout = st.g_layout;
    r.stage = drawn ? VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT
                    : VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    r.access = drawn ? VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT : VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;
  }
  f.hook_sets = {st.set};
  return f;
}

/// The component's colour (and sample counts) into the read-back buffer.
Status read_component(State& st, const AdaptiveOutput& rec, bool counts,
                      deferred::ShadeResult& out) {
  Result<VkCommandBuffer> cmd = st.device->begin();
  if (!cmd) return cmd.status();
  const Api& api = *st.api;
  record_full_barrier(api, *cmd);
  // The outputs to TRANSFER_SRC (the component's next record starts them from UNDEFINED).
  Barrier in;
  for (const ImageResource* r : {&rec.colour, &rec.sample_counts}) {
    if (r == &rec.sample_counts && !counts) continue;
    in.image(r->image, r->layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, r->stage, r->access,
             VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  }
  in.record(api, *cmd);
  const std::size_t pixels = std::size_t(st.w) * std::size_t(st.h);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {std::uint32_t(st.w), std::uint32_t(st.h), 1};
  api.CmdCopyImageToBuffer(*cmd, rec.colour.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           st.readback.get(), 1, &region);
  if (counts) {
    region.bufferOffset = pixels * 16;
    api.CmdCopyImageToBuffer(*cmd, rec.sample_counts.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                             st.readback.get(), 1, &region);
  }
  record_host_read_barrier(api, *cmd);
  if (Status s = st.device->submit_and_wait(*cmd); !s.ok()) return s;
  st.readback.invalidate();
  const auto* bytes = static_cast<const std::uint8_t*>(st.readback.mapped());
  out.image = ImageRGBAF(st.w, st.h);
  std::memcpy(out.image.pixels.data(), bytes, pixels * 16);
  for (std::size_t i = 0; i < pixels; ++i) out.image.pixels[i * 4 + 3] = 1.0f;
  if (counts) {
    out.samples.assign(bytes + pixels * 16, bytes + pixels * 17);
    out.samples_shaded = 0;
    for (std::uint8_t s : out.samples) out.samples_shaded += s;
  }
  return Status::success();
}

/// Runs `method`'s passes (deferred::gpu_method_passes, the list the GL renderer runs too), the
/// extra pass with the loop schedule.
Status run_method(State& st, deferred::GpuMethod method, std::vector<PassTime>& passes,
                  const deferred::FxaaOptions& fxaa = {}) {
  Result<std::vector<deferred::GpuPass>> list = deferred::gpu_method_passes(method, fxaa);
  if (!list) return list.status();
  for (deferred::GpuPass& p : *list) {
    if (p.extra) p.defines.push_back("TESSERA_SCHEDULE_LOOP");
    if (Status s = run_deferred_pass(st, p.name, p.defines, passes); !s.ok()) return s;
  }
  return Status::success();
}

/// A pass buffer of float4 per pixel as the image (alpha 1).
Status read_rgba(State& st, int index, deferred::ShadeResult& out) {
  out.image = ImageRGBAF(st.w, st.h);
  if (Status s = read_pass_buffer(st, index, out.image.pixels.size() * 4, out.image.pixels.data());
      !s.ok()) {
    return s;
  }
  for (std::size_t i = 0; i < out.image.pixel_count(); ++i) out.image.pixels[i * 4 + 3] = 1.0f;
  return Status::success();
}

/// The k map (k per pixel) as samples per pixel (k + 1).
Status read_samples(State& st, deferred::ShadeResult& out) {
  const std::size_t pixels = std::size_t(st.w) * std::size_t(st.h);
  std::vector<std::uint32_t> k(pixels);
  if (Status s = read_pass_buffer(st, kBufK, pixels * 4, k.data()); !s.ok()) return s;
  out.samples.resize(pixels);
  out.samples_shaded = 0;
  for (std::size_t i = 0; i < pixels; ++i) {
    out.samples[i] = std::uint8_t(k[i] + 1);
    out.samples_shaded += k[i] + 1;
  }
  return Status::success();
}

}  // namespace

Status shade_with_component(State& st, adaptive::Mode mode, const AdaptiveThresholds* a,
                            deferred::ShadeResult& out) {
  Result<AdaptiveSupersampler*> c = component(st);
  if (!c) return c.status();
  if (a) (*c)->set_thresholds(*a);
  Result<VkCommandBuffer> cmd = st.device->begin();
  if (!cmd) return cmd.status();
  record_full_barrier(*st.api, *cmd);
  const AdaptiveFrame frame = component_frame(st);
  if (Status s = (*c)->begin_frame(0); !s.ok()) return s;  // the last frame completed
  Result<AdaptiveOutput> rec = mode == adaptive::Mode::adaptive ? (*c)->record(*cmd, frame)
                               : mode == adaptive::Mode::reference
                                   ? (*c)->record_reference(*cmd, frame)
                                   : (*c)->record_first_sample(*cmd, frame);
  const auto wall0 = std::chrono::steady_clock::now();
  Status submitted = st.device->submit_and_wait(*cmd);  // also frees it when recording failed
  if (!rec) return rec.status();
  if (!submitted.ok()) return submitted;
  const double wall_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wall0).count();
  st.g_layout = rec->gbuffer_layout[0];
  Result<AdaptiveProfile> prof = (*c)->read_profile(rec->frame_slot, rec->view);
  if (!prof) return prof.status();
  // The component's passes share one submission: each has its GPU time, and the submission's
  // wall time is split between them by those times (evenly where they are unknown), so that
  // the passes' wall times add up to the method's.
  const double gpu_ms = total_gpu_ms(prof->passes);
  const bool by_gpu = std::isfinite(gpu_ms) && gpu_ms > 0.0;
  for (const PassTime& p : prof->passes) {
    const double share =
        by_gpu ? p.gpu_ms / gpu_ms : 1.0 / double(std::max<std::size_t>(prof->passes.size(), 1));
    out.passes.push_back({p.pass, wall_ms * share, p.gpu_ms});
  }
  const bool counts = mode == adaptive::Mode::adaptive;
  if (Status s = read_component(st, *rec, counts, out); !s.ok()) return s;
  const std::uint64_t pixels = std::uint64_t(st.w) * std::uint64_t(st.h);
  if (!counts) {
    out.samples_shaded =
        pixels * (mode == adaptive::Mode::reference ? std::uint64_t(st.m * st.m) : 1u);
  }
  return Status::success();
}

Result<deferred::ShadeResult> DeferredRenderer::shade_reference(const deferred::ShadingOptions& o) {
  State& st = *state_;
  if (Status s = bind_deferred_inputs(st, o, nullptr, nullptr); !s.ok()) return s;
  deferred::ShadeResult out;
  if (st.m >= 2) {
    if (Status s = shade_with_component(st, adaptive::Mode::reference, nullptr, out); !s.ok()) {
      return s;
    }
    return out;
  }
  if (Status s = run_method(st, deferred::GpuMethod::reference, out.passes); !s.ok()) return s;
  if (Status s = read_rgba(st, kBufOut, out); !s.ok()) return s;
  out.samples_shaded = std::uint64_t(st.w) * std::uint64_t(st.h) * std::uint64_t(st.m * st.m);
  return out;
}

Result<deferred::ShadeResult> DeferredRenderer::shade_default(const deferred::ShadingOptions& o) {
  State& st = *state_;
  if (Status s = bind_deferred_inputs(st, o, nullptr, nullptr); !s.ok()) return s;
  deferred::ShadeResult out;
  if (st.m >= 2) {
    if (Status s = shade_with_component(st, adaptive::Mode::first, nullptr, out); !s.ok()) {
      return s;
    }
    return out;
  }
  if (Status s = run_method(st, deferred::GpuMethod::first, out.passes); !s.ok()) return s;
  if (Status s = read_rgba(st, kBufS, out); !s.ok()) return s;
  out.samples_shaded = std::uint64_t(st.w) * std::uint64_t(st.h);
  return out;
}

Result<deferred::ShadeResult> DeferredRenderer::shade_adaptive(const deferred::ShadingOptions& o,
                                                               const AdaptiveThresholds& a) {
  State& st = *state_;
  if (Status s = bind_deferred_inputs(st, o, &a, nullptr); !s.ok()) return s;
  deferred::ShadeResult out;
  if (st.m >= 2) {  // m = 1 has no window to adapt: deferred_passes.comp's three passes
    if (Status s = shade_with_component(st, adaptive::Mode::adaptive, &a, out); !s.ok()) {
      return s;
    }
    return out;
  }
  if (Status s = run_method(st, deferred::GpuMethod::adaptive, out.passes); !s.ok()) return s;
  if (Status s = read_rgba(st, kBufOut, out); !s.ok()) return s;
  if (Status s = read_samples(st, out); !s.ok()) return s;
  return out;
}

Result<deferred::ShadeResult> DeferredRenderer::shade_edge_per_sample(
    const deferred::ShadingOptions& o, const deferred::EdgePerSampleOptions& e) {
  State& st = *state_;
  if (Status s = bind_deferred_inputs(st, o, nullptr, &e); !s.ok()) return s;
  deferred::ShadeResult out;
  if (Status s = run_method(st, deferred::GpuMethod::edge_per_sample, out.passes); !s.ok()) {
    return s;
  }
  if (Status s = read_rgba(st, kBufOut, out); !s.ok()) return s;
  if (Status s = read_samples(st, out); !s.ok()) return s;
  return out;
}

Result<deferred::FxaaResult> DeferredRenderer::shade_default_fxaa(const deferred::ShadingOptions& o,
                                                                  const deferred::FxaaOptions& f) {
  State& st = *state_;
  if (Status s = deferred::gpu_fxaa_defines(f).status(); !s.ok()) return s;
  if (Status s = bind_deferred_inputs(st, o, nullptr, nullptr); !s.ok()) return s;
  deferred::FxaaResult out;
  if (Status s = run_method(st, deferred::GpuMethod::fxaa, out.passes, f); !s.ok()) return s;
  out.image = ImageRGBA8(st.w, st.h);
  if (Status s =
          read_pass_buffer(st, kBufRgba8Out, out.image.pixels.size(), out.image.pixels.data());
      !s.ok()) {
    return s;
  }
  return out;
}

}  // namespace tessera::vk
