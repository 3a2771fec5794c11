// Private: the four-lane form of the isotropic one-probe lookup plan (bilinear / trilinear
// `Texture::sample`): footprint lengths, LOD clamping, level choice, texel coordinates and
// bilinear weights of four lookups at once, one lookup per SIMD lane (core/simd.h's vf32x4 and
// vi32x4). Pure functions.
//
// Every lane performs the same IEEE single-precision operations in the same order as the scalar
// path (`isotropic_lod_inline`, `clamp_lod`, `plan_levels`, `sample_one_probe`), so a lane's
// results are bit-identical to one scalar lookup: add, sub, mul, sqrt, min/max and compares are
// lane-wise exact, and the selects below reproduce the scalar branches (NaN included).
// Only the log2 of the LOD stays scalar (the caller calls std::log2 per lane, the same libm
// function as the scalar path). Compiled only with a vector backend (TESSERA_SIMD_VECTOR, i.e.
// SSE2 or NEON); elsewhere the texture keeps its scalar per-lookup path.
#pragma once

#include "core/simd.h"

#if TESSERA_SIMD_VECTOR

#include "texture/sampler_kernel.h"

namespace tessera::texture::detail {

using simd::vf32x4;
using simd::vi32x4;

/// `max(|d/dx|, |d/dy|)` of four lookups, the argument of the log2 in `isotropic_lod_inline`:
/// lane i from gradients (dudx[i], dvdx[i], dudy[i], dvdy[i]) in normalised units, scaled by
/// the level-0 size (w, h) first exactly as `Texture::sample` does.
inline vf32x4 footprint_length4(vf32x4 dudx, vf32x4 dvdx, vf32x4 dudy, vf32x4 dvdy, float w,
                                float h) {
  const vf32x4 vw(w), vh(h);
  const vf32x4 tux = dudx * vw, tvx = dvdx * vh;
  const vf32x4 tuy = dudy * vw, tvy = dvdy * vh;
  const vf32x4 px = simd::sqrt(tux * tux + tvx * tvx);
  const vf32x4 py = simd::sqrt(tuy * tuy + tvy * tvy);
  // px > py ? px : py (max returns its second operand when the compare fails, NaN included).
  return simd::max(px, py);
}

/// True when `clamp_lod` maps every LOD <= 0 (that is, log2 of a length in [0, 1]) to a value
/// that `plan_levels` treats as level 0 alone, so the log2 can be skipped for such lengths: no
/// bias, max_lod >= 0 (no clamp) and min_lod <= 0 (a clamp to min_lod still ends at +-0).
inline bool magnification_shortcut(const SamplerState& sampler) {
  return sampler.lod_bias == 0.0f && sampler.max_lod >= 0.0f && sampler.min_lod <= 0.0f;
}

/// `clamp_lod` of four raw LODs.
inline vf32x4 clamp_lod4(const SamplerState& sampler, const TextureShape& shape, vf32x4 lod) {
  const vf32x4 zero;
  lod = simd::keep_where(simd::cmpord(lod, lod), lod);  // NaN -> 0
  lod = lod + vf32x4(sampler.lod_bias);
  const vf32x4 max_lod(sampler.max_lod);
  lod = simd::select(simd::cmpgt(lod, max_lod), max_lod, lod);
  const vf32x4 min_lod(sampler.min_lod);
  lod = simd::select(simd::cmplt(lod, min_lod), min_lod, lod);
  const vf32x4 last(float(shape.levels > 1 ? shape.levels - 1 : 0));
  lod = simd::zero_where(simd::cmpnge(lod, zero), lod);  // !(lod >= 0) -> 0
  return simd::select(simd::cmpgt(lod, last), last, lod);
}

/// Lane-wise `mip_dimension(size, level)` for 0 <= level < 31 and size < 2^24:
/// size * 2^-level is exact in float, its truncation is size >> level, then max(1, .).
inline vi32x4 level_size4(int size, vi32x4 level) {
  const vf32x4 scale = simd::as_float(simd::sll<23>(vi32x4(127) - level));
  const vi32x4 s = simd::to_int_trunc(vf32x4(float(size)) * scale);
  return s - simd::cmpeq(s, vi32x4());  // 0 -> 1
}

/// Whether `resolve_pair4` handles `mode` for an axis whose level-0 size is `size`: wrap of a
/// power-of-two size (every level is then a power of two too) or clamp. Mirror, border and
/// other wraps take the scalar `resolve_pair`.
inline bool vector_address(AddressMode mode, int size) {
  return (mode == AddressMode::wrap && (size & (size - 1)) == 0) || mode == AddressMode::clamp;
}

/// `resolve_pair(x0, size, mode)` of four lanes for a mode accepted by `vector_address`:
/// wrap by mask (two's complement x & (size - 1) is x mod size), clamp to [0, size - 1].
inline void resolve_pair4(vi32x4 x0, vi32x4 size, AddressMode mode, vi32x4& r0, vi32x4& r1) {
  const vi32x4 one(1);
  const vi32x4 top = size - one;
  const vi32x4 x1 = x0 + one;
  if (mode == AddressMode::wrap) {
    r0 = x0 & top;
    r1 = x1 & top;
    return;
  }
  // clamp: x < 0 -> 0, x > size - 1 -> size - 1.
  const vi32x4 zero;
  r0 = simd::select(simd::cmpgt(x0, top), top, simd::andnot(simd::cmplt(x0, zero), x0));
  r1 = simd::select(simd::cmpgt(x1, top), top, simd::andnot(simd::cmplt(x1, zero), x1));
}

/// The one-probe plan of four lookups (lane i = lookup i): what `sample_one_probe` computes per
/// lookup before it reads texels. Level li (0, 1) of a lane is read when li < count.
struct OneProbe4 {
  alignas(16) int count[4];
  alignas(16) int level[2][4];
  alignas(16) int w[2][4];   ///< Level widths.
  alignas(16) int h[2][4];   ///< Level heights.
  alignas(16) int x0[2][4];  ///< Bilinear block's first column (before address resolution).
  alignas(16) int y0[2][4];  ///< First row.
  /// Tap weights wx[k] * wy[j] of the block, per lane: weight[li][lane][2 * j + k].
  alignas(16) float weight[2][4][4];
  /// Set by `plan_one_probe4` when both address modes pass `vector_address`: the taps' float
  /// offsets from the level's first texel, (ry[j] * w + rx[k]) * 4, as offset[li][lane][2j + k].
  bool has_offsets = false;
  alignas(16) int offset[2][4][4];
};

/// Plans four lookups at (u, v) with LODs already clamped by `clamp_lod4`, for a bilinear or
/// trilinear `sampler.filter`, as `plan_levels` + `sample_one_probe` do per lookup. Level sizes
/// must be below 2^24 and hold fewer than 2^29 texels (as `check_image_size` guarantees).
inline void plan_one_probe4(const SamplerState& sampler, const TextureShape& shape, vf32x4 lod,
                            vf32x4 u, vf32x4 v, OneProbe4& out) {
  const vi32x4 one_i(1);
  const vf32x4 one(1.0f);
  out.has_offsets = vector_address(sampler.address_u, shape.width) &&
                    vector_address(sampler.address_v, shape.height);
  const int last = shape.levels - 1;
  vi32x4 lev0, lev1;
  vf32x4 lw0, lw1;
  vi32x4 single;
  if (sampler.filter == TextureFilter::trilinear) {
    // l0 = int(lod) (lod >= 0), frac = lod - l0; one level when l0 >= last or frac <= 0.
    const vi32x4 l0 = simd::to_int_trunc(lod);
    const vf32x4 frac = lod - simd::to_float(l0);
    single = simd::cmpgt(l0, vi32x4(last - 1)) | simd::cmple(frac, vf32x4());
    // lod <= last, so min(l0, last) = l0 on the single-level branch too.
    lev0 = l0;
    lev1 = simd::select(single, l0, l0 + one_i);
    lw0 = simd::select(single, one, one - frac);
    lw1 = simd::zero_where(single, frac);
  } else {
    // GL's nearest-level rule: 0 up to lod 0.5, then ceil(lod + 0.5) - 1, at most last.
    const vf32x4 x = lod + vf32x4(0.5f);
    const vi32x4 t = simd::to_int_trunc(x);  // x >= 0.5: truncation is floor
    // ceil(x) - 1 = t - 1 + (x > t)
    vi32x4 l = (t - one_i) - simd::cmpgt(x, simd::to_float(t));
    l = simd::andnot(simd::cmple(lod, vf32x4(0.5f)), l);
    const vi32x4 vlast(last);
    l = simd::select(simd::cmpgt(l, vlast), vlast, l);
    single = vi32x4(-1);
    lev0 = lev1 = l;
    lw0 = one;
    lw1 = vf32x4();
  }
  simd::store4_aligned(vi32x4(2) - (single & one_i), out.count);
  const vi32x4 lev[2] = {lev0, lev1};
  const vf32x4 lw[2] = {lw0, lw1};
  const vf32x4 half(0.5f);
  const vf32x4 lim(kCoordLimit);
  const vf32x4 nlim(-kCoordLimit);
  for (int li = 0; li < 2; ++li) {
    const vi32x4 w = level_size4(shape.width, lev[li]);
    const vi32x4 h = level_size4(shape.height, lev[li]);
    simd::store4_aligned(lev[li], out.level[li]);
    simd::store4_aligned(w, out.w[li]);
    simd::store4_aligned(h, out.h[li]);
    vf32x4 frac[2];
    for (int axis = 0; axis < 2; ++axis) {
      const vf32x4 size = simd::to_float(axis == 0 ? w : h);
      const vf32x4 p = (axis == 0 ? u : v) * size - half;
      // clamp_coord, then floor_to_int.
      const vf32x4 pc = simd::select(simd::cmpgt(p, nlim), simd::min(p, lim), nlim);
      const vi32x4 tr = simd::to_int_trunc(pc);
      const vi32x4 fl = tr + simd::cmplt(pc, simd::to_float(tr));
      frac[axis] = pc - simd::to_float(fl);
      simd::store4_aligned(fl, axis == 0 ? out.x0[li] : out.y0[li]);
    }
    // wx = (1 - ax, ax), wy = ((1 - ay) * lw, ay * lw); tap (k, j) weighs wx[k] * wy[j].
    const vf32x4 wx0 = one - frac[0];
    const vf32x4 wx1 = frac[0];
    const vf32x4 wy0 = (one - frac[1]) * lw[li];
    const vf32x4 wy1 = frac[1] * lw[li];
    vf32x4 t00 = wx0 * wy0, t10 = wx1 * wy0;
    vf32x4 t01 = wx0 * wy1, t11 = wx1 * wy1;
    simd::transpose(t00, t10, t01, t11);  // now one vector per lane
    simd::storef4_aligned(t00, out.weight[li][0]);
    simd::storef4_aligned(t10, out.weight[li][1]);
    simd::storef4_aligned(t01, out.weight[li][2]);
    simd::storef4_aligned(t11, out.weight[li][3]);
    if (out.has_offsets) {
      vi32x4 rx0, rx1, ry0, ry1;
      resolve_pair4(simd::load4_aligned(out.x0[li]), w, sampler.address_u, rx0, rx1);
      resolve_pair4(simd::load4_aligned(out.y0[li]), h, sampler.address_v, ry0, ry1);
      // Products below 2^31 (fewer than 2^29 texels per level).
      const vi32x4 row0 = ry0 * w, row1 = ry1 * w;
      vi32x4 o00 = simd::sll<2>(row0 + rx0);
      vi32x4 o10 = simd::sll<2>(row0 + rx1);
      vi32x4 o01 = simd::sll<2>(row1 + rx0);
      vi32x4 o11 = simd::sll<2>(row1 + rx1);
      simd::transpose(o00, o10, o01, o11);
      simd::store4_aligned(o00, out.offset[li][0]);
      simd::store4_aligned(o10, out.offset[li][1]);
      simd::store4_aligned(o01, out.offset[li][2]);
      simd::store4_aligned(o11, out.offset[li][3]);
    }
  }
}

}  // namespace tessera::texture::detail

#endif  // TESSERA_SIMD_VECTOR
