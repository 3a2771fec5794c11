// simd.h — the one small SIMD wrapper of the library's kernels (PVRTC today; shared here in
// src/core so texture and raster kernels use the same one): `vint4`, four 32-bit lanes
// (one RGBA texel in the PVRTC decoder's working precision). SSE2 on x86-64 (always available
// there), SSE4.1 when the compiler targets it, and a portable scalar backend otherwise
// (define TESSERA_NO_SIMD to force it). Every backend gives bit-identical results.
#pragma once

#include <cstdint>
#include <cstring>

#if !defined(TESSERA_NO_SIMD) && (defined(__SSE2__) || defined(_M_X64))
#define TESSERA_SIMD_SSE2 1
#include <emmintrin.h>
#if defined(__SSE4_1__)
#define TESSERA_SIMD_SSE41 1
#include <smmintrin.h>
#endif
#endif

namespace tessera::simd {

#if defined(TESSERA_SIMD_SSE2)

struct vint4 {
  __m128i v;
  vint4() : v(_mm_setzero_si128()) {}
  explicit vint4(__m128i x) : v(x) {}
  vint4(std::int32_t a, std::int32_t b, std::int32_t c, std::int32_t d)
      : v(_mm_setr_epi32(a, b, c, d)) {}
  explicit vint4(std::int32_t a) : v(_mm_set1_epi32(a)) {}
  std::int32_t lane(int i) const {
    alignas(16) std::int32_t t[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(t), v);
    return t[i];
  }
};
inline vint4 load4(const std::int32_t* p) {
  return vint4(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)));
}
inline vint4 operator+(vint4 a, vint4 b) { return vint4(_mm_add_epi32(a.v, b.v)); }
inline vint4 operator-(vint4 a, vint4 b) { return vint4(_mm_sub_epi32(a.v, b.v)); }
inline vint4& operator+=(vint4& a, vint4 b) { return a = a + b; }
/// Lane-wise product of small values (|a*b| < 2^31).
inline vint4 operator*(vint4 a, vint4 b) {
#if defined(TESSERA_SIMD_SSE41)
  return vint4(_mm_mullo_epi32(a.v, b.v));
#else
  const __m128i even = _mm_mul_epu32(a.v, b.v);
  const __m128i odd = _mm_mul_epu32(_mm_srli_epi64(a.v, 32), _mm_srli_epi64(b.v, 32));
  return vint4(_mm_unpacklo_epi32(_mm_shuffle_epi32(even, _MM_SHUFFLE(0, 0, 2, 0)),
                                  _mm_shuffle_epi32(odd, _MM_SHUFFLE(0, 0, 2, 0))));
#endif
}
template <int N>
inline vint4 sra(vint4 a) {
  return vint4(_mm_srai_epi32(a.v, N));
}
/// Lane-wise signed minimum.
inline vint4 min(vint4 a, vint4 b) {
#if defined(TESSERA_SIMD_SSE41)
  return vint4(_mm_min_epi32(a.v, b.v));
#else
  const __m128i lt = _mm_cmplt_epi32(a.v, b.v);
  return vint4(_mm_or_si128(_mm_and_si128(lt, a.v), _mm_andnot_si128(lt, b.v)));
#endif
}
/// Lanes (1, 0, 3, 2): swaps adjacent lanes.
inline vint4 swap_pairs(vint4 a) { return vint4(_mm_shuffle_epi32(a.v, _MM_SHUFFLE(2, 3, 0, 1))); }
/// Lanes 0-2 from `rgb`, lane 3 from `a`.
inline vint4 select_alpha(vint4 rgb, vint4 a) {
  const __m128i m = _mm_setr_epi32(0, 0, 0, -1);
  return vint4(_mm_or_si128(_mm_andnot_si128(m, rgb.v), _mm_and_si128(m, a.v)));
}
/// Stores the four lanes (each 0..255) as bytes.
inline void store_u8x4(vint4 a, std::uint8_t* out) {
  const __m128i p16 = _mm_packs_epi32(a.v, a.v);
  const __m128i p8 = _mm_packus_epi16(p16, p16);
  const std::int32_t w = _mm_cvtsi128_si32(p8);
  std::memcpy(out, &w, 4);
}

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
/// Stores the low byte of each lane (lanes must be <= 255).
inline void store_u8x8(vu16x8 a, std::uint8_t* p) {
  _mm_storel_epi64(reinterpret_cast<__m128i*>(p), _mm_packus_epi16(a.v, a.v));
}
inline vu16x8 operator+(vu16x8 a, vu16x8 b) { return vu16x8(_mm_add_epi16(a.v, b.v)); }
inline vu16x8 operator-(vu16x8 a, vu16x8 b) { return vu16x8(_mm_sub_epi16(a.v, b.v)); }
/// Low 16 bits of the lane products.
inline vu16x8 mullo(vu16x8 a, vu16x8 b) { return vu16x8(_mm_mullo_epi16(a.v, b.v)); }
/// Signed lanes: sums of adjacent products, a0*b0 + a1*b1, ... as four 32-bit lanes.
inline vint4 madd(vu16x8 a, vu16x8 b) { return vint4(_mm_madd_epi16(a.v, b.v)); }
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

/// Four float lanes (exact integer arithmetic below 2^24 in the PVRTC kernels).
struct vf4 {
  __m128 v;
  vf4() : v(_mm_setzero_ps()) {}
  explicit vf4(__m128 x) : v(x) {}
  explicit vf4(float a) : v(_mm_set1_ps(a)) {}
};
inline vf4 loadf4(const float* p) { return vf4(_mm_loadu_ps(p)); }
inline void storef4(vf4 a, float* p) { _mm_storeu_ps(p, a.v); }
inline vf4 operator+(vf4 a, vf4 b) { return vf4(_mm_add_ps(a.v, b.v)); }
inline vf4 operator*(vf4 a, vf4 b) { return vf4(_mm_mul_ps(a.v, b.v)); }
inline vf4 max(vf4 a, vf4 b) { return vf4(_mm_max_ps(a.v, b.v)); }
inline vf4 min(vf4 a, vf4 b) { return vf4(_mm_min_ps(a.v, b.v)); }
/// All-ones 32-bit lanes where a == b.
inline vint4 cmpeq(vf4 a, vf4 b) { return vint4(_mm_castps_si128(_mm_cmpeq_ps(a.v, b.v))); }
inline vf4 to_float(vint4 a) { return vf4(_mm_cvtepi32_ps(a.v)); }
inline vint4 operator&(vint4 a, vint4 b) { return vint4(_mm_and_si128(a.v, b.v)); }
inline vint4 operator|(vint4 a, vint4 b) { return vint4(_mm_or_si128(a.v, b.v)); }
inline vint4 operator^(vint4 a, vint4 b) { return vint4(_mm_xor_si128(a.v, b.v)); }
/// Logical right shift of the 32-bit lanes.
template <int N>
inline vint4 srl(vint4 a) {
  return vint4(_mm_srli_epi32(a.v, N));
}
/// Loads four 4-byte texels as four 32-bit lanes.
inline vint4 load_texels4(const std::uint8_t* p) {
  return vint4(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)));
}

/// Sixteen unsigned 8-bit lanes.
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
/// Lanes of lo then hi, each (<= 255) as a byte.
inline vu8x16 narrow(vu16x8 lo, vu16x8 hi) { return vu8x16(_mm_packus_epi16(lo.v, hi.v)); }
/// Sixteen 32-bit lanes (each 0..255, in order a, b, c, d) as bytes.
inline vu8x16 narrow(vint4 a, vint4 b, vint4 c, vint4 d) {
  return vu8x16(_mm_packus_epi16(_mm_packs_epi32(a.v, b.v), _mm_packs_epi32(c.v, d.v)));
}

/// Lanes 0-3 of a then 0-3 of b (each 0..32767) as 16-bit lanes.
inline vu16x8 narrow16(vint4 a, vint4 b) { return vu16x8(_mm_packs_epi32(a.v, b.v)); }
/// Interleaves lanes 0-3 (zip_lo) or 4-7 (zip_hi) of a and b: a0 b0 a1 b1 ...
inline vu16x8 zip_lo(vu16x8 a, vu16x8 b) { return vu16x8(_mm_unpacklo_epi16(a.v, b.v)); }
inline vu16x8 zip_hi(vu16x8 a, vu16x8 b) { return vu16x8(_mm_unpackhi_epi16(a.v, b.v)); }
template <int N>
inline vint4 sll(vint4 a) {
  return vint4(_mm_slli_epi32(a.v, N));
}
inline void store4(vint4 a, std::int32_t* p) { _mm_storeu_si128(reinterpret_cast<__m128i*>(p), a.v); }
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

/// Every lane = the maximum (minimum) of the four lanes.
inline vf4 hmax(vf4 a) {
  const __m128 m = _mm_max_ps(a.v, _mm_shuffle_ps(a.v, a.v, _MM_SHUFFLE(2, 3, 0, 1)));
  return vf4(_mm_max_ps(m, _mm_shuffle_ps(m, m, _MM_SHUFFLE(1, 0, 3, 2))));
}
inline vf4 hmin(vf4 a) {
  const __m128 m = _mm_min_ps(a.v, _mm_shuffle_ps(a.v, a.v, _MM_SHUFFLE(2, 3, 0, 1)));
  return vf4(_mm_min_ps(m, _mm_shuffle_ps(m, m, _MM_SHUFFLE(1, 0, 3, 2))));
}
/// Bit i set when lane i of a mask (all ones / zero lanes) is set.
inline int movemask(vint4 mask) { return _mm_movemask_ps(_mm_castsi128_ps(mask.v)); }

/// Lanes (a0 + a1, a2 + a3, b0 + b1, b2 + b3).
inline vint4 pair_sums(vint4 a, vint4 b) {
  const __m128 x = _mm_castsi128_ps(a.v), y = _mm_castsi128_ps(b.v);
  return vint4(_mm_add_epi32(_mm_castps_si128(_mm_shuffle_ps(x, y, _MM_SHUFFLE(2, 0, 2, 0))),
                             _mm_castps_si128(_mm_shuffle_ps(x, y, _MM_SHUFFLE(3, 1, 3, 1)))));
}
/// Lanes (a0, a2, b0, b2).
inline vint4 even_lanes(vint4 a, vint4 b) {
  return vint4(_mm_castps_si128(
      _mm_shuffle_ps(_mm_castsi128_ps(a.v), _mm_castsi128_ps(b.v), _MM_SHUFFLE(2, 0, 2, 0))));
}
/// 2^23 + lane i of `a` (lanes 0-3: _lo, 4-7: _hi) as floats, exact: the 16-bit value placed in
/// the mantissa of 2^23.
inline vf4 f2p23_plus_lo(vu16x8 a) {
  return vf4(_mm_castsi128_ps(_mm_unpacklo_epi16(a.v, _mm_set1_epi16(0x4b00))));
}
inline vf4 f2p23_plus_hi(vu16x8 a) {
  return vf4(_mm_castsi128_ps(_mm_unpackhi_epi16(a.v, _mm_set1_epi16(0x4b00))));
}
inline vf4 operator-(vf4 a, vf4 b) { return vf4(_mm_sub_ps(a.v, b.v)); }
/// Lanes 0-3 (_lo) or 4-7 (_hi) zero-extended to 32 bits.
inline vint4 widen32_lo(vu16x8 a) { return vint4(_mm_unpacklo_epi16(a.v, _mm_setzero_si128())); }
inline vint4 widen32_hi(vu16x8 a) { return vint4(_mm_unpackhi_epi16(a.v, _mm_setzero_si128())); }
/// Sum of the four lanes.
inline std::int32_t sum_lanes(vint4 a) {
  const __m128i s = _mm_add_epi32(a.v, _mm_shuffle_epi32(a.v, _MM_SHUFFLE(1, 0, 3, 2)));
  return _mm_cvtsi128_si32(_mm_add_epi32(s, _mm_shuffle_epi32(s, _MM_SHUFFLE(2, 3, 0, 1))));
}
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

#else  // scalar backend

struct vint4 {
  std::int32_t l[4] = {0, 0, 0, 0};
  vint4() = default;
  vint4(std::int32_t a, std::int32_t b, std::int32_t c, std::int32_t d) : l{a, b, c, d} {}
  explicit vint4(std::int32_t a) : l{a, a, a, a} {}
  std::int32_t lane(int i) const { return l[i]; }
};
inline vint4 load4(const std::int32_t* p) { return {p[0], p[1], p[2], p[3]}; }
inline vint4 operator+(vint4 a, vint4 b) {
  return {a.l[0] + b.l[0], a.l[1] + b.l[1], a.l[2] + b.l[2], a.l[3] + b.l[3]};
}
inline vint4 operator-(vint4 a, vint4 b) {
  return {a.l[0] - b.l[0], a.l[1] - b.l[1], a.l[2] - b.l[2], a.l[3] - b.l[3]};
}
inline vint4& operator+=(vint4& a, vint4 b) { return a = a + b; }
inline vint4 operator*(vint4 a, vint4 b) {
  return {a.l[0] * b.l[0], a.l[1] * b.l[1], a.l[2] * b.l[2], a.l[3] * b.l[3]};
}
template <int N>
inline vint4 sra(vint4 a) {
  return {a.l[0] >> N, a.l[1] >> N, a.l[2] >> N, a.l[3] >> N};
}
inline vint4 min(vint4 a, vint4 b) {
  vint4 r;
  for (int i = 0; i < 4; ++i) r.l[i] = a.l[i] < b.l[i] ? a.l[i] : b.l[i];
  return r;
}
inline vint4 swap_pairs(vint4 a) { return {a.l[1], a.l[0], a.l[3], a.l[2]}; }
inline vint4 select_alpha(vint4 rgb, vint4 a) { return {rgb.l[0], rgb.l[1], rgb.l[2], a.l[3]}; }
inline void store_u8x4(vint4 a, std::uint8_t* out) {
  for (int i = 0; i < 4; ++i) out[i] = std::uint8_t(a.l[i]);
}

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
inline void store_u8x8(vu16x8 a, std::uint8_t* p) {
  for (int i = 0; i < 8; ++i) p[i] = std::uint8_t(a.l[i] > 255 ? 255 : a.l[i]);
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
inline vint4 madd(vu16x8 a, vu16x8 b) {
  vint4 r;
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
TESSERA_SIMD_U16_BINOP(operator|, a.l[i] | b.l[i])
TESSERA_SIMD_U16_BINOP(mulhi, (std::uint32_t(a.l[i]) * b.l[i]) >> 16)
TESSERA_SIMD_U16_BINOP(cmpeq, a.l[i] == b.l[i] ? 0xffff : 0)
#undef TESSERA_SIMD_U16_BINOP
template <int N>
inline vu16x8 srl(vu16x8 a) {
  vu16x8 r;
  for (int i = 0; i < 8; ++i) r.l[i] = std::uint16_t(a.l[i] >> N);
  return r;
}
inline vu16x8 select(vu16x8 mask, vu16x8 a, vu16x8 b) {
  vu16x8 r;
  for (int i = 0; i < 8; ++i) r.l[i] = std::uint16_t((mask.l[i] & a.l[i]) | (~mask.l[i] & b.l[i]));
  return r;
}


struct vf4 {
  float l[4] = {0, 0, 0, 0};
  vf4() = default;
  explicit vf4(float a) : l{a, a, a, a} {}
};
inline vf4 loadf4(const float* p) {
  vf4 r;
  for (int i = 0; i < 4; ++i) r.l[i] = p[i];
  return r;
}
inline void storef4(vf4 a, float* p) {
  for (int i = 0; i < 4; ++i) p[i] = a.l[i];
}
#define TESSERA_SIMD_F4_BINOP(op, expr) \
  inline vf4 op(vf4 a, vf4 b) {         \
    vf4 r;                              \
    for (int i = 0; i < 4; ++i) {       \
      const float x = a.l[i], y = b.l[i]; \
      r.l[i] = (expr);                  \
    }                                   \
    return r;                           \
  }
TESSERA_SIMD_F4_BINOP(operator+, x + y)
TESSERA_SIMD_F4_BINOP(operator*, x * y)
TESSERA_SIMD_F4_BINOP(max, x > y ? x : y)
TESSERA_SIMD_F4_BINOP(min, x < y ? x : y)
#undef TESSERA_SIMD_F4_BINOP
inline vint4 cmpeq(vf4 a, vf4 b) {
  vint4 r;
  for (int i = 0; i < 4; ++i) r.l[i] = a.l[i] == b.l[i] ? -1 : 0;
  return r;
}
inline vf4 to_float(vint4 a) {
  vf4 r;
  for (int i = 0; i < 4; ++i) r.l[i] = float(a.l[i]);
  return r;
}
inline vint4 operator&(vint4 a, vint4 b) {
  return {a.l[0] & b.l[0], a.l[1] & b.l[1], a.l[2] & b.l[2], a.l[3] & b.l[3]};
}
inline vint4 operator|(vint4 a, vint4 b) {
  return {a.l[0] | b.l[0], a.l[1] | b.l[1], a.l[2] | b.l[2], a.l[3] | b.l[3]};
}
inline vint4 operator^(vint4 a, vint4 b) {
  return {a.l[0] ^ b.l[0], a.l[1] ^ b.l[1], a.l[2] ^ b.l[2], a.l[3] ^ b.l[3]};
}
template <int N>
inline vint4 srl(vint4 a) {
  vint4 r;
  for (int i = 0; i < 4; ++i) r.l[i] = std::int32_t(std::uint32_t(a.l[i]) >> N);
  return r;
}
inline vint4 load_texels4(const std::uint8_t* p) {
  vint4 r;
  for (int i = 0; i < 4; ++i) {
    std::uint32_t x;
    std::memcpy(&x, p + 4 * i, 4);
    r.l[i] = std::int32_t(x);
  }
  return r;
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
#define TESSERA_SIMD_U8_BINOP(op, expr)                        \
  inline vu8x16 op(vu8x16 a, vu8x16 b) {                       \
    vu8x16 r;                                                  \
    for (int i = 0; i < 16; ++i) r.l[i] = std::uint8_t(expr);  \
    return r;                                                  \
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
    r.l[i] = std::uint8_t(lo.l[i] > 255 ? 255 : lo.l[i]);
    r.l[8 + i] = std::uint8_t(hi.l[i] > 255 ? 255 : hi.l[i]);
  }
  return r;
}
inline vu8x16 narrow(vint4 a, vint4 b, vint4 c, vint4 d) {
  vu8x16 r;
  const vint4* v[4] = {&a, &b, &c, &d};
  for (int i = 0; i < 16; ++i) {
    const std::int32_t x = v[i / 4]->l[i % 4];
    r.l[i] = std::uint8_t(x < 0 ? 0 : x > 255 ? 255 : x);
  }
  return r;
}


inline vu16x8 narrow16(vint4 a, vint4 b) {
  vu16x8 r;
  for (int i = 0; i < 4; ++i) {
    r.l[i] = std::uint16_t(a.l[i]);
    r.l[4 + i] = std::uint16_t(b.l[i]);
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
template <int N>
inline vint4 sll(vint4 a) {
  vint4 r;
  for (int i = 0; i < 4; ++i) r.l[i] = std::int32_t(std::uint32_t(a.l[i]) << N);
  return r;
}
inline void store4(vint4 a, std::int32_t* p) {
  for (int i = 0; i < 4; ++i) p[i] = a.l[i];
}
inline void taps8(const std::uint16_t* p, vu16x8& left, vu16x8& right) {
  static constexpr int kL[8] = {0, 0, 1, 1, 1, 1, 2, 2};
  for (int i = 0; i < 8; ++i) {
    left.l[i] = p[kL[i]];
    right.l[i] = p[kL[i] + 1];
  }
}


inline vf4 hmax(vf4 a) {
  float m = a.l[0];
  for (int i = 1; i < 4; ++i) m = a.l[i] > m ? a.l[i] : m;
  return vf4(m);
}
inline vf4 hmin(vf4 a) {
  float m = a.l[0];
  for (int i = 1; i < 4; ++i) m = a.l[i] < m ? a.l[i] : m;
  return vf4(m);
}
inline int movemask(vint4 mask) {
  int m = 0;
  for (int i = 0; i < 4; ++i) m |= (mask.l[i] < 0 ? 1 : 0) << i;
  return m;
}
inline vf4 f2p23_plus_lo(vu16x8 a) {
  vf4 r;
  for (int i = 0; i < 4; ++i) r.l[i] = 8388608.0f + float(a.l[i]);
  return r;
}
inline vf4 f2p23_plus_hi(vu16x8 a) {
  vf4 r;
  for (int i = 0; i < 4; ++i) r.l[i] = 8388608.0f + float(a.l[4 + i]);
  return r;
}
inline vf4 operator-(vf4 a, vf4 b) {
  vf4 r;
  for (int i = 0; i < 4; ++i) r.l[i] = a.l[i] - b.l[i];
  return r;
}
inline vint4 even_lanes(vint4 a, vint4 b) { return {a.l[0], a.l[2], b.l[0], b.l[2]}; }
inline vint4 pair_sums(vint4 a, vint4 b) {
  return {a.l[0] + a.l[1], a.l[2] + a.l[3], b.l[0] + b.l[1], b.l[2] + b.l[3]};
}
inline vint4 widen32_lo(vu16x8 a) { return {a.l[0], a.l[1], a.l[2], a.l[3]}; }
inline vint4 widen32_hi(vu16x8 a) { return {a.l[4], a.l[5], a.l[6], a.l[7]}; }
inline std::int32_t sum_lanes(vint4 a) { return a.l[0] + a.l[1] + a.l[2] + a.l[3]; }
inline void transpose_8x4(const std::uint16_t* p, vu16x8 out[4]) {
  for (int c = 0; c < 4; ++c) {
    for (int i = 0; i < 8; ++i) out[c].l[i] = p[4 * i + c];
  }
}

#endif

/// sum_lanes02: lane 0 + lane 2 of `a` (the PVRTC exact search keeps two texel sums there),
/// without a round trip through memory on SSE2.
/// to_int_trunc: float lanes to 32-bit integers, truncating toward zero (lanes within int32).
#if defined(TESSERA_SIMD_SSE2)
inline std::int32_t sum_lanes02(vint4 a) {
  return _mm_cvtsi128_si32(_mm_add_epi32(a.v, _mm_shuffle_epi32(a.v, _MM_SHUFFLE(1, 0, 3, 2))));
}
inline vint4 to_int_trunc(vf4 a) { return vint4(_mm_cvttps_epi32(a.v)); }
#else
inline std::int32_t sum_lanes02(vint4 a) { return a.lane(0) + a.lane(2); }
inline vint4 to_int_trunc(vf4 a) {
  return {std::int32_t(a.l[0]), std::int32_t(a.l[1]), std::int32_t(a.l[2]), std::int32_t(a.l[3])};
}
#endif

/// sll_bytes: each 32-bit lane shifted left by 8 * `k` bits (k = 0..3), e.g. to put row k's
/// 8-bit code into byte k of a packed word.
inline vint4 sll_bytes(vint4 v, int k) {
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
inline vu16x8 channel16(vint4 t0, vint4 t1, int c) {
  const vint4 m8(0xff);
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

}  // namespace tessera::simd
