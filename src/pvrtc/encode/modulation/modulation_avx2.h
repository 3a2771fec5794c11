// modulation_avx2.h — the AVX2 block-row driver of the 4 bpp brute-force modulation kernel
// (modulation_blends.h with the 8-lane types, in modulation_avx2.cpp, compiled with -mavx2)
// and the switch between it and the baseline driver (modulation_kernel.h) that
// `choose_modulation` makes once per call.
//
// Included by the -mavx2 translation unit, so it holds plain declarations and POD structs
// only: nothing here may be an inline function or a template (the linker could keep an AVX2
// copy of it for the whole program).
#pragma once

#include <cstddef>
#include <cstdint>

namespace tessera::pvrtc::detail {

/// Best modulation of one block, as `BlockMod` (modulation_kernel.h): mode 0, mode 1 without
/// and with punch-through (those four 0 unless `extra`), and whether some target alpha is
/// below 128 (alpha mode only, else 0).
struct BlockModAvx2 {
  std::uint32_t bits0, err0, bits1, err1, bits1p, err1p;
  std::uint32_t any_clear;
};

/// Scores every block of one block row, 16 texels (4 blocks) a step, with the results of
/// `block_pair_errors<alpha, extra, w != nullptr>` for each block. `v[j]`, `t[j]` and `w[j]`
/// are the column-sum planes, the target row and the colour scales of texel row j, laid out as
/// `ModRow4` (8 planes `vstride` apart, element bx + 1 holding block bx); `w` null: unweighted
/// colour error, else alpha-weighted (alpha only). Requires vstride >= nbx + 8 (a step reads 8
/// elements from element bx) and nbx >= 1. Writes out[0 .. nbx). Call only when
/// `modulation_avx2_supported()`; elsewhere it does nothing.
void block_row_errors_avx2(const std::uint16_t* const v[4], const std::uint8_t* const t[4],
                           const std::uint8_t* const w[4], std::size_t vstride, int nbx, bool alpha,
                           bool extra, BlockModAvx2* out);

/// True when this build has the AVX2 kernel and the CPU (and OS) can run it.
bool modulation_avx2_supported();

/// Tests: true makes `choose_modulation` use the baseline kernel even where the AVX2 one runs
/// (the output is the same). Returns the previous setting. Not for use while encoding.
bool set_modulation_baseline_only(bool on);

}  // namespace tessera::pvrtc::detail
