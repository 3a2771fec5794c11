// Private: the tap generator shared by Texture::taps (which stores the taps) and
// Texture::sample (which accumulates them as they are produced). One template, so the two paths
// produce the same taps in the same order and agree bit for bit.
#pragma once

#include <array>
#include <cmath>
#include <cstring>

#include "tessera/texture.h"

namespace tessera::texture::detail {

/// Float texel coordinates are clamped to +-2^24 before conversion to int: beyond that a float
/// has no fractional bits left, and the clamp keeps NaN / infinity out of the integer domain.
inline constexpr float kCoordLimit = 16777216.0f;

inline float clamp_coord(float x) {
  // NaN fails both comparisons and maps to -kCoordLimit: deterministic, in range.
  return x > -kCoordLimit ? (x < kCoordLimit ? x : kCoordLimit) : -kCoordLimit;
}

inline bool outside_axis(int x, int size) {
  return static_cast<unsigned>(x) >= static_cast<unsigned>(size);
}

inline int resolve_axis(int x, int size, AddressMode mode) {
  if (!outside_axis(x, size)) return x;  // common case
  switch (mode) {
    case AddressMode::wrap: {
      const int m = x % size;
      return m < 0 ? m + size : m;
    }
    case AddressMode::clamp:
      return x < 0 ? 0 : size - 1;
    case AddressMode::mirror: {
      const int period = 2 * size;
      int m = x % period;
      if (m < 0) m += period;
      return m >= size ? period - 1 - m : m;
    }
    case AddressMode::border:
      return -1;
  }
  return -1;
}

/// Resolves the adjacent pair (x0, x0 + 1) of a bilinear footprint: one test when both are
/// inside, one modulo for wrap. Same results as two `resolve_axis` calls.
inline void resolve_pair(int x0, int size, AddressMode mode, int out[2]) {
  if (x0 >= 0 && x0 < size - 1) {
    out[0] = x0;
    out[1] = x0 + 1;
    return;
  }
  out[0] = resolve_axis(x0, size, mode);
  if (mode == AddressMode::wrap) {
    out[1] = out[0] + 1 == size ? 0 : out[0] + 1;
  } else {
    out[1] = resolve_axis(x0 + 1, size, mode);
  }
}

/// Applies bias, the sampler's [min_lod, max_lod] and the texture's [0, levels - 1]. NaN in,
/// 0 out; the comparisons are ordered so that NaN settings cannot leak through either.
inline float clamp_lod(const SamplerState& sampler, const TextureShape& shape, float lod) {
  if (std::isnan(lod)) lod = 0.0f;
  lod += sampler.lod_bias;
  if (lod > sampler.max_lod) lod = sampler.max_lod;
  if (lod < sampler.min_lod) lod = sampler.min_lod;
  const float last = float(shape.levels > 1 ? shape.levels - 1 : 0);
  if (!(lod >= 0.0f)) lod = 0.0f;
  if (lod > last) lod = last;
  return lod;
}

/// `isotropic_lod`, inline for the sampling hot path.
inline float isotropic_lod_inline(const UvGradients& g) {
  const float px = std::sqrt(g.dudx * g.dudx + g.dvdx * g.dvdx);
  const float py = std::sqrt(g.dudy * g.dudy + g.dvdy * g.dvdy);
  return std::log2(px > py ? px : py);
}

/// The (at most two) mip levels a lookup reads and their weights.
struct LevelPlan {
  int level[2] = {0, 0};
  float weight[2] = {1.0f, 0.0f};
  int count = 1;
};

inline LevelPlan plan_levels(TextureFilter filter, float lod, int levels) {
  LevelPlan plan;
  const int last = levels - 1;
  if (filter == TextureFilter::nearest || filter == TextureFilter::bilinear) {
    // GL's nearest-level rule: level 0 up to lod 0.5, then ceil(lod + 0.5) - 1.
    int l = lod <= 0.5f ? 0 : int(std::ceil(lod + 0.5f)) - 1;
    plan.level[0] = l < last ? l : last;
    return plan;
  }
  const int l0 = int(lod);  // lod >= 0: truncation is floor
  const float frac = lod - float(l0);
  if (l0 >= last || frac <= 0.0f) {
    plan.level[0] = l0 < last ? l0 : last;
    return plan;
  }
  plan.level[0] = l0;
  plan.level[1] = l0 + 1;
  plan.weight[0] = 1.0f - frac;
  plan.weight[1] = frac;
  plan.count = 2;
  return plan;
}

/// floor() for |x| <= kCoordLimit, without the libm call baseline x86-64 would make.
inline int floor_to_int(float x) {
  const int i = int(x);  // truncates towards zero
  return x < float(i) ? i - 1 : i;
}

/// Weighted RGBA accumulator shared by the sampling driver and `Texture::resolve`, so both
/// perform the same operations in the same order (lane-wise `acc += w * texel`, no fused
/// multiply-add on the baseline targets) and agree bit for bit. Uses a 4-lane vector with GCC
/// and Clang; lane-wise IEEE arithmetic gives the same results as the scalar fallback.
#if defined(__GNUC__)
struct Accum4 {
  typedef float V4 __attribute__((vector_size(16)));
  V4 acc = {0.0f, 0.0f, 0.0f, 0.0f};

  void add(float w, const float* texel) {
    V4 t;
    std::memcpy(&t, texel, sizeof(t));
    const V4 wv = {w, w, w, w};
    acc += wv * t;
  }
  std::array<float, 4> value() const { return {acc[0], acc[1], acc[2], acc[3]}; }
};
#else
struct Accum4 {
  float acc[4] = {0.0f, 0.0f, 0.0f, 0.0f};

  void add(float w, const float* texel) {
    for (int c = 0; c < 4; ++c) acc[c] += w * texel[c];
  }
  std::array<float, 4> value() const { return {acc[0], acc[1], acc[2], acc[3]}; }
};
#endif

/// One bilinear 2x2 block of taps as the generator produces it. Tap (k, j) (column x[k], row
/// y[j]) weighs wx[k] * wy[j]; `wy` already includes the level and probe weights. Taps are
/// listed row by row: (0,0), (1,0), (0,1), (1,1).
struct QuadTaps {
  int level = 0;
  int layer = 0;
  int x[2] = {0, 0};
  int y[2] = {0, 0};
  int rx[2] = {0, 0};  ///< Resolved columns; -1 for border reads.
  int ry[2] = {0, 0};  ///< Resolved rows; -1 for border reads.
  bool out_x[2] = {false, false};
  bool out_y[2] = {false, false};
  float wx[2] = {0.0f, 0.0f};
  float wy[2] = {0.0f, 0.0f};

  TexelTap tap(int k, int j) const {
    TexelTap t;
    t.level = level;
    t.layer = layer;
    t.x = x[k];
    t.y = y[j];
    t.resolved_x = rx[k];
    t.resolved_y = ry[j];
    t.weight = wx[k] * wy[j];
    t.outside = out_x[k] || out_y[j];
    return t;
  }
};

/// Produces every tap of `footprint` on `layer` (already clamped), calling `sink.point(tap)`
/// for a nearest-filter tap and `sink.quad(quad)` for a bilinear block: levels in plan order,
/// then probes in order. `footprint.lod` must already be clamped to [0, levels - 1].
template <class Sink>
inline void for_each_tap(const SamplerState& sampler, const TextureShape& shape,
                         const Footprint& footprint, int layer, Sink&& sink) {
  const LevelPlan plan = plan_levels(sampler.filter, footprint.lod, shape.levels);
  int probes = footprint.probes;
  if (probes < 1) probes = 1;
  if (probes > kMaxAnisotropy) probes = kMaxAnisotropy;
  const float inv_probes = 1.0f / float(probes);
  const AddressMode mode_u = sampler.address_u;
  const AddressMode mode_v = sampler.address_v;

  if (sampler.filter == TextureFilter::nearest) {
    // One probe, one level.
    TexelTap tap;
    tap.layer = layer;
    tap.level = plan.level[0];
    const int w = shape.level_width(tap.level);
    const int h = shape.level_height(tap.level);
    tap.x = floor_to_int(clamp_coord(footprint.centre.u * float(w)));
    tap.y = floor_to_int(clamp_coord(footprint.centre.v * float(h)));
    tap.resolved_x = resolve_axis(tap.x, w, mode_u);
    tap.resolved_y = resolve_axis(tap.y, h, mode_v);
    tap.outside = outside_axis(tap.x, w) || outside_axis(tap.y, h);
    tap.weight = 1.0f;
    sink.point(static_cast<const TexelTap&>(tap));
    return;
  }

  QuadTaps q;
  q.layer = layer;
  for (int li = 0; li < plan.count; ++li) {
    q.level = plan.level[li];
    const int w = shape.level_width(q.level);
    const int h = shape.level_height(q.level);
    const float fw = float(w);
    const float fh = float(h);
    const float level_weight = plan.weight[li] * inv_probes;
    for (int i = 0; i < probes; ++i) {
      const float t = (float(i) + 0.5f) * inv_probes - 0.5f;
      const float u = footprint.centre.u + t * footprint.axis_u;
      const float v = footprint.centre.v + t * footprint.axis_v;
      const float px = clamp_coord(u * fw - 0.5f);
      const float py = clamp_coord(v * fh - 0.5f);
      const int x0 = floor_to_int(px);
      const int y0 = floor_to_int(py);
      const float ax = px - float(x0);
      const float ay = py - float(y0);
      q.x[0] = x0;
      q.x[1] = x0 + 1;
      q.y[0] = y0;
      q.y[1] = y0 + 1;
      resolve_pair(x0, w, mode_u, q.rx);
      resolve_pair(y0, h, mode_v, q.ry);
      q.out_x[0] = outside_axis(x0, w);
      q.out_x[1] = outside_axis(x0 + 1, w);
      q.out_y[0] = outside_axis(y0, h);
      q.out_y[1] = outside_axis(y0 + 1, h);
      q.wx[0] = 1.0f - ax;
      q.wx[1] = ax;
      q.wy[0] = (1.0f - ay) * level_weight;
      q.wy[1] = ay * level_weight;
      sink.quad(static_cast<const QuadTaps&>(q));
    }
  }
}

/// Sink that appends to a TapList (capacity is guaranteed by the generator's limits).
struct TapListSink {
  TapList& out;
  void point(const TexelTap& tap) { out.taps[std::size_t(out.count++)] = tap; }
  void quad(const QuadTaps& q) {
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 2; ++k) out.taps[std::size_t(out.count++)] = q.tap(k, j);
  }
};

}  // namespace tessera::texture::detail
