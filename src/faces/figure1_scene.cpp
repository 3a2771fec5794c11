// Scenes for the seam experiment: the Figure-1-like ground plane + character, per-face
// resolutions from edge lengths, and textures baked from one continuous 3D function.
#include <algorithm>
#include <cmath>
#include <map>

#include "tessera/faces.h"

namespace tessera::faces {

namespace {
float hash3(int x, int y, int z) {
  std::uint32_t h =
      std::uint32_t(x) * 73856093u ^ std::uint32_t(y) * 19349663u ^ std::uint32_t(z) * 83492791u;
  h ^= h >> 13;
  h *= 0x5bd1e995u;
  h ^= h >> 15;
  return float(h & 0xFFFFFF) / float(0xFFFFFF);
}

float smooth(float t) { return t * t * (3 - 2 * t); }

/// Trilinear value noise in [0, 1] with smoothstep interpolation (C1 continuous).
float value_noise(float x, float y, float z) {
  const float fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
  const int ix = int(fx), iy = int(fy), iz = int(fz);
  const float tx = smooth(x - fx), ty = smooth(y - fy), tz = smooth(z - fz);
  float r = 0;
  for (int c = 0; c < 8; ++c) {
    const int dx = c & 1, dy = (c >> 1) & 1, dz = (c >> 2) & 1;
    const float w = (dx ? tx : 1 - tx) * (dy ? ty : 1 - ty) * (dz ? tz : 1 - tz);
    r += w * hash3(ix + dx, iy + dy, iz + dz);
  }
  return r;
}

Vec3 face_normal(const QuadMesh& m, int f) {
  const auto& q = m.quads[std::size_t(f)];
  const Vec3 d0 = m.positions[std::size_t(q[2])] - m.positions[std::size_t(q[0])];
  const Vec3 d1 = m.positions[std::size_t(q[3])] - m.positions[std::size_t(q[1])];
  return cross(d0, d1);
}

/// Reverses quads whose normal points against `outward(centre)`.
template <class F>
void orient(QuadMesh& m, int first, F outward) {
  for (int f = first; f < m.face_count(); ++f) {
    const Vec3 c = m.point(f, {0.5f, 0.5f});
    if (dot(face_normal(m, f), outward(c)) < 0) {
      auto& q = m.quads[std::size_t(f)];
      std::swap(q[1], q[3]);
    }
  }
}
}  // namespace

std::array<float, 3> procedural_colour(const Vec3& p, float scale) {
  const float s = 3.0f * scale;
  const float n1 = value_noise(p.x * s, p.y * s, p.z * s);
  const float n2 = value_noise(p.x * s * 2.7f + 17, p.y * s * 2.7f, p.z * s * 2.7f);
  const float n = 0.65f * n1 + 0.35f * n2;
  // Fine detail: thin bands and a small-scale noise octave (periods of a few texels on the
  // Figure-1 faces), so filtering across face edges matters.
  const float stripe =
      0.5f + 0.5f * std::sin(24.0f * scale * (p.x + 0.6f * p.z + 0.3f * p.y) + 9.0f * n);
  const float fine = value_noise(p.x * s * 8.0f + 5, p.y * s * 8.0f, p.z * s * 8.0f - 3);
  const float t = smooth(std::clamp((stripe - 0.3f) * 2.5f, 0.0f, 1.0f));
  const std::array<float, 3> a = {0.80f, 0.35f, 0.06f};
  const std::array<float, 3> b = {0.06f, 0.30f, 0.60f};
  const float bright = (0.45f + 0.7f * n) * (0.6f + 0.5f * fine);
  std::array<float, 3> c;
  for (int k = 0; k < 3; ++k) {
    c[std::size_t(k)] =
        std::clamp((a[std::size_t(k)] * t + b[std::size_t(k)] * (1 - t)) * bright, 0.0f, 1.0f);
  }
  return c;
}

FaceScene figure1_scene(const Figure1Options& o) {
  FaceScene s;
  s.name = "figure1";
  QuadMesh& m = s.mesh;
  // Ground: o.ground x o.ground quads over [-4, 4]^2 at y = 0, facing up.
  const int g = std::max(1, o.ground);
  const float half = 4.0f;
  for (int j = 0; j <= g; ++j) {
    for (int i = 0; i <= g; ++i) {
      m.positions.push_back(
          {-half + 2 * half * float(i) / float(g), 0.0f, -half + 2 * half * float(j) / float(g)});
    }
  }
  for (int j = 0; j < g; ++j) {
    for (int i = 0; i < g; ++i) {
      const int a = j * (g + 1) + i;
      m.quads.push_back({a, a + g + 1, a + g + 2, a + 1});
    }
  }
  orient(m, 0, [](const Vec3&) { return Vec3{0, 1, 0}; });
  s.ground_faces = m.face_count();
  // Character: a cube-sphere of 6 n^2 quads (8 valence-3 corners), deformed into a blob body.
  const int n = std::max(1, o.character);
  const int base = int(m.positions.size());
  std::map<std::array<int, 3>, int> lattice;
  auto vertex = [&](int x, int y, int z) {
    const std::array<int, 3> key = {x, y, z};
    auto it = lattice.find(key);
    if (it != lattice.end()) return it->second;
    Vec3 p = normalize(Vec3{2.0f * float(x) / float(n) - 1, 2.0f * float(y) / float(n) - 1,
                            2.0f * float(z) / float(n) - 1});
    const float bump = 1.0f + 0.18f * std::sin(3 * p.x + 1) * std::sin(2 * p.y + 2) +
                       0.1f * std::sin(5 * p.z + 4 * p.y);
    p = p * bump;
    const Vec3 w{0.75f * p.x, 1.0f + 1.0f * p.y, 0.75f * p.z};
    const int id = int(m.positions.size());
    m.positions.push_back(w);
    lattice.emplace(key, id);
    return id;
  };
  const int first_char = m.face_count();
  if (!o.character_mesh.quads.empty()) {
    // A user mesh: scaled to 2 units tall, standing at the centre of the ground.
    const QuadMesh& cm = o.character_mesh;
    Vec3 lo{1e30f, 1e30f, 1e30f}, hi{-1e30f, -1e30f, -1e30f};
    for (const Vec3& p : cm.positions) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    const float sc = 2.0f / std::max(hi.y - lo.y, 1e-6f);
    for (const Vec3& p : cm.positions) {
      m.positions.push_back({(p.x - 0.5f * (lo.x + hi.x)) * sc, (p.y - lo.y) * sc,
                             (p.z - 0.5f * (lo.z + hi.z)) * sc});
    }
    for (const std::array<int, 4>& q : cm.quads) {
      m.quads.push_back({q[0] + base, q[1] + base, q[2] + base, q[3] + base});
    }
    randomise_orientation(m, o.seed);
    assign_resolutions(s, o.texels_per_unit, o.min_log2, o.max_log2);
    return s;
  }
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side <= 1; ++side) {
      for (int a = 0; a < n; ++a) {
        for (int b = 0; b < n; ++b) {
          int q[4];
          const int ca[4] = {a, a + 1, a + 1, a}, cb[4] = {b, b, b + 1, b + 1};
          for (int k = 0; k < 4; ++k) {
            int c[3];
            c[axis] = side * n;
            c[(axis + 1) % 3] = ca[k];
            c[(axis + 2) % 3] = cb[k];
            q[k] = vertex(c[0], c[1], c[2]);
          }
          m.quads.push_back({q[0], q[1], q[2], q[3]});
        }
      }
    }
  }
  const Vec3 centre{0, 1.0f, 0};
  orient(m, first_char, [&](const Vec3& c) { return c - centre; });
  randomise_orientation(m, o.seed);
  assign_resolutions(s, o.texels_per_unit, o.min_log2, o.max_log2);
  return s;
}

void assign_resolutions(FaceScene& s, float texels_per_unit, int min_log2, int max_log2) {
  const QuadMesh& m = s.mesh;
  s.ulog2.assign(std::size_t(m.face_count()), min_log2);
  s.vlog2.assign(std::size_t(m.face_count()), min_log2);
  auto res = [&](float len) {
    const float t = std::max(len * texels_per_unit, 1e-6f);
    return std::clamp(int(std::lround(std::log2(t))), min_log2, max_log2);
  };
  for (int f = 0; f < m.face_count(); ++f) {
    const auto& q = m.quads[std::size_t(f)];
    auto p = [&](int k) { return m.positions[std::size_t(q[std::size_t(k)])]; };
    // u runs along edges 0 and 2, v along edges 1 and 3.
    const float lu = 0.5f * (length(p(1) - p(0)) + length(p(2) - p(3)));
    const float lv = 0.5f * (length(p(3) - p(0)) + length(p(2) - p(1)));
    s.ulog2[std::size_t(f)] = res(lu);
    s.vlog2[std::size_t(f)] = res(lv);
  }
}

std::vector<ImageRGBAF> bake_faces(const FaceScene& s, const BakeOptions& options) {
  std::vector<ImageRGBAF> images(std::size_t(s.mesh.face_count()));
  parallel_for(0, s.mesh.face_count(), 16,
               [&](std::int64_t b, std::int64_t e) {
                 for (std::int64_t f = b; f < e; ++f) {
                   const int w = 1 << s.ulog2[std::size_t(f)], h = 1 << s.vlog2[std::size_t(f)];
                   ImageRGBAF img(w, h);
                   for (int y = 0; y < h; ++y) {
                     for (int x = 0; x < w; ++x) {
                       const Vec3 p = s.mesh.point(
                           int(f), {(float(x) + 0.5f) / float(w), (float(y) + 0.5f) / float(h)});
                       const std::array<float, 3> c = procedural_colour(p, options.scale);
                       float* px = img.at(x, y);
                       px[0] = c[0];
                       px[1] = c[1];
                       px[2] = c[2];
                       px[3] = 1.0f;
                     }
                   }
                   images[std::size_t(f)] = std::move(img);
                 }
               },
               {options.threads});
  return images;
}

scene::Camera face_orbit_camera(const FaceScene& s, int frame, int frames) {
  Vec3 lo{1e30f, 1e30f, 1e30f}, hi{-1e30f, -1e30f, -1e30f};
  // Look at the non-ground part (the character) when there is one.
  const int first = s.ground_faces < s.mesh.face_count() ? s.ground_faces : 0;
  for (int f = first; f < s.mesh.face_count(); ++f) {
    for (int k = 0; k < 4; ++k) {
      const Vec3& p = s.mesh.positions[std::size_t(s.mesh.quads[std::size_t(f)][std::size_t(k)])];
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
  }
  const Vec3 centre = (lo + hi) * 0.5f;
  const float r = std::max(0.5f * length(hi - lo), 1e-3f);
  const float angle = 6.2831853f * float(frame) / float(std::max(frames, 1));
  scene::Camera c;
  c.target = centre;
  // Far enough to see the whole character and the ground at grazing angles (where 16x
  // anisotropic footprints are long and cross many face edges).
  const float dist = s.ground_faces > 0 ? 2.3f : 1.7f;
  c.eye = {centre.x + dist * r * std::cos(angle), centre.y + 0.35f * r,
           centre.z + dist * r * std::sin(angle)};
  if (s.ground_faces > 0) c.target = {centre.x, centre.y - 0.25f * r, centre.z};
  c.fov_y_degrees = 50.0f;
  c.near_z = 0.02f * r;
  c.far_z = 20.0f * r;
  return c;
}

}  // namespace tessera::faces
