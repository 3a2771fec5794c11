// exact_search_lanes.h — the per-width pieces of the exact searches' window evaluators (4 bpp:
// exact_search_evaluators.h, 2 bpp: exact_search_2bpp_evaluator.h), overloaded on the SIMD
// wrapper's 4- and 8-lane types so that each evaluator's loop is written once: the endpoint and
// weight lanes, the minimum over the blends (float lanes on 4, integers on 8), and the texel
// order of a step's 32-bit lanes (pair_sums works per 128-bit half); and the decoder's blends,
// which every evaluator forms the same way.
//
// Included by the -mavx2 translation units: everything here is a template or inline function in
// an anonymous namespace (internal linkage), so no AVX2-compiled copy can stand in for a
// baseline one.
#pragma once

#include <cstdint>

#include "core/simd.h"

namespace tessera::pvrtc::detail {
namespace {

/// The four values `v` (r, g, b, a; 16-bit) in every texel's four lanes. (Read one by one on 4
/// lanes: callers have just stored v as four scalars, and one 16-byte load of those cannot be
/// store-forwarded.)
template <class V>
V endpoint_lanes(const std::int32_t v[4]);
template <>
[[maybe_unused]] inline simd::vu16x8 endpoint_lanes<simd::vu16x8>(const std::int32_t v[4]) {
  alignas(16) const std::uint16_t l[8] = {
      std::uint16_t(v[0]), std::uint16_t(v[1]), std::uint16_t(v[2]), std::uint16_t(v[3]),
      std::uint16_t(v[0]), std::uint16_t(v[1]), std::uint16_t(v[2]), std::uint16_t(v[3])};
  return simd::load_u16x8(l);
}
template <>
[[maybe_unused]] inline simd::vu16x16 endpoint_lanes<simd::vu16x16>(const std::int32_t v[4]) {
  return simd::broadcast64(
      std::uint64_t(std::uint16_t(v[0])) | std::uint64_t(std::uint16_t(v[1])) << 16 |
      std::uint64_t(std::uint16_t(v[2])) << 32 | std::uint64_t(std::uint16_t(v[3])) << 48);
}

/// The eight lanes at p (two texels' RGBA) repeated over V.
template <class V>
V twice_lanes(const std::uint16_t* p);
template <>
[[maybe_unused]] inline simd::vu16x8 twice_lanes<simd::vu16x8>(const std::uint16_t* p) {
  return simd::load_u16x8(p);
}
template <>
[[maybe_unused]] inline simd::vu16x16 twice_lanes<simd::vu16x16>(const std::uint16_t* p) {
  const simd::vu16x8 x = simd::load_u16x8(p);
  return simd::vu16x16(x, x);
}

// The minimum over the blends: the 4-lane evaluators take it in float lanes (SSE2 has no 32-bit
// integer min; fewer instructions than emulating it): errors are far below 2^24 (exact in
// float), excluded blends (2^24 and up) stay at least 2^24 once rounded, and the blends of
// weight 0 and 8 are never excluded, so the minimum is the exact integer minimum. The 8-lane
// ones (AVX2 has pminsd) take the integer minimum directly: the same number.
[[maybe_unused]] inline simd::vf32x4 min_lanes(simd::vi32x4 x) { return simd::to_float(x); }
[[maybe_unused]] inline simd::vi32x4 int_lanes(simd::vf32x4 x) { return simd::to_int_trunc(x); }
[[maybe_unused]] inline simd::vi32x8 min_lanes(simd::vi32x8 x) { return x; }
[[maybe_unused]] inline simd::vi32x8 int_lanes(simd::vi32x8 x) { return x; }

// A step's per-texel lanes come from pair_sums of its two vectors, which sums per 128-bit half:
// texels in order on 4 lanes, in the order 0 1 4 5 | 2 3 6 7 on 8.

/// kLanes<VI> consecutive texels' 32-bit values at p, in the lane order of pair_sums.
template <class VI>
VI load_texel_lanes(const std::int32_t* p);
template <>
[[maybe_unused]] inline simd::vi32x4 load_texel_lanes<simd::vi32x4>(const std::int32_t* p) {
  return simd::load4(p);
}
template <>
[[maybe_unused]] inline simd::vi32x8 load_texel_lanes<simd::vi32x8>(const std::int32_t* p) {
  return simd::permute64<0, 2, 1, 3>(simd::load8(p));
}

/// A step's per-texel errors (lanes in the order of pair_sums) stored in texel order, the first
/// n of them (4-lane: 4 texels; 8-lane: 8 or 4).
[[maybe_unused]] inline void store_texel_errors(simd::vi32x4 m, std::int32_t* p, int) {
  simd::store4(m, p);
}
[[maybe_unused]] inline void store_texel_errors(simd::vi32x8 m, std::int32_t* p, int n) {
  const simd::vi32x8 ordered = simd::permute64<0, 2, 1, 3>(m);
  if (n == 8) {
    simd::store8(ordered, p);
  } else {
    simd::store4(simd::low(ordered), p);
  }
}

/// The decoder's blends of unpacked A and B values (16-bit lanes): out = A (modulation weight
/// 0), B (8), (5A + 3B) >> 3 (3), (3A + 5B) >> 3 (5) and (A + B) >> 1 (4), the 3 and 5 from
/// 4 (A + B) +- (A - B) (the u16 lanes wrap in between; the results are exact).
template <class V>
inline void decoder_blends(V ua, V ub, V out[5]) {
  const V sum = ua + ub, sum2 = sum + sum, sum4 = sum2 + sum2, diff = ua - ub;
  out[0] = ua;
  out[1] = ub;
  out[2] = simd::srl<3>(sum4 + diff);
  out[3] = simd::srl<3>(sum4 - diff);
  out[4] = simd::srl<1>(sum);
}

/// decoder_blends' five blends scored by `err` (a V -> squared-error lanes function) into
/// o.e0, o.e8, o.e3, o.e5 and o.e4 (the modulation weights); returns the weight-4 blend.
template <class V, class Err, class Out>
inline V decoder_blend_errors(V ua, V ub, const Err& err, Out& o) {
  V bl[5];
  decoder_blends(ua, ub, bl);
  o.e0 = err(bl[0]);
  o.e8 = err(bl[1]);
  o.e3 = err(bl[2]);
  o.e5 = err(bl[3]);
  o.e4 = err(bl[4]);
  return bl[4];
}

}  // namespace
}  // namespace tessera::pvrtc::detail
