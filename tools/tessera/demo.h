// Sections of the `tessera demo` report. Each system adds one function here.
#pragma once

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "report.h"

namespace tessera::cli {

struct DemoOptions {
  int threads = 0;
  int size = 256;  ///< Edge length of the procedural images.
  /// `tessera demo --json`: when set, each section adds the numbers of its tables here, under
  /// its own key ("images", "pvrtc", "render", "seams", "aa").
  nlohmann::json* summary = nullptr;
};

/// A number for the summary: null where it is not finite (the PSNR of identical images).
inline nlohmann::json json_number(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

/// Images and metrics: the procedural content, sRGB round trip, metric examples.
Status demo_images_section(Report& report, const DemoOptions& options);

/// PVRTC1: every quality and 2 bpp on the procedural images, heatmaps, crops, a mip chain.
Status demo_pvrtc_section(Report& report, const DemoOptions& options);

/// One procedural image of the PVRTC section, as saved in the report.
struct PvrtcDemoImage {
  std::string name;
  std::string png_path;  ///< Absolute or relative to the working folder.
  ImageRGBA8 image;
  bool has_alpha = false;
};

/// PVRTC quality against time: tessera's levels and PVRTexTool's (when found) as whole
/// processes on the same PNG files, one SVG plot and a table.
Status demo_pvrtc_quality_time(Report& report, const DemoOptions& options,
                               const std::vector<PvrtcDemoImage>& images);

/// The PVRTC section's images as a static `tessera view` (DIR/pvrtc-view.html), linked from
/// the report.
Status demo_pvrtc_view(Report& report, const DemoOptions& options,
                       const std::vector<PvrtcDemoImage>& images);

/// Rendering core: the built-in scene at 1x, 4x MSAA and a 4x4 SSAA reference, with zooms.
Status demo_render_section(Report& report, const DemoOptions& options);

/// Seamless per-face texturing: the seam experiment run small on the built-in scene.
Status demo_seams_section(Report& report, const DemoOptions& options);

/// Adaptive supersampling for deferred shading: 4x4 reference, adaptive, 1x and FXAA, heatmaps.
Status demo_aa_section(Report& report, const DemoOptions& options);

}  // namespace tessera::cli
