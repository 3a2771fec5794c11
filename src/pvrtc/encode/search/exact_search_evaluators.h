// exact_search_evaluators.h — the window evaluators of the 4 bpp exact search, written once over
// the SIMD wrapper's 16-bit lane types: compiled with vu16x8 in the baseline
// (exact_search_kernel.h: `local_error_simd_t`, `planar_error_t`) and with vu16x16 in
// exact_search_avx2.cpp (twice the texels a vector), alpha-weighted colour error (kWeighted)
// included; the per-width pieces are the overloads of exact_search_lanes.h. `local_error_lanes`
// scores any candidate endpoint pair of one block over the 7x7 texels it influences
// (LocalWindow); `planar_error_lanes` scores a candidate that differs from the block's current
// pair in one colour channel only, kLanes<V> texels a vector, from each texel's per-blend error
// of the other channels under the current pair (PlanarWindow). Both are exact integer sums that
// stop once they reach a bound (the result is then >= the bound; the bound is checked once a
// step, so the 8-lane evaluators check it half as often, which changes nothing below it).
//
// Included by the -mavx2 translation unit: everything here is a template or inline function in
// an anonymous namespace (internal linkage), so no AVX2-compiled copy can stand in for a
// baseline one.
#pragma once

#include <cstdint>

#include "core/simd.h"
#include "pvrtc/encode/colour_scale_kernel.h"
#include "pvrtc/encode/search/exact_search_lanes.h"
#include "pvrtc/encode/search/exact_search_window.h"

namespace tessera::pvrtc::detail {
namespace {

/// Squared errors of the texels of one vector (kLanes<V> / 4 of them, from slot k on), per
/// blend: weight 0 (A), 8 (B), 3, 5, 4 and 4 with alpha punched through (kAlpha only). Lanes
/// (texel RG, texel BA) per texel, each the sum of its two channels' (weighted) squares.
template <class V>
struct BlendSq4 {
  decltype(simd::madd(V(), V())) e0, e8, e3, e5, e4, e4p;
};

/// The decoder's arithmetic from the window's bilinear sums S (weights sum to 16): 8-bit colour
/// (2S >> 7) + (2S >> 2), alpha (2S >> 5) + (2S >> 1) (alpha lanes are all zero for RGB input);
/// the blends (A (8 - m) + B m) >> 3 (decoder_blends). kWeighted (with
/// kAlpha): each difference scaled by lw.scale16 first (`scale_diff16`: the alpha lanes' scale
/// is 16, so alpha is as it was; magnitudes never grow, so the float-minimum bound still holds).
template <bool kAlpha, bool kWeighted, class V>
inline void blend_sq4(const LocalWindow& lw, int k, V av, V bv, V aw, BlendSq4<V>& o) {
  static_assert(kAlpha || !kWeighted);
  const V own = simd::load_as<V>(&lw.own16[k][0]);
  const V sa = simd::load_as<V>(&lw.rest16_a[k][0]) + simd::mullo(own, av);
  const V sb = simd::load_as<V>(&lw.rest16_b[k][0]) + simd::mullo(own, bv);
  V ua = simd::srl<6>(sa) + simd::srl<1>(sa), ub = simd::srl<6>(sb) + simd::srl<1>(sb);
  if constexpr (kAlpha) {
    ua = simd::select_alpha(ua, simd::srl<4>(sa) + sa);
    ub = simd::select_alpha(ub, simd::srl<4>(sb) + sb);
  }
  const V t = simd::load_as<V>(&lw.t16[k][0]);
  V scale;
  if constexpr (kWeighted) scale = simd::load_as<V>(&lw.scale16[k][0]);
  auto err = [&](V v) {
    V d = v - t;
    if constexpr (kWeighted) d = scale_diff16(d, scale);
    return kAlpha ? simd::madd(d, simd::mullo(d, aw)) : simd::madd(d, d);
  };
  const V v4 = decoder_blend_errors(ua, ub, err, o);
  if constexpr (kAlpha) o.e4p = err(simd::select_alpha(v4, V()));
}

/// Exact error of the local window with (a, b) ((r, g, b, a) 5-bit values) as block j's
/// endpoints, kLanes<V> / 2 texels a step; stops once it reaches `bound` (the result is then
/// >= bound). kAlpha: RGBA input (alpha lanes, punch-through blend, weighted alpha error); RGB
/// skips those. kStore: no bound; each texel's error goes to texel_err[slot] (slots 0 .. 52 in
/// layout order; 49-51 are pads, error 0). kWeighted: as blend_sq4. Out of line: inlined into
/// the search's candidate loop (the baseline's 4-lane copy) it pushes that loop's own helpers
/// out of line, which costs the AVX2 path more than the call.
template <bool kAlpha, bool kStore, bool kWeighted, class V>
[[gnu::noinline]] inline std::uint32_t local_error_lanes(const LocalWindow& lw,
                                                         const std::int32_t a[4],
                                                         const std::int32_t b[4],
                                                         std::uint32_t bound,
                                                         std::uint32_t* texel_err) {
  using VI = decltype(simd::madd(V(), V()));
  constexpr int kStep = simd::kLanes<VI>;  // texels a step: two vectors of kStep / 2
  constexpr int kSteps = (52 + kStep - 1) / kStep;
  const V av = endpoint_lanes<V>(a), bv = endpoint_lanes<V>(b);
  const V aw = twice_lanes<V>(lw.weight16);
  VI acc;
  for (int s = 0; s < kSteps; ++s) {
    BlendSq4<V> x, y;
    blend_sq4<kAlpha, kWeighted>(lw, kStep * s, av, bv, aw, x);
    blend_sq4<kAlpha, kWeighted>(lw, kStep * s + kStep / 2, av, bv, aw, y);
    using simd::pair_sums;
    // The biases of the step's texels (texel k at element 2k), in the lane order of pair_sums.
    auto bias = [&](const std::int32_t(*rows)[4]) {
      return simd::even_lanes(simd::load_as<VI>(rows[kStep / 2 * s]),
                              simd::load_as<VI>(rows[kStep / 2 * s + kStep / 4]));
    };
    const VI b35 = bias(lw.bias35);
    auto m4 = min_lanes(pair_sums(x.e4, y.e4) + bias(lw.bias4));
    if constexpr (kAlpha) m4 = simd::min(m4, min_lanes(pair_sums(x.e4p, y.e4p) + bias(lw.bias4p)));
    const VI m = int_lanes(simd::min(
        simd::min(simd::min(min_lanes(pair_sums(x.e0, y.e0)), min_lanes(pair_sums(x.e8, y.e8))),
                  simd::min(min_lanes(pair_sums(x.e3, y.e3) + b35),
                            min_lanes(pair_sums(x.e5, y.e5) + b35))),
        m4));
    acc += m;
    if constexpr (kStore) {
      const int n = 52 - kStep * s < kStep ? 52 - kStep * s : kStep;
      store_texel_errors(m, reinterpret_cast<std::int32_t*>(texel_err + kStep * s), n);
    } else {
      if (std::uint32_t(simd::sum_lanes(acc)) >= bound) break;
    }
  }
  return std::uint32_t(simd::sum_lanes(acc));
}

/// The five blends of the texels of one channel (c < 3: colour, 3: alpha) for endpoint values
/// av, bv: slots 0: A, 1: B, 2: (5A + 3B) >> 3, 3: (3A + 5B) >> 3, 4: (A + B) >> 1.
template <bool kAlphaChannel, class V>
inline void planar_blends(V own, V ra, V rb, V av, V bv, V out[5]) {
  const V sa = ra + simd::mullo(own, av), sb = rb + simd::mullo(own, bv);
  V ua, ub;
  if constexpr (kAlphaChannel) {
    ua = simd::srl<4>(sa) + sa;
    ub = simd::srl<4>(sb) + sb;
  } else {
    ua = simd::srl<6>(sa) + simd::srl<1>(sa);
    ub = simd::srl<6>(sb) + simd::srl<1>(sb);
  }
  decoder_blends(ua, ub, out);
}

/// A PlanarWindow plane's texels o .. o + kLanes<V> - 1 (kTail: o .. o + 7, the rest zero), in
/// the lane order whose f2p23_plus_lo / _hi give texels in order: as they are for vu16x8,
/// (0-3 8-11 | 4-7 12-15) for vu16x16 (64-bit units permuted).
template <bool kTail>
[[maybe_unused]] inline simd::vu16x8 planar_load(const std::uint16_t* p, simd::vu16x8) {
  return simd::load_u16x8(p);
}
template <bool kTail>
[[maybe_unused]] inline simd::vu16x16 planar_load(const std::uint16_t* p, simd::vu16x16) {
  const simd::vu16x16 v =
      kTail ? simd::vu16x16(simd::load_u16x8(p), simd::vu16x8()) : simd::load_u16x16(p);
  return simd::permute64<0, 2, 1, 3>(v);
}

/// Texels o .. o + kLanes<V> - 1 (kTail: o .. o + 7) of channel c: per texel the minimum over
/// the slots of (2^23 + d^2) + rest, as 32-bit lanes (two texel groups added lane for lane).
template <bool kTail, bool kWeighted, class V>
inline auto planar_group(const PlanarWindow& pw, int c, int o, V a16, V b16) {
  using VF = decltype(simd::f2p23_plus_lo(V()));
  constexpr int kHalf = simd::kLanes<V> / 2;
  V bl[5];
  planar_blends<false>(planar_load<kTail>(&pw.own[o], V()), planar_load<kTail>(&pw.ra[c][o], V()),
                       planar_load<kTail>(&pw.rb[c][o], V()), a16, b16, bl);
  const V t = planar_load<kTail>(&pw.t[c][o], V());
  V scale;
  if constexpr (kWeighted) scale = planar_load<kTail>(&pw.scale[o], V());
  VF mlo, mhi;
  for (int sl = 0; sl < PlanarWindow::kSlots; ++sl) {
    V d = bl[sl] - t;
    if constexpr (kWeighted) d = scale_diff16(d, scale);
    const V sq = simd::mullo(d, d);
    // (2^23 + d^2) + (total - e - 2^23): exact integers below 2^24.
    const VF lo = simd::f2p23_plus_lo(sq) + simd::load_as<VF>(&pw.rest[c][sl][o]);
    mlo = sl == 0 ? lo : simd::min(mlo, lo);
    if constexpr (!kTail) {
      const VF hi = simd::f2p23_plus_hi(sq) + simd::load_as<VF>(&pw.rest[c][sl][o + kHalf]);
      mhi = sl == 0 ? hi : simd::min(mhi, hi);
    }
  }
  if constexpr (kTail) {
    return simd::to_int_trunc(mlo);
  } else {
    return simd::to_int_trunc(mlo) + simd::to_int_trunc(mhi);
  }
}

/// Exact window error of the current pair with colour channel c (< 3) of A and B set to av, bv
/// (5-bit values), given planar_refresh and planar_rest(c) for the current pair, kLanes<V>
/// texels a step; stops once it reaches `bound` (the result is then >= bound). kWeighted:
/// colour differences scaled by pw.scale (pw.weighted).
template <bool kWeighted, class V>
inline std::uint32_t planar_error_lanes(const PlanarWindow& pw, int c, std::int32_t av,
                                        std::int32_t bv, std::uint32_t bound) {
  constexpr int kTexels = 56;  // PlanarWindow's planes: 49 texels and 7 pads
  constexpr int kStep = simd::kLanes<V>;
  const V a16{std::uint16_t(av)}, b16{std::uint16_t(bv)};
  decltype(simd::madd(V(), V())) acc;
  int o = 0;
  for (; o + kStep <= kTexels; o += kStep) {
    acc += planar_group<false, kWeighted>(pw, c, o, a16, b16);
    if (std::uint32_t(simd::sum_lanes(acc)) >= bound) return std::uint32_t(simd::sum_lanes(acc));
  }
  if constexpr (kTexels % kStep != 0) {
    static_assert(kTexels % kStep == 8);
    acc += planar_group<true, kWeighted>(pw, c, o, a16, b16);
  }
  return std::uint32_t(simd::sum_lanes(acc));
}

}  // namespace
}  // namespace tessera::pvrtc::detail
