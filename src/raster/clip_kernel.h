// Homogeneous clipping kernel: outcodes and Sutherland-Hodgman clipping of a triangle against
// the near and far planes and the x/y guard band, in clip space (varyings are interpolated
// linearly there, which is perspective-correct).
#pragma once

#include <cstdint>

#include "tessera/raster.h"

namespace tessera::raster::detail {

/// Clip planes as dot(plane, (x, y, z, w)) >= 0 means inside.
enum ClipBit : std::uint32_t {
  kClipNear = 1u << 0,
  kClipFar = 1u << 1,
  kClipLeft = 1u << 2,  ///< x < -w (outside the viewport; reject only)
  kClipRight = 1u << 3,
  kClipBottom = 1u << 4,
  kClipTop = 1u << 5,
  kGuardLeft = 1u << 6,  ///< x < -g w (must be clipped)
  kGuardRight = 1u << 7,
  kGuardBottom = 1u << 8,
  kGuardTop = 1u << 9,
};
inline constexpr std::uint32_t kRejectMask = 0x3Fu;
inline constexpr std::uint32_t kMustClipMask =
    kClipNear | kClipFar | kGuardLeft | kGuardRight | kGuardBottom | kGuardTop;
inline constexpr int kMaxClipVertices = 12;  // 3 + one per clipping plane (6), with slack

struct ClipParams {
  float near_z_weight = 1.0f;  ///< Near plane z + near_z_weight * w >= 0 (1 for GL, 0 for D3D).
  float guard_x = 1.0f;        ///< Guard band |x| <= guard_x * w.
  float guard_y = 1.0f;
};

/// Outcode of one clip-space position.
inline std::uint32_t outcode(const float p[4], const ClipParams& cp) {
  const float x = p[0], y = p[1], z = p[2], w = p[3];
  std::uint32_t c = 0;
  if (!(z + cp.near_z_weight * w >= 0.0f)) c |= kClipNear;  // NaN counts as outside
  if (!(z <= w)) c |= kClipFar;
  if (x < -w) c |= kClipLeft;
  if (x > w) c |= kClipRight;
  if (y < -w) c |= kClipBottom;
  if (y > w) c |= kClipTop;
  if (!(x >= -cp.guard_x * w)) c |= kGuardLeft;
  if (!(x <= cp.guard_x * w)) c |= kGuardRight;
  if (!(y >= -cp.guard_y * w)) c |= kGuardBottom;
  if (!(y <= cp.guard_y * w)) c |= kGuardTop;
  return c;
}

/// A polygon vertex: position then `n` varyings.
struct ClipVertex {
  float p[4];
  float v[kMaxVaryings];
};

/// Signed distance of `p` to the plane identified by `bit` (>= 0 inside).
inline float plane_distance(std::uint32_t bit, const float p[4], const ClipParams& cp) {
  switch (bit) {
    case kClipNear:
      return p[2] + cp.near_z_weight * p[3];
    case kClipFar:
      return p[3] - p[2];
    case kGuardLeft:
      return p[0] + cp.guard_x * p[3];
    case kGuardRight:
      return cp.guard_x * p[3] - p[0];
    case kGuardBottom:
      return p[1] + cp.guard_y * p[3];
    case kGuardTop:
      return cp.guard_y * p[3] - p[1];
    default:
      return 0.0f;
  }
}

/// Clips the convex polygon `in[0..n)` against one plane into `out`; returns the new count.
/// Intersections are always computed from the inside vertex towards the outside one, so an
/// edge shared by two triangles is cut at bit-identical points (no cracks after clipping).
inline int clip_against(std::uint32_t bit, const ClipVertex* in, int n, int nv,
                        const ClipParams& cp, ClipVertex* out) {
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const ClipVertex& a = in[i];
    const ClipVertex& b = in[(i + 1) % n];
    const float da = plane_distance(bit, a.p, cp);
    const float db = plane_distance(bit, b.p, cp);
    const bool ina = da >= 0.0f;
    const bool inb = db >= 0.0f;
    if (ina) out[m++] = a;
    if (ina != inb) {
      const ClipVertex& s = ina ? a : b;  // inside
      const ClipVertex& o = ina ? b : a;  // outside
      const float ds = ina ? da : db;
      const float dout = ina ? db : da;
      const float t = ds / (ds - dout);
      ClipVertex& r = out[m++];
      for (int k = 0; k < 4; ++k) r.p[k] = s.p[k] + t * (o.p[k] - s.p[k]);
      for (int k = 0; k < nv; ++k) r.v[k] = s.v[k] + t * (o.v[k] - s.v[k]);
    }
  }
  return m;
}

/// Clips triangle `poly[0..3)` against every plane in `planes` (kMustClipMask bits);
/// `poly` and `scratch` hold kMaxClipVertices each. Returns the vertex count (0 = gone) and
/// leaves the result in `poly`.
inline int clip_polygon(std::uint32_t planes, ClipVertex* poly, ClipVertex* scratch, int nv,
                        const ClipParams& cp) {
  int n = 3;
  for (std::uint32_t bit = 1; bit <= kGuardTop && n >= 3; bit <<= 1) {
    if (!(planes & bit) || !(bit & kMustClipMask)) continue;
    const int m = clip_against(bit, poly, n, nv, cp, scratch);
    for (int i = 0; i < m; ++i) poly[i] = scratch[i];
    n = m;
  }
  return n >= 3 ? n : 0;
}

}  // namespace tessera::raster::detail
