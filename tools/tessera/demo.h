// Sections of the `tessera demo` report. Each system adds one function here.
#pragma once

#include "report.h"

namespace tessera::cli {

struct DemoOptions {
  int threads = 0;
  int size = 256;  ///< Edge length of the procedural images.
};

/// Images and metrics: the procedural content, sRGB round trip, metric examples.
Status demo_images_section(Report& report, const DemoOptions& options);

/// PVRTC1: every quality and 2 bpp on the procedural images, heatmaps, crops, a mip chain.
Status demo_pvrtc_section(Report& report, const DemoOptions& options);

/// Rendering core: the built-in scene at 1x, 4x MSAA and a 4x4 SSAA reference, with zooms.
Status demo_render_section(Report& report, const DemoOptions& options);

/// Seamless per-face texturing: the seam experiment run small on the built-in scene.
Status demo_seams_section(Report& report, const DemoOptions& options);

/// Adaptive supersampling for deferred shading: 4x4 reference, adaptive, 1x and FXAA, heatmaps.
Status demo_aa_section(Report& report, const DemoOptions& options);

}  // namespace tessera::cli
