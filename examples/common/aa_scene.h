// The example engines' scene, shared by examples/engine_aa (OpenGL) and examples/engine_aa_vk
// (Vulkan) so that the two twins render the same frame: a floor, boxes and spheres as triangle
// vertices (position, normal, albedo, material id 0 floor / 1 box / 2 sphere), generated in
// code, a look-at camera (column-major matrices), the six point lights of the per-frame shading
// block and the shading hook's GLSL that reads it (each backend declares the block's binding).
// Header-only, like engine_context.h.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace engine {

struct Vertex {
  float p[3], n[3], albedo[3], id;
};

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

// The engine's camera: look-at view (and its inverse), tan(fov_y / 2) and the aspect; the
// projection `proj` is each backend's (GL's depth range -1..1, Vulkan's 0..1).
struct Camera {
  float eye[3] = {3.2f, 2.2f, 4.2f};
  float tan_half = 0, aspect = 1;
  float view[16], inv_view[16], proj[16] = {};
};

inline Camera make_camera(int w, int h) {
  Camera cam;
  const float at[3] = {0.0f, 0.4f, 0.0f};
  const float fov = 0.8f;
  cam.tan_half = std::tan(fov / 2);
  cam.aspect = float(w) / float(h);
  look_at(cam.eye, at, cam.view, cam.inv_view);
  return cam;
}

// The engine's per-frame shading data (std140, the hook's EngineFrame block): camera, grid
// size (gw x gh, the enlarged G-buffer), six point lights.
struct FrameBlock {
  float inv_view[16], eye_tan[4], grid_aspect[4], light_pos[6][4], light_col[6][4];
};

inline FrameBlock frame_block(const Camera& cam, int gw, int gh) {
  FrameBlock frame{};
  std::copy(cam.inv_view, cam.inv_view + 16, frame.inv_view);
  std::copy(cam.eye, cam.eye + 3, frame.eye_tan);
  frame.eye_tan[3] = cam.tan_half;
  frame.grid_aspect[0] = float(gw), frame.grid_aspect[1] = float(gh);
  frame.grid_aspect[2] = cam.aspect;
  const float lights[6][8] = {{2.5f, 3.0f, 2.0f, 0, 1.0f, 0.9f, 0.8f, 14.0f},
                              {-3.0f, 2.5f, 1.5f, 0, 0.5f, 0.6f, 1.0f, 10.0f},
                              {0.5f, 1.2f, 2.5f, 0, 1.0f, 0.5f, 0.3f, 4.0f},
                              {-1.0f, 4.0f, -2.5f, 0, 0.9f, 0.9f, 1.0f, 12.0f},
                              {3.0f, 0.6f, -1.0f, 0, 0.3f, 1.0f, 0.4f, 3.0f},
                              {0.0f, 6.0f, 0.0f, 0, 1.0f, 1.0f, 1.0f, 16.0f}};
  for (int i = 0; i < 6; ++i)
    for (int c = 0; c < 4; ++c) {
      frame.light_pos[i][c] = lights[i][c];
      frame.light_col[i][c] = lights[i][4 + c];
    }
  return frame;
}

// The engine's shading, handed to tessera as the hook: its own frame block and albedo texture
// (RT1) at the bindings its backend gives (`frame_layout`, `albedo_layout`: the layout
// qualifiers), positions from the linear depth, Blinn-Phong with a sharp specular lobe and a
// procedural checker floor.
inline std::string shading_hook(const std::string& frame_layout, const std::string& albedo_layout) {
  return "\nlayout(" + frame_layout + R"() uniform EngineFrame {
  mat4 inv_view;      // camera to world
  vec4 eye_tan;       // eye xyz, tan(fov_y / 2)
  vec4 grid_aspect;   // grid width, height, aspect
  vec4 light_pos[6];  // xyz, radius
  vec4 light_col[6];  // rgb intensity
};
layout()" +
         albedo_layout + R"() uniform sampler2D engine_albedo;  // RT1

vec3 engine_position(ivec2 g, float depth) {
  float nx = 2.0 * (float(g.x) + 0.5) / grid_aspect.x - 1.0;
  float ny = 1.0 - 2.0 * (float(g.y) + 0.5) / grid_aspect.y;
  float t = eye_tan.w;
  return (inv_view * vec4(nx * t * grid_aspect.z * depth, ny * t * depth, -depth, 1.0)).xyz;
}

vec4 tessera_shade_sample(ivec2 g, float footprint) {
  int id = tessera_adaptive_id(g);  // the component's accessor of the layout's id channel
  if (id < 0) return vec4(0.25, 0.35, 0.55, 1.0) * (1.0 - float(g.y) / grid_aspect.y * 0.6);
  vec3 n = normalize(tessera_adaptive_normal(g));
  vec3 p = engine_position(g, tessera_adaptive_depth(g));
  vec3 albedo = texelFetch(engine_albedo, g, 0).rgb;
  float shininess = id == 2 ? 600.0 : (id == 1 ? 24.0 : 120.0);
  float spec = id == 2 ? 6.0 : (id == 1 ? 0.3 : 1.5);
  if (id == 0) {  // checker floor: a texture term that aliases in the distance
    vec2 c = floor(p.xz * 4.0);
    albedo *= mod(c.x + c.y, 2.0) < 1.0 ? 1.0 : 0.15;
  }
  vec3 v = normalize(eye_tan.xyz - p);
  vec3 colour = 0.04 * albedo;
  for (int i = 0; i < 6; ++i) {
    vec3 to = light_pos[i].xyz - p;
    float d2 = dot(to, to);
    vec3 l = to * inversesqrt(d2);
    float ndl = max(dot(n, l), 0.0);
    if (ndl <= 0.0) continue;
    float fall = light_col[i].w / d2;
    float ndh = max(dot(n, normalize(l + v)), 0.0);
    colour += light_col[i].rgb * fall * ndl * (albedo + spec * pow(ndh, shininess));
  }
  return vec4(colour, 1.0);
}
)";
}

}  // namespace engine
