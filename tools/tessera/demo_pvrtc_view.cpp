// Demo section, PVRTC: the section's images as a static `tessera view` (view_export.cpp) beside
// the report, linked from it.
#include "demo.h"
#include "view.h"

namespace tessera::cli {

Status demo_pvrtc_view(Report& report, const DemoOptions& options,
                       const std::vector<PvrtcDemoImage>& images) {
  std::vector<ViewInput> inputs;
  for (const PvrtcDemoImage& im : images) {
    ViewInput in;
    in.path = im.png_path;
    in.name = im.name + ".png";
    in.image = im.image;
    inputs.push_back(std::move(in));
  }
  const std::string file = "pvrtc-view.html";
  if (Status s = write_view_export(inputs, {}, options.threads, report.dir() + "/" + file);
      !s.ok()) {
    return s;
  }
  report.html("<p><a href=\"" + file +
              "\">Open these images in tessera view</a>: original against PVRTC side by side "
              "or as a wipe, zoom to the texel, channels and alpha, error heatmaps, for fast, "
              "normal and high (and, with alpha, --alpha-bleed and --alpha-weighted); one file, "
              "as <code>tessera view IMAGE --html -o VIEW.html</code> writes it.</p>");
  return Status::success();
}

}  // namespace tessera::cli
