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

}  // namespace tessera::scene::detail
