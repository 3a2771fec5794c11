// modulation_kernel.h — the baseline driver of the 4 bpp brute-force modulation kernel for two
// horizontally adjacent blocks (8 texels a row, 4 rows): the kernel itself is written once for
// the 4- and 8-lane types (modulation_blends.h), with the fold into per-block results; here it
// runs with vu16x8. modulation_avx2.cpp runs it with vu16x16.
#pragma once

#include <cstdint>

#include "core/simd.h"
#include "pvrtc/encode/modulation/modulation_blends.h"
#include "pvrtc/format/pvrtc_kernel.h"

namespace tessera::pvrtc::detail {

/// Inputs of one block row: for each of its 4 texel rows, the column sums of the endpoint
/// images (`v[row]`: 8 planes, image * 4 + channel, `vstride` apart; element bx + 1 holds block
/// bx, element 0 the last block and element nbx + 1 the first: wrap-around) and the target row.
struct ModRow4 {
  const std::uint16_t* v[4] = {};
  const std::uint8_t* t[4] = {};
  /// Alpha-weighted colour error only: each texel row's colour scales (one byte a texel, 0..16,
  /// `EncoderState::colour_scale`).
  const std::uint8_t* w[4] = {};
  std::size_t vstride = 0;
};

/// Best modulation of one block: mode 0, mode 1 without and with punch-through.
struct BlockMod {
  std::uint32_t bits0 = 0, err0 = 0, bits1 = 0, err1 = 0, bits1p = 0, err1p = 0;
  bool any_clear = false;  ///< Some target alpha < 128 (alpha mode only).
};

/// Scores blocks bx and bx + 1 of a block row: `mod_step` (modulation_blends.h) with vu16x8.
/// kAlpha: alpha is a fourth channel (and the punch-through blend is scored); kExtra: also
/// mode 1 (weights 0, 4, 8) and punch-through; kWeighted (with kAlpha only): alpha-weighted
/// colour error, the scales from r.w.
template <bool kAlpha, bool kExtra, bool kWeighted = false>
inline void block_pair_errors(const ModRow4& r, int bx, BlockMod out[2]) {
  const std::uint8_t* t[4];
  const std::uint8_t* w[4] = {};
  for (int j = 0; j < 4; ++j) {
    t[j] = r.t[j] + std::size_t(bx) * 16;
    if constexpr (kWeighted) w[j] = r.w[j] + std::size_t(bx) * 4;
  }
  ModAcc<simd::vi32x4> acc[2];
  simd::vu16x8 clear_lanes;  // unused: the bytes below say it as cheaply
  mod_step<kAlpha, kExtra, kWeighted>(r.v, t, w, r.vstride, bx, acc, clear_lanes);
  mod_block_results<kExtra>(acc, out);
  for (int h = 0; h < 2; ++h) {
    bool clear = false;
    if constexpr (kAlpha) {
      for (int j = 0; j < 4; ++j) {
        const std::uint8_t* tp = t[j] + 16 * h;
        clear |= ((tp[3] & tp[7] & tp[11] & tp[15]) & 0x80) == 0;
      }
    }
    out[h].any_clear = clear;
  }
}

}  // namespace tessera::pvrtc::detail
