// exact_search_kernel.h — the baseline window evaluators of the PVRTC 4 bpp exact search
// (exact_search.cpp): `local_error_simd` scores any candidate endpoint pair of one block over
// the 7x7 texels it influences (LocalWindow); `planar_error` scores a candidate that differs
// from the block's current pair in one colour channel only (PlanarWindow), after
// `build_planar`, `planar_refresh` and `planar_rest`. The evaluators themselves are written once
// for the 4- and 8-lane types (exact_search_evaluators.h): here they run with vu16x8 (SSE2,
// NEON or scalar through simd.h), in exact_search_avx2.cpp with vu16x16; both are exact integer
// sums that stop once they reach a bound (the result is then >= the bound).
#pragma once

#include <cstdint>
#include <cstring>

#include "core/simd.h"
#include "pvrtc/encode/colour_scale_kernel.h"
#include "pvrtc/encode/search/exact_search_evaluators.h"
#include "pvrtc/encode/search/exact_search_window.h"
#include "pvrtc/format/pvrtc_kernel.h"

namespace tessera::pvrtc::detail {

// LocalWindow and PlanarWindow (the layouts) are in exact_search_window.h, with the AVX2 entry
// points of the evaluators (exact_search_avx2.cpp).

/// `local_error_lanes` (exact_search_evaluators.h) with vu16x8: two texels a vector, four a
/// step. kStore: no bound, each texel's error to texel_err[0 .. 52); kWeighted (with kAlpha):
/// alpha-weighted colour error (lw.weighted).
template <bool kAlpha, bool kStore = false, bool kWeighted = false>
inline std::uint32_t local_error_simd_t(const LocalWindow& lw, const Rgba5& a, const Rgba5& b,
                                        std::uint32_t bound, std::uint32_t* texel_err = nullptr) {
  const std::int32_t va[4] = {a.r, a.g, a.b, a.a}, vb[4] = {b.r, b.g, b.b, b.a};
  return local_error_lanes<kAlpha, kStore, kWeighted, simd::vu16x8>(lw, va, vb, bound, texel_err);
}

inline std::uint32_t local_error_simd(const LocalWindow& lw, const Rgba5& a, const Rgba5& b,
                                      std::uint32_t bound) {
  return lw.nch == 4 ? local_error_simd_t<true>(lw, a, b, bound)
                     : local_error_simd_t<false>(lw, a, b, bound);
}

/// `local_error_simd` with alpha-weighted colour error (lw.weighted, so nch 4).
inline std::uint32_t local_error_weighted(const LocalWindow& lw, const Rgba5& a, const Rgba5& b,
                                          std::uint32_t bound) {
  return local_error_simd_t<true, false, true>(lw, a, b, bound);
}

// The planar functions (PlanarWindow: exact_search_window.h) are kept out of line: inlined into
// the search loop they cost more instructions.

/// Channel-planar copy of `lw` (after any reordering of its texels).
[[gnu::noinline]] inline void build_planar(const LocalWindow& lw, PlanarWindow& pw) {
  using simd::vu16x8;
  pw.nch = lw.nch;
  pw.alpha_weight = lw.weight16[3];
  pw.weighted = lw.weighted;
  for (int g = 0; g < PlanarWindow::kGroups; ++g) {
    vu16x8 v[4];
    simd::transpose_8x4(&lw.rest16_a[8 * g][0], v);
    for (int c = 0; c < 4; ++c) simd::store_u16x8(v[c], &pw.ra[c][8 * g]);
    simd::transpose_8x4(&lw.rest16_b[8 * g][0], v);
    for (int c = 0; c < 4; ++c) simd::store_u16x8(v[c], &pw.rb[c][8 * g]);
    simd::transpose_8x4(&lw.t16[8 * g][0], v);
    for (int c = 0; c < 4; ++c) simd::store_u16x8(v[c], &pw.t[c][8 * g]);
    simd::transpose_8x4(&lw.own16[8 * g][0], v);
    simd::store_u16x8(v[0], &pw.own[8 * g]);
    if (lw.weighted) {
      simd::transpose_8x4(&lw.scale16[8 * g][0], v);
      simd::store_u16x8(v[0], &pw.scale[8 * g]);
    }
  }
  // The LocalWindow's biases are 0 or 2^24 (texel k at element 2k of each flat array).
  static_assert(PlanarWindow::kExclude == (1 << 24) >> 2);
  const std::int32_t* b35 = &lw.bias35[0][0];
  const std::int32_t* b4 = &lw.bias4[0][0];
  const std::int32_t* b4p = &lw.bias4p[0][0];
  for (int k = 0; k < 48; k += 4) {
    simd::store4(
        simd::srl<2>(simd::even_lanes(simd::load4(b35 + 2 * k), simd::load4(b35 + 2 * k + 4))),
        &pw.excl35[k]);
    simd::store4(
        simd::srl<2>(simd::even_lanes(simd::load4(b4 + 2 * k), simd::load4(b4 + 2 * k + 4))),
        &pw.excl4[k]);
    simd::store4(
        simd::srl<2>(simd::even_lanes(simd::load4(b4p + 2 * k), simd::load4(b4p + 2 * k + 4))),
        &pw.excl4p[k]);
  }
  pw.excl35[48] = b35[96] >> 2;
  pw.excl4[48] = b4[96] >> 2;
  pw.excl4p[48] = b4p[96] >> 2;
  for (int k = 49; k < 56; ++k) pw.excl35[k] = pw.excl4[k] = pw.excl4p[k] = 0;
}

/// Per-texel slot errors of the pair (a, b) (the block's current pair): `e`, then `total`.
/// kWeighted: colour differences scaled by pw.scale (pw.weighted).
template <bool kWeighted>
[[gnu::noinline]] inline void planar_refresh_t(PlanarWindow& pw, const Rgba5& a, const Rgba5& b) {
  using simd::vf32x4;
  using simd::vi32x4;
  using simd::vu16x8;
  const std::int32_t av[4] = {a.r, a.g, a.b, a.a}, bv[4] = {b.r, b.g, b.b, b.a};
  const vi32x4 w(pw.alpha_weight);
  for (int g = 0; g < PlanarWindow::kGroups; ++g) {
    const int o = 8 * g;
    const vu16x8 own = simd::load_u16x8(&pw.own[o]);
    vu16x8 bl[5], scale;
    if constexpr (kWeighted) scale = simd::load_u16x8(&pw.scale[o]);
    for (int c = 0; c < 3; ++c) {
      planar_blends<false>(own, simd::load_u16x8(&pw.ra[c][o]), simd::load_u16x8(&pw.rb[c][o]),
                           vu16x8{std::uint16_t(av[c])}, vu16x8{std::uint16_t(bv[c])}, bl);
      const vu16x8 t = simd::load_u16x8(&pw.t[c][o]);
      for (int sl = 0; sl < PlanarWindow::kSlots; ++sl) {
        vu16x8 d = bl[sl] - t;
        if constexpr (kWeighted) d = scale_diff16(d, scale);
        simd::store_u16x8(simd::mullo(d, d), &pw.e[c][sl][o]);  // d^2 <= 255^2: exact in u16
      }
    }
    vu16x8 ealpha[5], tt;  // alpha: squared errors per slot, and of alpha 0 (punch-through)
    if (pw.nch == 4) {
      planar_blends<true>(own, simd::load_u16x8(&pw.ra[3][o]), simd::load_u16x8(&pw.rb[3][o]),
                          vu16x8{std::uint16_t(av[3])}, vu16x8{std::uint16_t(bv[3])}, bl);
      const vu16x8 t = simd::load_u16x8(&pw.t[3][o]);
      for (int sl = 0; sl < PlanarWindow::kSlots; ++sl) {
        const vu16x8 d = bl[sl] - t;
        ealpha[sl] = simd::mullo(d, d);
      }
      tt = simd::mullo(t, t);
    }
    for (int sl = 0; sl < PlanarWindow::kSlots; ++sl) {
      const vu16x8 e0 = simd::load_u16x8(&pw.e[0][sl][o]), e1 = simd::load_u16x8(&pw.e[1][sl][o]),
                   e2 = simd::load_u16x8(&pw.e[2][sl][o]);
      vi32x4 lo = simd::widen32_lo(e0) + simd::widen32_lo(e1) + simd::widen32_lo(e2);
      vi32x4 hi = simd::widen32_hi(e0) + simd::widen32_hi(e1) + simd::widen32_hi(e2);
      vi32x4 plo, phi;  // punch-through (slot 4, RGBA): the colour of weight 4, alpha 0
      if (sl == 4 && pw.nch == 4) {
        plo = lo + simd::widen32_lo(tt) * w + simd::load4(&pw.excl4p[o]);
        phi = hi + simd::widen32_hi(tt) * w + simd::load4(&pw.excl4p[o + 4]);
      }
      if (pw.nch == 4) {
        lo += simd::widen32_lo(ealpha[sl]) * w;
        hi += simd::widen32_hi(ealpha[sl]) * w;
      }
      if (sl >= 2) {
        const std::int32_t* ex = sl == 4 ? pw.excl4 : pw.excl35;
        lo += simd::load4(&ex[o]);
        hi += simd::load4(&ex[o + 4]);
      }
      vf32x4 flo = simd::to_float(lo), fhi = simd::to_float(hi);
      if (sl == 4 && pw.nch == 4) {
        flo = simd::min(flo, simd::to_float(plo));
        fhi = simd::min(fhi, simd::to_float(phi));
      }
      simd::storef4(flo, &pw.total[sl][o]);
      simd::storef4(fhi, &pw.total[sl][o + 4]);
    }
  }
}

/// rest[c] from total and e[c] (after planar_refresh); c < 3.
[[gnu::noinline]] inline void planar_rest(PlanarWindow& pw, int c) {
  for (int sl = 0; sl < PlanarWindow::kSlots; ++sl) {
    for (int g = 0; g < PlanarWindow::kGroups; ++g) {
      const int o = 8 * g;
      const simd::vu16x8 e = simd::load_u16x8(&pw.e[c][sl][o]);
      simd::storef4(simd::loadf4(&pw.total[sl][o]) - simd::f2p23_plus_lo(e), &pw.rest[c][sl][o]);
      simd::storef4(simd::loadf4(&pw.total[sl][o + 4]) - simd::f2p23_plus_hi(e),
                    &pw.rest[c][sl][o + 4]);
    }
  }
}

/// Exact window error of the current pair with colour channel c (< 3) of A and B set to av, bv
/// (5-bit values), given planar_refresh and planar_rest(c) for the current pair:
/// `planar_error_lanes` (exact_search_evaluators.h) with vu16x8, 8 texels a step; stops once it
/// reaches `bound` (the result is then >= bound). kWeighted: as planar_refresh_t.
template <bool kWeighted>
[[gnu::noinline]] inline std::uint32_t planar_error_t(const PlanarWindow& pw, int c,
                                                      std::int32_t av, std::int32_t bv,
                                                      std::uint32_t bound) {
  return planar_error_lanes<kWeighted, simd::vu16x8>(pw, c, av, bv, bound);
}

inline void planar_refresh(PlanarWindow& pw, const Rgba5& a, const Rgba5& b) {
  planar_refresh_t<false>(pw, a, b);
}
inline std::uint32_t planar_error(const PlanarWindow& pw, int c, std::int32_t av, std::int32_t bv,
                                  std::uint32_t bound) {
  return planar_error_t<false>(pw, c, av, bv, bound);
}

/// The one colour channel (0-2) in which (a, b) differs from (ca, cb), or -1 (none, or another
/// channel too; alpha counts only when nch is 4).
inline int single_colour_channel(const Rgba5& a, const Rgba5& b, const Rgba5& ca, const Rgba5& cb,
                                 int nch) {
  if (nch == 4 && (a.a != ca.a || b.a != cb.a)) return -1;
  const bool dr = a.r != ca.r || b.r != cb.r, dg = a.g != ca.g || b.g != cb.g,
             db = a.b != ca.b || b.b != cb.b;
  if (int(dr) + int(dg) + int(db) != 1) return -1;
  return dr ? 0 : dg ? 1 : 2;
}

}  // namespace tessera::pvrtc::detail
