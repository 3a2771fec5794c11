// simd.h — the library's one small SIMD wrapper, shared by the kernels of PVRTC, texture
// sampling and rasterisation, which use it instead of raw intrinsics (no intrinsic appears
// outside src/core/simd*.h). Include this header; it pulls in the parts, one file per backend:
//
//   simd_select.h   the one place the backend is chosen (one #if ladder: the backend's macros
//                   and inline namespace), and the includes of the chosen files below.
//   simd_sse.h      4 lanes on x86-64: SSE2, with SSE4.1 instructions where the compiler targets
//                   SSE4.1. The reference semantics, documented per operation.
//   simd_neon.h     4 lanes on little-endian AArch64: NEON.
//   simd_scalar.h   4 lanes anywhere else (or with -DTESSERA_NO_SIMD): four plain lanes a type.
//   simd_compose4.h operations on the 4-lane types that SSE2 has no instruction for, composed
//                   once for every 4-lane backend (div255_u32, load_planes, lookup8).
//   simd_avx2.h     8 lanes in translation units compiled with -mavx2: AVX2.
//   simd_halves.h   8 lanes everywhere else: two 4-lane halves of the chosen 4-lane backend.
//   simd_generic.h  width-generic names over both widths (kLanes, load_as, store, ...) for
//                   kernels written once and compiled per width.
//   this file       backend-independent compositions (sll_bytes, channel16, load_texel_planes).
// Not pulled in: simd_dispatch.h, the run-time CPU checks and the one SSSE3 routine.
//
// The types, which every backend of a width defines:
//   vi32x4   four int32 lanes: RGBA texels in the PVRTC decoder's working precision, texel
//            coordinates / offsets / level sizes of four texture lookups, comparison masks (all
//            ones / zero per lane) of vi32x4 and vf32x4 compares.
//   vi64x2   two int64 lanes: the rasteriser's fixed-point edge values.
//   vf32x4   four float lanes: each operation is one IEEE single-precision operation per lane
//            (correctly rounded add, sub, mul, div, sqrt; no fused multiply-add; min / max /
//            compares with SSE's NaN rules, spelled out per function), so a lane gives the same
//            bits as the scalar expression written in the comment. Compares return vi32x4 masks;
//            selects, conversions, shuffles, 4x4 transpose.
//   vu16x8   eight unsigned 16-bit lanes: one plane of eight texels widened from bytes.
//   vu8x16   sixteen unsigned 8-bit lanes: sixteen bytes of texels or codes. With vu16x8: the
//            PVRTC texel planes, and their widening / narrowing to and from vi32x4 and vf32x4.
//   vi32x8   eight int32 lanes        (vi32x4 x 2)
//   vf32x8   eight float lanes        (vf32x4 x 2)
//   vu16x16  sixteen uint16 lanes     (vu16x8 x 2)
//   vu8x32   thirty-two uint8 lanes   (vu8x16 x 2)
// Integer lanes wrap on overflow in every backend except where a comment says otherwise. The
// 8-lane types, twice the width of the 4-lane ones, serve the kernels built with -mavx2 and
// dispatched at run time. Every 8-lane type is two 128-bit halves, low(x) and high(x), and most
// operations are the 4-lane operation of the same name applied to each half (AVX2's own rule for
// its unpacks, packs, horizontal adds and byte shuffles): `pair_sums`, `even_lanes`, `zip_lo`,
// `madd`, `narrow16`, `f2p23_plus_lo` ... A few cross the halves, and say so: loads and stores
// (in lane order), `narrow`, `widen_lo/hi`, `permute64`, `swap_halves`, `sum_lanes`,
// `movemask_bytes`, `load_planes`.
//
// Every type is a value type with free functions (operators, min, max, select, cmp*, ...) in
// tessera::simd, found by argument-dependent lookup.
//
// Backends and portability. x86-64: SSE2, always (part of the ABI), plus SSE4.1 instructions
// (pmulld, pminsd) when the compiler targets SSE4.1; AVX2 for the 8-lane types in the
// `*_avx2.cpp` kernels, which are compiled with -mavx2 and dispatched at run time (their copies
// of the wrapper live in an inline namespace of their own, see simd_select.h, so no AVX2 encoding
// can stand in for a baseline function). Little-endian AArch64:
// NEON (part of its base ISA). Anywhere else (other CPUs, or -DTESSERA_NO_SIMD for the whole
// build): a portable scalar backend, four plain lanes per type. Each backend is one file holding
// all the types of its width, and all the backends of a width are bit-identical for every
// operation, SSE2's semantics being the reference: IEEE single
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

#include "core/simd_generic.h"
#include "core/simd_select.h"

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
/// Each lane shifted left by 8 * `k` bits (k = 0..3), as sll_bytes(vi32x4).
inline vi32x8 sll_bytes(vi32x8 v, int k) { return sll(v, 8 * k); }

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
