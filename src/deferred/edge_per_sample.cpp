// The engine baseline on the CPU: per-pixel classification "do the window's samples differ?"
// (Lauritzen 2010: depth against the derivatives of sample 0's plane, and a normal test), then
// one sample for simple pixels and all m^2 for complex ones. Same formulas as
// share/tessera/glsl/edge_classify.glsl and deferred_passes.comp (TESSERA_EDGE).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "deferred_internal.h"

namespace tessera::deferred {

namespace {

bool is_background(const float* s) { return std::lround(s[kChMaterial]) < 0; }

Vec3 rotate(const Mat4& m, const Vec3& v) {
  return {m.m[0][0] * v.x + m.m[1][0] * v.y + m.m[2][0] * v.z,
          m.m[0][1] * v.x + m.m[1][1] * v.y + m.m[2][1] * v.z,
          m.m[0][2] * v.x + m.m[1][2] * v.y + m.m[2][2] * v.z};
}

bool complex_pixel(const GBuffer& gb, int x, int y, int first, const EdgePerSampleOptions& o) {
  const int m = gb.m, n = m * m;
  int background = 0;
  for (int q = 0; q < n; ++q) background += is_background(gb.sample(m * x + q % m, m * y + q / m));
  if (background == n) return false;
  if (background > 0) return true;
  const int g0x = m * x + first % m, g0y = m * y + first / m;
  const float* s0 = gb.sample(g0x, g0y);
  const float d0 = s0[kChDepth];
  const Vec3 n0 = normalize(Vec3{s0[kChNormal], s0[kChNormal + 1], s0[kChNormal + 2]});
  // Depth derivatives of the plane through sample 0 (see edge_classify.glsl).
  const float gw = float(gb.fb.grid_width()), gh = float(gb.fb.grid_height());
  const float t = gb.tan_half_fov_y, aspect = gb.aspect;
  const float nx = 2.0f * (float(g0x) + 0.5f) / gw - 1.0f;
  const float ny = 1.0f - 2.0f * (float(g0y) + 0.5f) / gh;
  const Vec3 ray = rotate(gb.inv_view, {nx * t * aspect, ny * t, -1.0f});
  const Vec3 ray_dx = rotate(gb.inv_view, {2.0f * t * aspect / gw, 0.0f, 0.0f});
  const Vec3 ray_dy = rotate(gb.inv_view, {0.0f, -2.0f * t / gh, 0.0f});
  const float nr = dot(n0, ray);
  float ddx = std::numeric_limits<float>::infinity(), ddy = ddx;
  if (std::fabs(nr) >= 1e-12f) {
    ddx = -d0 * dot(n0, ray_dx) / nr;
    ddy = -d0 * dot(n0, ray_dy) / nr;
  }
  const float tolerance = o.depth_slack * float(m) * (std::fabs(ddx) + std::fabs(ddy)) + 1e-4f * d0;
  for (int q = 0; q < n; ++q) {
    const int gx = m * x + q % m, gy = m * y + q / m;
    if (gx == g0x && gy == g0y) continue;
    const float* s = gb.sample(gx, gy);
    if (std::fabs(s[kChDepth] - d0) > tolerance) return true;
    const Vec3 ni = normalize(Vec3{s[kChNormal], s[kChNormal + 1], s[kChNormal + 2]});
    if (dot(ni, n0) < o.min_normal_dot) return true;
  }
  return false;
}

}  // namespace

std::vector<std::uint8_t> classify_edge_per_sample(const GBuffer& gb,
                                                   const EdgePerSampleOptions& options) {
  const int w = gb.width(), h = gb.height();
  std::vector<std::uint8_t> out(std::size_t(w) * std::size_t(h), 0);
  if (w <= 0 || h <= 0 || gb.m < 1) return out;
  const int first = sample_order(gb.m)[0];
  parallel_for(0, h, 1,
               [&](std::int64_t y0, std::int64_t y1) {
                 for (int y = int(y0); y < int(y1); ++y) {
                   for (int x = 0; x < w; ++x) {
                     out[std::size_t(y) * std::size_t(w) + std::size_t(x)] =
                         complex_pixel(gb, x, y, first, options) ? 1 : 0;
                   }
                 }
               },
               {options.threads});
  return out;
}

AdaptiveResult shade_edge_per_sample(const DeferredRenderer& renderer, const GBuffer& gb,
                                     const ShadingOptions& shading,
                                     const EdgePerSampleOptions& options) {
  using clock = std::chrono::steady_clock;
  const ShadeContext ctx(renderer, gb, shading);
  const int m = gb.m, n = m * m, w = gb.width(), h = gb.height();
  const std::span<const std::uint8_t> order = sample_order(m);
  AdaptiveResult res;
  res.image = ImageRGBAF(w, h);
  auto t0 = clock::now();
  EdgePerSampleOptions o = options;
  o.threads = shading.threads;
  const std::vector<std::uint8_t> complex = classify_edge_per_sample(gb, o);
  res.ms_metric = std::chrono::duration<double, std::milli>(clock::now() - t0).count();
  t0 = clock::now();
  res.samples.assign(complex.size(), 1);
  parallel_for(0, h, 1,
               [&](std::int64_t y0, std::int64_t y1) {
                 for (int y = int(y0); y < int(y1); ++y) {
                   for (int x = 0; x < w; ++x) {
                     const std::size_t i = std::size_t(y) * std::size_t(w) + std::size_t(x);
                     std::array<float, 3> c{0, 0, 0};
                     if (complex[i]) {
                       for (int p = 0; p < n; ++p) {
                         const int cell = order[std::size_t(p)];
                         const std::array<float, 3> s =
                             ctx.shade(m * x + cell % m, m * y + cell / m, 1.0f);
                         for (int k = 0; k < 3; ++k) c[std::size_t(k)] += s[std::size_t(k)];
                       }
                       for (float& v : c) v /= float(n);
                       res.samples[i] = std::uint8_t(n);
                     } else {
                       const int cell = order[0];
                       c = ctx.shade(m * x + cell % m, m * y + cell / m, float(m));
                     }
                     float* px = res.image.at(x, y);
                     px[0] = c[0];
                     px[1] = c[1];
                     px[2] = c[2];
                     px[3] = 1.0f;
                   }
                 }
               },
               {shading.threads});
  res.ms_rest = std::chrono::duration<double, std::milli>(clock::now() - t0).count();
  for (std::uint8_t s : res.samples) res.samples_shaded += s;
  return res;
}

}  // namespace tessera::deferred
