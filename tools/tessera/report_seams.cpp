// The files of `tessera seams`: seams.json and seams.md as the library writes them
// (experiments::to_json / to_markdown), the CSV, the SVG/PNG plots, the frame-0 images and zooms
// on the worst seam (report_seams_plots.cpp).
#include "report_seams.h"

#include <cstdint>
#include <span>
#include <string>

#include "report_seams_internal.h"
#include "tessera/io.h"

namespace tessera::cli {

namespace seams_report {

Status write_text(const std::string& path, const std::string& text) {
  return io::write_file_atomic(
      path, std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()),
                                          text.size()));
}

}  // namespace seams_report

Status write_seams_report(const experiments::SeamsConfig& config,
                          const experiments::SeamsResult& result, const std::string& dir,
                          bool images, std::string& json) {
  if (result.rates.empty()) {
    return Status::error(ErrorCode::invalid_argument, "seams report: empty result");
  }
  if (images) {
    if (Status s = seams_report::write_images(config, result, dir); !s.ok()) return s;
  }
  if (Status s = seams_report::write_plots(result, dir); !s.ok()) return s;
  const experiments::SeamsReportOptions options{images};
  if (Status s = seams_report::write_text(dir + "/seams.md",
                                          experiments::to_markdown(config, result, options));
      !s.ok()) {
    return s;
  }
  json = experiments::to_json(config, result, options);
  return seams_report::write_text(dir + "/seams.json", json);
}

}  // namespace tessera::cli
