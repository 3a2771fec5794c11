// colour_scale_kernel.h — the vector form of `scale_diff` (encode_internal.h) for the 4 bpp
// kernels that weight colour error by alpha (`EncodeOptions::alpha_weighted`): the modulation
// choice (modulation_blends.h) and the exact search's window evaluators
// (exact_search_evaluators.h), each written once for the 4- and 8-lane types.
//
// Included by -mavx2 translation units: a template in an anonymous namespace (internal
// linkage), so no AVX2-compiled copy can stand in for a baseline one.
#pragma once

#include <cstdint>

#include "core/simd.h"

namespace tessera::pvrtc::detail {
namespace {

/// Differences `d` (wrapping u16 lanes holding -255..255; V = simd::vu16x8 or vu16x16) scaled
/// by `scale` / 16 (lanes 0..16), rounded half up: lane for lane `scale_diff(d, scale)`.
/// d * scale lies in [-4080, 4080], so its low 16 bits plus 4104 is d * scale + 4104 in
/// [24, 8184] (no wrap): the logical shift floors it, and 256 (= 4096 / 16) comes off again.
/// Scale 16 gives d.
template <class V>
inline V scale_diff16(V d, V scale) {
  return simd::srl<4>(simd::mullo(d, scale) + V(std::uint16_t(4104))) - V(std::uint16_t(256));
}

}  // namespace
}  // namespace tessera::pvrtc::detail
