// simd_halves.h — part of the SIMD wrapper (include "core/simd.h", which documents the whole
// set; simd_select.h includes this file where it chose this backend): the portable backend of
// the 8-lane types, for every translation unit not compiled for AVX2. Each type is two 4-lane
// halves of whatever 4-lane backend simd_select.h chose (SSE2, NEON or scalar); an operation is
// the 4-lane one on each half, or spelled out lane by lane where it has no 4-lane counterpart.
// The same bits as the AVX2 backend (simd_avx2.h) for every operation.
#pragma once

#include <cstdint>
#include <cstring>

namespace tessera::simd {
inline namespace TESSERA_SIMD_ISA {

struct vi32x8 {
  vi32x4 lo, hi;
  vi32x8() = default;
  explicit vi32x8(std::int32_t a) : lo(a), hi(a) {}
  vi32x8(vi32x4 l, vi32x4 h) : lo(l), hi(h) {}
};
struct vf32x8 {
  vf32x4 lo, hi;
  vf32x8() = default;
  explicit vf32x8(float a) : lo(a), hi(a) {}
  vf32x8(vf32x4 l, vf32x4 h) : lo(l), hi(h) {}
};
struct vu16x16 {
  vu16x8 lo, hi;
  vu16x16() = default;
  explicit vu16x16(std::uint16_t a) : lo(a), hi(a) {}
  vu16x16(vu16x8 l, vu16x8 h) : lo(l), hi(h) {}
};
struct vu8x32 {
  vu8x16 lo, hi;
  vu8x32() = default;
  explicit vu8x32(std::uint8_t a) : lo(a), hi(a) {}
  vu8x32(vu8x16 l, vu8x16 h) : lo(l), hi(h) {}
};

inline vi32x4 low(vi32x8 a) { return a.lo; }
inline vi32x4 high(vi32x8 a) { return a.hi; }
inline vf32x4 low(vf32x8 a) { return a.lo; }
inline vf32x4 high(vf32x8 a) { return a.hi; }
inline vu16x8 low(vu16x16 a) { return a.lo; }
inline vu16x8 high(vu16x16 a) { return a.hi; }
inline vu8x16 low(vu8x32 a) { return a.lo; }
inline vu8x16 high(vu8x32 a) { return a.hi; }

// Lane arrays, for what has no 4-lane counterpart (spelled out lane by lane).
namespace detail {
struct I32x8 {
  std::int32_t l[8];
};
struct U16x16 {
  std::uint16_t l[16];
};
inline I32x8 lanes(vi32x8 a) {
  I32x8 r;
  store4(a.lo, r.l);
  store4(a.hi, r.l + 4);
  return r;
}
inline vi32x8 from_lanes(const I32x8& r) { return vi32x8(load4(r.l), load4(r.l + 4)); }
inline U16x16 lanes(vu16x16 a) {
  U16x16 r;
  store_u16x8(a.lo, r.l);
  store_u16x8(a.hi, r.l + 8);
  return r;
}
inline vu16x16 from_lanes(const U16x16& r) { return vu16x16(load_u16x8(r.l), load_u16x8(r.l + 8)); }
}  // namespace detail

inline vi32x8 load8(const std::int32_t* p) { return vi32x8(load4(p), load4(p + 4)); }
inline void store8(vi32x8 a, std::int32_t* p) {
  store4(a.lo, p);
  store4(a.hi, p + 4);
}
inline vf32x8 loadf8(const float* p) { return vf32x8(loadf4(p), loadf4(p + 4)); }
inline void storef8(vf32x8 a, float* p) {
  storef4(a.lo, p);
  storef4(a.hi, p + 4);
}
inline vu16x16 load_u16x16(const std::uint16_t* p) {
  return vu16x16(load_u16x8(p), load_u16x8(p + 8));
}
inline void store_u16x16(vu16x16 a, std::uint16_t* p) {
  store_u16x8(a.lo, p);
  store_u16x8(a.hi, p + 8);
}
inline vu8x32 load_u8x32(const std::uint8_t* p) {
  return vu8x32(load_u8x16(p), load_u8x16(p + 16));
}
inline void store_u8x32(vu8x32 a, std::uint8_t* p) {
  store_u8x16(a.lo, p);
  store_u8x16(a.hi, p + 16);
}
inline vi32x8 load_texels8(const std::uint8_t* p) {
  return vi32x8(load_texels4(p), load_texels4(p + 16));
}
inline vu16x16 load_u8x16_u16(const std::uint8_t* p) {
  return vu16x16(load_u8x8(p), load_u8x8(p + 8));
}
inline vu16x16 broadcast64(std::uint64_t x) {
  detail::U16x16 r;
  for (int i = 0; i < 16; ++i) r.l[i] = std::uint16_t(x >> (16 * (i & 3)));
  return detail::from_lanes(r);
}
inline void store_u8x8(vi32x8 a, std::uint8_t* p) {
  store_u8x4(a.lo, p);
  store_u8x4(a.hi, p + 4);
}
inline void store_u8x16(vu16x16 a, std::uint8_t* p) {
  store_u8x8(a.lo, p);
  store_u8x8(a.hi, p + 8);
}

#define TESSERA_SIMD_HALVES2(T, op) \
  inline T op(T a, T b) { return T(op(a.lo, b.lo), op(a.hi, b.hi)); }
#define TESSERA_SIMD_HALVES2R(R, T, op) \
  inline R op(T a, T b) { return R(op(a.lo, b.lo), op(a.hi, b.hi)); }

// ---- vi32x8 ----
TESSERA_SIMD_HALVES2(vi32x8, operator+)
TESSERA_SIMD_HALVES2(vi32x8, operator-)
TESSERA_SIMD_HALVES2(vi32x8, operator*)
TESSERA_SIMD_HALVES2(vi32x8, operator&)
TESSERA_SIMD_HALVES2(vi32x8, operator|)
TESSERA_SIMD_HALVES2(vi32x8, operator^)
TESSERA_SIMD_HALVES2(vi32x8, andnot)
TESSERA_SIMD_HALVES2(vi32x8, cmpeq)
TESSERA_SIMD_HALVES2(vi32x8, cmpgt)
TESSERA_SIMD_HALVES2(vi32x8, cmplt)
TESSERA_SIMD_HALVES2(vi32x8, min)
TESSERA_SIMD_HALVES2(vi32x8, pair_sums)
TESSERA_SIMD_HALVES2(vi32x8, even_lanes)
inline vi32x8& operator+=(vi32x8& a, vi32x8 b) { return a = a + b; }
template <int N>
inline vi32x8 sra(vi32x8 a) {
  return vi32x8(sra<N>(a.lo), sra<N>(a.hi));
}
template <int N>
inline vi32x8 srl(vi32x8 a) {
  return vi32x8(srl<N>(a.lo), srl<N>(a.hi));
}
template <int N>
inline vi32x8 sll(vi32x8 a) {
  return vi32x8(sll<N>(a.lo), sll<N>(a.hi));
}
inline vi32x8 sllv(vi32x8 a, vi32x8 n) {
  detail::I32x8 x = detail::lanes(a);
  const detail::I32x8 s = detail::lanes(n);
  for (int i = 0; i < 8; ++i) {
    const std::uint32_t k = std::uint32_t(s.l[i]);
    x.l[i] = k < 32 ? std::int32_t(std::uint32_t(x.l[i]) << k) : 0;
  }
  return detail::from_lanes(x);
}
inline vi32x8 sll(vi32x8 a, int n) {
  detail::I32x8 x = detail::lanes(a);
  for (auto& v : x.l) v = n >= 0 && n < 32 ? std::int32_t(std::uint32_t(v) << n) : 0;
  return detail::from_lanes(x);
}
inline vi32x8 select(vi32x8 mask, vi32x8 a, vi32x8 b) {
  return vi32x8(select(mask.lo, a.lo, b.lo), select(mask.hi, a.hi, b.hi));
}
inline vi32x8 max(vi32x8 a, vi32x8 b) { return vi32x8(max(a.lo, b.lo), max(a.hi, b.hi)); }
inline vi32x8 swap_pairs(vi32x8 a) { return vi32x8(swap_pairs(a.lo), swap_pairs(a.hi)); }
inline vi32x8 swap_pairs64(vi32x8 a) {
  const detail::I32x8 x = detail::lanes(a);
  return detail::from_lanes(
      detail::I32x8{{x.l[2], x.l[3], x.l[0], x.l[1], x.l[6], x.l[7], x.l[4], x.l[5]}});
}
inline vi32x8 swap_halves(vi32x8 a) { return vi32x8(a.hi, a.lo); }
template <int I0, int I1, int I2, int I3>
inline vi32x8 permute64(vi32x8 a) {
  const detail::I32x8 x = detail::lanes(a);
  detail::I32x8 r;
  const int idx[4] = {I0, I1, I2, I3};
  for (int k = 0; k < 4; ++k) {
    r.l[2 * k] = x.l[2 * idx[k]];
    r.l[2 * k + 1] = x.l[2 * idx[k] + 1];
  }
  return detail::from_lanes(r);
}
inline std::int32_t sum_lanes(vi32x8 a) {
  return std::int32_t(std::uint32_t(sum_lanes(a.lo)) + std::uint32_t(sum_lanes(a.hi)));
}
inline vi32x8 div255_u32(vi32x8 a) {
  detail::I32x8 x = detail::lanes(a);
  for (auto& v : x.l) v = std::int32_t(std::uint32_t(v) / 255u);
  return detail::from_lanes(x);
}

// ---- vf32x8 ----
TESSERA_SIMD_HALVES2(vf32x8, operator+)
TESSERA_SIMD_HALVES2(vf32x8, operator-)
TESSERA_SIMD_HALVES2(vf32x8, operator*)
TESSERA_SIMD_HALVES2(vf32x8, max)
TESSERA_SIMD_HALVES2(vf32x8, min)
TESSERA_SIMD_HALVES2R(vi32x8, vf32x8, cmpeq)
TESSERA_SIMD_HALVES2R(vi32x8, vf32x8, cmplt)
inline vf32x8 to_float(vi32x8 a) { return vf32x8(to_float(a.lo), to_float(a.hi)); }
inline vi32x8 to_int_trunc(vf32x8 a) { return vi32x8(to_int_trunc(a.lo), to_int_trunc(a.hi)); }

// ---- vu16x16 ----
TESSERA_SIMD_HALVES2(vu16x16, operator+)
TESSERA_SIMD_HALVES2(vu16x16, operator-)
TESSERA_SIMD_HALVES2(vu16x16, operator&)
TESSERA_SIMD_HALVES2(vu16x16, operator|)
TESSERA_SIMD_HALVES2(vu16x16, mullo)
TESSERA_SIMD_HALVES2(vu16x16, mulhi)
TESSERA_SIMD_HALVES2(vu16x16, cmpeq)
TESSERA_SIMD_HALVES2(vu16x16, zip_lo)
TESSERA_SIMD_HALVES2(vu16x16, zip_hi)
TESSERA_SIMD_HALVES2R(vi32x8, vu16x16, madd)
TESSERA_SIMD_HALVES2R(vu16x16, vi32x8, narrow16)
template <int N>
inline vu16x16 srl(vu16x16 a) {
  return vu16x16(srl<N>(a.lo), srl<N>(a.hi));
}
inline vu16x16 cmpgt_s16(vu16x16 a, vu16x16 b) {
  const detail::U16x16 x = detail::lanes(a), y = detail::lanes(b);
  detail::U16x16 r;
  for (int i = 0; i < 16; ++i) r.l[i] = std::int16_t(x.l[i]) > std::int16_t(y.l[i]) ? 0xffff : 0;
  return detail::from_lanes(r);
}
inline vu16x16 select(vu16x16 mask, vu16x16 a, vu16x16 b) {
  return vu16x16(select(mask.lo, a.lo, b.lo), select(mask.hi, a.hi, b.hi));
}
inline vu16x16 select_alpha(vu16x16 rgb, vu16x16 a) {
  detail::U16x16 r = detail::lanes(rgb);
  const detail::U16x16 x = detail::lanes(a);
  for (int i = 3; i < 16; i += 4) r.l[i] = x.l[i];
  return detail::from_lanes(r);
}
inline vf32x8 f2p23_plus_lo(vu16x16 a) { return vf32x8(f2p23_plus_lo(a.lo), f2p23_plus_lo(a.hi)); }
inline vf32x8 f2p23_plus_hi(vu16x16 a) { return vf32x8(f2p23_plus_hi(a.lo), f2p23_plus_hi(a.hi)); }
inline vu16x16 shuffle_bytes(vu16x16 table, vu16x16 idx) {
  std::uint8_t t[32], x[32], r[32];
  const detail::U16x16 tl = detail::lanes(table), il = detail::lanes(idx);
  std::memcpy(t, tl.l, 32);
  std::memcpy(x, il.l, 32);
  for (int i = 0; i < 32; ++i) r[i] = (x[i] & 0x80) ? 0 : t[(i & 16) | (x[i] & 15)];
  detail::U16x16 out;
  std::memcpy(out.l, r, 32);
  return detail::from_lanes(out);
}
template <int I0, int I1, int I2, int I3>
inline vu16x16 permute64(vu16x16 a) {
  const detail::U16x16 x = detail::lanes(a);
  detail::U16x16 r;
  const int idx[4] = {I0, I1, I2, I3};
  for (int k = 0; k < 4; ++k) {
    for (int j = 0; j < 4; ++j) r.l[4 * k + j] = x.l[4 * idx[k] + j];
  }
  return detail::from_lanes(r);
}
inline std::uint32_t movemask_bytes(vu16x16 a) {
  const detail::U16x16 x = detail::lanes(a);
  std::uint8_t b[32];
  std::memcpy(b, x.l, 32);
  std::uint32_t m = 0;
  for (int i = 0; i < 32; ++i) m |= std::uint32_t(b[i] >> 7) << i;
  return m;
}
inline vu8x32 narrow(vu16x16 a, vu16x16 b) {
  return vu8x32(narrow(a.lo, a.hi), narrow(b.lo, b.hi));
}

// ---- vu8x32 ----
TESSERA_SIMD_HALVES2(vu8x32, operator+)
TESSERA_SIMD_HALVES2(vu8x32, operator&)
TESSERA_SIMD_HALVES2(vu8x32, operator|)
TESSERA_SIMD_HALVES2(vu8x32, andnot)
TESSERA_SIMD_HALVES2(vu8x32, cmpeq)
inline vu8x32 select(vu8x32 mask, vu8x32 a, vu8x32 b) {
  return vu8x32(select(mask.lo, a.lo, b.lo), select(mask.hi, a.hi, b.hi));
}
inline bool any(vu8x32 mask) { return any(mask.lo) || any(mask.hi); }
inline vu16x16 widen_lo(vu8x32 a) { return vu16x16(widen_lo(a.lo), widen_hi(a.lo)); }
inline vu16x16 widen_hi(vu8x32 a) { return vu16x16(widen_lo(a.hi), widen_hi(a.hi)); }

#undef TESSERA_SIMD_HALVES2
#undef TESSERA_SIMD_HALVES2R

inline void load_planes(const std::uint8_t* p, vu8x32 out[4]) {
  std::uint8_t r[4][32];
  for (int i = 0; i < 32; ++i) {
    for (int c = 0; c < 4; ++c) r[c][i] = p[4 * i + c];
  }
  for (int c = 0; c < 4; ++c) out[c] = load_u8x32(r[c]);
}
inline void load_planes(const std::uint8_t* p, vu16x16 out[4]) {
  std::uint16_t r[4][16];
  for (int i = 0; i < 16; ++i) {
    for (int c = 0; c < 4; ++c) r[c][i] = p[4 * i + c];
  }
  for (int c = 0; c < 4; ++c) out[c] = load_u16x16(r[c]);
}

// ---- lookup8 (the 4-lane form and its contract: simd_compose4.h) ----
/// lookup8(vu16x8) on each half.
inline vu16x16 lookup8(const std::uint16_t* table, vu16x16 idx) {
  return vu16x16(lookup8(table, low(idx)), lookup8(table, high(idx)));
}

}  // namespace TESSERA_SIMD_ISA
}  // namespace tessera::simd
