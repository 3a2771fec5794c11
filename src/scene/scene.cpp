// Scene helpers: bounds, loading by extension, camera parsing and orbits.
#include "tessera/scene.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <sstream>

namespace tessera::scene {

std::size_t Scene::triangle_count() const {
  std::size_t n = 0;
  for (const Mesh& m : meshes) n += m.triangle_count();
  return n;
}

void Scene::update_bounds() {
  constexpr float inf = std::numeric_limits<float>::infinity();
  bounds_min = {inf, inf, inf};
  bounds_max = {-inf, -inf, -inf};
  for (const Mesh& m : meshes) {
    for (const Vec3& p : m.positions) {
      bounds_min = {std::min(bounds_min.x, p.x), std::min(bounds_min.y, p.y),
                    std::min(bounds_min.z, p.z)};
      bounds_max = {std::max(bounds_max.x, p.x), std::max(bounds_max.y, p.y),
                    std::max(bounds_max.z, p.z)};
    }
  }
  if (bounds_min.x > bounds_max.x) bounds_min = bounds_max = {0, 0, 0};
}

Result<Scene> load_scene(const std::string& path, const LoadOptions& options) {
  std::string ext;
  const auto dot = path.find_last_of('.');
  if (dot != std::string::npos) ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".obj") return load_obj(path, options);
  if (ext == ".gltf" || ext == ".glb") return load_gltf(path, options);
  return Status::error(ErrorCode::unsupported,
                       path + ": unknown scene format (expected .obj, .gltf or .glb)");
}

Result<Camera> parse_camera(const std::string& text) {
  std::vector<float> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    try {
      std::size_t used = 0;
      const float f = std::stof(item, &used);
      if (used != item.size() || !std::isfinite(f)) throw std::invalid_argument(item);
      v.push_back(f);
    } catch (const std::exception&) {
      return Status::error(ErrorCode::invalid_argument,
                           "--camera: '" + item + "' is not a number in '" + text + "'");
    }
  }
  if (v.size() != 10) {
    return Status::error(ErrorCode::invalid_argument,
                         "--camera: expected 10 numbers eye(3),target(3),up(3),fov, got " +
                             std::to_string(v.size()));
  }
  Camera c;
  c.eye = {v[0], v[1], v[2]};
  c.target = {v[3], v[4], v[5]};
  c.up = {v[6], v[7], v[8]};
  c.fov_y_degrees = v[9];
  if (!(c.fov_y_degrees > 0.5f && c.fov_y_degrees < 179.5f)) {
    return Status::error(ErrorCode::invalid_argument,
                         "--camera: field of view must be in (0.5, 179.5) degrees");
  }
  if (length(c.target - c.eye) == 0.0f || length(cross(c.target - c.eye, c.up)) == 0.0f) {
    return Status::error(ErrorCode::invalid_argument,
                         "--camera: eye equals target, or up is parallel to the view direction");
  }
  return c;
}

Camera orbit_camera(const Scene& scene, int frame, int frames) {
  const Vec3 centre = (scene.bounds_min + scene.bounds_max) * 0.5f;
  const float half_diag = std::max(1e-3f, length(scene.bounds_max - scene.bounds_min) * 0.5f);
  const double angle = 2.0 * std::numbers::pi * double(frame) / double(std::max(1, frames));
  Camera c;
  c.target = centre;
  c.eye = {centre.x + 0.9f * half_diag * float(std::cos(angle)), centre.y + 0.3f * half_diag,
           centre.z + 0.9f * half_diag * float(std::sin(angle))};
  c.up = {0, 1, 0};
  c.fov_y_degrees = 60.0f;
  c.near_z = std::max(1e-3f, half_diag * 0.002f);
  c.far_z = half_diag * 4.0f;
  return c;
}

Result<Camera> camera_from_text(const Scene& scene, const std::string& camera,
                                const std::string& orbit) {
  const Camera fit = orbit_camera(scene, 0, 1);
  if (!camera.empty()) {
    Result<Camera> c = parse_camera(camera);
    if (!c) return c.status();
    c->near_z = fit.near_z;
    c->far_z = fit.far_z;
    return c;
  }
  if (!orbit.empty()) {
    int f = -1, n = 0;
    char tail = 0;
    if (std::sscanf(orbit.c_str(), "%d/%d%c", &f, &n, &tail) != 2 || n <= 0 || f < 0 || f >= n) {
      return Status::error(ErrorCode::invalid_argument,
                           "--orbit: expected FRAME/N with 0 <= FRAME < N, got '" + orbit + "'");
    }
    return orbit_camera(scene, f, n);
  }
  return fit;
}

}  // namespace tessera::scene
