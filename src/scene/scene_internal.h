// Helpers shared by the scene loaders.
#pragma once

#include <string>

#include "tessera/scene.h"

namespace tessera::scene::detail {

/// Fills missing normals (area-weighted vertex normals) and UVs (zero), normalises normals, and
/// checks that every index is in range. `what` names the file for messages.
Status finish_mesh(Mesh& mesh, const std::string& what);

/// Folder part of a path ("" when none), with a trailing slash.
std::string folder_of(const std::string& path);

/// Reads and decodes an image file for a scene texture; on failure, a one-line error naming the
/// scene file and the texture.
Result<ImageRGBA8> load_texture_image(const std::string& scene_path, const std::string& image_path);

/// tinyobjloader's failure to parse `path` as one line: "PATH: cannot read OBJ: WHY" (its
/// message without trailing line breaks, the others as spaces; "parse error" when empty).
inline Status obj_parse_error(const std::string& path, std::string why) {
  while (!why.empty() && (why.back() == '\n' || why.back() == '\r')) why.pop_back();
  for (char& c : why) {
    if (c == '\n') c = ' ';
  }
  return Status::error(ErrorCode::corrupt_data,
                       path + ": cannot read OBJ: " + (why.empty() ? "parse error" : why));
}

}  // namespace tessera::scene::detail
