// Internal: the scene and textures of the seam experiment (built-in Figure-1 scene, or an .obj
// with its Ptex file or procedural textures).
#pragma once

#include <string>

#include "tessera/experiments/seams.h"

namespace tessera::experiments::detail {

struct SeamsContent {
  faces::FaceScene scene;
  faces::FaceTextureSet set;
  std::string description;  ///< One line for the report.
};

/// Loads or builds the content `config` names; the loader's error on a bad file.
Result<SeamsContent> load_seams_content(const SeamsConfig& config);

}  // namespace tessera::experiments::detail
