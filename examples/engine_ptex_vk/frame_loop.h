// engine_ptex_vk --frame-loop: the engine's forward pass in the frame loop of a real engine
// around tessera::vk::FaceTextureSet, as engine_aa_vk --frame-loop is for AdaptiveSupersampler —
// F frames in flight (a fence and a command buffer per frame slot, no queue or device wait
// inside the loop), several views a frame (each its own camera, colour and depth targets,
// uniform buffer and frame descriptor set per frame slot), and dynamic resolution (the render
// scale cycles 100 % -> 70 % -> 85 %: the pipeline's viewport and scissor are dynamic and each
// view is drawn into the top-left of max-size targets, with no re-create and no wait). The
// texture set's upload is recorded into the first frame's command buffer (Frame::before_pass)
// and its staging released after that frame's fence.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "engine.h"

namespace engine {

class Window;

struct FrameLoopOptions {
  int w = 0, h = 0;  ///< The largest render size and the window's.
  int frames = 0;    ///< Frames to run.
  std::uint32_t frames_in_flight = 2;
  int views = 2;
  /// Frames from this index on read every view's image back (after the slot's fence) into
  /// ViewResult::image, for the engine's check.
  int read_back_from = 0;
  /// The frame block (set 0, binding 0) of view `view` in frame `frame` at render size `size`.
  std::function<std::vector<std::uint8_t>(int frame, int view, VkExtent2D size)> frame_block;
  /// Called once, after the first frame's fence (the upload's command buffer completed); "" or
  /// the problem.
  std::function<std::string()> first_frame_completed;
  Window* window = nullptr;  ///< --window: view 0 presented every frame (vk_window.h).
};

/// One view of one completed frame.
struct ViewResult {
  int view = 0;
  std::uint32_t w = 0, h = 0;  ///< Render size.
  std::vector<float> image;    ///< RGBA32F, w x h, top row first (frames >= read_back_from).
};
struct FrameResult {
  int frame = 0;  ///< The engine's frame index, from 0.
  std::uint32_t slot = 0;
  int scale_percent = 100;
  std::vector<ViewResult> views;
};

/// The render scale of frame i (percent): 100, 70, 85, 100, ... (as engine_aa_vk's).
int render_scale(int frame);
/// The render size of `scale` percent of w x h, each side rounded to an even number (2x2
/// derivative quads, as --size), at least 2.
VkExtent2D render_size(int w, int h, int scale);

/// Runs the loop drawing `scene` (its vertices, indices, stages, extra set layouts, bind_extra
/// and before_pass; its width, height and block are the loop's) on `d`; the completed frames in
/// order into `out`; "" or the error.
std::string run_frame_loop(Device& d, const Frame& scene, const FrameLoopOptions& o,
                           std::vector<FrameResult>& out);

}  // namespace engine
