// Rasterisation kernels: pure functions for fixed-point edge functions with the top-left rule,
// bounding boxes, sample offsets, interpolation planes, perspective-correct interpolation,
// quad derivatives and centroid selection. Drivers (setup.cpp, tile.cpp) call these; nothing
// here touches a frame buffer or a thread.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "core/simd.h"
#include "raster/raster_internal.h"

namespace tessera::raster::detail {

// ---------------------------------------------------------------------------------------------
// Fixed point and edge functions
// ---------------------------------------------------------------------------------------------

/// Rounds a grid coordinate (pixels) to 1/256 pixel, half away from zero. The caller has
/// checked |v| is far below 2^40.
inline std::int64_t snap(double v) { return std::llround(v * double(kSubpixel)); }

/// Floor division by 256 (arithmetic shift; defined for negative values in C++20).
inline std::int64_t floor_pixel(std::int64_t v) { return v >> kSubpixelBits; }

/// Top-left rule (Direct3D) for the edge a -> b of a triangle wound so that the interior is on
/// the positive side of every edge with y pointing down (visually clockwise). A top edge is
/// horizontal and traversed to the right; a left edge goes up the screen.
inline bool is_top_left(std::int64_t dx, std::int64_t dy) { return dy < 0 || (dy == 0 && dx > 0); }

/// Edge function of a -> b: E(X, Y) = (Xb - Xa)(Y - Ya) - (Yb - Ya)(X - Xa) = a X + b Y + c,
/// positive on the interior side; samples exactly on a non-top-left edge are excluded by
/// subtracting 1 from c, so "inside" is simply E >= 0 for all three edges.
struct Edge {
  std::int64_t a, b, c;
};
inline Edge make_edge(std::int64_t xa, std::int64_t ya, std::int64_t xb, std::int64_t yb) {
  Edge e;
  e.a = ya - yb;
  e.b = xb - xa;
  e.c = -(e.a * xa + e.b * ya);
  if (!is_top_left(xb - xa, yb - ya)) e.c -= 1;
  return e;
}

/// Twice the signed area of the snapped triangle, in (1/256 px)^2; > 0 when visually clockwise
/// with y down (the orientation `make_edge` expects).
inline std::int64_t doubled_area(const std::int64_t x[3], const std::int64_t y[3]) {
  return (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
}

/// Inclusive range of pixels whose samples can lie in [lo, hi] (fixed point). Samples of pixel
/// p lie in [256 p, 256 p + 240] for every pattern (offsets -8..7 sixteenths from the centre).
inline void pixel_range(std::int64_t lo, std::int64_t hi, std::int64_t& p0, std::int64_t& p1) {
  p0 = floor_pixel(lo);  // smallest p with 256 p + 255 >= lo
  p1 = floor_pixel(hi);
}

/// Fixed-point position of sample `s` inside its pixel (relative to the pixel's top-left
/// corner): 128 + 16 * offset.
inline std::int64_t sample_fixed(int offset_sixteenths) {
  return kSubpixel / 2 + std::int64_t(offset_sixteenths) * (kSubpixel / 16);
}

/// Coverage mask of one pixel: bit s set when sample s is inside all three edges.
/// `e` holds the edge values at the pixel's top-left corner, `off[k][s]` the per-sample edge
/// increments.
inline std::uint32_t coverage_mask(const std::int64_t e[3], const std::int64_t* const off[3],
                                   int samples) {
  std::uint32_t mask = 0;
  for (int s = 0; s < samples; ++s) {
    const std::int64_t v = (e[0] + off[0][s]) | (e[1] + off[1][s]) | (e[2] + off[2][s]);
    mask |= std::uint32_t(v >= 0) << s;
  }
  return mask;
}

/// Coverage masks of the four pixels of a quad: `e0` holds the edge values at the top-left
/// pixel's corner, `sx` / `sy` the steps to the next pixel right / down, `off[k][s]` the
/// per-sample increments. Same results as `coverage_mask` per lane; with a SIMD backend two
/// 64-bit edge values are tested per instruction (sign bits gathered with simd::movemask).
inline void quad_coverage(const std::int64_t e0[3], const std::int64_t sx[3],
                          const std::int64_t sy[3], const std::int64_t* const off[3], int samples,
                          std::uint32_t mask[4]) {
#if TESSERA_SIMD_VECTOR
  using simd::vi64x2;
  if (samples == 1) {
    // Lanes (0, 1) and (2, 3) in one register each.
    vi64x2 top, bottom;
    for (int k = 0; k < 3; ++k) {
      const vi64x2 l01 = vi64x2(e0[k], e0[k] + sx[k]) + vi64x2(off[k][0]);
      top = top | l01;
      bottom = bottom | (l01 + vi64x2(sy[k]));
    }
    const int t = simd::movemask(top);
    const int b = simd::movemask(bottom);
    mask[0] = ~t & 1u;
    mask[1] = ~t >> 1 & 1u;
    mask[2] = ~b & 1u;
    mask[3] = ~b >> 1 & 1u;
    return;
  }
  if (samples % 2 == 0) {
    for (int lane = 0; lane < 4; ++lane) {
      vi64x2 e[3];
      for (int k = 0; k < 3; ++k) {
        e[k] = vi64x2(e0[k] + (lane & 1 ? sx[k] : 0) + (lane >> 1 ? sy[k] : 0));
      }
      std::uint32_t m = 0;
      for (int s = 0; s < samples; s += 2) {
        vi64x2 v = e[0] + simd::load_i64x2(off[0] + s);
        v = v | (e[1] + simd::load_i64x2(off[1] + s));
        v = v | (e[2] + simd::load_i64x2(off[2] + s));
        m |= std::uint32_t(~simd::movemask(v) & 3) << s;
      }
      mask[lane] = m;
    }
    return;
  }
#endif
  for (int lane = 0; lane < 4; ++lane) {
    std::int64_t e[3];
    for (int k = 0; k < 3; ++k) e[k] = e0[k] + (lane & 1 ? sx[k] : 0) + (lane >> 1 ? sy[k] : 0);
    mask[lane] = coverage_mask(e, off, samples);
  }
}

/// Largest |a|, |b| of a "narrow" triangle (edges shorter than 512 grid pixels on each axis),
/// whose coverage can be computed in 32-bit arithmetic: see `quad_coverage32`.
inline constexpr std::int64_t kNarrowEdgeLimit = std::int64_t{1} << 17;
/// Quad-corner edge values are clamped to +-2^30 before narrowing to 32 bits.
inline constexpr std::int64_t kNarrowClamp = std::int64_t{1} << 30;

/// 32-bit coverage of a quad of a narrow triangle: `e0` as in `quad_coverage`, `sx32` / `sy32`
/// the one-pixel steps and `off32[k][s]` the sample increments as int32 (all below 2^26 in
/// magnitude for a narrow triangle). Exact: a corner value is clamped to [-2^30, 2^30], and
/// adding at most 2^27 of steps and offsets neither overflows nor changes the sign of a value
/// that was clamped. Same masks as `quad_coverage`. `samples` is 1 or a multiple of 4.
inline void quad_coverage32(const std::int64_t e0[3], const std::int32_t sx32[3],
                            const std::int32_t sy32[3], const std::int32_t (*off32)[16],
                            int samples, std::uint32_t mask[4]) {
  std::int32_t c[3];
  for (int k = 0; k < 3; ++k) {
    c[k] = std::int32_t(std::clamp(e0[k], -kNarrowClamp, kNarrowClamp));
  }
#if TESSERA_SIMD_VECTOR
  using simd::vi32x4;
  if (samples == 1) {
    vi32x4 v;
    for (int k = 0; k < 3; ++k) {
      const vi32x4 lanes(0, sx32[k], sy32[k], sx32[k] + sy32[k]);
      v = v | (vi32x4(c[k] + off32[k][0]) + lanes);
    }
    const std::uint32_t in = ~std::uint32_t(simd::movemask(v));
    for (int lane = 0; lane < 4; ++lane) mask[lane] = in >> lane & 1u;
    return;
  }
  std::int32_t lanes[3][4];
  for (int k = 0; k < 3; ++k) {
    lanes[k][0] = c[k];
    lanes[k][1] = c[k] + sx32[k];
    lanes[k][2] = c[k] + sy32[k];
    lanes[k][3] = lanes[k][2] + sx32[k];
  }
  for (int lane = 0; lane < 4; ++lane) {
    const vi32x4 e[3] = {vi32x4(lanes[0][lane]), vi32x4(lanes[1][lane]), vi32x4(lanes[2][lane])};
    std::uint32_t m = 0;
    for (int s = 0; s < samples; s += 4) {
      vi32x4 v = e[0] + simd::load4(off32[0] + s);
      v = v | (e[1] + simd::load4(off32[1] + s));
      v = v | (e[2] + simd::load4(off32[2] + s));
      m |= (~std::uint32_t(simd::movemask(v)) & 15u) << s;
    }
    mask[lane] = m;
  }
#else
  for (int lane = 0; lane < 4; ++lane) {
    std::uint32_t m = 0;
    for (int s = 0; s < samples; ++s) {
      std::int32_t v = 0;
      for (int k = 0; k < 3; ++k) {
        v |= c[k] + (lane & 1 ? sx32[k] : 0) + (lane >> 1 ? sy32[k] : 0) + off32[k][s];
      }
      m |= std::uint32_t(v >= 0) << s;
    }
    mask[lane] = m;
  }
#endif
}

/// Block classification against one edge over the fixed-point rectangle [x0, x1] x [y0, y1]:
/// -1 no point inside (reject), 1 every point inside (accept), 0 partial.
inline int classify_block(const Edge& e, std::int64_t x0, std::int64_t y0, std::int64_t x1,
                          std::int64_t y1) {
  const std::int64_t hi = e.c + e.a * (e.a > 0 ? x1 : x0) + e.b * (e.b > 0 ? y1 : y0);
  if (hi < 0) return -1;
  const std::int64_t lo = e.c + e.a * (e.a > 0 ? x0 : x1) + e.b * (e.b > 0 ? y0 : y1);
  return lo >= 0 ? 1 : 0;
}

// ---------------------------------------------------------------------------------------------
// Interpolation
// ---------------------------------------------------------------------------------------------

/// Screen-space geometry of a snapped triangle for plane set-up (double precision, pixels).
struct PlaneBasis {
  double px0, py0;  ///< Vertex 0.
  double e1x, e1y;  ///< Vertex 1 - vertex 0.
  double e2x, e2y;  ///< Vertex 2 - vertex 0.
  double inv_area;  ///< 1 / (e1 x e2).
  double ax, ay;    ///< Anchor (where the plane constant is evaluated).
};

/// Plane (value at anchor, d/dx, d/dy) of a quantity that is linear in screen space and takes
/// q0, q1, q2 at the three vertices.
inline void make_plane(const PlaneBasis& g, double q0, double q1, double q2, float out[3]) {
  const double d1 = q1 - q0, d2 = q2 - q0;
  const double ddx = (d1 * g.e2y - d2 * g.e1y) * g.inv_area;
  const double ddy = (d2 * g.e1x - d1 * g.e2x) * g.inv_area;
  out[0] = float(q0 + ddx * (g.ax - g.px0) + ddy * (g.ay - g.py0));
  out[1] = float(ddx);
  out[2] = float(ddy);
}

/// Evaluates a plane at grid position (x, y), given as offsets from the anchor.
inline float eval_plane(const float p[3], float dx, float dy) {
  return p[0] + p[1] * dx + p[2] * dy;
}

/// Varying count rounded up to a multiple of 4: the stored and interpolated width, so the
/// fixed-size loops below vectorise; the padding holds zeros.
inline constexpr int padded_varyings(int n) { return (n + 3) & ~3; }

/// The loops below run on N4 / 4 groups of four floats (simd::vf32x4, unaligned loads and
/// stores: simd::loadf4 / storef4).
using simd::vf32x4;

/// Perspective-correct varyings at offsets (dx, dy) from the triangle's anchor:
/// v = v0 + b1 (v1 - v0) + b2 (v2 - v0) with b_i = (lambda_i / w_i) / (1 / w).
/// `base` is the triangle's varying block (v0, v1 - v0, v2 - v0, each N4 floats). Returns 1/w.
template <int N4>
inline float interpolate(const TriSetup& t, const float* base, float dx, float dy, float* out) {
  const float iw = eval_plane(t.inv_w, dx, dy);
  const float rcp = 1.0f / iw;
  const float b1 = eval_plane(t.l1, dx, dy) * rcp;
  const float b2 = eval_plane(t.l2, dx, dy) * rcp;
  const vf32x4 vb1(b1), vb2(b2);
  for (int i = 0; i < N4; i += 4) {
    simd::storef4(simd::loadf4(base + i) + vb1 * simd::loadf4(base + N4 + i) +
                      vb2 * simd::loadf4(base + 2 * N4 + i),
                  out + i);
  }
  return iw;
}

/// Varyings from the perspective-correct barycentrics b1, b2 (see `interpolate`).
template <int N4>
inline void interpolate_at(const float* base, float b1, float b2, float* out) {
  const vf32x4 vb1(b1), vb2(b2);
  for (int i = 0; i < N4; i += 4) {
    simd::storef4(simd::loadf4(base + i) + vb1 * simd::loadf4(base + N4 + i) +
                      vb2 * simd::loadf4(base + 2 * N4 + i),
                  out + i);
  }
}

/// `eval_plane` at four positions at once (lane-wise the same operations).
inline vf32x4 eval_plane4(const float p[3], vf32x4 dx, vf32x4 dy) {
  return vf32x4(p[0]) + vf32x4(p[1]) * dx + vf32x4(p[2]) * dy;
}

/// Lane-wise std::clamp(v, 0, 1) (NaN stays NaN, -0 stays -0).
inline vf32x4 clamp01(vf32x4 v) {
  // simd::max / min return their second operand when the comparison fails (NaN included),
  // which is exactly std::clamp's `v < 0 ? 0 : (1 < v ? 1 : v)`.
  return simd::min(vf32x4(1.0f), simd::max(vf32x4(), v));
}

/// Centroid sample of a partially covered pixel: the covered sample nearest the pixel centre,
/// lowest index on ties. `mask` must be non-zero.
inline int centroid_sample(std::uint32_t mask, const SampleOffset* pos, int samples) {
  int best = -1;
  int best_d = 0;
  for (int s = 0; s < samples; ++s) {
    if (!(mask >> s & 1u)) continue;
    const int d = pos[s].x * pos[s].x + pos[s].y * pos[s].y;
    if (best < 0 || d < best_d) {
      best = s;
      best_d = d;
    }
  }
  return best;
}

/// Depth test of a new value against the stored one.
inline bool depth_passes(DepthTest test, float z, float stored) {
  switch (test) {
    case DepthTest::less:
      return z < stored;
    case DepthTest::less_equal:
      return z <= stored;
    case DepthTest::equal:
      return z == stored;
    case DepthTest::always:
      return true;
  }
  return false;
}

/// `depth_passes` for four samples: bit i set when lane i passes.
inline std::uint32_t depth_mask4(DepthTest test, vf32x4 a, vf32x4 b) {
  switch (test) {
    case DepthTest::less:
      return std::uint32_t(simd::movemask(simd::cmplt(a, b)));
    case DepthTest::less_equal:
      return std::uint32_t(simd::movemask(simd::cmple(a, b)));
    case DepthTest::equal:
      return std::uint32_t(simd::movemask(simd::cmpeq(a, b)));
    case DepthTest::always:
      return 15u;
  }
  return 0u;
}

}  // namespace tessera::raster::detail
