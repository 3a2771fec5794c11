// colour_scale_kernel.h — the vector form of `scale_diff` (encode_internal.h) for the 4 bpp
// kernels that weight colour error by alpha (`EncodeOptions::alpha_weighted`): the modulation
// choice (modulation_kernel.h) and the exact search's window evaluators (exact_search_kernel.h).
#pragma once

#include <cstdint>

#include "core/simd.h"

namespace tessera::pvrtc::detail {

/// Eight differences `d` (wrapping u16 lanes holding -255..255) scaled by `scale` / 16 (lanes
/// 0..16), rounded half up: lane for lane `scale_diff(d, scale)`. d * scale lies in
/// [-4080, 4080], so its low 16 bits plus 4104 is d * scale + 4104 in [24, 8184] (no wrap):
/// the logical shift floors it, and 256 (= 4096 / 16) comes off again. Scale 16 gives d.
inline simd::vu16x8 scale_diff16(simd::vu16x8 d, simd::vu16x8 scale) {
  return simd::srl<4>(simd::mullo(d, scale) + simd::vu16x8(std::uint16_t(4104))) -
         simd::vu16x8(std::uint16_t(256));
}

}  // namespace tessera::pvrtc::detail
