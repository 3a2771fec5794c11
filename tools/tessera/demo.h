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

}  // namespace tessera::cli
