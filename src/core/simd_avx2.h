// simd_avx2.h — part of the SIMD wrapper (include "core/simd.h", which documents the whole set;
// simd_select.h includes this file where it chose this backend): the 8-lane types with AVX2, in
// x86-64 translation units compiled with -mavx2 (the run-time dispatched *_avx2.cpp kernels,
// whose copies of the wrapper live in an inline namespace of their own, see simd_select.h). One
// instruction where AVX2 has one; the same bits as the portable backend of two 4-lane halves
// (simd_halves.h) for every operation.
#pragma once

#include <immintrin.h>

#include <cstdint>

namespace tessera::simd {
inline namespace TESSERA_SIMD_ISA {

struct vi32x8 {
  __m256i v;
  vi32x8() : v(_mm256_setzero_si256()) {}
  explicit vi32x8(__m256i x) : v(x) {}
  explicit vi32x8(std::int32_t a) : v(_mm256_set1_epi32(a)) {}
  /// Lanes 0-3 from `lo`, 4-7 from `hi`.
  vi32x8(vi32x4 lo, vi32x4 hi) : v(_mm256_set_m128i(hi.v, lo.v)) {}
};
struct vf32x8 {
  __m256 v;
  vf32x8() : v(_mm256_setzero_ps()) {}
  explicit vf32x8(__m256 x) : v(x) {}
  explicit vf32x8(float a) : v(_mm256_set1_ps(a)) {}
  vf32x8(vf32x4 lo, vf32x4 hi) : v(_mm256_set_m128(hi.v, lo.v)) {}
};
struct vu16x16 {
  __m256i v;
  vu16x16() : v(_mm256_setzero_si256()) {}
  explicit vu16x16(__m256i x) : v(x) {}
  explicit vu16x16(std::uint16_t a) : v(_mm256_set1_epi16(static_cast<short>(a))) {}
  vu16x16(vu16x8 lo, vu16x8 hi) : v(_mm256_set_m128i(hi.v, lo.v)) {}
};
struct vu8x32 {
  __m256i v;
  vu8x32() : v(_mm256_setzero_si256()) {}
  explicit vu8x32(__m256i x) : v(x) {}
  explicit vu8x32(std::uint8_t a) : v(_mm256_set1_epi8(static_cast<char>(a))) {}
  vu8x32(vu8x16 lo, vu8x16 hi) : v(_mm256_set_m128i(hi.v, lo.v)) {}
};

// ---- halves, loads, stores ----
inline vi32x4 low(vi32x8 a) { return vi32x4(_mm256_castsi256_si128(a.v)); }
inline vi32x4 high(vi32x8 a) { return vi32x4(_mm256_extracti128_si256(a.v, 1)); }
inline vf32x4 low(vf32x8 a) { return vf32x4(_mm256_castps256_ps128(a.v)); }
inline vf32x4 high(vf32x8 a) { return vf32x4(_mm256_extractf128_ps(a.v, 1)); }
inline vu16x8 low(vu16x16 a) { return vu16x8(_mm256_castsi256_si128(a.v)); }
inline vu16x8 high(vu16x16 a) { return vu16x8(_mm256_extracti128_si256(a.v, 1)); }
inline vu8x16 low(vu8x32 a) { return vu8x16(_mm256_castsi256_si128(a.v)); }
inline vu8x16 high(vu8x32 a) { return vu8x16(_mm256_extracti128_si256(a.v, 1)); }

namespace detail {
inline __m256i load256(const void* p) { return _mm256_loadu_si256(static_cast<const __m256i*>(p)); }
inline void store256(void* p, __m256i v) { _mm256_storeu_si256(static_cast<__m256i*>(p), v); }
}  // namespace detail
inline vi32x8 load8(const std::int32_t* p) { return vi32x8(detail::load256(p)); }
inline void store8(vi32x8 a, std::int32_t* p) { detail::store256(p, a.v); }
inline vf32x8 loadf8(const float* p) { return vf32x8(_mm256_loadu_ps(p)); }
inline void storef8(vf32x8 a, float* p) { _mm256_storeu_ps(p, a.v); }
inline vu16x16 load_u16x16(const std::uint16_t* p) { return vu16x16(detail::load256(p)); }
inline void store_u16x16(vu16x16 a, std::uint16_t* p) { detail::store256(p, a.v); }
inline vu8x32 load_u8x32(const std::uint8_t* p) { return vu8x32(detail::load256(p)); }
inline void store_u8x32(vu8x32 a, std::uint8_t* p) { detail::store256(p, a.v); }
/// Eight 4-byte texels as eight 32-bit lanes (little-endian).
inline vi32x8 load_texels8(const std::uint8_t* p) { return vi32x8(detail::load256(p)); }
/// Sixteen bytes zero-extended to 16-bit lanes, in order.
inline vu16x16 load_u8x16_u16(const std::uint8_t* p) {
  return vu16x16(_mm256_cvtepu8_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p))));
}
/// Every 64-bit unit = `x`: lanes 4k .. 4k + 3 = the four 16-bit parts of x, low first.
inline vu16x16 broadcast64(std::uint64_t x) {
  return vu16x16(_mm256_set1_epi64x(static_cast<long long>(x)));
}
/// The eight lanes as bytes, each clamped to 0..255 (as store_u8x4 twice).
inline void store_u8x8(vi32x8 a, std::uint8_t* p) {
  const __m128i p16 =
      _mm_packs_epi32(_mm256_castsi256_si128(a.v), _mm256_extracti128_si256(a.v, 1));
  _mm_storel_epi64(reinterpret_cast<__m128i*>(p), _mm_packus_epi16(p16, p16));
}
/// The sixteen lanes as bytes, each read as int16 and clamped to 0..255 (as store_u8x8 twice).
inline void store_u8x16(vu16x16 a, std::uint8_t* p) {
  const __m256i b = _mm256_permute4x64_epi64(_mm256_packus_epi16(a.v, a.v), 0xd8);
  _mm_storeu_si128(reinterpret_cast<__m128i*>(p), _mm256_castsi256_si128(b));
}

// ---- vi32x8 ----
inline vi32x8 operator+(vi32x8 a, vi32x8 b) { return vi32x8(_mm256_add_epi32(a.v, b.v)); }
inline vi32x8 operator-(vi32x8 a, vi32x8 b) { return vi32x8(_mm256_sub_epi32(a.v, b.v)); }
inline vi32x8& operator+=(vi32x8& a, vi32x8 b) { return a = a + b; }
inline vi32x8 operator*(vi32x8 a, vi32x8 b) { return vi32x8(_mm256_mullo_epi32(a.v, b.v)); }
inline vi32x8 operator&(vi32x8 a, vi32x8 b) { return vi32x8(_mm256_and_si256(a.v, b.v)); }
inline vi32x8 operator|(vi32x8 a, vi32x8 b) { return vi32x8(_mm256_or_si256(a.v, b.v)); }
inline vi32x8 operator^(vi32x8 a, vi32x8 b) { return vi32x8(_mm256_xor_si256(a.v, b.v)); }
inline vi32x8 andnot(vi32x8 a, vi32x8 b) { return vi32x8(_mm256_andnot_si256(a.v, b.v)); }
template <int N>
inline vi32x8 sra(vi32x8 a) {
  return vi32x8(_mm256_srai_epi32(a.v, N));
}
template <int N>
inline vi32x8 srl(vi32x8 a) {
  return vi32x8(_mm256_srli_epi32(a.v, N));
}
template <int N>
inline vi32x8 sll(vi32x8 a) {
  return vi32x8(_mm256_slli_epi32(a.v, N));
}
/// Lane i shifted left by lane i of `n` (as unsigned; 32 or more gives 0).
inline vi32x8 sllv(vi32x8 a, vi32x8 n) { return vi32x8(_mm256_sllv_epi32(a.v, n.v)); }
/// Every lane shifted left by the run-time count `n` (0 .. 31; 32 or more gives 0).
inline vi32x8 sll(vi32x8 a, int n) { return vi32x8(_mm256_sll_epi32(a.v, _mm_cvtsi32_si128(n))); }
inline vi32x8 cmpeq(vi32x8 a, vi32x8 b) { return vi32x8(_mm256_cmpeq_epi32(a.v, b.v)); }
inline vi32x8 cmpgt(vi32x8 a, vi32x8 b) { return vi32x8(_mm256_cmpgt_epi32(a.v, b.v)); }
inline vi32x8 cmplt(vi32x8 a, vi32x8 b) { return vi32x8(_mm256_cmpgt_epi32(b.v, a.v)); }
/// Bitwise, as vi32x4's select.
inline vi32x8 select(vi32x8 mask, vi32x8 a, vi32x8 b) {
  return vi32x8(_mm256_or_si256(_mm256_and_si256(mask.v, a.v), _mm256_andnot_si256(mask.v, b.v)));
}
inline vi32x8 min(vi32x8 a, vi32x8 b) { return vi32x8(_mm256_min_epi32(a.v, b.v)); }
inline vi32x8 max(vi32x8 a, vi32x8 b) { return vi32x8(_mm256_max_epi32(a.v, b.v)); }
/// Per half, as vi32x4: lanes (1, 0, 3, 2), and (2, 3, 0, 1).
inline vi32x8 swap_pairs(vi32x8 a) { return vi32x8(_mm256_shuffle_epi32(a.v, 0xb1)); }
inline vi32x8 swap_pairs64(vi32x8 a) { return vi32x8(_mm256_shuffle_epi32(a.v, 0x4e)); }
/// The halves exchanged: lanes (4 .. 7, 0 .. 3).
inline vi32x8 swap_halves(vi32x8 a) { return vi32x8(_mm256_permute2x128_si256(a.v, a.v, 0x01)); }
/// Per half, as vi32x4: (a0 + a1, a2 + a3, b0 + b1, b2 + b3) and (a0, a2, b0, b2).
inline vi32x8 pair_sums(vi32x8 a, vi32x8 b) { return vi32x8(_mm256_hadd_epi32(a.v, b.v)); }
inline vi32x8 even_lanes(vi32x8 a, vi32x8 b) {
  return vi32x8(_mm256_castps_si256(
      _mm256_shuffle_ps(_mm256_castsi256_ps(a.v), _mm256_castsi256_ps(b.v), 0x88)));
}
/// 64-bit units (lane pairs) picked across the halves: unit k of the result = unit Ik of `a`.
template <int I0, int I1, int I2, int I3>
inline vi32x8 permute64(vi32x8 a) {
  return vi32x8(_mm256_permute4x64_epi64(a.v, I0 | I1 << 2 | I2 << 4 | I3 << 6));
}
/// Sum of the eight lanes (wrapping).
inline std::int32_t sum_lanes(vi32x8 a) {
  __m128i s = _mm_add_epi32(_mm256_castsi256_si128(a.v), _mm256_extracti128_si256(a.v, 1));
  s = _mm_add_epi32(s, _mm_shuffle_epi32(s, 0x4e));
  s = _mm_add_epi32(s, _mm_shuffle_epi32(s, 0xb1));
  return _mm_cvtsi128_si32(s);
}
/// floor(x / 255) of each lane read as uint32: (x * ceil(2^39 / 255)) >> 39, which is exact for
/// every uint32 x (the compilers' own division by 255), on the even and the odd lanes.
inline vi32x8 div255_u32(vi32x8 a) {
  const __m256i k = _mm256_set1_epi32(static_cast<int>(0x80808081u));
  const __m256i even = _mm256_srli_epi64(_mm256_mul_epu32(a.v, k), 39);
  const __m256i odd = _mm256_srli_epi64(_mm256_mul_epu32(_mm256_srli_epi64(a.v, 32), k), 7);
  return vi32x8(_mm256_blend_epi32(even, odd, 0xaa));
}

// ---- vf32x8 (the rules of vf32x4, lane for lane) ----
inline vf32x8 operator+(vf32x8 a, vf32x8 b) { return vf32x8(_mm256_add_ps(a.v, b.v)); }
inline vf32x8 operator-(vf32x8 a, vf32x8 b) { return vf32x8(_mm256_sub_ps(a.v, b.v)); }
inline vf32x8 operator*(vf32x8 a, vf32x8 b) { return vf32x8(_mm256_mul_ps(a.v, b.v)); }
inline vf32x8 max(vf32x8 a, vf32x8 b) { return vf32x8(_mm256_max_ps(a.v, b.v)); }
inline vf32x8 min(vf32x8 a, vf32x8 b) { return vf32x8(_mm256_min_ps(a.v, b.v)); }
inline vi32x8 cmpeq(vf32x8 a, vf32x8 b) {
  return vi32x8(_mm256_castps_si256(_mm256_cmp_ps(a.v, b.v, _CMP_EQ_OQ)));
}
inline vi32x8 cmplt(vf32x8 a, vf32x8 b) {
  return vi32x8(_mm256_castps_si256(_mm256_cmp_ps(a.v, b.v, _CMP_LT_OS)));
}
inline vf32x8 to_float(vi32x8 a) { return vf32x8(_mm256_cvtepi32_ps(a.v)); }
inline vi32x8 to_int_trunc(vf32x8 a) { return vi32x8(_mm256_cvttps_epi32(a.v)); }

// ---- vu16x16 ----
inline vu16x16 operator+(vu16x16 a, vu16x16 b) { return vu16x16(_mm256_add_epi16(a.v, b.v)); }
inline vu16x16 operator-(vu16x16 a, vu16x16 b) { return vu16x16(_mm256_sub_epi16(a.v, b.v)); }
inline vu16x16 operator&(vu16x16 a, vu16x16 b) { return vu16x16(_mm256_and_si256(a.v, b.v)); }
inline vu16x16 operator|(vu16x16 a, vu16x16 b) { return vu16x16(_mm256_or_si256(a.v, b.v)); }
inline vu16x16 mullo(vu16x16 a, vu16x16 b) { return vu16x16(_mm256_mullo_epi16(a.v, b.v)); }
inline vu16x16 mulhi(vu16x16 a, vu16x16 b) { return vu16x16(_mm256_mulhi_epu16(a.v, b.v)); }
template <int N>
inline vu16x16 srl(vu16x16 a) {
  return vu16x16(_mm256_srli_epi16(a.v, N));
}
inline vu16x16 cmpeq(vu16x16 a, vu16x16 b) { return vu16x16(_mm256_cmpeq_epi16(a.v, b.v)); }
/// Lanes read as int16.
inline vu16x16 cmpgt_s16(vu16x16 a, vu16x16 b) { return vu16x16(_mm256_cmpgt_epi16(a.v, b.v)); }
/// Lanes of `a` where `mask` is all ones, else of `b`; every mask lane all ones or zero.
inline vu16x16 select(vu16x16 mask, vu16x16 a, vu16x16 b) {
  return vu16x16(_mm256_blendv_epi8(b.v, a.v, mask.v));
}
/// Lanes 3, 7, 11 and 15 (the alpha lanes of four RGBA texels) from `a`, the rest from `rgb`.
inline vu16x16 select_alpha(vu16x16 rgb, vu16x16 a) {
  return vu16x16(_mm256_blend_epi16(rgb.v, a.v, 0x88));
}
/// Per half, as vu16x8: pmaddwd, the interleavings, and SSE2's packs_epi32 of (a, b).
inline vi32x8 madd(vu16x16 a, vu16x16 b) { return vi32x8(_mm256_madd_epi16(a.v, b.v)); }
inline vu16x16 zip_lo(vu16x16 a, vu16x16 b) { return vu16x16(_mm256_unpacklo_epi16(a.v, b.v)); }
inline vu16x16 zip_hi(vu16x16 a, vu16x16 b) { return vu16x16(_mm256_unpackhi_epi16(a.v, b.v)); }
inline vu16x16 narrow16(vi32x8 a, vi32x8 b) { return vu16x16(_mm256_packs_epi32(a.v, b.v)); }
inline vf32x8 f2p23_plus_lo(vu16x16 a) {
  return vf32x8(_mm256_castsi256_ps(_mm256_unpacklo_epi16(a.v, _mm256_set1_epi16(0x4b00))));
}
inline vf32x8 f2p23_plus_hi(vu16x16 a) {
  return vf32x8(_mm256_castsi256_ps(_mm256_unpackhi_epi16(a.v, _mm256_set1_epi16(0x4b00))));
}
/// Per half, pshufb over the bytes: result byte i = byte (idx_i & 15) of the same half of
/// `table`, or 0 where idx_i has its top bit set (bytes in little-endian order of the lanes).
inline vu16x16 shuffle_bytes(vu16x16 table, vu16x16 idx) {
  return vu16x16(_mm256_shuffle_epi8(table.v, idx.v));
}
template <int I0, int I1, int I2, int I3>
inline vu16x16 permute64(vu16x16 a) {
  return vu16x16(_mm256_permute4x64_epi64(a.v, I0 | I1 << 2 | I2 << 4 | I3 << 6));
}
/// Bit i = the top bit of byte i (little-endian order of the lanes).
inline std::uint32_t movemask_bytes(vu16x16 a) {
  return static_cast<std::uint32_t>(_mm256_movemask_epi8(a.v));
}
/// The 32 lanes of (a, b) as bytes in order, each read as int16 and clamped to 0..255.
inline vu8x32 narrow(vu16x16 a, vu16x16 b) {
  return vu8x32(_mm256_permute4x64_epi64(_mm256_packus_epi16(a.v, b.v), 0xd8));
}

// ---- vu8x32 ----
inline vu8x32 operator+(vu8x32 a, vu8x32 b) { return vu8x32(_mm256_add_epi8(a.v, b.v)); }
inline vu8x32 operator&(vu8x32 a, vu8x32 b) { return vu8x32(_mm256_and_si256(a.v, b.v)); }
inline vu8x32 operator|(vu8x32 a, vu8x32 b) { return vu8x32(_mm256_or_si256(a.v, b.v)); }
inline vu8x32 andnot(vu8x32 a, vu8x32 b) { return vu8x32(_mm256_andnot_si256(a.v, b.v)); }
inline vu8x32 cmpeq(vu8x32 a, vu8x32 b) { return vu8x32(_mm256_cmpeq_epi8(a.v, b.v)); }
/// Every mask lane all ones or zero.
inline vu8x32 select(vu8x32 mask, vu8x32 a, vu8x32 b) {
  return vu8x32(_mm256_blendv_epi8(b.v, a.v, mask.v));
}
/// Whether some lane has its top bit set.
inline bool any(vu8x32 mask) { return _mm256_movemask_epi8(mask.v) != 0; }
/// Lanes 0-15 (widen_lo) or 16-31 (widen_hi) zero-extended to 16 bits, in order.
inline vu16x16 widen_lo(vu8x32 a) {
  return vu16x16(_mm256_cvtepu8_epi16(_mm256_castsi256_si128(a.v)));
}
inline vu16x16 widen_hi(vu8x32 a) {
  return vu16x16(_mm256_cvtepu8_epi16(_mm256_extracti128_si256(a.v, 1)));
}

// ---- RGBA8 texels to planes ----
/// 32 RGBA8 texels at p (128 bytes) as one byte plane per channel: out[c] lane i = p[4 i + c].
inline void load_planes(const std::uint8_t* p, vu8x32 out[4]) {
  // Per half, 4 texels to R0..R3 G0..G3 B0..B3 A0..A3; then a dword transposition.
  const __m256i shuf = _mm256_setr_epi8(0, 4, 8, 12, 1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15, 0, 4,
                                        8, 12, 1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15);
  const __m256i order = _mm256_setr_epi32(0, 4, 1, 5, 2, 6, 3, 7);
  __m256i v[4];
  for (int i = 0; i < 4; ++i) v[i] = _mm256_shuffle_epi8(detail::load256(p + 32 * i), shuf);
  const __m256i a = _mm256_unpacklo_epi32(v[0], v[1]), b = _mm256_unpackhi_epi32(v[0], v[1]),
                c = _mm256_unpacklo_epi32(v[2], v[3]), d = _mm256_unpackhi_epi32(v[2], v[3]);
  out[0] = vu8x32(_mm256_permutevar8x32_epi32(_mm256_unpacklo_epi64(a, c), order));
  out[1] = vu8x32(_mm256_permutevar8x32_epi32(_mm256_unpackhi_epi64(a, c), order));
  out[2] = vu8x32(_mm256_permutevar8x32_epi32(_mm256_unpacklo_epi64(b, d), order));
  out[3] = vu8x32(_mm256_permutevar8x32_epi32(_mm256_unpackhi_epi64(b, d), order));
}
/// 16 RGBA8 texels at p (64 bytes) as one 16-bit plane per channel: out[c] lane i = p[4 i + c].
inline void load_planes(const std::uint8_t* p, vu16x16 out[4]) {
  const __m128i* q = reinterpret_cast<const __m128i*>(p);
  // a: texels 0-3 | 8-11, b: texels 4-7 | 12-15; then bytes RRRR GGGG BBBB AAAA per half.
  const __m256i a = _mm256_inserti128_si256(_mm256_castsi128_si256(_mm_loadu_si128(q)),
                                            _mm_loadu_si128(q + 2), 1);
  const __m256i b = _mm256_inserti128_si256(_mm256_castsi128_si256(_mm_loadu_si128(q + 1)),
                                            _mm_loadu_si128(q + 3), 1);
  const __m256i planar = _mm256_setr_epi8(0, 4, 8, 12, 1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15,  //
                                          0, 4, 8, 12, 1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15);
  const __m256i pa = _mm256_shuffle_epi8(a, planar), pb = _mm256_shuffle_epi8(b, planar);
  const __m256i rg = _mm256_unpacklo_epi32(pa, pb), ba = _mm256_unpackhi_epi32(pa, pb);
  const __m256i zero = _mm256_setzero_si256();
  out[0] = vu16x16(_mm256_unpacklo_epi8(rg, zero));
  out[1] = vu16x16(_mm256_unpackhi_epi8(rg, zero));
  out[2] = vu16x16(_mm256_unpacklo_epi8(ba, zero));
  out[3] = vu16x16(_mm256_unpackhi_epi8(ba, zero));
}

// ---- lookup8 (the 4-lane form and its contract: simd_compose4.h) ----
/// lookup8(vu16x8) on each half, as one byte shuffle.
inline vu16x16 lookup8(const std::uint16_t* table, vu16x16 idx) {
  // Bytes (2 idx, 2 idx + 1) of the table in each half; for idx -8..-1 both have the top bit
  // set, which shuffles in 0.
  const vu16x8 t = load_u16x8(table);
  return shuffle_bytes(vu16x16(t, t),
                       mullo(idx, vu16x16(std::uint16_t{514})) + vu16x16(std::uint16_t{256}));
}

}  // namespace TESSERA_SIMD_ISA
}  // namespace tessera::simd
