// simd_neon.h — part of the SIMD wrapper (include "core/simd.h", which documents the whole set;
// simd_select.h includes this file where it chose this backend): the 4-lane types on
// little-endian AArch64 with NEON (part of its base ISA), giving SSE2's results bit for bit.
//   vi32x4, vi64x2   the 32- and 64-bit integer lanes
//   vf32x4           the single-precision lanes
//   vu16x8, vu8x16   the packed small-integer lanes, with their conversions to and from vi32x4
//                    and vf32x4
#pragma once

#include <arm_neon.h>

#include <cstdint>
#include <cstring>

namespace tessera::simd {
inline namespace TESSERA_SIMD_ISA {

// ---- vi32x4, vi64x2 ----

// NEON: the same operations as the SSE2 backend, lane for lane. Where the instructions differ
// (SSE's saturating packs, movemask, shifts by the lane width or more) the comments say how
// SSE2's result is reproduced.
struct vi32x4 {
  int32x4_t v;
  vi32x4() : v(vdupq_n_s32(0)) {}
  explicit vi32x4(int32x4_t x) : v(x) {}
  vi32x4(std::int32_t a, std::int32_t b, std::int32_t c, std::int32_t d) {
    const std::int32_t t[4] = {a, b, c, d};
    v = vld1q_s32(t);
  }
  explicit vi32x4(std::int32_t a) : v(vdupq_n_s32(a)) {}
  std::int32_t lane(int i) const {
    std::int32_t t[4];
    vst1q_s32(t, v);
    return t[i];
  }
};
inline vi32x4 load4(const std::int32_t* p) { return vi32x4(vld1q_s32(p)); }
inline vi32x4 load4_aligned(const std::int32_t* p) { return vi32x4(vld1q_s32(p)); }
inline void store4(vi32x4 a, std::int32_t* p) { vst1q_s32(p, a.v); }
inline void store4_aligned(vi32x4 a, std::int32_t* p) { vst1q_s32(p, a.v); }
/// Little-endian (the NEON backend is selected only there), as SSE2's 16-byte load.
inline vi32x4 load_texels4(const std::uint8_t* p) {
  return vi32x4(vreinterpretq_s32_u8(vld1q_u8(p)));
}
inline vi32x4 operator+(vi32x4 a, vi32x4 b) { return vi32x4(vaddq_s32(a.v, b.v)); }
inline vi32x4 operator-(vi32x4 a, vi32x4 b) { return vi32x4(vsubq_s32(a.v, b.v)); }
inline vi32x4& operator+=(vi32x4& a, vi32x4 b) { return a = a + b; }
inline vi32x4 operator*(vi32x4 a, vi32x4 b) { return vi32x4(vmulq_s32(a.v, b.v)); }
inline vi32x4 operator&(vi32x4 a, vi32x4 b) { return vi32x4(vandq_s32(a.v, b.v)); }
inline vi32x4 operator|(vi32x4 a, vi32x4 b) { return vi32x4(vorrq_s32(a.v, b.v)); }
inline vi32x4 operator^(vi32x4 a, vi32x4 b) { return vi32x4(veorq_s32(a.v, b.v)); }
inline vi32x4 andnot(vi32x4 a, vi32x4 b) { return vi32x4(vbicq_s32(b.v, a.v)); }
// NEON's immediate shifts take 1..32 (right) or 0..31 (left): N = 0 and N >= 32 are spelled
// out, with SSE2's results (sra fills with the sign, srl and sll give zero).
template <int N>
inline vi32x4 sra(vi32x4 a) {
  static_assert(N >= 0);
  if constexpr (N == 0) {
    return a;
  } else {
    return vi32x4(vshrq_n_s32(a.v, N < 32 ? N : 32));
  }
}
template <int N>
inline vi32x4 srl(vi32x4 a) {
  static_assert(N >= 0);
  if constexpr (N == 0) {
    return a;
  } else if constexpr (N >= 32) {
    return vi32x4();
  } else {
    return vi32x4(vreinterpretq_s32_u32(vshrq_n_u32(vreinterpretq_u32_s32(a.v), N)));
  }
}
template <int N>
inline vi32x4 sll(vi32x4 a) {
  static_assert(N >= 0);
  if constexpr (N == 0) {
    return a;
  } else if constexpr (N >= 32) {
    return vi32x4();
  } else {
    return vi32x4(vshlq_n_s32(a.v, N));
  }
}
inline vi32x4 cmpeq(vi32x4 a, vi32x4 b) {
  return vi32x4(vreinterpretq_s32_u32(vceqq_s32(a.v, b.v)));
}
inline vi32x4 cmpgt(vi32x4 a, vi32x4 b) {
  return vi32x4(vreinterpretq_s32_u32(vcgtq_s32(a.v, b.v)));
}
inline vi32x4 cmplt(vi32x4 a, vi32x4 b) {
  return vi32x4(vreinterpretq_s32_u32(vcltq_s32(a.v, b.v)));
}
/// Bitwise, as SSE2's and / andnot / or (any mask, not only all-ones / zero lanes).
inline vi32x4 select(vi32x4 mask, vi32x4 a, vi32x4 b) {
  return vi32x4(vbslq_s32(vreinterpretq_u32_s32(mask.v), a.v, b.v));
}
inline vi32x4 min(vi32x4 a, vi32x4 b) { return vi32x4(vminq_s32(a.v, b.v)); }
inline vi32x4 max(vi32x4 a, vi32x4 b) { return vi32x4(vmaxq_s32(a.v, b.v)); }
inline vi32x4 swap_pairs(vi32x4 a) { return vi32x4(vrev64q_s32(a.v)); }
inline vi32x4 swap_pairs64(vi32x4 a) { return vi32x4(vextq_s32(a.v, a.v, 2)); }
inline vi32x4 select_alpha(vi32x4 rgb, vi32x4 a) {
  return vi32x4(vcopyq_laneq_s32(rgb.v, 3, a.v, 3));
}
/// The sign bits, shifted to bit i and summed across the lanes.
inline int movemask(vi32x4 mask) {
  const std::int32_t k[4] = {0, 1, 2, 3};
  const uint32x4_t s = vshrq_n_u32(vreinterpretq_u32_s32(mask.v), 31);
  return int(vaddvq_u32(vshlq_u32(s, vld1q_s32(k))));
}
inline vi32x4 pair_sums(vi32x4 a, vi32x4 b) { return vi32x4(vpaddq_s32(a.v, b.v)); }
inline vi32x4 even_lanes(vi32x4 a, vi32x4 b) { return vi32x4(vuzp1q_s32(a.v, b.v)); }
/// Wrapping, as SSE2's adds (the order of wrapping additions does not change the sum).
inline std::int32_t sum_lanes(vi32x4 a) {
  return std::int32_t(vaddvq_u32(vreinterpretq_u32_s32(a.v)));
}
inline std::int32_t sum_lanes02(vi32x4 a) {
  return std::int32_t(std::uint32_t(vgetq_lane_s32(a.v, 0)) +
                      std::uint32_t(vgetq_lane_s32(a.v, 2)));
}
/// SSE2's packs_epi32 + packus_epi16 are two saturating narrowings (int32 -> int16 -> uint8),
/// as vqmovn_s32 + vqmovun_s16: a lane outside 0..255 gives the same clamped byte.
inline void store_u8x4(vi32x4 a, std::uint8_t* out) {
  const int16x4_t h = vqmovn_s32(a.v);
  const uint8x8_t b = vqmovun_s16(vcombine_s16(h, h));
  const std::uint32_t w = vget_lane_u32(vreinterpret_u32_u8(b), 0);
  std::memcpy(out, &w, 4);
}

struct vi64x2 {
  int64x2_t v;
  vi64x2() : v(vdupq_n_s64(0)) {}
  explicit vi64x2(int64x2_t x) : v(x) {}
  explicit vi64x2(std::int64_t a) : v(vdupq_n_s64(a)) {}
  vi64x2(std::int64_t lo, std::int64_t hi)
      : v(vcombine_s64(vcreate_s64(std::uint64_t(lo)), vcreate_s64(std::uint64_t(hi)))) {}
};
inline vi64x2 load_i64x2(const std::int64_t* p) { return vi64x2(vld1q_s64(p)); }
inline vi64x2 operator+(vi64x2 a, vi64x2 b) { return vi64x2(vaddq_s64(a.v, b.v)); }
inline vi64x2 operator|(vi64x2 a, vi64x2 b) { return vi64x2(vorrq_s64(a.v, b.v)); }
inline int movemask(vi64x2 a) {
  const uint64x2_t s = vshrq_n_u64(vreinterpretq_u64_s64(a.v), 63);
  return int(vgetq_lane_u64(s, 0) | vgetq_lane_u64(s, 1) << 1);
}

// ---- vf32x4 ----

// NEON: add, sub, mul, sqrt and int -> float are single correctly rounded IEEE operations as
// on SSE (AArch64 Linux runs with round-to-nearest and without flush-to-zero, like SSE's
// default MXCSR; the build turns off GCC's contraction of a * b + c into a fused multiply-add:
// see CMakeLists.txt). min / max and float -> int differ in their instructions and are
// emulated; compares are the same predicates.
struct vf32x4 {
  float32x4_t v;
  vf32x4() : v(vdupq_n_f32(0.0f)) {}
  explicit vf32x4(float32x4_t x) : v(x) {}
  explicit vf32x4(float a) : v(vdupq_n_f32(a)) {}
  vf32x4(float a, float b, float c, float d) {
    const float t[4] = {a, b, c, d};
    v = vld1q_f32(t);
  }
};
inline vf32x4 loadf4(const float* p) { return vf32x4(vld1q_f32(p)); }
inline void storef4(vf32x4 a, float* p) { vst1q_f32(p, a.v); }
inline vf32x4 loadf4_aligned(const float* p) { return vf32x4(vld1q_f32(p)); }
inline void storef4_aligned(vf32x4 a, float* p) { vst1q_f32(p, a.v); }
inline vf32x4 operator+(vf32x4 a, vf32x4 b) { return vf32x4(vaddq_f32(a.v, b.v)); }
inline vf32x4 operator-(vf32x4 a, vf32x4 b) { return vf32x4(vsubq_f32(a.v, b.v)); }
inline vf32x4 operator*(vf32x4 a, vf32x4 b) { return vf32x4(vmulq_f32(a.v, b.v)); }
inline vf32x4 operator/(vf32x4 a, vf32x4 b) { return vf32x4(vdivq_f32(a.v, b.v)); }
inline vf32x4 sqrt(vf32x4 a) { return vf32x4(vsqrtq_f32(a.v)); }
/// Not vmaxq_f32 / vminq_f32 (NaN when either lane is NaN, and +0 > -0): a compare and a
/// bitwise select, which give SSE's maxps / minps exactly (`b` when the compare fails).
inline vf32x4 max(vf32x4 a, vf32x4 b) { return vf32x4(vbslq_f32(vcgtq_f32(a.v, b.v), a.v, b.v)); }
inline vf32x4 min(vf32x4 a, vf32x4 b) { return vf32x4(vbslq_f32(vcltq_f32(a.v, b.v), a.v, b.v)); }
inline vi32x4 cmpeq(vf32x4 a, vf32x4 b) {
  return vi32x4(vreinterpretq_s32_u32(vceqq_f32(a.v, b.v)));
}
inline vi32x4 cmplt(vf32x4 a, vf32x4 b) {
  return vi32x4(vreinterpretq_s32_u32(vcltq_f32(a.v, b.v)));
}
inline vi32x4 cmple(vf32x4 a, vf32x4 b) {
  return vi32x4(vreinterpretq_s32_u32(vcleq_f32(a.v, b.v)));
}
inline vi32x4 cmpgt(vf32x4 a, vf32x4 b) {
  return vi32x4(vreinterpretq_s32_u32(vcgtq_f32(a.v, b.v)));
}
inline vi32x4 cmpnge(vf32x4 a, vf32x4 b) {
  return vi32x4(vreinterpretq_s32_u32(vmvnq_u32(vcgeq_f32(a.v, b.v))));
}
inline vi32x4 cmpord(vf32x4 a, vf32x4 b) {
  return vi32x4(vreinterpretq_s32_u32(vandq_u32(vceqq_f32(a.v, a.v), vceqq_f32(b.v, b.v))));
}
inline vf32x4 select(vi32x4 mask, vf32x4 a, vf32x4 b) {
  return vf32x4(vbslq_f32(vreinterpretq_u32_s32(mask.v), a.v, b.v));
}
inline vf32x4 keep_where(vi32x4 mask, vf32x4 a) {
  return vf32x4(vreinterpretq_f32_s32(vandq_s32(mask.v, vreinterpretq_s32_f32(a.v))));
}
inline vf32x4 zero_where(vi32x4 mask, vf32x4 a) {
  return vf32x4(vreinterpretq_f32_s32(vbicq_s32(vreinterpretq_s32_f32(a.v), mask.v)));
}
inline vf32x4 as_float(vi32x4 a) { return vf32x4(vreinterpretq_f32_s32(a.v)); }
inline vi32x4 as_int(vf32x4 a) { return vi32x4(vreinterpretq_s32_f32(a.v)); }
inline vf32x4 to_float(vi32x4 a) { return vf32x4(vcvtq_f32_s32(a.v)); }
/// fcvtzs saturates (>= 2^31 -> INT32_MAX, NaN -> 0) where cvttps2dq gives INT32_MIN for
/// every lane it cannot represent: those lanes (NaN, >= 2^31; below -2^31 both give INT32_MIN)
/// are set to INT32_MIN.
inline vi32x4 to_int_trunc(vf32x4 a) {
  const uint32x4_t in_range = vcltq_f32(a.v, vdupq_n_f32(2147483648.0f));
  return vi32x4(vbslq_s32(in_range, vcvtq_s32_f32(a.v), vdupq_n_s32(INT32_MIN)));
}
inline vf32x4 even_lanes(vf32x4 a, vf32x4 b) { return vf32x4(vuzp1q_f32(a.v, b.v)); }
inline vf32x4 odd_lanes(vf32x4 a, vf32x4 b) { return vf32x4(vuzp2q_f32(a.v, b.v)); }
namespace detail {
/// 4x4 transpose of 32-bit lanes (bits moved, never converted): trn1 / trn2 of the 32-bit
/// lanes, then of the 64-bit halves.
inline void transpose_u32x4(uint32x4_t& a, uint32x4_t& b, uint32x4_t& c, uint32x4_t& d) {
  const uint64x2_t ab0 = vreinterpretq_u64_u32(vtrn1q_u32(a, b));  // a0 b0 a2 b2
  const uint64x2_t ab1 = vreinterpretq_u64_u32(vtrn2q_u32(a, b));  // a1 b1 a3 b3
  const uint64x2_t cd0 = vreinterpretq_u64_u32(vtrn1q_u32(c, d));  // c0 d0 c2 d2
  const uint64x2_t cd1 = vreinterpretq_u64_u32(vtrn2q_u32(c, d));  // c1 d1 c3 d3
  a = vreinterpretq_u32_u64(vtrn1q_u64(ab0, cd0));
  b = vreinterpretq_u32_u64(vtrn1q_u64(ab1, cd1));
  c = vreinterpretq_u32_u64(vtrn2q_u64(ab0, cd0));
  d = vreinterpretq_u32_u64(vtrn2q_u64(ab1, cd1));
}
}  // namespace detail
inline void transpose(vf32x4& a, vf32x4& b, vf32x4& c, vf32x4& d) {
  uint32x4_t w = vreinterpretq_u32_f32(a.v), x = vreinterpretq_u32_f32(b.v);
  uint32x4_t y = vreinterpretq_u32_f32(c.v), z = vreinterpretq_u32_f32(d.v);
  detail::transpose_u32x4(w, x, y, z);
  a = vf32x4(vreinterpretq_f32_u32(w));
  b = vf32x4(vreinterpretq_f32_u32(x));
  c = vf32x4(vreinterpretq_f32_u32(y));
  d = vf32x4(vreinterpretq_f32_u32(z));
}
inline void transpose(vi32x4& a, vi32x4& b, vi32x4& c, vi32x4& d) {
  uint32x4_t w = vreinterpretq_u32_s32(a.v), x = vreinterpretq_u32_s32(b.v);
  uint32x4_t y = vreinterpretq_u32_s32(c.v), z = vreinterpretq_u32_s32(d.v);
  detail::transpose_u32x4(w, x, y, z);
  a = vi32x4(vreinterpretq_s32_u32(w));
  b = vi32x4(vreinterpretq_s32_u32(x));
  c = vi32x4(vreinterpretq_s32_u32(y));
  d = vi32x4(vreinterpretq_s32_u32(z));
}
/// SSE2's pairwise order (lanes 1 0 3 2, then 2 3 0 1) with its max / min: the same NaN result.
inline vf32x4 hmax(vf32x4 a) {
  const vf32x4 m = max(a, vf32x4(vrev64q_f32(a.v)));
  return max(m, vf32x4(vextq_f32(m.v, m.v, 2)));
}
inline vf32x4 hmin(vf32x4 a) {
  const vf32x4 m = min(a, vf32x4(vrev64q_f32(a.v)));
  return min(m, vf32x4(vextq_f32(m.v, m.v, 2)));
}

// ---- vu16x8, vu8x16 ----

// NEON. SSE2's packus_epi16 / packs_epi32 read their lanes as signed and saturate: vqmovun_s16
// / vqmovn_s32 do the same, so narrowings give SSE2's bytes for every lane value.
struct vu16x8 {
  uint16x8_t v;
  vu16x8() : v(vdupq_n_u16(0)) {}
  explicit vu16x8(uint16x8_t x) : v(x) {}
  explicit vu16x8(std::uint16_t a) : v(vdupq_n_u16(a)) {}
  std::int32_t lane_sq(int i) const {
    std::int16_t t[8];
    vst1q_s16(t, vreinterpretq_s16_u16(v));
    return std::int32_t(t[i]) * t[i];
  }
};
inline vu16x8 load_u8x8(const std::uint8_t* p) { return vu16x8(vmovl_u8(vld1_u8(p))); }
inline vu16x8 load_u16x8(const std::uint16_t* p) { return vu16x8(vld1q_u16(p)); }
inline void store_u16x8(vu16x8 a, std::uint16_t* p) { vst1q_u16(p, a.v); }
inline void store_u8x8(vu16x8 a, std::uint8_t* p) {
  vst1_u8(p, vqmovun_s16(vreinterpretq_s16_u16(a.v)));
}
inline vu16x8 operator+(vu16x8 a, vu16x8 b) { return vu16x8(vaddq_u16(a.v, b.v)); }
inline vu16x8 operator-(vu16x8 a, vu16x8 b) { return vu16x8(vsubq_u16(a.v, b.v)); }
inline vu16x8 mullo(vu16x8 a, vu16x8 b) { return vu16x8(vmulq_u16(a.v, b.v)); }
/// pmaddwd: signed 16 x 16 -> 32-bit products, adjacent pairs added (wrapping: only
/// 2 * (-32768)^2 overflows, to INT32_MIN, as pmaddwd).
inline vi32x4 madd(vu16x8 a, vu16x8 b) {
  const int16x8_t x = vreinterpretq_s16_u16(a.v), y = vreinterpretq_s16_u16(b.v);
  const int32x4_t lo = vmull_s16(vget_low_s16(x), vget_low_s16(y));
  return vi32x4(vpaddq_s32(lo, vmull_high_s16(x, y)));
}
inline vu16x8 load_u8x4x2(const std::uint8_t* p0, const std::uint8_t* p1) {
  std::uint32_t a, b;
  std::memcpy(&a, p0, 4);
  std::memcpy(&b, p1, 4);
  const uint32x2_t w = vset_lane_u32(b, vdup_n_u32(a), 1);
  return vu16x8(vmovl_u8(vreinterpret_u8_u32(w)));
}
inline vu16x8 operator&(vu16x8 a, vu16x8 b) { return vu16x8(vandq_u16(a.v, b.v)); }
inline vu16x8 operator|(vu16x8 a, vu16x8 b) { return vu16x8(vorrq_u16(a.v, b.v)); }
/// The odd 16-bit halves (the high ones, little-endian) of the 32-bit products.
inline vu16x8 mulhi(vu16x8 a, vu16x8 b) {
  const uint32x4_t lo = vmull_u16(vget_low_u16(a.v), vget_low_u16(b.v));
  const uint32x4_t hi = vmull_high_u16(a.v, b.v);
  return vu16x8(vuzp2q_u16(vreinterpretq_u16_u32(lo), vreinterpretq_u16_u32(hi)));
}
/// N = 0 and N >= 16 spelled out (NEON's immediate takes 1..16): SSE2 gives zero for N >= 16.
template <int N>
inline vu16x8 srl(vu16x8 a) {
  static_assert(N >= 0);
  if constexpr (N == 0) {
    return a;
  } else if constexpr (N >= 16) {
    return vu16x8();
  } else {
    return vu16x8(vshrq_n_u16(a.v, N));
  }
}
inline vu16x8 cmpeq(vu16x8 a, vu16x8 b) { return vu16x8(vceqq_u16(a.v, b.v)); }
inline vu16x8 select(vu16x8 mask, vu16x8 a, vu16x8 b) {
  return vu16x8(vbslq_u16(mask.v, a.v, b.v));
}

inline vu16x8 max_s16(vu16x8 a, vu16x8 b) {
  return vu16x8(
      vreinterpretq_u16_s16(vmaxq_s16(vreinterpretq_s16_u16(a.v), vreinterpretq_s16_u16(b.v))));
}
inline vu16x8 min_s16(vu16x8 a, vu16x8 b) {
  return vu16x8(
      vreinterpretq_u16_s16(vminq_s16(vreinterpretq_s16_u16(a.v), vreinterpretq_s16_u16(b.v))));
}
inline vu16x8 cmpgt_s16(vu16x8 a, vu16x8 b) {
  return vu16x8(vcgtq_s16(vreinterpretq_s16_u16(a.v), vreinterpretq_s16_u16(b.v)));
}
inline vu16x8 select_alpha(vu16x8 rgb, vu16x8 a) {
  const uint16x8_t m = vreinterpretq_u16_u64(vdupq_n_u64(0xffff000000000000ull));
  return vu16x8(vbslq_u16(m, a.v, rgb.v));
}
inline vu16x8 load_u8x4_lo(const std::uint8_t* p) {
  std::uint32_t w;
  std::memcpy(&w, p, 4);
  return vu16x8(vmovl_u8(vreinterpret_u8_u32(vset_lane_u32(w, vdup_n_u32(0), 0))));
}
inline void store_u8x4(vu16x8 a, std::uint8_t* p) {
  const std::uint32_t w =
      vget_lane_u32(vreinterpret_u32_u8(vqmovun_s16(vreinterpretq_s16_u16(a.v))), 0);
  std::memcpy(p, &w, 4);
}

struct vu8x16 {
  uint8x16_t v;
  vu8x16() : v(vdupq_n_u8(0)) {}
  explicit vu8x16(uint8x16_t x) : v(x) {}
  explicit vu8x16(std::uint8_t a) : v(vdupq_n_u8(a)) {}
};
inline vu8x16 load_u8x16(const std::uint8_t* p) { return vu8x16(vld1q_u8(p)); }
inline void store_u8x16(vu8x16 a, std::uint8_t* p) { vst1q_u8(p, a.v); }
inline vu8x16 operator+(vu8x16 a, vu8x16 b) { return vu8x16(vaddq_u8(a.v, b.v)); }
inline vu8x16 operator&(vu8x16 a, vu8x16 b) { return vu8x16(vandq_u8(a.v, b.v)); }
inline vu8x16 operator|(vu8x16 a, vu8x16 b) { return vu8x16(vorrq_u8(a.v, b.v)); }
inline vu8x16 cmpeq(vu8x16 a, vu8x16 b) { return vu8x16(vceqq_u8(a.v, b.v)); }
inline vu8x16 andnot(vu8x16 a, vu8x16 b) { return vu8x16(vbicq_u8(b.v, a.v)); }
inline vu8x16 select(vu8x16 mask, vu8x16 a, vu8x16 b) { return vu8x16(vbslq_u8(mask.v, a.v, b.v)); }
/// A lane has its top bit set exactly when the largest lane does.
inline bool any(vu8x16 mask) { return vmaxvq_u8(mask.v) >= 0x80; }
inline vu16x8 widen_lo(vu8x16 a) { return vu16x8(vmovl_u8(vget_low_u8(a.v))); }
inline vu16x8 widen_hi(vu8x16 a) { return vu16x8(vmovl_high_u8(a.v)); }
inline vu8x16 narrow(vu16x8 lo, vu16x8 hi) {
  return vu8x16(vcombine_u8(vqmovun_s16(vreinterpretq_s16_u16(lo.v)),
                            vqmovun_s16(vreinterpretq_s16_u16(hi.v))));
}
inline vu8x16 narrow(vi32x4 a, vi32x4 b, vi32x4 c, vi32x4 d) {
  const int16x8_t ab = vcombine_s16(vqmovn_s32(a.v), vqmovn_s32(b.v));
  const int16x8_t cd = vcombine_s16(vqmovn_s32(c.v), vqmovn_s32(d.v));
  return vu8x16(vcombine_u8(vqmovun_s16(ab), vqmovun_s16(cd)));
}

inline vu16x8 narrow16(vi32x4 a, vi32x4 b) {
  return vu16x8(vreinterpretq_u16_s16(vcombine_s16(vqmovn_s32(a.v), vqmovn_s32(b.v))));
}
inline vu16x8 zip_lo(vu16x8 a, vu16x8 b) { return vu16x8(vzip1q_u16(a.v, b.v)); }
inline vu16x8 zip_hi(vu16x8 a, vu16x8 b) { return vu16x8(vzip2q_u16(a.v, b.v)); }
/// One table lookup each over the bytes of p[0..3] (the 8 bytes SSE2 loads).
inline void taps8(const std::uint16_t* p, vu16x8& left, vu16x8& right) {
  static constexpr std::uint8_t kLeft[16] = {0, 1, 0, 1, 2, 3, 2, 3, 2, 3, 2, 3, 4, 5, 4, 5};
  static constexpr std::uint8_t kRight[16] = {2, 3, 2, 3, 4, 5, 4, 5, 4, 5, 4, 5, 6, 7, 6, 7};
  const uint8x16_t x = vreinterpretq_u8_u16(vcombine_u16(vld1_u16(p), vdup_n_u16(0)));
  left = vu16x8(vreinterpretq_u16_u8(vqtbl1q_u8(x, vld1q_u8(kLeft))));
  right = vu16x8(vreinterpretq_u16_u8(vqtbl1q_u8(x, vld1q_u8(kRight))));
}
inline vf32x4 f2p23_plus_lo(vu16x8 a) {
  return vf32x4(vreinterpretq_f32_u16(vzip1q_u16(a.v, vdupq_n_u16(0x4b00))));
}
inline vf32x4 f2p23_plus_hi(vu16x8 a) {
  return vf32x4(vreinterpretq_f32_u16(vzip2q_u16(a.v, vdupq_n_u16(0x4b00))));
}
inline vi32x4 widen32_lo(vu16x8 a) {
  return vi32x4(vreinterpretq_s32_u32(vmovl_u16(vget_low_u16(a.v))));
}
inline vi32x4 widen32_hi(vu16x8 a) { return vi32x4(vreinterpretq_s32_u32(vmovl_high_u16(a.v))); }
/// vld4q_u16 de-interleaves exactly this way.
inline void transpose_8x4(const std::uint16_t* p, vu16x8 out[4]) {
  const uint16x8x4_t t = vld4q_u16(p);
  for (int c = 0; c < 4; ++c) out[c] = vu16x8(t.val[c]);
}

}  // namespace TESSERA_SIMD_ISA
}  // namespace tessera::simd
