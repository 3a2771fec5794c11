// Internal to the report of `tessera seams` (report_seams.h): what its two halves share
// (report_seams.cpp: the library's JSON and Markdown written; report_seams_plots.cpp: cdf.csv,
// the Figure-5 plots and the frame-0 images).
#pragma once

#include <string>

#include "tessera/experiments.h"

namespace tessera::cli::seams_report {

inline constexpr double kStep = experiments::kSeamsCdfStep;
inline constexpr int kBins = experiments::kSeamsCdfBins;

/// "4x" for MSAA rate 4: the key of a rate in the JSON, CSV columns and file names.
inline std::string rate_key(int r) { return experiments::seams_rate_key(r); }

/// Writes `text` to `path` atomically.
Status write_text(const std::string& path, const std::string& text);

/// Frame 0 of every method and rate, the reference, and a zoom on the worst seam
/// (experiments::seams_zoom_window) into DIR/images (which must exist).
Status write_images(const experiments::SeamsConfig& c, const experiments::SeamsResult& res,
                    const std::string& dir);

/// DIR/cdf.csv and the Figure-5 plots (fig5_left/right.svg/.png, fig5_<rate>.svg).
Status write_plots(const experiments::SeamsResult& res, const std::string& dir);

}  // namespace tessera::cli::seams_report
