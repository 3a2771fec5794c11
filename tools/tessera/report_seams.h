// Reports of the seam experiment of Toth 2013 (Table 1 and Figure 5), shared by `tessera seams`
// and the demo report: the JSON summary, the Markdown tables, the CDF data and plots, and the
// frame-0 images of an `experiments::run_seams` result.
#pragma once

#include <string>

#include "tessera/experiments.h"

namespace tessera::cli {

/// Writes DIR/seams.json, seams.md (experiments::to_json / to_markdown), cdf.csv,
/// fig5_left.svg/.png, fig5_right.svg/.png and (with `write_images`, from the result's frame-0
/// images) images/ for `result`, the outcome of `config`. DIR/images must exist when
/// `write_images`. `json` receives the JSON written.
Status write_seams_report(const experiments::SeamsConfig& config,
                          const experiments::SeamsResult& result, const std::string& dir,
                          bool write_images, std::string& json);

}  // namespace tessera::cli
