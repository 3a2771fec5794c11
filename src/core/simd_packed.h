// simd_packed.h — part of the SIMD wrapper (include "core/simd.h", which documents the whole set):
// the packed small-integer lanes of the PVRTC kernels, and their conversions to and from the
// 32-bit lanes (vi32x4) and floats (vf32x4):
//   vu16x8  eight unsigned 16-bit lanes: one plane of eight texels widened from bytes.
//   vu8x16  sixteen unsigned 8-bit lanes: sixteen bytes of texels or codes.
#pragma once

#include <cstdint>
#include <cstring>

#include "core/simd_float.h"
#include "core/simd_int.h"

namespace tessera::simd {
inline namespace TESSERA_SIMD_ISA {

#if defined(TESSERA_SIMD_SSE2)

/// Eight unsigned 16-bit lanes (texels of one plane widened from bytes).
struct vu16x8 {
  __m128i v;
  vu16x8() : v(_mm_setzero_si128()) {}
  explicit vu16x8(__m128i x) : v(x) {}
  explicit vu16x8(std::uint16_t a) : v(_mm_set1_epi16(static_cast<short>(a))) {}
  /// Square of lane i read as a signed 16-bit value.
  std::int32_t lane_sq(int i) const {
    alignas(16) std::int16_t t[8];
    _mm_store_si128(reinterpret_cast<__m128i*>(t), v);
    return std::int32_t(t[i]) * t[i];
  }
};
/// Loads 8 bytes, zero-extended to 16-bit lanes.
inline vu16x8 load_u8x8(const std::uint8_t* p) {
  return vu16x8(
      _mm_unpacklo_epi8(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(p)), _mm_setzero_si128()));
}
inline vu16x8 load_u16x8(const std::uint16_t* p) {
  return vu16x8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)));
}
inline void store_u16x8(vu16x8 a, std::uint16_t* p) {
  _mm_storeu_si128(reinterpret_cast<__m128i*>(p), a.v);
}
/// Stores each lane as a byte: lanes 0..255 as they are (SSE2's packus_epi16, in every backend:
/// others clamped to 0..255 as signed 16-bit values).
inline void store_u8x8(vu16x8 a, std::uint8_t* p) {
  _mm_storel_epi64(reinterpret_cast<__m128i*>(p), _mm_packus_epi16(a.v, a.v));
}
inline vu16x8 operator+(vu16x8 a, vu16x8 b) { return vu16x8(_mm_add_epi16(a.v, b.v)); }
inline vu16x8 operator-(vu16x8 a, vu16x8 b) { return vu16x8(_mm_sub_epi16(a.v, b.v)); }
/// Low 16 bits of the lane products.
inline vu16x8 mullo(vu16x8 a, vu16x8 b) { return vu16x8(_mm_mullo_epi16(a.v, b.v)); }
/// Signed lanes: sums of adjacent products, a0*b0 + a1*b1, ... as four 32-bit lanes.
inline vi32x4 madd(vu16x8 a, vu16x8 b) { return vi32x4(_mm_madd_epi16(a.v, b.v)); }
/// Loads 8 bytes, zero-extended, from two 4-byte texels.
inline vu16x8 load_u8x4x2(const std::uint8_t* p0, const std::uint8_t* p1) {
  std::int32_t a, b;
  std::memcpy(&a, p0, 4);
  std::memcpy(&b, p1, 4);
  return vu16x8(_mm_unpacklo_epi8(_mm_unpacklo_epi32(_mm_cvtsi32_si128(a), _mm_cvtsi32_si128(b)),
                                  _mm_setzero_si128()));
}
inline vu16x8 operator&(vu16x8 a, vu16x8 b) { return vu16x8(_mm_and_si128(a.v, b.v)); }
inline vu16x8 operator|(vu16x8 a, vu16x8 b) { return vu16x8(_mm_or_si128(a.v, b.v)); }
/// High 16 bits of the 32-bit products.
inline vu16x8 mulhi(vu16x8 a, vu16x8 b) { return vu16x8(_mm_mulhi_epu16(a.v, b.v)); }
template <int N>
inline vu16x8 srl(vu16x8 a) {
  return vu16x8(_mm_srli_epi16(a.v, N));
}
/// All-ones lanes where a == b.
inline vu16x8 cmpeq(vu16x8 a, vu16x8 b) { return vu16x8(_mm_cmpeq_epi16(a.v, b.v)); }
/// Lanes of `a` where `mask` is all ones, else lanes of `b`.
inline vu16x8 select(vu16x8 mask, vu16x8 a, vu16x8 b) {
  return vu16x8(_mm_or_si128(_mm_and_si128(mask.v, a.v), _mm_andnot_si128(mask.v, b.v)));
}

/// Sixteen unsigned 8-bit lanes.
/// Lanes read as int16: the signed maximum, minimum and greater-than mask.
inline vu16x8 max_s16(vu16x8 a, vu16x8 b) { return vu16x8(_mm_max_epi16(a.v, b.v)); }
inline vu16x8 min_s16(vu16x8 a, vu16x8 b) { return vu16x8(_mm_min_epi16(a.v, b.v)); }
inline vu16x8 cmpgt_s16(vu16x8 a, vu16x8 b) { return vu16x8(_mm_cmpgt_epi16(a.v, b.v)); }
/// Lanes 3 and 7 (the alpha lanes of two RGBA texels) from `a`, the rest from `rgb`.
inline vu16x8 select_alpha(vu16x8 rgb, vu16x8 a) {
  const __m128i m = _mm_setr_epi16(0, 0, 0, -1, 0, 0, 0, -1);
  return vu16x8(_mm_or_si128(_mm_andnot_si128(m, rgb.v), _mm_and_si128(m, a.v)));
}
/// Four bytes zero-extended into lanes 0-3; lanes 4-7 zero.
inline vu16x8 load_u8x4_lo(const std::uint8_t* p) {
  std::int32_t w;
  std::memcpy(&w, p, 4);
  return vu16x8(_mm_unpacklo_epi8(_mm_cvtsi32_si128(w), _mm_setzero_si128()));
}
/// Lanes 0-3 as four bytes, clamped as store_u8x8.
inline void store_u8x4(vu16x8 a, std::uint8_t* p) {
  const std::int32_t w = _mm_cvtsi128_si32(_mm_packus_epi16(a.v, a.v));
  std::memcpy(p, &w, 4);
}

struct vu8x16 {
  __m128i v;
  vu8x16() : v(_mm_setzero_si128()) {}
  explicit vu8x16(__m128i x) : v(x) {}
  explicit vu8x16(std::uint8_t a) : v(_mm_set1_epi8(static_cast<char>(a))) {}
};
inline vu8x16 load_u8x16(const std::uint8_t* p) {
  return vu8x16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)));
}
inline void store_u8x16(vu8x16 a, std::uint8_t* p) {
  _mm_storeu_si128(reinterpret_cast<__m128i*>(p), a.v);
}
/// Wrapping 8-bit addition.
inline vu8x16 operator+(vu8x16 a, vu8x16 b) { return vu8x16(_mm_add_epi8(a.v, b.v)); }
inline vu8x16 operator&(vu8x16 a, vu8x16 b) { return vu8x16(_mm_and_si128(a.v, b.v)); }
inline vu8x16 operator|(vu8x16 a, vu8x16 b) { return vu8x16(_mm_or_si128(a.v, b.v)); }
inline vu8x16 cmpeq(vu8x16 a, vu8x16 b) { return vu8x16(_mm_cmpeq_epi8(a.v, b.v)); }
/// ~a & b.
inline vu8x16 andnot(vu8x16 a, vu8x16 b) { return vu8x16(_mm_andnot_si128(a.v, b.v)); }
inline vu8x16 select(vu8x16 mask, vu8x16 a, vu8x16 b) {
  return vu8x16(_mm_or_si128(_mm_and_si128(mask.v, a.v), _mm_andnot_si128(mask.v, b.v)));
}
/// True when any lane is non-zero in its top bit (masks from cmpeq).
inline bool any(vu8x16 mask) { return _mm_movemask_epi8(mask.v) != 0; }
/// Lanes 0-7 / 8-15 zero-extended to 16 bits.
inline vu16x8 widen_lo(vu8x16 a) { return vu16x8(_mm_unpacklo_epi8(a.v, _mm_setzero_si128())); }
inline vu16x8 widen_hi(vu8x16 a) { return vu16x8(_mm_unpackhi_epi8(a.v, _mm_setzero_si128())); }
/// Lanes of lo then hi as bytes (each 0..255; others clamped as by store_u8x8).
inline vu8x16 narrow(vu16x8 lo, vu16x8 hi) { return vu8x16(_mm_packus_epi16(lo.v, hi.v)); }
/// Sixteen 32-bit lanes (in order a, b, c, d) as bytes, each clamped to 0..255.
inline vu8x16 narrow(vi32x4 a, vi32x4 b, vi32x4 c, vi32x4 d) {
  return vu8x16(_mm_packus_epi16(_mm_packs_epi32(a.v, b.v), _mm_packs_epi32(c.v, d.v)));
}

/// Lanes 0-3 of a then 0-3 of b as 16-bit lanes (each 0..32767; others clamped to
/// -32768..32767, SSE2's packs_epi32, in every backend).
inline vu16x8 narrow16(vi32x4 a, vi32x4 b) { return vu16x8(_mm_packs_epi32(a.v, b.v)); }
/// Interleaves lanes 0-3 (zip_lo) or 4-7 (zip_hi) of a and b: a0 b0 a1 b1 ...
inline vu16x8 zip_lo(vu16x8 a, vu16x8 b) { return vu16x8(_mm_unpacklo_epi16(a.v, b.v)); }
inline vu16x8 zip_hi(vu16x8 a, vu16x8 b) { return vu16x8(_mm_unpackhi_epi16(a.v, b.v)); }
/// Bilinear taps of 8 texels spanning two 4-texel blocks: from p[0..3], left =
/// (p0 p0 p1 p1 p1 p1 p2 p2) and right = (p1 p1 p2 p2 p2 p2 p3 p3).
inline void taps8(const std::uint16_t* p, vu16x8& left, vu16x8& right) {
  const __m128i x = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(p));
  const __m128i xx = _mm_unpacklo_epi64(x, x);
  left = vu16x8(_mm_shufflehi_epi16(_mm_shufflelo_epi16(xx, _MM_SHUFFLE(1, 1, 0, 0)),
                                    _MM_SHUFFLE(2, 2, 1, 1)));
  right = vu16x8(_mm_shufflehi_epi16(_mm_shufflelo_epi16(xx, _MM_SHUFFLE(2, 2, 1, 1)),
                                     _MM_SHUFFLE(3, 3, 2, 2)));
}
/// 2^23 + lane i of `a` (lanes 0-3: _lo, 4-7: _hi) as floats, exact: the 16-bit value placed in
/// the mantissa of 2^23.
inline vf32x4 f2p23_plus_lo(vu16x8 a) {
  return vf32x4(_mm_castsi128_ps(_mm_unpacklo_epi16(a.v, _mm_set1_epi16(0x4b00))));
}
inline vf32x4 f2p23_plus_hi(vu16x8 a) {
  return vf32x4(_mm_castsi128_ps(_mm_unpackhi_epi16(a.v, _mm_set1_epi16(0x4b00))));
}
/// Lanes 0-3 (_lo) or 4-7 (_hi) zero-extended to 32 bits.
inline vi32x4 widen32_lo(vu16x8 a) { return vi32x4(_mm_unpacklo_epi16(a.v, _mm_setzero_si128())); }
inline vi32x4 widen32_hi(vu16x8 a) { return vi32x4(_mm_unpackhi_epi16(a.v, _mm_setzero_si128())); }
/// Eight texels of four 16-bit channels (p: 32 values, texel by texel) as one vector per
/// channel: out[c] lane i = p[4 i + c].
inline void transpose_8x4(const std::uint16_t* p, vu16x8 out[4]) {
  const __m128i* q = reinterpret_cast<const __m128i*>(p);
  const __m128i v0 = _mm_loadu_si128(q), v1 = _mm_loadu_si128(q + 1);
  const __m128i v2 = _mm_loadu_si128(q + 2), v3 = _mm_loadu_si128(q + 3);
  const __m128i a0 = _mm_unpacklo_epi16(v0, v1), a1 = _mm_unpackhi_epi16(v0, v1);
  const __m128i a2 = _mm_unpacklo_epi16(v2, v3), a3 = _mm_unpackhi_epi16(v2, v3);
  const __m128i b0 = _mm_unpacklo_epi16(a0, a1), b1 = _mm_unpackhi_epi16(a0, a1);
  const __m128i b2 = _mm_unpacklo_epi16(a2, a3), b3 = _mm_unpackhi_epi16(a2, a3);
  out[0] = vu16x8(_mm_unpacklo_epi64(b0, b2));
  out[1] = vu16x8(_mm_unpackhi_epi64(b0, b2));
  out[2] = vu16x8(_mm_unpacklo_epi64(b1, b3));
  out[3] = vu16x8(_mm_unpackhi_epi64(b1, b3));
}

#elif defined(TESSERA_SIMD_NEON)

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

#else  // scalar backend

struct vu16x8 {
  std::uint16_t l[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  vu16x8() = default;
  explicit vu16x8(std::uint16_t a) {
    for (auto& x : l) x = a;
  }
  std::int32_t lane_sq(int i) const {
    return std::int32_t(std::int16_t(l[i])) * std::int16_t(l[i]);
  }
};
inline vu16x8 load_u8x8(const std::uint8_t* p) {
  vu16x8 r;
  for (int i = 0; i < 8; ++i) r.l[i] = p[i];
  return r;
}
inline vu16x8 load_u16x8(const std::uint16_t* p) {
  vu16x8 r;
  for (int i = 0; i < 8; ++i) r.l[i] = p[i];
  return r;
}
inline void store_u16x8(vu16x8 a, std::uint16_t* p) {
  for (int i = 0; i < 8; ++i) p[i] = a.l[i];
}
// SSE2's packus_epi16 (narrowings to bytes): the lane read as signed, clamped to 0..255.
namespace detail {
inline std::uint8_t packus16(std::uint16_t x) {
  const std::int16_t s = std::int16_t(x);
  return std::uint8_t(s < 0 ? 0 : s > 255 ? 255 : s);
}
}  // namespace detail
inline void store_u8x8(vu16x8 a, std::uint8_t* p) {
  for (int i = 0; i < 8; ++i) p[i] = detail::packus16(a.l[i]);
}
#define TESSERA_SIMD_U16_BINOP(op, expr)                      \
  inline vu16x8 op(vu16x8 a, vu16x8 b) {                      \
    vu16x8 r;                                                 \
    for (int i = 0; i < 8; ++i) r.l[i] = std::uint16_t(expr); \
    return r;                                                 \
  }
TESSERA_SIMD_U16_BINOP(operator+, a.l[i] + b.l[i])
TESSERA_SIMD_U16_BINOP(operator&, a.l[i] & b.l[i])
TESSERA_SIMD_U16_BINOP(operator-, a.l[i] - b.l[i])
TESSERA_SIMD_U16_BINOP(mullo, std::uint32_t(a.l[i]) * b.l[i])
TESSERA_SIMD_U16_BINOP(operator|, a.l[i] | b.l[i])
TESSERA_SIMD_U16_BINOP(mulhi, (std::uint32_t(a.l[i]) * b.l[i]) >> 16)
TESSERA_SIMD_U16_BINOP(cmpeq, a.l[i] == b.l[i] ? 0xffff : 0)
#undef TESSERA_SIMD_U16_BINOP
inline vi32x4 madd(vu16x8 a, vu16x8 b) {
  vi32x4 r;
  for (int i = 0; i < 4; ++i) {
    r.l[i] = std::int32_t(std::int16_t(a.l[2 * i])) * std::int16_t(b.l[2 * i]) +
             std::int32_t(std::int16_t(a.l[2 * i + 1])) * std::int16_t(b.l[2 * i + 1]);
  }
  return r;
}
inline vu16x8 load_u8x4x2(const std::uint8_t* p0, const std::uint8_t* p1) {
  vu16x8 r;
  for (int i = 0; i < 4; ++i) {
    r.l[i] = p0[i];
    r.l[4 + i] = p1[i];
  }
  return r;
}
template <int N>
inline vu16x8 srl(vu16x8 a) {
  static_assert(N >= 0);
  vu16x8 r;
  if constexpr (N < 16) {
    for (int i = 0; i < 8; ++i) r.l[i] = std::uint16_t(a.l[i] >> N);
  }
  return r;
}
inline vu16x8 select(vu16x8 mask, vu16x8 a, vu16x8 b) {
  vu16x8 r;
  for (int i = 0; i < 8; ++i) r.l[i] = std::uint16_t((mask.l[i] & a.l[i]) | (~mask.l[i] & b.l[i]));
  return r;
}

inline vu16x8 max_s16(vu16x8 a, vu16x8 b) {
  vu16x8 r;
  for (int i = 0; i < 8; ++i)
    r.l[i] = std::int16_t(a.l[i]) > std::int16_t(b.l[i]) ? a.l[i] : b.l[i];
  return r;
}
inline vu16x8 min_s16(vu16x8 a, vu16x8 b) {
  vu16x8 r;
  for (int i = 0; i < 8; ++i)
    r.l[i] = std::int16_t(a.l[i]) < std::int16_t(b.l[i]) ? a.l[i] : b.l[i];
  return r;
}
inline vu16x8 cmpgt_s16(vu16x8 a, vu16x8 b) {
  vu16x8 r;
  for (int i = 0; i < 8; ++i) r.l[i] = std::int16_t(a.l[i]) > std::int16_t(b.l[i]) ? 0xffff : 0;
  return r;
}
inline vu16x8 select_alpha(vu16x8 rgb, vu16x8 a) {
  rgb.l[3] = a.l[3];
  rgb.l[7] = a.l[7];
  return rgb;
}
inline vu16x8 load_u8x4_lo(const std::uint8_t* p) {
  vu16x8 r;
  for (int i = 0; i < 4; ++i) r.l[i] = p[i];
  return r;
}
inline void store_u8x4(vu16x8 a, std::uint8_t* p) {
  for (int i = 0; i < 4; ++i) p[i] = detail::packus16(a.l[i]);
}

struct vu8x16 {
  std::uint8_t l[16] = {};
  vu8x16() = default;
  explicit vu8x16(std::uint8_t a) {
    for (auto& x : l) x = a;
  }
};
inline vu8x16 load_u8x16(const std::uint8_t* p) {
  vu8x16 r;
  std::memcpy(r.l, p, 16);
  return r;
}
inline void store_u8x16(vu8x16 a, std::uint8_t* p) { std::memcpy(p, a.l, 16); }
#define TESSERA_SIMD_U8_BINOP(op, expr)                       \
  inline vu8x16 op(vu8x16 a, vu8x16 b) {                      \
    vu8x16 r;                                                 \
    for (int i = 0; i < 16; ++i) r.l[i] = std::uint8_t(expr); \
    return r;                                                 \
  }
TESSERA_SIMD_U8_BINOP(operator+, a.l[i] + b.l[i])
TESSERA_SIMD_U8_BINOP(operator&, a.l[i] & b.l[i])
TESSERA_SIMD_U8_BINOP(operator|, a.l[i] | b.l[i])
TESSERA_SIMD_U8_BINOP(cmpeq, a.l[i] == b.l[i] ? 0xff : 0)
TESSERA_SIMD_U8_BINOP(andnot, ~a.l[i] & b.l[i])
#undef TESSERA_SIMD_U8_BINOP
inline vu8x16 select(vu8x16 mask, vu8x16 a, vu8x16 b) {
  vu8x16 r;
  for (int i = 0; i < 16; ++i) r.l[i] = std::uint8_t((mask.l[i] & a.l[i]) | (~mask.l[i] & b.l[i]));
  return r;
}
inline bool any(vu8x16 mask) {
  for (std::uint8_t x : mask.l) {
    if (x & 0x80) return true;
  }
  return false;
}
inline vu16x8 widen_lo(vu8x16 a) {
  vu16x8 r;
  for (int i = 0; i < 8; ++i) r.l[i] = a.l[i];
  return r;
}
inline vu16x8 widen_hi(vu8x16 a) {
  vu16x8 r;
  for (int i = 0; i < 8; ++i) r.l[i] = a.l[8 + i];
  return r;
}
inline vu8x16 narrow(vu16x8 lo, vu16x8 hi) {
  vu8x16 r;
  for (int i = 0; i < 8; ++i) {
    r.l[i] = detail::packus16(lo.l[i]);
    r.l[8 + i] = detail::packus16(hi.l[i]);
  }
  return r;
}
inline vu8x16 narrow(vi32x4 a, vi32x4 b, vi32x4 c, vi32x4 d) {
  vu8x16 r;
  const vi32x4* v[4] = {&a, &b, &c, &d};
  for (int i = 0; i < 16; ++i) {
    const std::int32_t x = v[i / 4]->l[i % 4];
    r.l[i] = std::uint8_t(x < 0 ? 0 : x > 255 ? 255 : x);
  }
  return r;
}

// SSE2's packs_epi32: clamped to -32768..32767.
inline vu16x8 narrow16(vi32x4 a, vi32x4 b) {
  const auto packs = [](std::int32_t x) {
    return std::uint16_t(x < -32768 ? -32768 : x > 32767 ? 32767 : x);
  };
  vu16x8 r;
  for (int i = 0; i < 4; ++i) {
    r.l[i] = packs(a.l[i]);
    r.l[4 + i] = packs(b.l[i]);
  }
  return r;
}
inline vu16x8 zip_lo(vu16x8 a, vu16x8 b) {
  vu16x8 r;
  for (int i = 0; i < 4; ++i) {
    r.l[2 * i] = a.l[i];
    r.l[2 * i + 1] = b.l[i];
  }
  return r;
}
inline vu16x8 zip_hi(vu16x8 a, vu16x8 b) {
  vu16x8 r;
  for (int i = 0; i < 4; ++i) {
    r.l[2 * i] = a.l[4 + i];
    r.l[2 * i + 1] = b.l[4 + i];
  }
  return r;
}
inline void taps8(const std::uint16_t* p, vu16x8& left, vu16x8& right) {
  static constexpr int kL[8] = {0, 0, 1, 1, 1, 1, 2, 2};
  for (int i = 0; i < 8; ++i) {
    left.l[i] = p[kL[i]];
    right.l[i] = p[kL[i] + 1];
  }
}
inline vf32x4 f2p23_plus_lo(vu16x8 a) {
  vf32x4 r;
  for (int i = 0; i < 4; ++i) r.l[i] = 8388608.0f + float(a.l[i]);
  return r;
}
inline vf32x4 f2p23_plus_hi(vu16x8 a) {
  vf32x4 r;
  for (int i = 0; i < 4; ++i) r.l[i] = 8388608.0f + float(a.l[4 + i]);
  return r;
}
inline vi32x4 widen32_lo(vu16x8 a) { return {a.l[0], a.l[1], a.l[2], a.l[3]}; }
inline vi32x4 widen32_hi(vu16x8 a) { return {a.l[4], a.l[5], a.l[6], a.l[7]}; }
inline void transpose_8x4(const std::uint16_t* p, vu16x8 out[4]) {
  for (int c = 0; c < 4; ++c) {
    for (int i = 0; i < 8; ++i) out[c].l[i] = p[4 * i + c];
  }
}

#endif

}  // namespace TESSERA_SIMD_ISA
}  // namespace tessera::simd
