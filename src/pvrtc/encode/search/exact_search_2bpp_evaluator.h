// exact_search_2bpp_evaluator.h — the window evaluator of the 2 bpp exact search
// (exact_search_2bpp.cpp), written once over the SIMD wrapper's 16-bit lane types: compiled with
// vu16x8 (two texels a vector, four a step) in exact_search_2bpp.cpp's baseline and with
// vu16x16 (four texels a vector, eight a step) in exact_search_2bpp_avx2.cpp. The same
// operations lane for lane, so the same per-texel errors; the per-width pieces (the minimum over
// the blends in float lanes on 4, integers on 8; the texel order of pair_sums' lanes) are the
// overloads of exact_search_lanes.h, shared with the 4 bpp evaluators.
//
// Included by the -mavx2 translation unit: everything here is a template in an anonymous
// namespace (internal linkage), so no AVX2-compiled copy can stand in for a baseline one.
#pragma once

#include <cstdint>

#include "core/simd.h"
#include "pvrtc/encode/search/exact_search_lanes.h"
#include "pvrtc/encode/search/exact_search_window.h"

namespace tessera::pvrtc::detail {
namespace {

/// Squared errors of the texels in one vector (slots k, k + 1, ...: as many as V holds four
/// lanes), per blend: weight 0 (A), 8 (B), 3, 5 and 4. Lanes (texel RG, texel BA) per texel,
/// the sums of each texel's two channel pairs (weighted by `aw` with alpha).
template <class V>
struct BlendSq2 {
  decltype(simd::madd(V(), V())) e0, e8, e3, e5, e4;
};

/// The decoder's arithmetic: 8-bit colour (S >> 7) + (S >> 2) and alpha (S >> 5) + (S >> 1) of
/// the bilinear sum S = rest + own * endpoint, blends 3 and 5 from 4 (A + B) +- (A - B) (the
/// 16-bit lanes wrap in between; exact results) and 4 from A + B. `av` / `bv`: the endpoints'
/// (r, g, b, a) in every texel's four lanes; `aw`: the per-lane error weights.
template <bool kAlpha, class V>
inline void blend_sq2(const Window2& w, int k, V av, V bv, V aw, BlendSq2<V>& o) {
  const V own = simd::load_as<V>(&w.own[k][0]);
  const V sa = simd::load_as<V>(&w.rest_a[k][0]) + simd::mullo(own, av);
  const V sb = simd::load_as<V>(&w.rest_b[k][0]) + simd::mullo(own, bv);
  V ua = simd::srl<7>(sa) + simd::srl<2>(sa), ub = simd::srl<7>(sb) + simd::srl<2>(sb);
  if constexpr (kAlpha) {
    ua = simd::select_alpha(ua, simd::srl<5>(sa) + simd::srl<1>(sa));
    ub = simd::select_alpha(ub, simd::srl<5>(sb) + simd::srl<1>(sb));
  }
  const V t = simd::load_as<V>(&w.t[k][0]);
  auto err = [&](V v) {
    const V d = v - t;
    return kAlpha ? simd::madd(d, simd::mullo(d, aw)) : simd::madd(d, d);
  };
  decoder_blend_errors(ua, ub, err, o);
}

/// The window error of block j's endpoints (a, b) ((r, g, b, a) 5-bit values), kLanes<V> / 2
/// texels a step; stops once it reaches `bound` (the result is then >= bound; checked once a
/// step, so every 4 or 8 texels, which changes nothing below it). kAlpha: RGBA input (alpha
/// lanes, weighted alpha error). kStore: no bound; each slot's error to texel_err[0 .. 112).
/// The texels' blend exclusions (w.bias35, w.bias4) are added before the minimum.
template <bool kAlpha, bool kStore, class V>
inline std::uint32_t window2_error_lanes(const Window2& w, const std::int32_t a[4],
                                         const std::int32_t b[4], std::uint32_t bound,
                                         std::uint32_t* texel_err) {
  using VI = decltype(simd::madd(V(), V()));
  constexpr int kStep = simd::kLanes<VI>;  // texels a step: two vectors of kStep / 2
  static_assert(Window2::kSlots % kStep == 0);
  const V av = endpoint_lanes<V>(a), bv = endpoint_lanes<V>(b);
  const V aw = twice_lanes<V>(w.weight16);
  VI acc;
  for (int s = 0; s < Window2::kSlots / kStep; ++s) {
    BlendSq2<V> x, y;
    blend_sq2<kAlpha>(w, kStep * s, av, bv, aw, x);
    blend_sq2<kAlpha>(w, kStep * s + kStep / 2, av, bv, aw, y);
    using simd::pair_sums;
    const VI b35 = load_texel_lanes<VI>(&w.bias35[kStep * s]);
    const VI b4 = load_texel_lanes<VI>(&w.bias4[kStep * s]);
    const VI m = int_lanes(simd::min(
        simd::min(simd::min(min_lanes(pair_sums(x.e0, y.e0)), min_lanes(pair_sums(x.e8, y.e8))),
                  simd::min(min_lanes(pair_sums(x.e3, y.e3) + b35),
                            min_lanes(pair_sums(x.e5, y.e5) + b35))),
        min_lanes(pair_sums(x.e4, y.e4) + b4)));
    acc += m;
    if constexpr (kStore) {
      store_texel_errors(m, reinterpret_cast<std::int32_t*>(texel_err + kStep * s), kStep);
    } else {
      if (std::uint32_t(simd::sum_lanes(acc)) >= bound) break;
    }
  }
  return std::uint32_t(simd::sum_lanes(acc));
}

/// `window2_error_lanes` for the window's channel count, bounded.
template <class V>
inline std::uint32_t window2_error_bounded(const Window2& w, const std::int32_t a[4],
                                           const std::int32_t b[4], std::uint32_t bound) {
  return w.nch == 4 ? window2_error_lanes<true, false, V>(w, a, b, bound, nullptr)
                    : window2_error_lanes<false, false, V>(w, a, b, bound, nullptr);
}

/// `window2_error_lanes` for the window's channel count, no bound, each slot's error stored.
template <class V>
inline std::uint32_t window2_error_stored(const Window2& w, const std::int32_t a[4],
                                          const std::int32_t b[4], std::uint32_t* texel_err) {
  return w.nch == 4 ? window2_error_lanes<true, true, V>(w, a, b, 0, texel_err)
                    : window2_error_lanes<false, true, V>(w, a, b, 0, texel_err);
}

}  // namespace
}  // namespace tessera::pvrtc::detail
