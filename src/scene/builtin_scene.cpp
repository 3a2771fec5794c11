// The built-in procedural scene used by the demo and the tests: hard silhouettes, thin
// geometry and high-frequency textures, all generated in code.
#include <cmath>
#include <numbers>

#include "scene_internal.h"
#include "tessera/procedural.h"

namespace tessera::scene {

namespace {

void add_quad_grid(Mesh& m, Vec3 origin, Vec3 du, Vec3 dv, int nu, int nv, float uv_scale) {
  const std::uint32_t base = std::uint32_t(m.positions.size());
  const Vec3 n = normalize(cross(dv, du));
  for (int j = 0; j <= nv; ++j) {
    for (int i = 0; i <= nu; ++i) {
      const float s = float(i) / float(nu), t = float(j) / float(nv);
      m.positions.push_back(origin + du * s + dv * t);
      m.normals.push_back(n);
      m.uvs.push_back({s * uv_scale, t * uv_scale});
    }
  }
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      const std::uint32_t a = base + std::uint32_t(j * (nu + 1) + i), b = a + 1,
                          c = a + std::uint32_t(nu + 1), d = c + 1;
      m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
    }
  }
}

/// An axis-aligned box rotated by `angle` about y, centred at `c` with half extents `h`.
Mesh make_box(const std::string& name, Vec3 c, Vec3 h, float angle, int material) {
  Mesh m;
  m.name = name;
  m.material = material;
  const Vec3 corner[6][3] = {
      {{-1, -1, 1}, {2, 0, 0}, {0, 2, 0}}, {{1, -1, -1}, {-2, 0, 0}, {0, 2, 0}},
      {{1, -1, 1}, {0, 0, -2}, {0, 2, 0}}, {{-1, -1, -1}, {0, 0, 2}, {0, 2, 0}},
      {{-1, 1, 1}, {2, 0, 0}, {0, 0, -2}}, {{-1, -1, -1}, {2, 0, 0}, {0, 0, 2}}};
  for (const auto& f : corner) {
    auto scale = [&](Vec3 v) { return Vec3{v.x * h.x, v.y * h.y, v.z * h.z}; };
    add_quad_grid(m, scale(f[0]), scale(f[1]), scale(f[2]), 2, 2, 1.0f);
  }
  const Mat4 xf = translation(c) * rotation_quat(0, std::sin(angle / 2), 0, std::cos(angle / 2));
  const Mat4 nxf = transpose(inverse(xf));
  for (Vec3& p : m.positions) p = xf.transform_point(p);
  for (Vec3& n : m.normals) n = normalize(nxf.transform_vector(n));
  return m;
}

Mesh make_sphere(Vec3 c, float r, int slices, int stacks, int material) {
  Mesh m;
  m.name = "sphere";
  m.material = material;
  for (int j = 0; j <= stacks; ++j) {
    const float v = float(j) / float(stacks), phi = v * float(std::numbers::pi);
    for (int i = 0; i <= slices; ++i) {
      const float u = float(i) / float(slices), th = u * 2.0f * float(std::numbers::pi);
      const Vec3 n{std::sin(phi) * std::cos(th), std::cos(phi), std::sin(phi) * std::sin(th)};
      m.positions.push_back(c + n * r);
      m.normals.push_back(n);
      m.uvs.push_back({u * 4.0f, v * 2.0f});
    }
  }
  for (int j = 0; j < stacks; ++j) {
    for (int i = 0; i < slices; ++i) {
      const std::uint32_t a = std::uint32_t(j * (slices + 1) + i), b = a + 1,
                          cc = a + std::uint32_t(slices + 1), d = cc + 1;
      m.indices.insert(m.indices.end(), {a, b, cc, b, d, cc});
    }
  }
  return m;
}

}  // namespace

Scene builtin_scene() {
  Scene s;
  const Procedural kinds[3] = {Procedural::bricks, Procedural::text, Procedural::noise};
  for (int i = 0; i < 3; ++i) {
    s.textures.push_back({procedural_name(kinds[i]), make_procedural(kinds[i], 256, 256, 3), true});
    Material m;
    m.name = procedural_name(kinds[i]);
    m.base_color_texture = i;
    s.materials.push_back(m);
  }
  Material plain;
  plain.name = "white";
  s.materials.push_back(plain);

  Mesh ground;
  ground.name = "ground";
  ground.material = 0;
  add_quad_grid(ground, {-10, 0, 10}, {20, 0, 0}, {0, 0, -20}, 16, 16, 12.0f);
  s.meshes.push_back(std::move(ground));
  s.meshes.push_back(make_box("box-a", {-3, 1.5f, -1}, {1.5f, 1.5f, 1.5f}, 0.5f, 1));
  s.meshes.push_back(make_box("box-b", {3.5f, 1, 1}, {1, 1, 2}, -0.3f, 1));
  s.meshes.push_back(make_sphere({0.5f, 2, -4}, 2.0f, 48, 24, 2));
  // Thin poles: sub-pixel wide at a distance, the classic aliasing case.
  for (int i = 0; i < 6; ++i) {
    const float x = -7.5f + 3.0f * float(i);
    s.meshes.push_back(make_box("pole", {x, 2.5f, 5.0f}, {0.04f, 2.5f, 0.04f}, 0.2f * float(i), 3));
  }
  for (int i = 0; i < 4; ++i) {
    PointLight l;
    const float a = float(i) * 0.5f * float(std::numbers::pi) + 0.4f;
    l.position = {6.0f * std::cos(a), 4.0f + float(i), 6.0f * std::sin(a)};
    l.color[0] = i == 1 ? 0.6f : 1.0f;
    l.color[2] = i == 3 ? 0.6f : 1.0f;
    l.intensity = 40.0f;
    s.lights.push_back(l);
  }
  s.update_bounds();
  return s;
}

}  // namespace tessera::scene
