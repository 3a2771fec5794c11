// Reports of the adaptive-supersampling experiment (Hollander et al. 2013), from an
// `experiments::run_aa` result: aa.json, aa.md (Table 1, Figures 6a, 7 and 8 analogues) and the
// images and heatmaps as PNG.
#pragma once

#include <string>

#include "tessera/experiments.h"

namespace tessera::cli {

/// Writes DIR/aa.json, DIR/aa.md (experiments::to_json / to_markdown) and the PNGs of every
/// rate into the existing folder DIR. `scene_label` names the scene in both reports ("builtin"
/// or the path). On success `markdown` and `json` (when not null) receive the text written.
Status write_aa_report(const experiments::AaConfig& config, const experiments::AaResult& result,
                       const std::string& scene_label, const std::string& dir,
                       std::string* markdown = nullptr, std::string* json = nullptr);

}  // namespace tessera::cli
