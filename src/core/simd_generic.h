// simd_generic.h — part of the SIMD wrapper (include "core/simd.h", which documents the whole
// set): width-generic names over the 4- and 8-lane types, for kernels written once and compiled
// per width (kLanes, load_as, store, store_bytes, ...), and the few operations such kernels need
// on both widths that are compositions of the backends' own: on the 4-lane types where SSE2 has
// no instruction for them (a byte shuffle, a 64-bit multiply), the same results spelled out.
#pragma once

#include <cstdint>

#include "core/simd_wide.h"

namespace tessera::simd {
inline namespace TESSERA_SIMD_ISA {

// ---- width-generic names, for kernels written once over the 4- and 8-lane types ----
/// Lanes of a vector type.
template <class V>
inline constexpr int kLanes = -1;  // not a wrapper type
template <>
inline constexpr int kLanes<vf32x4> = 4;
template <>
inline constexpr int kLanes<vf32x8> = 8;
template <>
inline constexpr int kLanes<vi32x4> = 4;
template <>
inline constexpr int kLanes<vi32x8> = 8;
template <>
inline constexpr int kLanes<vu16x8> = 8;
template <>
inline constexpr int kLanes<vu16x16> = 16;
template <>
inline constexpr int kLanes<vu8x16> = 16;
template <>
inline constexpr int kLanes<vu8x32> = 32;
/// load_as<V>(p): kLanes<V> elements at p (no alignment assumed).
template <class V>
V load_as(const float* p);
template <>
inline vf32x4 load_as<vf32x4>(const float* p) {
  return loadf4(p);
}
template <>
inline vf32x8 load_as<vf32x8>(const float* p) {
  return loadf8(p);
}
template <class V>
V load_as(const std::uint16_t* p);
template <>
inline vu16x8 load_as<vu16x8>(const std::uint16_t* p) {
  return load_u16x8(p);
}
template <>
inline vu16x16 load_as<vu16x16>(const std::uint16_t* p) {
  return load_u16x16(p);
}
template <class V>
V load_as(const std::uint8_t* p);
template <>
inline vu8x16 load_as<vu8x16>(const std::uint8_t* p) {
  return load_u8x16(p);
}
template <>
inline vu8x32 load_as<vu8x32>(const std::uint8_t* p) {
  return load_u8x32(p);
}
/// store(v, p): the lanes of v to p.
inline void store(vf32x4 a, float* p) { storef4(a, p); }
inline void store(vf32x8 a, float* p) { storef8(a, p); }
inline void store(vu16x8 a, std::uint16_t* p) { store_u16x8(a, p); }
inline void store(vu16x16 a, std::uint16_t* p) { store_u16x16(a, p); }
inline void store(vu8x16 a, std::uint8_t* p) { store_u8x16(a, p); }
inline void store(vu8x32 a, std::uint8_t* p) { store_u8x32(a, p); }
/// The 32-bit lanes as bytes, each clamped to 0..255 (store_u8x4 / store_u8x8).
inline void store_bytes(vi32x4 a, std::uint8_t* p) { store_u8x4(a, p); }
inline void store_bytes(vi32x8 a, std::uint8_t* p) { store_u8x8(a, p); }
template <class V>
V load_as(const std::int32_t* p);
template <>
inline vi32x4 load_as<vi32x4>(const std::int32_t* p) {
  return load4(p);
}
template <>
inline vi32x8 load_as<vi32x8>(const std::int32_t* p) {
  return load8(p);
}
inline void store(vi32x4 a, std::int32_t* p) { store4(a, p); }
inline void store(vi32x8 a, std::int32_t* p) { store8(a, p); }
/// load_texels_as<V>(p): kLanes<V> RGBA8 texels as 32-bit lanes (load_texels4 / load_texels8).
template <class V>
V load_texels_as(const std::uint8_t* p);
template <>
inline vi32x4 load_texels_as<vi32x4>(const std::uint8_t* p) {
  return load_texels4(p);
}
template <>
inline vi32x8 load_texels_as<vi32x8>(const std::uint8_t* p) {
  return load_texels8(p);
}
/// load_widen_as<V>(p): kLanes<V> bytes zero-extended to 16-bit lanes, in order (load_u8x8 /
/// load_u8x16_u16).
template <class V>
V load_widen_as(const std::uint8_t* p);
template <>
inline vu16x8 load_widen_as<vu16x8>(const std::uint8_t* p) {
  return load_u8x8(p);
}
template <>
inline vu16x16 load_widen_as<vu16x16>(const std::uint8_t* p) {
  return load_u8x16_u16(p);
}

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
/// form compares with each index (SSE2 has no byte shuffle); the 8-lane AVX2 form is one byte
/// shuffle, the portable one the 4-lane form on each half.
inline vu16x8 lookup8(const std::uint16_t* table, vu16x8 idx) {
  vu16x8 r(std::uint16_t{0});
  for (std::uint16_t k = 0; k < 8; ++k) r = r | (cmpeq(idx, vu16x8(k)) & vu16x8(table[k]));
  return r;
}
inline vu16x16 lookup8(const std::uint16_t* table, vu16x16 idx) {
#if defined(TESSERA_SIMD_AVX2)
  // Bytes (2 idx, 2 idx + 1) of the table in each half; for idx -8..-1 both have the top bit
  // set, which shuffles in 0.
  const vu16x8 t = load_u16x8(table);
  return shuffle_bytes(vu16x16(t, t),
                       mullo(idx, vu16x16(std::uint16_t{514})) + vu16x16(std::uint16_t{256}));
#else
  return vu16x16(lookup8(table, low(idx)), lookup8(table, high(idx)));
#endif
}

}  // namespace TESSERA_SIMD_ISA
}  // namespace tessera::simd
