// simd_compose4.h — part of the SIMD wrapper (include "core/simd.h", which documents the whole
// set): operations on the 4-lane types that kernels written once for both widths need and that
// SSE2 has no instruction for (a byte shuffle, a 64-bit multiply), the same results spelled out
// once with every 4-lane backend's own operations. simd_select.h includes it after the 4-lane
// backend and before the 8-lane one, whose lookup8 (simd_halves.h) builds on the one here; the
// 8-lane forms of the others are in the 8-lane backends.
#pragma once

#include <cstdint>

namespace tessera::simd {
inline namespace TESSERA_SIMD_ISA {

// ---- compositions the 4-lane backends have no one instruction for ----
/// floor(x / 255) of each lane read as uint32, as div255_u32(vi32x8).
inline vi32x4 div255_u32(vi32x4 a) {
  std::int32_t x[4];
  store4(a, x);
  for (auto& v : x) v = std::int32_t(std::uint32_t(v) / 255u);
  return load4(x);
}
/// 16 RGBA8 texels at p (64 bytes) as one byte plane per channel: out[c] lane i = p[4 i + c],
/// as load_planes(p, vu8x32[4]).
inline void load_planes(const std::uint8_t* p, vu8x16 out[4]) {
  const vi32x4 m8(0xff);
  const vi32x4 t0 = load_texels4(p), t1 = load_texels4(p + 16), t2 = load_texels4(p + 32),
               t3 = load_texels4(p + 48);
  out[0] = narrow(t0 & m8, t1 & m8, t2 & m8, t3 & m8);
  out[1] = narrow(srl<8>(t0) & m8, srl<8>(t1) & m8, srl<8>(t2) & m8, srl<8>(t3) & m8);
  out[2] = narrow(srl<16>(t0) & m8, srl<16>(t1) & m8, srl<16>(t2) & m8, srl<16>(t3) & m8);
  out[3] = narrow(srl<24>(t0), srl<24>(t1), srl<24>(t2), srl<24>(t3));
}
/// Table lookup of 16-bit lanes: lane i = table[idx_i] where idx_i is 0..7, and 0 where idx_i
/// read as int16 is -8..-1 (other indices: unspecified). `table` holds 8 entries. The 4-lane
/// form compares with each index (SSE2 has no byte shuffle); the 8-lane AVX2 form (simd_avx2.h)
/// is one byte shuffle, the portable one (simd_halves.h) the 4-lane form on each half.
inline vu16x8 lookup8(const std::uint16_t* table, vu16x8 idx) {
  vu16x8 r(std::uint16_t{0});
  for (std::uint16_t k = 0; k < 8; ++k) r = r | (cmpeq(idx, vu16x8(k)) & vu16x8(table[k]));
  return r;
}

}  // namespace TESSERA_SIMD_ISA
}  // namespace tessera::simd
