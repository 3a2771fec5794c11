// The seam experiment of Toth 2013 (Table 1 and Figure 5), shared by `tessera seams` and the
// demo report: every sampling method at every MSAA rate along a camera orbit, timed side by
// side, compared against the Mitchell-Netravali-downsampled supersampled Traverse reference.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tessera/faces.h"

namespace tessera::cli {

struct SeamsConfig {
  std::string scene = "figure1";  ///< "figure1" or an all-quad .obj.
  std::string ptex;               ///< Optional .ptx for the .obj (else procedural textures).
  std::string character;          ///< figure1: an all-quad .obj replacing the cube-sphere.
  int subdivide = 1;              ///< Linear subdivision steps applied to `character`.
  std::vector<int> msaa = {1, 2, 4, 8};
  int frames = 8;                 ///< Orbit frames (timed and, up to quality_frames, compared).
  int quality_frames = 0;         ///< Frames with a reference (0 = all).
  int width = 480, height = 540;  ///< The paper's image size.
  int reference_factor = 8;       ///< Reference at factor x factor the resolution.
  faces::Figure1Options figure1;
  int threads = 0;
  std::string out;  ///< Output folder.
  bool write_images = true;
};

/// Runs the experiment and writes DIR/seams.json, seams.md, cdf.csv, fig5_left.svg/.png,
/// fig5_right.svg/.png and images/. `summary` receives the JSON written. Progress goes to stderr
/// when `verbose`.
Status run_seams(const SeamsConfig& config, nlohmann::json& summary, bool verbose);

}  // namespace tessera::cli
