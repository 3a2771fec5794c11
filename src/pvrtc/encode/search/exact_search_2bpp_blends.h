// exact_search_2bpp_blends.h — the per-texel blend errors of the 2 bpp exact search's window
// evaluator, written once over the SIMD wrapper's 16-bit lane types: compiled with vu16x8 (two
// texels a vector) in exact_search_2bpp.cpp's baseline evaluator and with vu16x16 (four texels)
// in exact_search_2bpp_avx2.cpp. Each evaluator then takes the minimum over the blends and the
// window sum its own way (float lanes on SSE2, which has no 32-bit integer minimum; integers on
// AVX2; the same numbers).
//
// Included by the -mavx2 translation unit: everything here is a template in an anonymous
// namespace (internal linkage), so no AVX2-compiled copy can stand in for a baseline one.
#pragma once

#include <cstdint>

#include "core/simd.h"
#include "pvrtc/encode/search/exact_search_window.h"

namespace tessera::pvrtc::detail {
namespace {

/// Sixteen-bit lanes of `V` (simd::vu16x8 or simd::vu16x16) loaded from p.
template <class V>
V load_blend_lanes(const std::uint16_t* p);
template <>
[[maybe_unused]] inline simd::vu16x8 load_blend_lanes<simd::vu16x8>(const std::uint16_t* p) {
  return simd::load_u16x8(p);
}
template <>
[[maybe_unused]] inline simd::vu16x16 load_blend_lanes<simd::vu16x16>(const std::uint16_t* p) {
  return simd::load_u16x16(p);
}

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
  const V own = load_blend_lanes<V>(&w.own[k][0]);
  const V sa = load_blend_lanes<V>(&w.rest_a[k][0]) + simd::mullo(own, av);
  const V sb = load_blend_lanes<V>(&w.rest_b[k][0]) + simd::mullo(own, bv);
  V ua = simd::srl<7>(sa) + simd::srl<2>(sa), ub = simd::srl<7>(sb) + simd::srl<2>(sb);
  if constexpr (kAlpha) {
    ua = simd::select_alpha(ua, simd::srl<5>(sa) + simd::srl<1>(sa));
    ub = simd::select_alpha(ub, simd::srl<5>(sb) + simd::srl<1>(sb));
  }
  const V t = load_blend_lanes<V>(&w.t[k][0]);
  auto err = [&](V v) {
    const V d = v - t;
    return kAlpha ? simd::madd(d, simd::mullo(d, aw)) : simd::madd(d, d);
  };
  const V sum = ua + ub, sum2 = sum + sum, sum4 = sum2 + sum2, diff = ua - ub;
  o.e0 = err(ua);
  o.e8 = err(ub);
  o.e3 = err(simd::srl<3>(sum4 + diff));
  o.e5 = err(simd::srl<3>(sum4 - diff));
  o.e4 = err(simd::srl<1>(sum));
}

}  // namespace
}  // namespace tessera::pvrtc::detail
