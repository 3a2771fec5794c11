// engine_aa_vk's scene (its own, generated in code): a floor, boxes and spheres as triangle
// vertices (position, normal, albedo, material id 0 floor / 1 box / 2 sphere), and a look-at
// camera (column-major matrices).
#pragma once

#include <array>
#include <vector>

namespace engine {

struct Vertex {
  float p[3], n[3], albedo[3], id;
};

std::vector<Vertex> make_scene();
/// View matrix from `eye` to `at` (y up) and its inverse.
void look_at(const float eye[3], const float at[3], float view[16], float inv[16]);

}  // namespace engine
