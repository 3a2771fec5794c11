// Private: the tap generator shared by Texture::taps (which stores the taps) and
// Texture::sample (which accumulates them as they are produced). One template, so the two paths
// produce the same taps in the same order and agree bit for bit.
#pragma once

#include <cmath>

#include "tessera/texture.h"

namespace tessera::texture_detail {

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
  const float fl = std::floor(lod);
  const int l0 = int(fl);
  const float frac = lod - fl;
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

/// Calls `sink(const TexelTap&)` for every tap of `footprint` on `layer` (already clamped):
/// levels in plan order, probes in order, and within a bilinear quad (x0,y0), (x1,y0),
/// (x0,y1), (x1,y1). `footprint.lod` must already be clamped to [0, levels - 1].
template <class Sink>
inline void for_each_tap(const SamplerState& sampler, const TextureShape& shape,
                         const Footprint& footprint, int layer, Sink&& sink) {
  const LevelPlan plan = plan_levels(sampler.filter, footprint.lod, shape.levels);
  int probes = footprint.probes;
  if (probes < 1) probes = 1;
  if (probes > kMaxAnisotropy) probes = kMaxAnisotropy;
  const float inv_probes = 1.0f / float(probes);
  const bool nearest = sampler.filter == TextureFilter::nearest;
  const AddressMode mode_u = sampler.address_u;
  const AddressMode mode_v = sampler.address_v;

  TexelTap tap;
  tap.layer = layer;
  for (int li = 0; li < plan.count; ++li) {
    const int level = plan.level[li];
    const int w = shape.level_width(level);
    const int h = shape.level_height(level);
    const float fw = float(w);
    const float fh = float(h);
    const float level_weight = plan.weight[li] * inv_probes;
    tap.level = level;
    for (int i = 0; i < probes; ++i) {
      const float t = (float(i) + 0.5f) * inv_probes - 0.5f;
      const float u = footprint.center.u + t * footprint.axis_u;
      const float v = footprint.center.v + t * footprint.axis_v;
      if (nearest) {
        tap.x = int(std::floor(clamp_coord(u * fw)));
        tap.y = int(std::floor(clamp_coord(v * fh)));
        tap.resolved_x = resolve_axis(tap.x, w, mode_u);
        tap.resolved_y = resolve_axis(tap.y, h, mode_v);
        tap.outside = outside_axis(tap.x, w) || outside_axis(tap.y, h);
        tap.weight = level_weight;
        sink(static_cast<const TexelTap&>(tap));
        continue;
      }
      const float px = clamp_coord(u * fw - 0.5f);
      const float py = clamp_coord(v * fh - 0.5f);
      const float fx0 = std::floor(px);
      const float fy0 = std::floor(py);
      const float ax = px - fx0;
      const float ay = py - fy0;
      const int x0 = int(fx0);
      const int y0 = int(fy0);
      const int xs[2] = {x0, x0 + 1};
      const int ys[2] = {y0, y0 + 1};
      const int rxs[2] = {resolve_axis(x0, w, mode_u), resolve_axis(x0 + 1, w, mode_u)};
      const int rys[2] = {resolve_axis(y0, h, mode_v), resolve_axis(y0 + 1, h, mode_v)};
      const bool out_x[2] = {outside_axis(x0, w), outside_axis(x0 + 1, w)};
      const bool out_y[2] = {outside_axis(y0, h), outside_axis(y0 + 1, h)};
      const float wx[2] = {1.0f - ax, ax};
      const float wy[2] = {(1.0f - ay) * level_weight, ay * level_weight};
      for (int j = 0; j < 2; ++j) {
        for (int k = 0; k < 2; ++k) {
          tap.x = xs[k];
          tap.y = ys[j];
          tap.resolved_x = rxs[k];
          tap.resolved_y = rys[j];
          tap.outside = out_x[k] || out_y[j];
          tap.weight = wx[k] * wy[j];
          sink(static_cast<const TexelTap&>(tap));
        }
      }
    }
  }
}

}  // namespace tessera::texture_detail
