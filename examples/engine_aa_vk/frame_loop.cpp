// engine_aa_vk --frame-loop (frame_loop.h).
#include "frame_loop.h"

#include <memory>

#include "scene_frame.h"
#include "vk_window.h"  // examples/common: the GLFW window and swapchain

namespace engine {

int render_scale(int frame) {
  static const int kScales[3] = {100, 70, 85};
  return kScales[frame % 3];
}

namespace {

/// One frame slot: its fence, its command buffer while in flight, and per view the targets
/// the engine writes from the host (the uniform buffer) or the GPU (the G-buffer).
struct Slot {
  VkFence fence = VK_NULL_HANDLE;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  std::vector<std::unique_ptr<Frame>> views;
  FrameResult pending;
};

/// The profiles of the slot's frame, once its fence signalled.
std::string collect(Device& d, tessera::vk::AdaptiveSupersampler& aa, std::uint32_t slot, Slot& s,
                    std::vector<FrameResult>& out) {
  d.wait(s.fence);
  d.free(s.cmd);
  s.cmd = VK_NULL_HANDLE;
  for (ViewResult& v : s.pending.views) {
    auto p = aa.read_profile(slot, std::uint32_t(v.view));
    if (!p) return p.status().message;
    s.pending.frame = p->frame;
    v.extra_samples = p->extra_samples;
    v.tessera_gpu_ms = p->total_gpu_ms();
  }
  out.push_back(s.pending);
  return "";
}

}  // namespace

std::string run_frame_loop(Device& d, const GeometryPipeline& gp, const FrameLoopOptions& o,
                           tessera::vk::AdaptiveSupersampler& aa, std::vector<FrameResult>& out) {
  std::vector<Slot> slots(o.frames_in_flight);
  for (Slot& s : slots) {
    s.fence = d.fence();
    for (int v = 0; v < o.views; ++v) {
      s.views.push_back(std::make_unique<Frame>());
      setup(d, o.w, o.h, o.m, v, *s.views.back());
    }
  }
  std::string err;
  for (int i = 0; i < o.frames && err.empty(); ++i) {
    const std::uint32_t slot = std::uint32_t(i) % o.frames_in_flight;
    Slot& s = slots[slot];
    // ---- the engine's frame start: wait for this slot's last frame, then reuse its objects ----
    if (s.cmd != VK_NULL_HANDLE) err = collect(d, aa, slot, s, out);
    if (!err.empty()) break;
    const int scale = render_scale(i);
    const VkExtent2D size{std::uint32_t((o.w * scale + 50) / 100),
                          std::uint32_t((o.h * scale + 50) / 100)};
    // ---- tessera: the slot's earlier records have completed (its fence) ----
    if (tessera::Status st = aa.begin_frame(slot); !st.ok()) {
      err = st.message;
      break;
    }
    s.cmd = d.begin();
    s.pending = FrameResult{};
    s.pending.slot = slot;
    s.pending.scale_percent = scale;
    for (int v = 0; v < o.views && err.empty(); ++v) {
      Frame& f = *s.views[std::size_t(v)];
      set_grid(f, size.width * std::uint32_t(o.m), size.height * std::uint32_t(o.m));
      record_gbuffer(s.cmd, gp, f,
                     {size.width * std::uint32_t(o.m), size.height * std::uint32_t(o.m)});
      // ---- tessera: this view's G-buffer in, its record into the frame's command buffer ----
      tessera::vk::AdaptiveFrame in;
      in.gbuffer[0] = rendered(f.rt0);
      in.gbuffer[1] = rendered(f.rt1);
      in.hook_sets = {f.set};
      in.render_size = size;
      if (o.budget >= 0) in.budget = o.budget;
      tessera::Result<tessera::vk::AdaptiveOutput> r = aa.record(s.cmd, in);
      if (!r) {
        err = r.status().message;
        break;
      }
      // r->colour (GENERAL, top-left `size` texels) is this view's image until the slot comes
      // round again: the engine composites or presents it (view 0 to the window).
      if (v == 0 && o.window != nullptr) {
        err = o.window->acquire(d, slot);
        if (err.empty()) {
          // The blit's source: from tessera's last write to TRANSFER_SRC_OPTIMAL (its next
          // record of the image starts from UNDEFINED).
          barrier(s.cmd, r->colour.image, r->colour.layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                  r->colour.stage, r->colour.access, VK_PIPELINE_STAGE_2_BLIT_BIT,
                  VK_ACCESS_2_TRANSFER_READ_BIT);
          o.window->record_blit(s.cmd, r->colour.image, size);
        }
      }
      s.pending.views.push_back({v, size.width, size.height, 0, 0.0});
    }
    if (o.window == nullptr) {
      d.submit(s.cmd, s.fence);  // no wait: the next frame starts at once
    } else if (err.empty()) {
      d.submit(s.cmd, s.fence, o.window->acquired(slot), o.window->rendered());
      err = o.window->present(d);
    }
  }
  for (std::uint32_t k = 0; k < o.frames_in_flight; ++k) {  // drain, oldest first
    const std::uint32_t slot = std::uint32_t(o.frames + int(k)) % o.frames_in_flight;
    if (slots[slot].cmd == VK_NULL_HANDLE) continue;
    const std::string e = collect(d, aa, slot, slots[slot], out);
    if (err.empty()) err = e;
  }
  for (Slot& s : slots) {
    for (auto& f : s.views) destroy(d, *f);
    vkDestroyFence(d.device, s.fence, nullptr);
  }
  return err;
}

}  // namespace engine
