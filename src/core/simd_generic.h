// simd_generic.h — part of the SIMD wrapper (include "core/simd.h", which documents the whole set):
// width-generic names over the 4- and 8-lane types, for kernels written once and compiled per
// width (kLanes, load_as, store, store_bytes, ...). The operations such kernels need on both
// widths that SSE2 has no instruction for are in simd_compose4.h and the 8-lane backends.
#pragma once

#include <cstdint>

#include "core/simd_select.h"

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

}  // namespace TESSERA_SIMD_ISA
}  // namespace tessera::simd
