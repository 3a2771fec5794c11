// The example engines' scene, shared by examples/engine_aa (OpenGL) and examples/engine_aa_vk
// (Vulkan) so that the two twins render the same frame: a floor, boxes and spheres as triangle
// vertices (position, normal, albedo, material id 0 floor / 1 box / 2 sphere), generated in
// code, and a look-at camera (column-major matrices). Header-only, like engine_context.h.
#pragma once

#include <array>
#include <cmath>
#include <utility>
#include <vector>

namespace engine {

struct Vertex {
  float p[3], n[3], albedo[3], id;
};

using F3 = std::array<float, 3>;

using F3 = std::array<float, 3>;

inline void add_box(std::vector<Vertex>& v, const F3& c, const F3& s, const F3& col, float id) {
  static const int faces[6][3] = {{0, 1, 2}, {0, 1, 2}, {1, 2, 0}, {1, 2, 0}, {2, 0, 1}, {2, 0, 1}};
  for (int f = 0; f < 6; ++f) {
    const int a = faces[f][0], b = faces[f][1], nrm = faces[f][2];
    const float sign = (f % 2 == 0) ? 1.0f : -1.0f;
    float corner[4][3];
    const float uv[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (int k = 0; k < 4; ++k) {
      corner[k][a] = c[a] + uv[k][0] * s[a];
      corner[k][b] = c[b] + uv[k][1] * s[b];
      corner[k][nrm] = c[nrm] + sign * s[nrm];
    }
    float n[3] = {0, 0, 0};
    n[nrm] = sign;
    for (int k : {0, 1, 2, 0, 2, 3}) {
      v.push_back({{corner[k][0], corner[k][1], corner[k][2]},
                   {n[0], n[1], n[2]},
                   {col[0], col[1], col[2]},
                   id});
    }
  }
}

inline void add_sphere(std::vector<Vertex>& v, const F3& c, float r, const F3& col, float id) {
  const int rings = 24, segments = 48;
  const float pi = 3.14159265f;
  auto vert = [&](int i, int j) {
    const float th = pi * float(i) / rings, ph = 2 * pi * float(j) / segments;
    const float n[3] = {std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph)};
    return Vertex{{c[0] + r * n[0], c[1] + r * n[1], c[2] + r * n[2]},
                  {n[0], n[1], n[2]},
                  {col[0], col[1], col[2]},
                  id};
  };
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      for (const auto& [a, b] :
           {std::pair{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j}, {i + 1, j + 1}, {i, j + 1}}) {
        v.push_back(vert(a, b));
      }
    }
  }
}

inline std::vector<Vertex> make_scene() {
  std::vector<Vertex> v;
  const F3 grey = {0.8f, 0.8f, 0.8f};
  add_box(v, F3{0, -0.05f, 0}, F3{8, 0.05f, 8}, grey, 0);  // floor
  const F3 red = {0.8f, 0.15f, 0.1f}, blue = {0.1f, 0.25f, 0.8f};
  const F3 gold = {0.9f, 0.7f, 0.2f}, white = {0.9f, 0.9f, 0.9f};
  add_box(v, F3{-1.6f, 0.5f, -0.8f}, F3{0.5f, 0.5f, 0.5f}, red, 1);
  add_box(v, F3{1.5f, 0.9f, -1.4f}, F3{0.35f, 0.9f, 0.35f}, blue, 1);
  add_box(v, F3{0.3f, 0.15f, 1.3f}, F3{1.2f, 0.15f, 0.2f}, white, 1);
  add_sphere(v, F3{0.0f, 0.7f, -0.2f}, 0.7f, gold, 2);
  add_sphere(v, F3{-0.9f, 0.35f, 1.0f}, 0.35f, white, 2);
  add_sphere(v, F3{1.3f, 0.45f, 0.5f}, 0.45f, red, 2);
  return v;
}

inline void look_at(const float eye[3], const float at[3], float view[16], float inv[16]) {
  float f[3] = {at[0] - eye[0], at[1] - eye[1], at[2] - eye[2]};
  float fl = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
  for (float& x : f) x /= fl;
  float s[3] = {f[1] * 0 - f[2] * 1, f[2] * 0 - f[0] * 0, f[0] * 1 - f[1] * 0};  // f x up
  float sl = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
  for (float& x : s) x /= sl;
  const float u[3] = {s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2],
                      s[0] * f[1] - s[1] * f[0]};
  // Column-major: rows of the rotation are s, u, -f.
  const float r[3][3] = {{s[0], s[1], s[2]}, {u[0], u[1], u[2]}, {-f[0], -f[1], -f[2]}};
  for (int c = 0; c < 4; ++c)
    for (int k = 0; k < 4; ++k) view[c * 4 + k] = inv[c * 4 + k] = (c == k) ? 1.0f : 0.0f;
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) {
      view[col * 4 + row] = r[row][col];
      inv[row * 4 + col] = r[row][col];  // transpose
    }
    view[12 + row] = -(r[row][0] * eye[0] + r[row][1] * eye[1] + r[row][2] * eye[2]);
    inv[12 + row] = eye[row];
  }
}

}  // namespace engine
