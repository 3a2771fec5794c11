// The sampling driver of texture::Texture: resolves the kernel's taps (texture/sampler_kernel.h)
// to texels, with the one-probe bilinear/trilinear hot path and its four-lane SIMD form
// (sample4). Storage, mip chains and construction: texture.cpp.
//
// Cost (bench/sampler_bench.cpp): one `compute_footprint` per lookup (two square roots, one
// log2), then a few tens of instructions per tap; trilinear reads 8 taps, 16x anisotropic 128.
// The tap-list path stores 32 bytes per tap, so it is slower than `sample` (BM_TapsAniso16
// against BM_SampleAniso/16 in docs/benchmarks/sampler.md).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "core/simd.h"
#include "tessera/texture.h"
#include "texture/sampler_kernel.h"
#include "texture/sampler_quad_kernel.h"

namespace tessera::texture {

namespace {

/// Accumulates tap values as the kernel produces them, in the same order and arithmetic as
/// `Texture::resolve` (acc += weight * value per tap, weight = wx * wy), so both paths agree
/// bit for bit. Quads read their 2x2 texels through two row pointers.
struct AccumulateSink {
  const float* texels;
  const std::size_t* level_offsets;  // offsets of the lookup's layer, indexed by level
  const TextureShape* shape;
  const float* border;
  detail::Accum4 acc;

  void add(float w, const float* p) { acc.add(w, p); }

  void point(const TexelTap& tap) {
    const float* p = border;
    if (!tap.is_border()) {
      const std::size_t stride = std::size_t(shape->level_width(tap.level)) * 4;
      p = texels + level_offsets[tap.level] + std::size_t(tap.resolved_y) * stride +
          std::size_t(tap.resolved_x) * 4;
    }
    add(tap.weight, p);
  }

  void quad(const detail::QuadTaps& q) {
    const float* base = texels + level_offsets[q.level];
    const std::size_t stride = std::size_t(shape->level_width(q.level)) * 4;
    const std::ptrdiff_t c0 = std::ptrdiff_t(q.rx[0]) * 4;
    const std::ptrdiff_t c1 = std::ptrdiff_t(q.rx[1]) * 4;
    if ((q.rx[0] | q.rx[1] | q.ry[0] | q.ry[1]) >= 0) {  // no border reads (the common case)
      const float* r0 = base + std::size_t(q.ry[0]) * stride;
      const float* r1 = base + std::size_t(q.ry[1]) * stride;
      add(q.wx[0] * q.wy[0], r0 + c0);
      add(q.wx[1] * q.wy[0], r0 + c1);
      add(q.wx[0] * q.wy[1], r1 + c0);
      add(q.wx[1] * q.wy[1], r1 + c1);
      return;
    }
    for (int j = 0; j < 2; ++j) {
      const float* row = base + std::size_t(q.ry[j] < 0 ? 0 : q.ry[j]) * stride;
      for (int k = 0; k < 2; ++k) {
        const bool is_border = q.ry[j] < 0 || q.rx[k] < 0;
        add(q.wx[k] * q.wy[j], is_border ? border : row + (k ? c1 : c0));
      }
    }
  }
};

/// Resolves the adjacent pair (x0, x0 + 1) like `resolve_pair`, with a mask instead of a
/// modulo for the common wrap of a power-of-two size (two's complement `x & (size - 1)` is the
/// mathematical x mod size, negative x included).
inline void resolve_pair_fast(int x0, int size, AddressMode mode, int out[2]) {
  if (mode == AddressMode::wrap && (size & (size - 1)) == 0) {
    out[0] = x0 & (size - 1);
    out[1] = (x0 + 1) & (size - 1);
    return;
  }
  detail::resolve_pair(x0, size, mode, out);
}

/// Adds the four taps of one bilinear block with weights `w` = (w00, w10, w01, w11), tap (k, j)
/// at column rx[k], row ry[j], rows then columns, as `AccumulateSink::quad` does. Border taps
/// (rx or ry < 0) read `border`.
inline void add_bilinear_weights(detail::Accum4& acc, const float* base, std::size_t stride,
                                 const int rx[2], const int ry[2], const float w[4],
                                 const float* border) {
  const std::ptrdiff_t c0 = std::ptrdiff_t(rx[0]) * 4;
  const std::ptrdiff_t c1 = std::ptrdiff_t(rx[1]) * 4;
  if ((rx[0] | rx[1] | ry[0] | ry[1]) >= 0) {
    const float* r0 = base + std::size_t(ry[0]) * stride;
    const float* r1 = base + std::size_t(ry[1]) * stride;
    acc.add(w[0], r0 + c0);
    acc.add(w[1], r0 + c1);
    acc.add(w[2], r1 + c0);
    acc.add(w[3], r1 + c1);
    return;
  }
  for (int j = 0; j < 2; ++j) {
    const float* row = base + std::size_t(ry[j] < 0 ? 0 : ry[j]) * stride;
    for (int k = 0; k < 2; ++k) {
      const bool is_border = ry[j] < 0 || rx[k] < 0;
      acc.add(w[2 * j + k], is_border ? border : row + (k ? c1 : c0));
    }
  }
}

/// Adds the four taps of one bilinear block (tap weight wx[k] * wy[j]), as
/// `AccumulateSink::quad` does.
inline void add_bilinear(const AccumulateSink& sink, detail::Accum4& acc, const float* base,
                         std::size_t stride, const int rx[2], const int ry[2], const float wx[2],
                         const float wy[2]) {
  const float w[4] = {wx[0] * wy[0], wx[1] * wy[0], wx[0] * wy[1], wx[1] * wy[1]};
  add_bilinear_weights(acc, base, stride, rx, ry, w, sink.border);
}

/// Bilinear or trilinear lookup of a one-probe footprint (the shading hot path): exactly the
/// taps `for_each_tap` generates for it, accumulated in the same order with the same
/// arithmetic as `AccumulateSink`, without materialising `QuadTaps`, so the result is
/// bit-identical to the generic path. With a SIMD backend (core/simd.h) the texel coordinates
/// and weights of both levels are computed in one vector (lane-wise the same IEEE operations).
/// `footprint.lod` must be clamped to [0, levels - 1].
std::array<float, 4> sample_one_probe(const AccumulateSink& sink, const SamplerState& sampler,
                                      const Footprint& footprint) {
  using namespace detail;
  const TextureShape& shape = *sink.shape;
  const LevelPlan plan = plan_levels(sampler.filter, footprint.lod, shape.levels);
  // for_each_tap with one probe: inv_probes = 1 and t = 0, kept as operations so that
  // non-finite axes behave the same; level weights times inv_probes = 1 are exact.
  const float t = (0.0f + 0.5f) * 1.0f - 0.5f;
  const float u = footprint.centre.u + t * footprint.axis_u;
  const float v = footprint.centre.v + t * footprint.axis_v;
  int lv[2] = {plan.level[0], plan.level[plan.count - 1]};
  int w[2], h[2];
  for (int li = 0; li < 2; ++li) {
    w[li] = shape.level_width(lv[li]);
    h[li] = shape.level_height(lv[li]);
  }
  // Per level li: x0, y0, the weights wx[2] (= 1 - ax, ax) and wy[2] (times the level weight).
  int x0[2], y0[2];
  float wx[2][2], wy[2][2];
#if TESSERA_SIMD_VECTOR
  {
    using simd::vf32x4;
    using simd::vi32x4;
    // Lanes (x of level 0, y of level 0, x of level 1, y of level 1).
    const vf32x4 size{float(w[0]), float(h[0]), float(w[1]), float(h[1])};
    const vf32x4 p = vf32x4(u, v, u, v) * size - vf32x4(0.5f);
    // clamp_coord: p > -L ? (p < L ? p : L) : -L (NaN -> -L).
    const vf32x4 lim(kCoordLimit);
    const vf32x4 nlim(-kCoordLimit);
    const vf32x4 pc = simd::select(simd::cmpgt(p, nlim), simd::min(p, lim), nlim);
    // floor_to_int: truncate, then subtract 1 where p < float(trunc).
    const vi32x4 tr = simd::to_int_trunc(pc);
    const vi32x4 fl = tr + simd::cmplt(pc, simd::to_float(tr));
    const vf32x4 frac = pc - simd::to_float(fl);
    const vf32x4 lw(1.0f, plan.weight[0], 1.0f, plan.weight[1]);
    alignas(16) float lo[4], hi[4];
    alignas(16) int ic[4];
    // x lanes: 1 - ax and ax (times 1, exact); y lanes: (1 - ay) * lw and ay * lw.
    simd::storef4_aligned((vf32x4(1.0f) - frac) * lw, lo);
    simd::storef4_aligned(frac * lw, hi);
    simd::store4_aligned(fl, ic);
    for (int li = 0; li < 2; ++li) {
      x0[li] = ic[2 * li];
      y0[li] = ic[2 * li + 1];
      wx[li][0] = lo[2 * li];
      wx[li][1] = hi[2 * li];
      wy[li][0] = lo[2 * li + 1];
      wy[li][1] = hi[2 * li + 1];
    }
  }
#else
  for (int li = 0; li < 2; ++li) {
    const float px = clamp_coord(u * float(w[li]) - 0.5f);
    const float py = clamp_coord(v * float(h[li]) - 0.5f);
    x0[li] = floor_to_int(px);
    y0[li] = floor_to_int(py);
    const float ax = px - float(x0[li]);
    const float ay = py - float(y0[li]);
    wx[li][0] = 1.0f - ax;
    wx[li][1] = ax;
    wy[li][0] = (1.0f - ay) * plan.weight[li];
    wy[li][1] = ay * plan.weight[li];
  }
#endif
  Accum4 acc;
  for (int li = 0; li < plan.count; ++li) {
    int rx[2], ry[2];
    resolve_pair_fast(x0[li], w[li], sampler.address_u, rx);
    resolve_pair_fast(y0[li], h[li], sampler.address_v, ry);
    add_bilinear(sink, acc, sink.texels + sink.level_offsets[lv[li]], std::size_t(w[li]) * 4, rx,
                 ry, wx[li], wy[li]);
  }
  return acc.value();
}

}  // namespace

std::array<float, 4> Texture::sample_footprint(const SamplerState& sampler,
                                               const Footprint& footprint, int layer) const {
  if (empty()) return sampler.border_color;
  layer = std::clamp(layer, 0, shape_.layers - 1);
  Footprint fp = footprint;
  const float last = float(shape_.levels - 1);
  if (!(fp.lod >= 0.0f)) fp.lod = 0.0f;
  if (fp.lod > last) fp.lod = last;
  AccumulateSink sink{texels_.data(),
                      offsets_.data() + std::size_t(layer) * shape_.levels,
                      &shape_,
                      sampler.border_color.data(),
                      {}};
  if ((sampler.filter == TextureFilter::trilinear || sampler.filter == TextureFilter::bilinear) &&
      fp.probes <= 1) {
    return sample_one_probe(sink, sampler, fp);
  }
  detail::for_each_tap(sampler, shape_, fp, layer, sink);
  return sink.acc.value();
}

std::array<float, 4> Texture::sample(const SamplerState& sampler, Uv uv,
                                     const UvGradients& gradients, int layer) const {
  if (!empty() &&
      (sampler.filter == TextureFilter::trilinear || sampler.filter == TextureFilter::bilinear)) {
    // The hot path, inlined: `compute_footprint` for an isotropic filter (one probe, zero
    // axis) followed by `sample_footprint`, with the same operations.
    const float w = float(shape_.width);
    const float h = float(shape_.height);
    const UvGradients texel{gradients.dudx * w, gradients.dvdx * h, gradients.dudy * w,
                            gradients.dvdy * h};
    Footprint fp;
    fp.centre = uv;
    fp.lod = detail::clamp_lod(sampler, shape_, detail::isotropic_lod_inline(texel));
    layer = std::clamp(layer, 0, shape_.layers - 1);
    const AccumulateSink sink{texels_.data(),
                              offsets_.data() + std::size_t(layer) * shape_.levels,
                              &shape_,
                              sampler.border_color.data(),
                              {}};
    return sample_one_probe(sink, sampler, fp);
  }
  return sample_footprint(sampler, compute_footprint(sampler, shape_, uv, gradients), layer);
}

void Texture::sample4(const SamplerState& sampler, const std::array<Uv, 4>& uv,
                      const std::array<UvGradients, 4>& gradients, std::uint32_t active,
                      std::array<std::array<float, 4>, 4>& out, int layer) const {
  active &= 15u;
#if TESSERA_SIMD_VECTOR
  constexpr int kExact = 1 << 24;  // level sizes stay exact in float (see level_size4)
  if (active && !empty() &&
      (sampler.filter == TextureFilter::trilinear || sampler.filter == TextureFilter::bilinear) &&
      shape_.width < kExact && shape_.height < kExact) {
    using namespace detail;
    // Structure-of-arrays inputs; inactive lanes compute on zeros and their results are dropped.
    alignas(16) static constexpr std::int32_t kLaneBits[16][4] = {
        {0, 0, 0, 0},   {-1, 0, 0, 0},   {0, -1, 0, 0},   {-1, -1, 0, 0},
        {0, 0, -1, 0},  {-1, 0, -1, 0},  {0, -1, -1, 0},  {-1, -1, -1, 0},
        {0, 0, 0, -1},  {-1, 0, 0, -1},  {0, -1, 0, -1},  {-1, -1, 0, -1},
        {0, 0, -1, -1}, {-1, 0, -1, -1}, {0, -1, -1, -1}, {-1, -1, -1, -1}};
    const simd::vi32x4 lanes = simd::load4_aligned(kLaneBits[active]);
    float in[16];
    std::memcpy(in, gradients.data(), sizeof in);  // dudx, dvdx, dudy, dvdy per lane
    simd::vf32x4 dudx = simd::loadf4(in), dvdx = simd::loadf4(in + 4);
    simd::vf32x4 dudy = simd::loadf4(in + 8), dvdy = simd::loadf4(in + 12);
    simd::transpose(dudx, dvdx, dudy, dvdy);
    std::memcpy(in, uv.data(), 8 * sizeof(float));  // u, v per lane
    const simd::vf32x4 uv01 = simd::loadf4(in), uv23 = simd::loadf4(in + 4);
    const simd::vf32x4 u = simd::keep_where(lanes, simd::even_lanes(uv01, uv23));
    const simd::vf32x4 v = simd::keep_where(lanes, simd::odd_lanes(uv01, uv23));
    alignas(16) float len[4], raw_lod[4];
    simd::storef4_aligned(
        footprint_length4(simd::keep_where(lanes, dudx), simd::keep_where(lanes, dvdx),
                          simd::keep_where(lanes, dudy), simd::keep_where(lanes, dvdy),
                          float(shape_.width), float(shape_.height)),
        len);
    // The scalar path's log2, per lane; skipped where the LOD is known to end at level 0.
    const bool shortcut = magnification_shortcut(sampler);
    for (int lane = 0; lane < 4; ++lane) {
      const bool skip = !(active >> lane & 1u) || (shortcut && len[lane] <= 1.0f);
      raw_lod[lane] = skip ? 0.0f : std::log2(len[lane]);
    }
    OneProbe4 plan;
    plan_one_probe4(sampler, shape_, clamp_lod4(sampler, shape_, simd::loadf4_aligned(raw_lod)), u,
                    v, plan);
    layer = std::clamp(layer, 0, shape_.layers - 1);
    const std::size_t* level_offsets = offsets_.data() + std::size_t(layer) * shape_.levels;
    const float* texels = texels_.data();
    if (plan.has_offsets) {
      // Same taps and order as add_bilinear_weights without border reads (the loop below with
      // its address resolution hoisted out).
      for (int lane = 0; lane < 4; ++lane) {
        if (!(active >> lane & 1u)) continue;
        Accum4 acc;
        const int count = plan.count[lane];
        for (int li = 0; li < count; ++li) {
          const float* base = texels + level_offsets[plan.level[li][lane]];
          const float* w4 = plan.weight[li][lane];
          const int* o = plan.offset[li][lane];
          acc.add(w4[0], base + o[0]);
          acc.add(w4[1], base + o[1]);
          acc.add(w4[2], base + o[2]);
          acc.add(w4[3], base + o[3]);
        }
        out[std::size_t(lane)] = acc.value();
      }
      return;
    }
    for (int lane = 0; lane < 4; ++lane) {
      if (!(active >> lane & 1u)) continue;
      Accum4 acc;
      for (int li = 0; li < plan.count[lane]; ++li) {
        const float* base = texels + level_offsets[plan.level[li][lane]];
        const float* w4 = plan.weight[li][lane];
        if (plan.has_offsets) {
          // Same taps and order as add_bilinear_weights without border reads.
          const int* o = plan.offset[li][lane];
          acc.add(w4[0], base + o[0]);
          acc.add(w4[1], base + o[1]);
          acc.add(w4[2], base + o[2]);
          acc.add(w4[3], base + o[3]);
          continue;
        }
        const int w = plan.w[li][lane], h = plan.h[li][lane];
        int rx[2], ry[2];
        resolve_pair_fast(plan.x0[li][lane], w, sampler.address_u, rx);
        resolve_pair_fast(plan.y0[li][lane], h, sampler.address_v, ry);
        add_bilinear_weights(acc, base, std::size_t(w) * 4, rx, ry, w4,
                             sampler.border_color.data());
      }
      out[std::size_t(lane)] = acc.value();
    }
    return;
  }
#endif
  for (int lane = 0; lane < 4; ++lane) {
    if (active >> lane & 1u) {
      out[std::size_t(lane)] =
          sample(sampler, uv[std::size_t(lane)], gradients[std::size_t(lane)], layer);
    }
  }
}

std::array<float, 4> Texture::sample_lod(const SamplerState& sampler, Uv uv, float lod,
                                         int layer) const {
  return sample_footprint(sampler, footprint_at_lod(sampler, shape_, uv, lod), layer);
}

std::array<std::array<float, 4>, 4> Texture::sample_quad(const SamplerState& sampler,
                                                         const std::array<Uv, 4>& quad,
                                                         int layer) const {
  const UvGradients g = quad_gradients(quad);
  std::array<std::array<float, 4>, 4> out;
  for (int i = 0; i < 4; ++i) out[std::size_t(i)] = sample(sampler, quad[std::size_t(i)], g, layer);
  return out;
}

void Texture::taps(const SamplerState& sampler, Uv uv, const UvGradients& gradients, int layer,
                   TapList& out) const {
  generate_taps(sampler, shape_, compute_footprint(sampler, shape_, uv, gradients), layer, out);
}

std::array<float, 4> Texture::fetch(const SamplerState& sampler, const TexelTap& tap) const {
  if (tap.is_border() || empty()) return sampler.border_color;
  const TextureLevelView view = level(tap.layer, tap.level);
  const float* p = view.at(tap.resolved_x, tap.resolved_y);
  return {p[0], p[1], p[2], p[3]};
}

std::array<float, 4> Texture::resolve(const SamplerState& sampler, const TapList& taps) const {
  detail::Accum4 acc;
  for (const TexelTap& tap : taps) {
    const std::array<float, 4> c = fetch(sampler, tap);
    acc.add(tap.weight, c.data());
  }
  return acc.value();
}

}  // namespace tessera::texture
