// modulation_2bpp_bits.h — the stored modulation bits of an interpolated (mode 1) 2 bpp block,
// shared by the baseline passes (modulation_2bpp.cpp) and the AVX2 ones
// (modulation_2bpp_avx2.cpp). Internal linkage (anonymous namespace): each translation unit
// keeps its own copy, so the -mavx2 one can never stand in for the baseline's.
#pragma once

#include <cstddef>
#include <cstdint>

namespace tessera::pvrtc::detail {
namespace {

/// Stored values in raster order of the checkerboard, 2 bits each, from the greedy map rows
/// in[1..4] (texel rows 0-3 of the block, at element x): greedy codes, texel (0,0) restricted
/// to 0/3 (only its high bit is stored; bit 0 flags the H/V-only variants), and (4,2) too for
/// H/V only (bit 20, its low bit, tells V from H). variant: 0 H+V, 1 H only, 2 V only.
inline std::uint32_t interpolated_bits(const std::uint8_t* const in[6], std::size_t x,
                                       int variant) {
  std::uint32_t bits = 0;
  for (int j = 0; j < 4; ++j) {
    const std::uint8_t* cur = in[j + 1] + x;
    for (int i = 0; i < 4; ++i) {
      bits |= std::uint32_t(cur[(j & 1) + 2 * i] & 3) << (8 * j + 2 * i);
    }
  }
  const std::uint8_t* row0 = in[1] + x;
  const std::uint8_t* row2 = in[3] + x;
  bits = (bits & ~3u) | ((row0[0] & 4) ? 2u : 0u);
  if (variant > 0) {
    bits = (bits & ~(3u << 20)) | ((row2[4] & 4) ? (2u << 20) : 0u) | 1u;
    if (variant == 2) bits |= 1u << 20;
  } else {
    bits &= ~(1u << 20);
  }
  return bits;
}

}  // namespace
}  // namespace tessera::pvrtc::detail
