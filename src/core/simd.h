// simd.h — the library's one small SIMD wrapper, shared by the kernels of PVRTC, texture
// sampling and rasterisation, which use it instead of raw intrinsics (no intrinsic appears
// outside src/core/simd*.h). Include this header; it pulls in the parts:
//
//   simd_int.h     backend selection; vi32x4 (4 x int32: texels, texel coordinates, offsets,
//                  level sizes, comparison masks) and vi64x2 (2 x int64: fixed-point edges).
//   simd_float.h   vf32x4 (4 x float, one IEEE operation per lane, compares -> vi32x4 masks,
//                  selects, conversions, shuffles, 4x4 transpose).
//   simd_packed.h  vu16x8 (8 x uint16) and vu8x16 (16 x uint8): the PVRTC texel planes, with
//                  their widening / narrowing to and from vi32x4 and vf32x4.
//   simd_wide.h    the 8-lane types vi32x8, vf32x8, vu16x16 and vu8x32: two 4-lane halves, with an
//                  AVX2 backend where the translation unit is compiled with -mavx2.
//   simd_generic.h width-generic names over both widths (kLanes, load_as, store, ...) for
//                  kernels written once and compiled per width, and the operations such
//                  kernels need that the 4-lane backends compose (div255_u32, lookup8, ...).
//   this file      backend-independent compositions (sll_bytes, channel16, load_texel_planes).
// Not pulled in: simd_dispatch.h, the run-time CPU checks and the one SSSE3 routine.
//
// Every type is a value type with free functions (operators, min, max, select, cmp*, ...) in
// tessera::simd, found by argument-dependent lookup.
//
// Backends and portability. x86-64: SSE2, always (part of the ABI), plus SSE4.1 instructions
// (pmulld, pminsd) when the compiler targets SSE4.1; AVX2 for the 8-lane types in the
// `*_avx2.cpp` kernels, which are compiled with -mavx2 and dispatched at run time (their copies
// of the wrapper live in an inline namespace of their own, see simd_int.h, so no AVX2 encoding
// can stand in for a baseline function). Little-endian AArch64:
// NEON (part of its base ISA). Anywhere else (other CPUs, or -DTESSERA_NO_SIMD for the whole
// build): a portable scalar backend, four plain lanes per type. Each part header holds its
// types' three backends one after another (SSE2, NEON, scalar), and all three are
// bit-identical for every operation, SSE2's semantics being the reference: IEEE single
// precision per lane, SSE's NaN / signed-zero rules for min, max, compares and selects, wrapping
// integers, saturating narrowings (packs), shifts by the lane width or more, cvttps2dq's
// INT32_MIN for unrepresentable floats. Where NEON's instructions differ (vminq / vmaxq with
// NaN, fcvtzs saturating, immediate shift ranges, no movemask) the NEON code emulates SSE2, as
// its comments say; the scalar code spells the same rules out. Only which NaN an arithmetic
// operation returns (one it makes, as 0 * inf, or which of two NaN operands) is not fixed.
// tests/unit/simd_test.cpp and simd_int_test.cpp (4 lanes) and tests/unit/simd_wide_test.cpp (8
// lanes, also built with -mavx2) hold every backend to the reference expressions
// (scripts/test.sh runs them natively, with TESSERA_NO_SIMD, and cross-compiled under
// qemu-aarch64). The build compiles with
// -ffp-contract=off (CMakeLists.txt): GCC would otherwise fuse NEON's separate multiply and add
// into one fused multiply-add, rounding once. TESSERA_SIMD_VECTOR (1 with SSE2 or NEON, else 0)
// tells kernels that also have a scalar per-lookup path (texture `sample4` / one-probe lookups,
// raster quad coverage) whether to take the vector path; both paths give the same results, and
// without a vector backend they take their own scalar code, unchanged by this wrapper.
// Type names: v, the lane type (i signed, u unsigned, f float) and its bits, x, the lane count.
// TESSERA_NO_SIMD must be the same for every translation unit of the library (the types
// differ).
#pragma once

#include <cstdint>

#include "core/simd_float.h"
#include "core/simd_generic.h"
#include "core/simd_int.h"
#include "core/simd_packed.h"
#include "core/simd_wide.h"

namespace tessera::simd {
inline namespace TESSERA_SIMD_ISA {

/// sll_bytes: each 32-bit lane shifted left by 8 * `k` bits (k = 0..3), e.g. to put row k's
/// 8-bit code into byte k of a packed word.
inline vi32x4 sll_bytes(vi32x4 v, int k) {
  switch (k) {
    case 0:
      return v;
    case 1:
      return sll<8>(v);
    case 2:
      return sll<16>(v);
    default:
      return sll<24>(v);
  }
}

/// channel16: channel `c` (0 = R ... 3 = A) of the eight RGBA8 texels held in `t0` and `t1`
/// (from load_texels4), as 16-bit lanes in texel order.
inline vu16x8 channel16(vi32x4 t0, vi32x4 t1, int c) {
  const vi32x4 m8(0xff);
  switch (c) {
    case 1:
      return narrow16(srl<8>(t0) & m8, srl<8>(t1) & m8);
    case 2:
      return narrow16(srl<16>(t0) & m8, srl<16>(t1) & m8);
    case 3:
      return narrow16(srl<24>(t0) & m8, srl<24>(t1) & m8);
    default:
      return narrow16(t0 & m8, t1 & m8);
  }
}

/// kLanes<V> RGBA8 texels at p as one 16-bit plane per channel: out[c] lane i = p[4 i + c]. The
/// 4-lane form makes the first nch planes only; the 8-lane form is load_planes (all four).
template <int nch>
inline void load_texel_planes(const std::uint8_t* p, vu16x8 out[4]) {
  const vi32x4 t0 = load_texels4(p), t1 = load_texels4(p + 16);
  for (int c = 0; c < nch; ++c) out[c] = channel16(t0, t1, c);
}
template <int nch>
inline void load_texel_planes(const std::uint8_t* p, vu16x16 out[4]) {
  load_planes(p, out);
}

}  // namespace TESSERA_SIMD_ISA
}  // namespace tessera::simd
