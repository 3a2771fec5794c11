// simd_sse.h — part of the SIMD wrapper (include "core/simd.h", which documents the whole set;
// simd_select.h includes this file where it chose this backend): the 4-lane types on x86-64,
// with SSE2 (part of the ABI, so always there) and SSE4.1 instructions (pmulld, pminsd / pmaxsd)
// where the compiler targets SSE4.1. SSE2's results are the reference that the other backends
// reproduce bit for bit.
//   vi32x4, vi64x2   the 32- and 64-bit integer lanes
//   vf32x4           the single-precision lanes
//   vu16x8, vu8x16   the packed small-integer lanes, with their conversions to and from vi32x4
//                    and vf32x4
#pragma once

#include <emmintrin.h>

#include <cstdint>
#include <cstring>
#if defined(TESSERA_SIMD_SSE41)
#include <smmintrin.h>
#endif

namespace tessera::simd {
inline namespace TESSERA_SIMD_ISA {

// ---- vi32x4, vi64x2 ----

struct vi32x4 {
  __m128i v;
  vi32x4() : v(_mm_setzero_si128()) {}
  explicit vi32x4(__m128i x) : v(x) {}
  vi32x4(std::int32_t a, std::int32_t b, std::int32_t c, std::int32_t d)
      : v(_mm_setr_epi32(a, b, c, d)) {}
  explicit vi32x4(std::int32_t a) : v(_mm_set1_epi32(a)) {}
  std::int32_t lane(int i) const {
    alignas(16) std::int32_t t[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(t), v);
    return t[i];
  }
};
inline vi32x4 load4(const std::int32_t* p) {
  return vi32x4(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)));
}
/// `p` 16-byte aligned.
inline vi32x4 load4_aligned(const std::int32_t* p) {
  return vi32x4(_mm_load_si128(reinterpret_cast<const __m128i*>(p)));
}
inline void store4(vi32x4 a, std::int32_t* p) {
  _mm_storeu_si128(reinterpret_cast<__m128i*>(p), a.v);
}
/// `p` 16-byte aligned.
inline void store4_aligned(vi32x4 a, std::int32_t* p) {
  _mm_store_si128(reinterpret_cast<__m128i*>(p), a.v);
}
/// Loads four 4-byte texels as four 32-bit lanes.
inline vi32x4 load_texels4(const std::uint8_t* p) {
  return vi32x4(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)));
}
inline vi32x4 operator+(vi32x4 a, vi32x4 b) { return vi32x4(_mm_add_epi32(a.v, b.v)); }
inline vi32x4 operator-(vi32x4 a, vi32x4 b) { return vi32x4(_mm_sub_epi32(a.v, b.v)); }
inline vi32x4& operator+=(vi32x4& a, vi32x4 b) { return a = a + b; }
/// Lane-wise product, the low 32 bits (exact for |a*b| < 2^31).
inline vi32x4 operator*(vi32x4 a, vi32x4 b) {
#if defined(TESSERA_SIMD_SSE41)
  return vi32x4(_mm_mullo_epi32(a.v, b.v));
#else
  const __m128i even = _mm_mul_epu32(a.v, b.v);
  const __m128i odd = _mm_mul_epu32(_mm_srli_epi64(a.v, 32), _mm_srli_epi64(b.v, 32));
  return vi32x4(_mm_unpacklo_epi32(_mm_shuffle_epi32(even, _MM_SHUFFLE(0, 0, 2, 0)),
                                   _mm_shuffle_epi32(odd, _MM_SHUFFLE(0, 0, 2, 0))));
#endif
}
inline vi32x4 operator&(vi32x4 a, vi32x4 b) { return vi32x4(_mm_and_si128(a.v, b.v)); }
inline vi32x4 operator|(vi32x4 a, vi32x4 b) { return vi32x4(_mm_or_si128(a.v, b.v)); }
inline vi32x4 operator^(vi32x4 a, vi32x4 b) { return vi32x4(_mm_xor_si128(a.v, b.v)); }
/// ~a & b.
inline vi32x4 andnot(vi32x4 a, vi32x4 b) { return vi32x4(_mm_andnot_si128(a.v, b.v)); }
/// Arithmetic (sra), logical (srl) right and left (sll) shifts of the 32-bit lanes.
template <int N>
inline vi32x4 sra(vi32x4 a) {
  return vi32x4(_mm_srai_epi32(a.v, N));
}
template <int N>
inline vi32x4 srl(vi32x4 a) {
  return vi32x4(_mm_srli_epi32(a.v, N));
}
template <int N>
inline vi32x4 sll(vi32x4 a) {
  return vi32x4(_mm_slli_epi32(a.v, N));
}
/// Signed compares: all-ones lanes where true, zero lanes where false.
inline vi32x4 cmpeq(vi32x4 a, vi32x4 b) { return vi32x4(_mm_cmpeq_epi32(a.v, b.v)); }
inline vi32x4 cmpgt(vi32x4 a, vi32x4 b) { return vi32x4(_mm_cmpgt_epi32(a.v, b.v)); }
inline vi32x4 cmplt(vi32x4 a, vi32x4 b) { return vi32x4(_mm_cmplt_epi32(a.v, b.v)); }
/// Lanes of `a` where `mask` is all ones, else lanes of `b`.
inline vi32x4 select(vi32x4 mask, vi32x4 a, vi32x4 b) {
  return vi32x4(_mm_or_si128(_mm_and_si128(mask.v, a.v), _mm_andnot_si128(mask.v, b.v)));
}
/// Lane-wise signed minimum.
inline vi32x4 min(vi32x4 a, vi32x4 b) {
#if defined(TESSERA_SIMD_SSE41)
  return vi32x4(_mm_min_epi32(a.v, b.v));
#else
  const __m128i lt = _mm_cmplt_epi32(a.v, b.v);
  return vi32x4(_mm_or_si128(_mm_and_si128(lt, a.v), _mm_andnot_si128(lt, b.v)));
#endif
}
/// Lane-wise signed maximum.
inline vi32x4 max(vi32x4 a, vi32x4 b) {
#if defined(TESSERA_SIMD_SSE41)
  return vi32x4(_mm_max_epi32(a.v, b.v));
#else
  const __m128i gt = _mm_cmpgt_epi32(a.v, b.v);
  return vi32x4(_mm_or_si128(_mm_and_si128(gt, a.v), _mm_andnot_si128(gt, b.v)));
#endif
}
/// Lanes (1, 0, 3, 2): swaps adjacent lanes.
inline vi32x4 swap_pairs(vi32x4 a) {
  return vi32x4(_mm_shuffle_epi32(a.v, _MM_SHUFFLE(2, 3, 0, 1)));
}
/// Lanes (2, 3, 0, 1): swaps the two lane pairs.
inline vi32x4 swap_pairs64(vi32x4 a) {
  return vi32x4(_mm_shuffle_epi32(a.v, _MM_SHUFFLE(1, 0, 3, 2)));
}
/// Lanes 0-2 from `rgb`, lane 3 from `a`.
inline vi32x4 select_alpha(vi32x4 rgb, vi32x4 a) {
  const __m128i m = _mm_setr_epi32(0, 0, 0, -1);
  return vi32x4(_mm_or_si128(_mm_andnot_si128(m, rgb.v), _mm_and_si128(m, a.v)));
}
/// Bit i set when lane i is negative (the sign bits; for masks: lane i set).
inline int movemask(vi32x4 mask) { return _mm_movemask_ps(_mm_castsi128_ps(mask.v)); }
/// Lanes (a0 + a1, a2 + a3, b0 + b1, b2 + b3).
inline vi32x4 pair_sums(vi32x4 a, vi32x4 b) {
  const __m128 x = _mm_castsi128_ps(a.v), y = _mm_castsi128_ps(b.v);
  return vi32x4(_mm_add_epi32(_mm_castps_si128(_mm_shuffle_ps(x, y, _MM_SHUFFLE(2, 0, 2, 0))),
                              _mm_castps_si128(_mm_shuffle_ps(x, y, _MM_SHUFFLE(3, 1, 3, 1)))));
}
/// Lanes (a0, a2, b0, b2).
inline vi32x4 even_lanes(vi32x4 a, vi32x4 b) {
  return vi32x4(_mm_castps_si128(
      _mm_shuffle_ps(_mm_castsi128_ps(a.v), _mm_castsi128_ps(b.v), _MM_SHUFFLE(2, 0, 2, 0))));
}
/// Sum of the four lanes.
inline std::int32_t sum_lanes(vi32x4 a) {
  const __m128i s = _mm_add_epi32(a.v, _mm_shuffle_epi32(a.v, _MM_SHUFFLE(1, 0, 3, 2)));
  return _mm_cvtsi128_si32(_mm_add_epi32(s, _mm_shuffle_epi32(s, _MM_SHUFFLE(2, 3, 0, 1))));
}
/// Lane 0 + lane 2 (the PVRTC exact search keeps two texel sums there), without a round trip
/// through memory.
inline std::int32_t sum_lanes02(vi32x4 a) {
  return _mm_cvtsi128_si32(_mm_add_epi32(a.v, _mm_shuffle_epi32(a.v, _MM_SHUFFLE(1, 0, 3, 2))));
}
/// Stores the four lanes as bytes, each clamped to 0..255 (SSE2's saturating packs; every
/// backend gives those bytes).
inline void store_u8x4(vi32x4 a, std::uint8_t* out) {
  const __m128i p16 = _mm_packs_epi32(a.v, a.v);
  const __m128i p8 = _mm_packus_epi16(p16, p16);
  const std::int32_t w = _mm_cvtsi128_si32(p8);
  std::memcpy(out, &w, 4);
}

/// Two signed 64-bit lanes.
struct vi64x2 {
  __m128i v;
  vi64x2() : v(_mm_setzero_si128()) {}
  explicit vi64x2(__m128i x) : v(x) {}
  explicit vi64x2(std::int64_t a) : v(_mm_set1_epi64x(a)) {}
  /// Lane 0 = `lo`, lane 1 = `hi`.
  vi64x2(std::int64_t lo, std::int64_t hi) : v(_mm_set_epi64x(hi, lo)) {}
};
/// Loads p[0], p[1] (no alignment assumed).
inline vi64x2 load_i64x2(const std::int64_t* p) {
  return vi64x2(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)));
}
inline vi64x2 operator+(vi64x2 a, vi64x2 b) { return vi64x2(_mm_add_epi64(a.v, b.v)); }
inline vi64x2 operator|(vi64x2 a, vi64x2 b) { return vi64x2(_mm_or_si128(a.v, b.v)); }
/// Bit i set when lane i is negative.
inline int movemask(vi64x2 a) { return _mm_movemask_pd(_mm_castsi128_pd(a.v)); }

// ---- vf32x4 ----

struct vf32x4 {
  __m128 v;
  vf32x4() : v(_mm_setzero_ps()) {}
  explicit vf32x4(__m128 x) : v(x) {}
  explicit vf32x4(float a) : v(_mm_set1_ps(a)) {}
  /// Lanes (a, b, c, d), lane 0 first.
  vf32x4(float a, float b, float c, float d) : v(_mm_setr_ps(a, b, c, d)) {}
};
inline vf32x4 loadf4(const float* p) { return vf32x4(_mm_loadu_ps(p)); }
inline void storef4(vf32x4 a, float* p) { _mm_storeu_ps(p, a.v); }
/// `p` 16-byte aligned.
inline vf32x4 loadf4_aligned(const float* p) { return vf32x4(_mm_load_ps(p)); }
inline void storef4_aligned(vf32x4 a, float* p) { _mm_store_ps(p, a.v); }
inline vf32x4 operator+(vf32x4 a, vf32x4 b) { return vf32x4(_mm_add_ps(a.v, b.v)); }
inline vf32x4 operator-(vf32x4 a, vf32x4 b) { return vf32x4(_mm_sub_ps(a.v, b.v)); }
inline vf32x4 operator*(vf32x4 a, vf32x4 b) { return vf32x4(_mm_mul_ps(a.v, b.v)); }
inline vf32x4 operator/(vf32x4 a, vf32x4 b) { return vf32x4(_mm_div_ps(a.v, b.v)); }
inline vf32x4 sqrt(vf32x4 a) { return vf32x4(_mm_sqrt_ps(a.v)); }
/// max: a > b ? a : b; min: a < b ? a : b (the second operand when the compare fails, NaN
/// included).
inline vf32x4 max(vf32x4 a, vf32x4 b) { return vf32x4(_mm_max_ps(a.v, b.v)); }
inline vf32x4 min(vf32x4 a, vf32x4 b) { return vf32x4(_mm_min_ps(a.v, b.v)); }
/// Compares as masks: all-ones lanes where `a op b`; false where either is NaN, except cmpnge
/// (!(a >= b)), which is true there; cmpord is true where neither is NaN.
inline vi32x4 cmpeq(vf32x4 a, vf32x4 b) { return vi32x4(_mm_castps_si128(_mm_cmpeq_ps(a.v, b.v))); }
inline vi32x4 cmplt(vf32x4 a, vf32x4 b) { return vi32x4(_mm_castps_si128(_mm_cmplt_ps(a.v, b.v))); }
inline vi32x4 cmple(vf32x4 a, vf32x4 b) { return vi32x4(_mm_castps_si128(_mm_cmple_ps(a.v, b.v))); }
inline vi32x4 cmpgt(vf32x4 a, vf32x4 b) { return vi32x4(_mm_castps_si128(_mm_cmpgt_ps(a.v, b.v))); }
inline vi32x4 cmpnge(vf32x4 a, vf32x4 b) {
  return vi32x4(_mm_castps_si128(_mm_cmpnge_ps(a.v, b.v)));
}
inline vi32x4 cmpord(vf32x4 a, vf32x4 b) {
  return vi32x4(_mm_castps_si128(_mm_cmpord_ps(a.v, b.v)));
}
/// Lanes of `a` where `mask` is all ones, else lanes of `b` (bitwise, NaN payloads kept).
inline vf32x4 select(vi32x4 mask, vf32x4 a, vf32x4 b) {
  const __m128 m = _mm_castsi128_ps(mask.v);
  return vf32x4(_mm_or_ps(_mm_and_ps(m, a.v), _mm_andnot_ps(m, b.v)));
}
/// mask & a: lanes of `a` where `mask` is all ones, +0.0f elsewhere.
inline vf32x4 keep_where(vi32x4 mask, vf32x4 a) {
  return vf32x4(_mm_and_ps(_mm_castsi128_ps(mask.v), a.v));
}
/// ~mask & a: +0.0f where `mask` is all ones, lanes of `a` elsewhere.
inline vf32x4 zero_where(vi32x4 mask, vf32x4 a) {
  return vf32x4(_mm_andnot_ps(_mm_castsi128_ps(mask.v), a.v));
}
/// The lanes' bits reinterpreted (no conversion).
inline vf32x4 as_float(vi32x4 a) { return vf32x4(_mm_castsi128_ps(a.v)); }
inline vi32x4 as_int(vf32x4 a) { return vi32x4(_mm_castps_si128(a.v)); }
/// int32 -> float, round to nearest even (exact below 2^24).
inline vf32x4 to_float(vi32x4 a) { return vf32x4(_mm_cvtepi32_ps(a.v)); }
/// float -> int32 truncating towards zero; lanes outside int32 and NaN give INT32_MIN (in
/// every backend).
inline vi32x4 to_int_trunc(vf32x4 a) { return vi32x4(_mm_cvttps_epi32(a.v)); }
/// Lanes (a0, a2, b0, b2) and (a1, a3, b1, b3): e.g. u and v of four interleaved (u, v) pairs.
inline vf32x4 even_lanes(vf32x4 a, vf32x4 b) {
  return vf32x4(_mm_shuffle_ps(a.v, b.v, _MM_SHUFFLE(2, 0, 2, 0)));
}
inline vf32x4 odd_lanes(vf32x4 a, vf32x4 b) {
  return vf32x4(_mm_shuffle_ps(a.v, b.v, _MM_SHUFFLE(3, 1, 3, 1)));
}
/// 4x4 transpose: row i of the result holds lane i of a, b, c, d.
inline void transpose(vf32x4& a, vf32x4& b, vf32x4& c, vf32x4& d) {
  _MM_TRANSPOSE4_PS(a.v, b.v, c.v, d.v);
}
inline void transpose(vi32x4& a, vi32x4& b, vi32x4& c, vi32x4& d) {
  vf32x4 fa = as_float(a), fb = as_float(b), fc = as_float(c), fd = as_float(d);
  transpose(fa, fb, fc, fd);
  a = as_int(fa);
  b = as_int(fb);
  c = as_int(fc);
  d = as_int(fd);
}
/// Every lane = the maximum (minimum) of the four lanes.
inline vf32x4 hmax(vf32x4 a) {
  const __m128 m = _mm_max_ps(a.v, _mm_shuffle_ps(a.v, a.v, _MM_SHUFFLE(2, 3, 0, 1)));
  return vf32x4(_mm_max_ps(m, _mm_shuffle_ps(m, m, _MM_SHUFFLE(1, 0, 3, 2))));
}
inline vf32x4 hmin(vf32x4 a) {
  const __m128 m = _mm_min_ps(a.v, _mm_shuffle_ps(a.v, a.v, _MM_SHUFFLE(2, 3, 0, 1)));
  return vf32x4(_mm_min_ps(m, _mm_shuffle_ps(m, m, _MM_SHUFFLE(1, 0, 3, 2))));
}

// ---- vu16x8, vu8x16 ----

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

}  // namespace TESSERA_SIMD_ISA
}  // namespace tessera::simd
