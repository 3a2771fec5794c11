#include <cmath>

#include "scene_internal.h"
#include "tessera/io.h"

namespace tessera::scene::detail {

Status finish_mesh(Mesh& mesh, const std::string& what) {
  const std::size_t n = mesh.positions.size();
  if (mesh.indices.size() % 3 != 0) {
    return Status::error(ErrorCode::corrupt_data, what + ": index count is not a multiple of 3");
  }
  for (std::uint32_t i : mesh.indices) {
    if (i >= n) {
      return Status::error(ErrorCode::corrupt_data, what + ": vertex index " + std::to_string(i) +
                                                        " out of range (" + std::to_string(n) +
                                                        " vertices) in mesh '" + mesh.name + "'");
    }
  }
  for (const Vec3& p : mesh.positions) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      return Status::error(ErrorCode::corrupt_data,
                           what + ": non-finite vertex position in mesh '" + mesh.name + "'");
    }
  }
  if (mesh.uvs.size() != n) mesh.uvs.assign(n, Vec2{});
  if (mesh.normals.size() != n) {
    mesh.normals.assign(n, Vec3{});
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
      const Vec3 fn = cross(mesh.positions[b] - mesh.positions[a],
                            mesh.positions[c] - mesh.positions[a]);  // length = 2 * area
      mesh.normals[a] = mesh.normals[a] + fn;
      mesh.normals[b] = mesh.normals[b] + fn;
      mesh.normals[c] = mesh.normals[c] + fn;
    }
  }
  for (Vec3& v : mesh.normals) {
    v = normalize(v);
    if (!std::isfinite(v.x) || length(v) == 0.0f) v = {0, 1, 0};
  }
  return Status::success();
}

std::string folder_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

Result<ImageRGBA8> load_texture_image(const std::string& scene_path,
                                      const std::string& image_path) {
  Result<ImageRGBA8> img = io::read_image(image_path);
  if (!img) {
    return Status::error(img.status().code, scene_path + ": texture: " + img.status().message);
  }
  return img;
}

}  // namespace tessera::scene::detail
