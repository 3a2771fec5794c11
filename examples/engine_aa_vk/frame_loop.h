// engine_aa_vk --frame-loop: the frame loop of a real engine around tessera::vk::
// AdaptiveSupersampler — F frames in flight (a fence and a command buffer per frame slot, no
// queue or device wait inside the loop), several views a frame (each its own camera, G-buffer,
// uniform buffer and hook descriptor set per frame slot), and dynamic resolution (the render
// scale cycles 100 % -> 70 % -> 85 %: the G-buffer is rendered into the top-left of max-size
// images and tessera records at that render size, with no re-create and no wait).
#pragma once

#include <string>
#include <vector>

#include "engine.h"
#include "tessera/vk_adaptive.h"

namespace engine {

class Window;

struct FrameLoopOptions {
  int w = 0, h = 0, m = 4;  ///< The largest output size and the window side.
  int frames = 0;           ///< Frames to run.
  std::uint32_t frames_in_flight = 2;
  int views = 2;
  long long budget = -1;  ///< -1: none.
  Window* window =
      nullptr;  ///< --window: view 0 presented every frame (examples/common/vk_window.h).
};

/// One view of one completed frame, as its profile reported it.
struct ViewResult {
  int view = 0;
  std::uint32_t w = 0, h = 0;  ///< Render size.
  unsigned long long extra_samples = 0;
  double tessera_gpu_ms = 0;  ///< The component's passes (GPU timestamps).
};
struct FrameResult {
  unsigned long long frame = 0;  ///< The component's frame number (its profile names it).
  std::uint32_t slot = 0;
  int scale_percent = 100;
  std::vector<ViewResult> views;
};

/// The render scale of frame i (percent): 100, 70, 85, 100, ...
int render_scale(int frame);

/// Runs the loop on `aa` (created with frames_in_flight = o.frames_in_flight, profile on, the
/// hook's set 0 layout `hook_layout`'s); "" or the error.
std::string run_frame_loop(Device& d, const GeometryPipeline& gp, const FrameLoopOptions& o,
                           tessera::vk::AdaptiveSupersampler& aa, std::vector<FrameResult>& out);

}  // namespace engine
