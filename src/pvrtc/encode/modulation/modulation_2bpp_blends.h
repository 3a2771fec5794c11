// modulation_2bpp_blends.h — the per-texel arithmetic of the 2 bpp modulation passes, written
// once over the SIMD wrapper's 16-bit lane types: compiled with vu16x8 (one block's 8 texels of
// a row) in modulation_2bpp.cpp and with vu16x16 (two blocks) in modulation_2bpp_avx2.cpp. The
// passes load their rows and reduce their sums their own way around it.
//
// Included by the -mavx2 translation unit: everything here is a template in an anonymous
// namespace (internal linkage), so no AVX2-compiled copy can stand in for a baseline one.
// `K` is the including file's constants (members k3, k4, k8: those values in every lane).
#pragma once

#include "core/simd.h"

namespace tessera::pvrtc::detail {
namespace {

/// Squared error of (v[c] - t[c]) summed over the channels (alpha only when kAlpha): texels
/// 0-3 (lo) and 4-7 (hi) of each 8-lane group.
template <bool kAlpha, class V, class VI>
inline void sq_err(const V v[4], const V t[4], VI& lo, VI& hi) {
  const V dr = v[0] - t[0], dg = v[1] - t[1], db = v[2] - t[2];
  V da;
  if constexpr (kAlpha) da = v[3] - t[3];
  const V rg0 = simd::zip_lo(dr, dg), rg1 = simd::zip_hi(dr, dg);
  const V ba0 = simd::zip_lo(db, da), ba1 = simd::zip_hi(db, da);
  lo = simd::madd(rg0, rg0) + simd::madd(ba0, ba0);
  hi = simd::madd(rg1, rg1) + simd::madd(ba1, ba1);
}

/// Error of the blend (a (8 - m) + b m) / 8 with per-lane weights m, texels 0-3 and 4-7 of each
/// 8-lane group summed.
template <bool kAlpha, class K, class V>
inline auto blend_err(const K& k, const V a[4], const V b[4], const V t[4], V m) {
  constexpr int nch = kAlpha ? 4 : 3;
  const V im = k.k8 - m;
  V v[4];
  for (int c = 0; c < nch; ++c) v[c] = simd::srl<3>(simd::mullo(a[c], im) + simd::mullo(b[c], m));
  decltype(simd::madd(V(), V())) lo, hi;
  sq_err<kAlpha>(v, t, lo, hi);
  return lo + hi;
}

/// Map byte -> weight of its greedy code (0, 3, 5, 8) and of its A/B choice (0 or 8).
template <class K, class V>
inline V greedy_weight(const K& k, V bytes) {
  const V c = bytes & k.k3;
  return simd::mullo(c, k.k3) - simd::srl<1>(c);
}
template <class K, class V>
inline V ab_weight(const K& k, V bytes) {
  const V f = bytes & k.k4;
  return f + f;
}

}  // namespace
}  // namespace tessera::pvrtc::detail
