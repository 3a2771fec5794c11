// Private: the four-lane form of the isotropic one-probe lookup plan (bilinear / trilinear
// `Texture::sample`): footprint lengths, LOD clamping, level choice, texel coordinates and
// bilinear weights of four lookups at once, one lookup per SSE lane. Pure functions.
//
// Every lane performs the same IEEE single-precision operations in the same order as the scalar
// path (`isotropic_lod_inline`, `clamp_lod`, `plan_levels`, `sample_one_probe`), so a lane's
// results are bit-identical to one scalar lookup: add, sub, mul, sqrt, min/max and compares are
// lane-wise exact on SSE, and the selects below reproduce the scalar branches (NaN included).
// Only the log2 of the LOD stays scalar (the caller calls std::log2 per lane, the same libm
// function as the scalar path).
#pragma once

#if defined(__SSE2__)

#include <emmintrin.h>

#include "texture/sampler_kernel.h"

namespace tessera::texture_detail {

/// Lane-wise `c ? a : b` for a comparison mask `c`.
inline __m128 select4(__m128 c, __m128 a, __m128 b) {
  return _mm_or_ps(_mm_and_ps(c, a), _mm_andnot_ps(c, b));
}
inline __m128i select4i(__m128i c, __m128i a, __m128i b) {
  return _mm_or_si128(_mm_and_si128(c, a), _mm_andnot_si128(c, b));
}

/// `max(|d/dx|, |d/dy|)` of four lookups, the argument of the log2 in `isotropic_lod_inline`:
/// lane i from gradients (dudx[i], dvdx[i], dudy[i], dvdy[i]) in normalised units, scaled by
/// the level-0 size (w, h) first exactly as `Texture::sample` does.
inline __m128 footprint_length4(__m128 dudx, __m128 dvdx, __m128 dudy, __m128 dvdy, float w,
                                float h) {
  const __m128 vw = _mm_set1_ps(w), vh = _mm_set1_ps(h);
  const __m128 tux = _mm_mul_ps(dudx, vw), tvx = _mm_mul_ps(dvdx, vh);
  const __m128 tuy = _mm_mul_ps(dudy, vw), tvy = _mm_mul_ps(dvdy, vh);
  const __m128 px = _mm_sqrt_ps(_mm_add_ps(_mm_mul_ps(tux, tux), _mm_mul_ps(tvx, tvx)));
  const __m128 py = _mm_sqrt_ps(_mm_add_ps(_mm_mul_ps(tuy, tuy), _mm_mul_ps(tvy, tvy)));
  // px > py ? px : py (maxps returns its second operand when the compare fails, NaN included).
  return _mm_max_ps(px, py);
}

/// True when `clamp_lod` maps every LOD <= 0 (that is, log2 of a length in [0, 1]) to a value
/// that `plan_levels` treats as level 0 alone, so the log2 can be skipped for such lengths: no
/// bias, max_lod >= 0 (no clamp) and min_lod <= 0 (a clamp to min_lod still ends at +-0).
inline bool magnification_shortcut(const SamplerState& sampler) {
  return sampler.lod_bias == 0.0f && sampler.max_lod >= 0.0f && sampler.min_lod <= 0.0f;
}

/// `clamp_lod` of four raw LODs.
inline __m128 clamp_lod4(const SamplerState& sampler, const TextureShape& shape, __m128 lod) {
  const __m128 zero = _mm_setzero_ps();
  lod = _mm_and_ps(_mm_cmpord_ps(lod, lod), lod);  // NaN -> 0
  lod = _mm_add_ps(lod, _mm_set1_ps(sampler.lod_bias));
  const __m128 max_lod = _mm_set1_ps(sampler.max_lod);
  lod = select4(_mm_cmpgt_ps(lod, max_lod), max_lod, lod);
  const __m128 min_lod = _mm_set1_ps(sampler.min_lod);
  lod = select4(_mm_cmplt_ps(lod, min_lod), min_lod, lod);
  const __m128 last = _mm_set1_ps(float(shape.levels > 1 ? shape.levels - 1 : 0));
  lod = _mm_andnot_ps(_mm_cmpnge_ps(lod, zero), lod);  // !(lod >= 0) -> 0
  return select4(_mm_cmpgt_ps(lod, last), last, lod);
}

/// Lane-wise `mip_dimension(size, level)` for 0 <= level < 31 and size < 2^24:
/// size * 2^-level is exact in float, its truncation is size >> level, then max(1, .).
inline __m128i level_size4(int size, __m128i level) {
  const __m128 scale =
      _mm_castsi128_ps(_mm_slli_epi32(_mm_sub_epi32(_mm_set1_epi32(127), level), 23));
  const __m128i s = _mm_cvttps_epi32(_mm_mul_ps(_mm_set1_ps(float(size)), scale));
  return _mm_sub_epi32(s, _mm_cmpeq_epi32(s, _mm_setzero_si128()));  // 0 -> 1
}

/// Lane-wise 32-bit a * b for non-negative products below 2^31 (SSE2 has no pmulld).
inline __m128i mul32(__m128i a, __m128i b) {
  const __m128i even = _mm_mul_epu32(a, b);
  const __m128i odd = _mm_mul_epu32(_mm_srli_si128(a, 4), _mm_srli_si128(b, 4));
  return _mm_unpacklo_epi32(_mm_shuffle_epi32(even, _MM_SHUFFLE(0, 0, 2, 0)),
                            _mm_shuffle_epi32(odd, _MM_SHUFFLE(0, 0, 2, 0)));
}

/// Whether `resolve_pair4` handles `mode` for an axis whose level-0 size is `size`: wrap of a
/// power-of-two size (every level is then a power of two too) or clamp. Mirror, border and
/// other wraps take the scalar `resolve_pair`.
inline bool vector_address(AddressMode mode, int size) {
  return (mode == AddressMode::wrap && (size & (size - 1)) == 0) || mode == AddressMode::clamp;
}

/// `resolve_pair(x0, size, mode)` of four lanes for a mode accepted by `vector_address`:
/// wrap by mask (two's complement x & (size - 1) is x mod size), clamp to [0, size - 1].
inline void resolve_pair4(__m128i x0, __m128i size, AddressMode mode, __m128i& r0, __m128i& r1) {
  const __m128i one = _mm_set1_epi32(1);
  const __m128i top = _mm_sub_epi32(size, one);
  const __m128i x1 = _mm_add_epi32(x0, one);
  if (mode == AddressMode::wrap) {
    r0 = _mm_and_si128(x0, top);
    r1 = _mm_and_si128(x1, top);
    return;
  }
  // clamp: x < 0 -> 0, x > size - 1 -> size - 1.
  const __m128i zero = _mm_setzero_si128();
  r0 = select4i(_mm_cmpgt_epi32(x0, top), top, _mm_andnot_si128(_mm_cmplt_epi32(x0, zero), x0));
  r1 = select4i(_mm_cmpgt_epi32(x1, top), top, _mm_andnot_si128(_mm_cmplt_epi32(x1, zero), x1));
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
inline void plan_one_probe4(const SamplerState& sampler, const TextureShape& shape, __m128 lod,
                            __m128 u, __m128 v, OneProbe4& out) {
  const __m128i one_i = _mm_set1_epi32(1);
  const __m128 one = _mm_set1_ps(1.0f);
  out.has_offsets = vector_address(sampler.address_u, shape.width) &&
                    vector_address(sampler.address_v, shape.height);
  const int last = shape.levels - 1;
  __m128i lev0, lev1;
  __m128 lw0, lw1;
  __m128i single;
  if (sampler.filter == TextureFilter::trilinear) {
    // l0 = int(lod) (lod >= 0), frac = lod - l0; one level when l0 >= last or frac <= 0.
    const __m128i l0 = _mm_cvttps_epi32(lod);
    const __m128 frac = _mm_sub_ps(lod, _mm_cvtepi32_ps(l0));
    single = _mm_or_si128(_mm_cmpgt_epi32(l0, _mm_set1_epi32(last - 1)),
                          _mm_castps_si128(_mm_cmple_ps(frac, _mm_setzero_ps())));
    // lod <= last, so min(l0, last) = l0 on the single-level branch too.
    lev0 = l0;
    lev1 = select4i(single, l0, _mm_add_epi32(l0, one_i));
    lw0 = select4(_mm_castsi128_ps(single), one, _mm_sub_ps(one, frac));
    lw1 = _mm_andnot_ps(_mm_castsi128_ps(single), frac);
  } else {
    // GL's nearest-level rule: 0 up to lod 0.5, then ceil(lod + 0.5) - 1, at most last.
    const __m128 x = _mm_add_ps(lod, _mm_set1_ps(0.5f));
    const __m128i t = _mm_cvttps_epi32(x);  // x >= 0.5: truncation is floor
    // ceil(x) - 1 = t - 1 + (x > t)
    __m128i l = _mm_sub_epi32(_mm_sub_epi32(t, one_i),
                              _mm_castps_si128(_mm_cmpgt_ps(x, _mm_cvtepi32_ps(t))));
    l = _mm_andnot_si128(_mm_castps_si128(_mm_cmple_ps(lod, _mm_set1_ps(0.5f))), l);
    const __m128i vlast = _mm_set1_epi32(last);
    l = select4i(_mm_cmpgt_epi32(l, vlast), vlast, l);
    single = _mm_set1_epi32(-1);
    lev0 = lev1 = l;
    lw0 = one;
    lw1 = _mm_setzero_ps();
  }
  _mm_store_si128(reinterpret_cast<__m128i*>(out.count),
                  _mm_sub_epi32(_mm_set1_epi32(2), _mm_and_si128(single, one_i)));
  const __m128i lev[2] = {lev0, lev1};
  const __m128 lw[2] = {lw0, lw1};
  const __m128 half = _mm_set1_ps(0.5f);
  const __m128 lim = _mm_set1_ps(kCoordLimit);
  const __m128 nlim = _mm_set1_ps(-kCoordLimit);
  for (int li = 0; li < 2; ++li) {
    const __m128i w = level_size4(shape.width, lev[li]);
    const __m128i h = level_size4(shape.height, lev[li]);
    _mm_store_si128(reinterpret_cast<__m128i*>(out.level[li]), lev[li]);
    _mm_store_si128(reinterpret_cast<__m128i*>(out.w[li]), w);
    _mm_store_si128(reinterpret_cast<__m128i*>(out.h[li]), h);
    __m128 frac[2];
    for (int axis = 0; axis < 2; ++axis) {
      const __m128 size = _mm_cvtepi32_ps(axis == 0 ? w : h);
      const __m128 p = _mm_sub_ps(_mm_mul_ps(axis == 0 ? u : v, size), half);
      // clamp_coord, then floor_to_int.
      const __m128 pc = select4(_mm_cmpgt_ps(p, nlim), _mm_min_ps(p, lim), nlim);
      const __m128i tr = _mm_cvttps_epi32(pc);
      const __m128i fl = _mm_add_epi32(tr, _mm_castps_si128(_mm_cmplt_ps(pc, _mm_cvtepi32_ps(tr))));
      frac[axis] = _mm_sub_ps(pc, _mm_cvtepi32_ps(fl));
      _mm_store_si128(reinterpret_cast<__m128i*>(axis == 0 ? out.x0[li] : out.y0[li]), fl);
    }
    // wx = (1 - ax, ax), wy = ((1 - ay) * lw, ay * lw); tap (k, j) weighs wx[k] * wy[j].
    const __m128 wx0 = _mm_sub_ps(one, frac[0]);
    const __m128 wx1 = frac[0];
    const __m128 wy0 = _mm_mul_ps(_mm_sub_ps(one, frac[1]), lw[li]);
    const __m128 wy1 = _mm_mul_ps(frac[1], lw[li]);
    __m128 t00 = _mm_mul_ps(wx0, wy0), t10 = _mm_mul_ps(wx1, wy0);
    __m128 t01 = _mm_mul_ps(wx0, wy1), t11 = _mm_mul_ps(wx1, wy1);
    _MM_TRANSPOSE4_PS(t00, t10, t01, t11);  // now one vector per lane
    _mm_store_ps(out.weight[li][0], t00);
    _mm_store_ps(out.weight[li][1], t10);
    _mm_store_ps(out.weight[li][2], t01);
    _mm_store_ps(out.weight[li][3], t11);
    if (out.has_offsets) {
      __m128i rx0, rx1, ry0, ry1;
      resolve_pair4(_mm_load_si128(reinterpret_cast<const __m128i*>(out.x0[li])), w,
                    sampler.address_u, rx0, rx1);
      resolve_pair4(_mm_load_si128(reinterpret_cast<const __m128i*>(out.y0[li])), h,
                    sampler.address_v, ry0, ry1);
      const __m128i row0 = mul32(ry0, w), row1 = mul32(ry1, w);
      __m128 o00 = _mm_castsi128_ps(_mm_slli_epi32(_mm_add_epi32(row0, rx0), 2));
      __m128 o10 = _mm_castsi128_ps(_mm_slli_epi32(_mm_add_epi32(row0, rx1), 2));
      __m128 o01 = _mm_castsi128_ps(_mm_slli_epi32(_mm_add_epi32(row1, rx0), 2));
      __m128 o11 = _mm_castsi128_ps(_mm_slli_epi32(_mm_add_epi32(row1, rx1), 2));
      _MM_TRANSPOSE4_PS(o00, o10, o01, o11);
      _mm_store_ps(reinterpret_cast<float*>(out.offset[li][0]), o00);
      _mm_store_ps(reinterpret_cast<float*>(out.offset[li][1]), o10);
      _mm_store_ps(reinterpret_cast<float*>(out.offset[li][2]), o01);
      _mm_store_ps(reinterpret_cast<float*>(out.offset[li][3]), o11);
    }
  }
}

}  // namespace tessera::texture_detail

#endif  // __SSE2__
