// The files of `tessera aa`: aa.json and aa.md as the library writes them
// (experiments::to_json / to_markdown), and every image and heatmap of each rate as PNG
// (experiments::aa_rate_images) with the colour bars as SVG.
#include "report_aa.h"

#include <filesystem>

#include "plot.h"
#include "tessera/io.h"
#include "tessera/metrics.h"

namespace tessera::cli {

namespace {

namespace fs = std::filesystem;

Status write_text(const fs::path& path, const std::string& text) {
  return io::write_file_atomic(path.string(),
                               {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
}

/// The images of one rate as DIR/PREFIX<name>.png and its colour bars.
Status write_rate_images(const experiments::AaConfig& c, const experiments::AaRateResult& rate,
                         const std::string& dir, const std::string& prefix) {
  const std::string r = std::to_string(rate.m) + "x" + std::to_string(rate.m);
  const int n = rate.m * rate.m;
  // Colour bars: the samples maps (1 + k of m*m) and the difference heatmaps.
  if (Status s = write_text(
          fs::path(dir) / (prefix + "samples-colourbar-" + r + ".svg"),
          colour_bar_svg(metrics::ColourMap::inferno, 0, n, n / 4 + 1,
                         "samples shaded per pixel (1 + k of " + std::to_string(n) + ")"));
      !s.ok()) {
    return s;
  }
  if (Status s = write_text(fs::path(dir) / "diff-colourbar.svg",
                            colour_bar_svg(metrics::ColourMap::inferno, 0, 32, 5,
                                           "max abs channel difference (8-bit levels; 32 and "
                                           "above saturate)"));
      !s.ok()) {
    return s;
  }
  Result<std::vector<experiments::AaRateImage>> images = experiments::aa_rate_images(c, rate);
  if (!images) return images.status();
  for (const experiments::AaRateImage& i : *images) {
    const fs::path path = fs::path(dir) / (prefix + i.name + ".png");
    if (Status s = io::write_png(path.string(), i.image); !s.ok()) return s;
  }
  return Status::success();
}

}  // namespace

Status write_aa_report(const experiments::AaConfig& c, const experiments::AaResult& res,
                       const std::string& scene_label, const std::string& dir,
                       std::string* markdown, std::string* json) {
  for (const experiments::AaRateResult& rate : res.rates) {
    if (Status s = write_rate_images(c, rate, dir, ""); !s.ok()) return s;
  }
  if (res.gl) {
    for (const experiments::AaRateResult& rate : res.gl->rates) {
      if (Status s = write_rate_images(c, rate, dir, "gl-"); !s.ok()) return s;
    }
  }
  const experiments::AaReportOptions options{scene_label};
  Result<std::string> j = experiments::to_json(c, res, options);
  if (!j) return j.status();
  Result<std::string> md = experiments::to_markdown(c, res, options);
  if (!md) return md.status();
  if (Status s = write_text(fs::path(dir) / "aa.json", *j + "\n"); !s.ok()) return s;
  if (Status s = write_text(fs::path(dir) / "aa.md", *md); !s.ok()) return s;
  if (markdown) *markdown = std::move(*md);
  if (json) *json = std::move(*j);
  return Status::success();
}

}  // namespace tessera::cli
