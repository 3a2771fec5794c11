// exact_search_kernel.h — the exact window evaluators of the PVRTC 4 bpp exact search
// (exact_search.cpp): `LocalWindow` / `local_error_simd` score any candidate endpoint pair of one
// block over the 7x7 texels it influences; `PlanarWindow` / `planar_error` score a candidate that
// differs from the block's current pair in one colour channel only, eight texels per vector, from
// each texel's per-blend error of the other channels under the current pair. Both are exact integer
// sums that stop once they reach a bound (the result is then >= the bound).
#pragma once

#include <cstdint>
#include <cstring>

#include "core/simd.h"
#include "pvrtc/encode/colour_scale_kernel.h"
#include "pvrtc/encode/search/exact_search_window.h"
#include "pvrtc/format/pvrtc_kernel.h"

namespace tessera::pvrtc::detail {

// LocalWindow and PlanarWindow (the layouts) are in exact_search_window.h, with the AVX2 versions
// of the evaluators below (exact_search_avx2.cpp).

// Exact error of the local window with (a, b) as block j's endpoints, two texels at a time;
// stops once it reaches `bound` (the result is then >= bound). kAlpha: RGBA input (alpha
// lanes, punch-through blend, weighted alpha error); RGB skips those. With the blends from
// A + B and A - B (fewer operations per blend, same output).
// kStore: no bound; each texel's error goes to texel_err[slot] (slots in layout order).
// kWeighted (with kAlpha): each difference scaled by lw.scale16 first (`scale_diff16`: the
// alpha lanes' scale is 16, so alpha is as it was; magnitudes never grow, so the float-minimum
// bound below still holds).
template <bool kAlpha, bool kStore = false, bool kWeighted = false>
inline std::uint32_t local_error_simd_t(const LocalWindow& lw, const Rgba5& a, const Rgba5& b,
                                        std::uint32_t bound, std::uint32_t* texel_err = nullptr) {
  using simd::vint4;
  using simd::vu16x8;
  alignas(16) const std::uint16_t a16[8] = {
      std::uint16_t(a.r), std::uint16_t(a.g), std::uint16_t(a.b), std::uint16_t(a.a),
      std::uint16_t(a.r), std::uint16_t(a.g), std::uint16_t(a.b), std::uint16_t(a.a)};
  alignas(16) const std::uint16_t b16[8] = {
      std::uint16_t(b.r), std::uint16_t(b.g), std::uint16_t(b.b), std::uint16_t(b.a),
      std::uint16_t(b.r), std::uint16_t(b.g), std::uint16_t(b.b), std::uint16_t(b.a)};
  const vu16x8 av = simd::load_u16x8(a16), bv = simd::load_u16x8(b16);
  alignas(16) static constexpr std::uint16_t kAlphaLanes[8] = {0, 0, 0, 0xffff, 0, 0, 0, 0xffff};
  alignas(16) static constexpr std::uint16_t kRgbLanes[8] = {0xffff, 0xffff, 0xffff, 0,
                                                             0xffff, 0xffff, 0xffff, 0};
  const vu16x8 alpha = simd::load_u16x8(kAlphaLanes), rgb = simd::load_u16x8(kRgbLanes);
  const vu16x8 aw = simd::load_u16x8(lw.weight16);
  // Squared errors of pair p's blends, lanes (texel 0 RG, texel 0 BA, texel 1 RG, texel 1 BA).
  struct PairSq {
    vint4 e0, e8, e3, e5, e4, e4p;
  };
  auto pair_sq = [&](int p, PairSq& o) {
    const vu16x8 own = simd::load_u16x8(&lw.own16[2 * p][0]);
    // Bilinear sums S (weights sum to 16); 8-bit colour (2S >> 7) + (2S >> 2), alpha
    // (2S >> 5) + (2S >> 1). (Alpha lanes are all zero for RGB input.)
    const vu16x8 sa = simd::load_u16x8(&lw.rest16_a[2 * p][0]) + simd::mullo(own, av);
    const vu16x8 sb = simd::load_u16x8(&lw.rest16_b[2 * p][0]) + simd::mullo(own, bv);
    vu16x8 ua = simd::srl<6>(sa) + simd::srl<1>(sa), ub = simd::srl<6>(sb) + simd::srl<1>(sb);
    if constexpr (kAlpha) {
      ua = simd::select(alpha, simd::srl<4>(sa) + sa, ua);
      ub = simd::select(alpha, simd::srl<4>(sb) + sb, ub);
    }
    const vu16x8 t = simd::load_u16x8(&lw.t16[2 * p][0]);
    static_assert(kAlpha || !kWeighted);
    vu16x8 scale;
    if constexpr (kWeighted) scale = simd::load_u16x8(&lw.scale16[2 * p][0]);
    auto err = [&](vu16x8 d) {
      if constexpr (kWeighted) d = scale_diff16(d, scale);
      return kAlpha ? simd::madd(d, simd::mullo(d, aw)) : simd::madd(d, d);
    };
    // Blends (A (8 - m) + B m) >> 3 from the sum: 4 (A + B) +- (A - B) for m = 3, 5 (the u16
    // lanes wrap in between, the results are exact), (A + B) >> 1 for m = 4.
    const vu16x8 sum = ua + ub, sum2 = sum + sum, sum4 = sum2 + sum2, diff = ua - ub;
    o.e0 = err(ua - t);
    o.e8 = err(ub - t);
    o.e3 = err(simd::srl<3>(sum4 + diff) - t);
    o.e5 = err(simd::srl<3>(sum4 - diff) - t);
    const vu16x8 v4 = simd::srl<1>(sum);
    o.e4 = err(v4 - t);
    if constexpr (kAlpha) o.e4p = err((v4 & rgb) - t);
  };
  // Four texels (two pairs) per step: the per-texel sums of the two pairs' lanes, then the
  // minimum over the blends in float lanes (SSE2 has no 32-bit integer min; fewer
  // instructions than emulating it): errors are far below 2^24 (exact in float), excluded blends
  // (2^24 and up) stay at least 2^24 once rounded, and e0 / e8 are never excluded, so the minimum
  // is the exact integer minimum.
  vint4 acc;
  for (int q = 0; q < 13; ++q) {
    PairSq x, y;
    pair_sq(2 * q, x);
    pair_sq(2 * q + 1, y);
    using simd::pair_sums;
    using simd::to_float;
    auto bias = [&](const std::int32_t(*rows)[4]) {
      return simd::even_lanes(simd::load4(rows[2 * q]), simd::load4(rows[2 * q + 1]));
    };
    const vint4 b35 = bias(lw.bias35);
    simd::vf4 m4 = to_float(pair_sums(x.e4, y.e4) + bias(lw.bias4));
    if constexpr (kAlpha) {
      m4 = simd::min(m4, to_float(pair_sums(x.e4p, y.e4p) + bias(lw.bias4p)));
    }
    const vint4 m = simd::to_int_trunc(simd::min(
        simd::min(simd::min(to_float(pair_sums(x.e0, y.e0)), to_float(pair_sums(x.e8, y.e8))),
                  simd::min(to_float(pair_sums(x.e3, y.e3) + b35),
                            to_float(pair_sums(x.e5, y.e5) + b35))),
        m4));
    acc += m;
    if constexpr (kStore) {
      alignas(16) std::int32_t m32[4];
      simd::store4(m, m32);
      for (int i = 0; i < 4; ++i) texel_err[4 * q + i] = std::uint32_t(m32[i]);
    } else {
      if (std::uint32_t(simd::sum_lanes(acc)) >= bound) break;
    }
  }
  return std::uint32_t(simd::sum_lanes(acc));
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

namespace planar_detail {
// The five blends of 8 texels of one channel (c < 3: colour, 3: alpha) for endpoint values
// av, bv: slots 0: A, 1: B, 2: (5A + 3B) >> 3, 3: (3A + 5B) >> 3, 4: (A + B) >> 1.
template <bool kAlphaChannel>
inline void blends(simd::vu16x8 own, simd::vu16x8 ra, simd::vu16x8 rb, simd::vu16x8 av,
                   simd::vu16x8 bv, simd::vu16x8 out[5]) {
  using simd::vu16x8;
  const vu16x8 sa = ra + simd::mullo(own, av), sb = rb + simd::mullo(own, bv);
  vu16x8 ua, ub;
  if constexpr (kAlphaChannel) {
    ua = simd::srl<4>(sa) + sa;
    ub = simd::srl<4>(sb) + sb;
  } else {
    ua = simd::srl<6>(sa) + simd::srl<1>(sa);
    ub = simd::srl<6>(sb) + simd::srl<1>(sb);
  }
  const vu16x8 sum = ua + ub, sum2 = sum + sum, sum4 = sum2 + sum2, diff = ua - ub;
  out[0] = ua;
  out[1] = ub;
  out[2] = simd::srl<3>(sum4 + diff);
  out[3] = simd::srl<3>(sum4 - diff);
  out[4] = simd::srl<1>(sum);
}
inline std::int32_t channel_value(const Rgba5& x, int c) {
  return c == 0 ? x.r : c == 1 ? x.g : c == 2 ? x.b : x.a;
}
}  // namespace planar_detail

/// Per-texel slot errors of the pair (a, b) (the block's current pair): `e`, then `total`.
/// kWeighted: colour differences scaled by pw.scale (pw.weighted).
template <bool kWeighted>
[[gnu::noinline]] inline void planar_refresh_t(PlanarWindow& pw, const Rgba5& a, const Rgba5& b) {
  using simd::vf4;
  using simd::vint4;
  using simd::vu16x8;
  const std::int32_t av[4] = {a.r, a.g, a.b, a.a}, bv[4] = {b.r, b.g, b.b, b.a};
  const vint4 w(pw.alpha_weight);
  for (int g = 0; g < PlanarWindow::kGroups; ++g) {
    const int o = 8 * g;
    const vu16x8 own = simd::load_u16x8(&pw.own[o]);
    vu16x8 bl[5], scale;
    if constexpr (kWeighted) scale = simd::load_u16x8(&pw.scale[o]);
    for (int c = 0; c < 3; ++c) {
      planar_detail::blends<false>(own, simd::load_u16x8(&pw.ra[c][o]),
                                   simd::load_u16x8(&pw.rb[c][o]), vu16x8{std::uint16_t(av[c])},
                                   vu16x8{std::uint16_t(bv[c])}, bl);
      const vu16x8 t = simd::load_u16x8(&pw.t[c][o]);
      for (int sl = 0; sl < PlanarWindow::kSlots; ++sl) {
        vu16x8 d = bl[sl] - t;
        if constexpr (kWeighted) d = scale_diff16(d, scale);
        simd::store_u16x8(simd::mullo(d, d), &pw.e[c][sl][o]);  // d^2 <= 255^2: exact in u16
      }
    }
    vu16x8 ealpha[5], tt;  // alpha: squared errors per slot, and of alpha 0 (punch-through)
    if (pw.nch == 4) {
      planar_detail::blends<true>(own, simd::load_u16x8(&pw.ra[3][o]),
                                  simd::load_u16x8(&pw.rb[3][o]), vu16x8{std::uint16_t(av[3])},
                                  vu16x8{std::uint16_t(bv[3])}, bl);
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
      vint4 lo = simd::widen32_lo(e0) + simd::widen32_lo(e1) + simd::widen32_lo(e2);
      vint4 hi = simd::widen32_hi(e0) + simd::widen32_hi(e1) + simd::widen32_hi(e2);
      vint4 plo, phi;  // punch-through (slot 4, RGBA): the colour of weight 4, alpha 0
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
      vf4 flo = simd::to_float(lo), fhi = simd::to_float(hi);
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
/// (5-bit values), given planar_refresh and planar_rest(c) for the current pair; stops once it
/// reaches `bound` (the result is then >= bound). kWeighted: as planar_refresh_t.
template <bool kWeighted>
[[gnu::noinline]] inline std::uint32_t planar_error_t(const PlanarWindow& pw, int c,
                                                      std::int32_t av, std::int32_t bv,
                                                      std::uint32_t bound) {
  using simd::vf4;
  using simd::vint4;
  using simd::vu16x8;
  const vu16x8 a16{std::uint16_t(av)}, b16{std::uint16_t(bv)};
  vint4 acc;
  for (int g = 0; g < PlanarWindow::kGroups; ++g) {
    const int o = 8 * g;
    vu16x8 bl[5];
    planar_detail::blends<false>(simd::load_u16x8(&pw.own[o]), simd::load_u16x8(&pw.ra[c][o]),
                                 simd::load_u16x8(&pw.rb[c][o]), a16, b16, bl);
    const vu16x8 t = simd::load_u16x8(&pw.t[c][o]);
    vu16x8 scale;
    if constexpr (kWeighted) scale = simd::load_u16x8(&pw.scale[o]);
    vf4 mlo, mhi;
    for (int sl = 0; sl < PlanarWindow::kSlots; ++sl) {
      vu16x8 d = bl[sl] - t;
      if constexpr (kWeighted) d = scale_diff16(d, scale);
      const vu16x8 sq = simd::mullo(d, d);
      // (2^23 + d^2) + (total - e - 2^23): exact integers below 2^24.
      const vf4 lo = simd::f2p23_plus_lo(sq) + simd::loadf4(&pw.rest[c][sl][o]);
      const vf4 hi = simd::f2p23_plus_hi(sq) + simd::loadf4(&pw.rest[c][sl][o + 4]);
      mlo = sl == 0 ? lo : simd::min(mlo, lo);
      mhi = sl == 0 ? hi : simd::min(mhi, hi);
    }
    acc += simd::to_int_trunc(mlo) + simd::to_int_trunc(mhi);
    if (std::uint32_t(simd::sum_lanes(acc)) >= bound) break;
  }
  return std::uint32_t(simd::sum_lanes(acc));
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
