// modulation_2bpp_avx2.h — one block row of the three 2 bpp modulation passes as plain pointers
// (`Mod2Row`, which the row kernels of modulation_2bpp_rows.h take at either width), their AVX2
// entry points (modulation_2bpp_avx2.cpp, compiled with -mavx2) and the switch between them and
// the baseline passes that `choose_modulation_2bpp` (modulation_2bpp.cpp) makes once per call.
//
// Included by the -mavx2 translation unit, so it holds plain declarations and a trivial struct
// only: nothing here may be an inline function, a template or a member initialiser (the linker
// could keep an AVX2 copy of it for the whole program).
#pragma once

#include <cstddef>
#include <cstdint>

namespace tessera::pvrtc::detail {

/// One block row `by` of the passes, as plain pointers (the driver owns the storage).
struct Mod2Row {
  /// Column sums of texel row j: 8 planes (image * 4 + channel) `vstride` apart, element bx + 1
  /// holding block bx, element 0 the last block and element nbx + 1 the first.
  const std::uint16_t* v[4];
  /// Target texel rows by * 4 + j (nbx * 32 bytes each).
  const std::uint8_t* t[4];
  std::size_t vstride;  ///< >= nbx + 8 (an AVX2 step reads 4 elements from element bx)
  int nbx;              ///< blocks in the row (AVX2: even and >= 2, a step takes two blocks)
  /// Map rows by * 4 - 1 .. by * 4 + 4 (wrapped vertically) with their wrap-around guard bytes
  /// at x = -1 and x = pw filled: pass 2 reads the greedy map, pass 3 the decoded one.
  const std::uint8_t* in[6];
  /// Map rows by * 4 .. by * 4 + 3 written (pass 1: greedy map, pass 2: decoded map; the driver
  /// fills their guard bytes afterwards).
  std::uint8_t* out[4];
  std::uint32_t* err0;  ///< the row's mode-0 errors (pass 1 writes them, passes 2 and 3 read)
  std::uint32_t* mod;   ///< the row's modulation bits (`EncoderState::mod` + by * nbx)
  std::uint8_t* mode;   ///< the row's modes (`EncoderState::mode` + by * nbx)
};

// The passes of modulation_2bpp_rows.h over the 8-lane types (two blocks a step), one block row
// `r` each; called only where the dispatch in modulation_2bpp.cpp chose them.

/// Pass 1 of one block row: greedy map rows (`out`), mode-0 bits (`mod`) and errors (`err0`).
void mod2_pass1_row_avx2(const Mod2Row& r, bool alpha);
/// Pass 2 of one block row: the choice (`mode`, `mod`) and the decoded map rows (`out`) from
/// the greedy map (`in`) and `err0`.
void mod2_pass2_row_avx2(const Mod2Row& r, bool alpha);
/// Pass 3 of one block row: the exact error of the decode (from the decoded map `in`, `mode`,
/// `mod` and `err0`). Reads the column sums only when some block of the row has mode 1.
std::uint64_t mod2_pass3_row_avx2(const Mod2Row& r, bool alpha);

/// Tests: true makes `choose_modulation_2bpp` use the baseline passes even where the AVX2 ones
/// run (the output is the same). Returns the previous setting. Not for use while encoding.
bool set_modulation_2bpp_baseline_only(bool on);

}  // namespace tessera::pvrtc::detail
