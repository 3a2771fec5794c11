// simd_int.h — part of the SIMD wrapper (include "core/simd.h", which documents the whole set):
// the backend selection shared by every simd_*.h header, and the 32- and 64-bit integer lanes:
//   vi32x4   four int32 lanes: RGBA texels in the PVRTC decoder's working precision, texel
//           coordinates / offsets / level sizes of four texture lookups, comparison masks
//           (all ones / zero per lane) of vi32x4 and vf32x4 compares.
//   vi64x2  two int64 lanes: the rasteriser's fixed-point edge values.
// Integer lanes wrap on overflow in every backend except where a comment says otherwise.
#pragma once

#include <cstdint>
#include <cstring>

// Backend: SSE2 on x86-64 (part of the ABI, so always there), SSE4.1 instructions where the
// compiler targets them; NEON on little-endian AArch64 (part of its base ISA); otherwise (other
// CPUs, or TESSERA_NO_SIMD defined for every translation unit of the build) a portable scalar
// backend. All three give bit-identical results. TESSERA_SIMD_VECTOR is 1 when the types map
// to vector registers (SSE2, NEON); kernels that have their own per-lane fallback (texture
// `sample4`, raster quad coverage) use the vector path only then.
#if !defined(TESSERA_NO_SIMD) && (defined(__SSE2__) || defined(_M_X64))
#define TESSERA_SIMD_SSE2 1
#include <emmintrin.h>
#if defined(__SSE4_1__)
#define TESSERA_SIMD_SSE41 1
#include <smmintrin.h>
#endif
#elif !defined(TESSERA_NO_SIMD) && defined(__aarch64__) && defined(__ARM_NEON) && \
    !defined(__ARM_BIG_ENDIAN)
#define TESSERA_SIMD_NEON 1
#include <arm_neon.h>
#endif

#if defined(TESSERA_SIMD_SSE2) || defined(TESSERA_SIMD_NEON)
#define TESSERA_SIMD_VECTOR 1
#else
#define TESSERA_SIMD_VECTOR 0
#endif

// The inline namespace that holds every type and function of the wrapper, one name per backend
// and per instruction set the translation unit is compiled for. The run-time dispatched AVX2
// kernels (*_avx2.cpp, built with -mavx2) include this wrapper too: there its inline functions
// are compiled with VEX encodings, so they must not share a mangled name with the baseline's
// copies (the linker keeps one copy of an inline function for the whole program, and an AVX2
// one must never run on a CPU without AVX2). The namespace keeps them apart; it also lets a
// TESSERA_NO_SIMD test link beside the vector backend.
#if defined(TESSERA_SIMD_SSE2) && defined(__AVX2__)
#define TESSERA_SIMD_ISA avx2
#elif defined(TESSERA_SIMD_SSE2)
#define TESSERA_SIMD_ISA sse2
#elif defined(TESSERA_SIMD_NEON)
#define TESSERA_SIMD_ISA neon
#elif defined(__AVX2__)
#define TESSERA_SIMD_ISA scalar_avx2
#else
#define TESSERA_SIMD_ISA scalar
#endif

namespace tessera::simd {
inline namespace TESSERA_SIMD_ISA {

#if defined(TESSERA_SIMD_SSE2)

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

#elif defined(TESSERA_SIMD_NEON)

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

#else  // scalar backend

struct vi32x4 {
  std::int32_t l[4] = {0, 0, 0, 0};
  vi32x4() = default;
  vi32x4(std::int32_t a, std::int32_t b, std::int32_t c, std::int32_t d) : l{a, b, c, d} {}
  explicit vi32x4(std::int32_t a) : l{a, a, a, a} {}
  std::int32_t lane(int i) const { return l[i]; }
};
inline vi32x4 load4(const std::int32_t* p) { return {p[0], p[1], p[2], p[3]}; }
inline vi32x4 load4_aligned(const std::int32_t* p) { return load4(p); }
inline void store4(vi32x4 a, std::int32_t* p) {
  for (int i = 0; i < 4; ++i) p[i] = a.l[i];
}
inline void store4_aligned(vi32x4 a, std::int32_t* p) { store4(a, p); }
inline vi32x4 load_texels4(const std::uint8_t* p) {
  vi32x4 r;
  for (int i = 0; i < 4; ++i) {
    std::uint32_t x;
    std::memcpy(&x, p + 4 * i, 4);
    r.l[i] = std::int32_t(x);
  }
  return r;
}
#define TESSERA_SIMD_I32_BINOP(op, expr)                                        \
  inline vi32x4 op(vi32x4 a, vi32x4 b) {                                        \
    vi32x4 r;                                                                   \
    for (int i = 0; i < 4; ++i) {                                               \
      const std::uint32_t x = std::uint32_t(a.l[i]), y = std::uint32_t(b.l[i]); \
      r.l[i] = std::int32_t(expr);                                              \
    }                                                                           \
    return r;                                                                   \
  }
TESSERA_SIMD_I32_BINOP(operator+, x + y)
TESSERA_SIMD_I32_BINOP(operator-, x - y)
TESSERA_SIMD_I32_BINOP(operator*, x* y)
TESSERA_SIMD_I32_BINOP(operator&, x& y)
TESSERA_SIMD_I32_BINOP(operator|, x | y)
TESSERA_SIMD_I32_BINOP(operator^, x ^ y)
TESSERA_SIMD_I32_BINOP(andnot, ~x& y)
TESSERA_SIMD_I32_BINOP(cmpeq, x == y ? ~0u : 0u)
TESSERA_SIMD_I32_BINOP(cmpgt, std::int32_t(x) > std::int32_t(y) ? ~0u : 0u)
TESSERA_SIMD_I32_BINOP(cmplt, std::int32_t(x) < std::int32_t(y) ? ~0u : 0u)
TESSERA_SIMD_I32_BINOP(min, std::int32_t(x) < std::int32_t(y) ? x : y)
TESSERA_SIMD_I32_BINOP(max, std::int32_t(x) > std::int32_t(y) ? x : y)
#undef TESSERA_SIMD_I32_BINOP
inline vi32x4& operator+=(vi32x4& a, vi32x4 b) { return a = a + b; }
// Shifts by 32 or more: SSE2's results (sra fills with the sign, srl and sll give zero).
template <int N>
inline vi32x4 sra(vi32x4 a) {
  static_assert(N >= 0);
  constexpr int n = N < 32 ? N : 31;
  return {a.l[0] >> n, a.l[1] >> n, a.l[2] >> n, a.l[3] >> n};
}
template <int N>
inline vi32x4 srl(vi32x4 a) {
  static_assert(N >= 0);
  vi32x4 r;
  if constexpr (N < 32) {
    for (int i = 0; i < 4; ++i) r.l[i] = std::int32_t(std::uint32_t(a.l[i]) >> N);
  }
  return r;
}
template <int N>
inline vi32x4 sll(vi32x4 a) {
  static_assert(N >= 0);
  vi32x4 r;
  if constexpr (N < 32) {
    for (int i = 0; i < 4; ++i) r.l[i] = std::int32_t(std::uint32_t(a.l[i]) << N);
  }
  return r;
}
inline vi32x4 select(vi32x4 mask, vi32x4 a, vi32x4 b) { return (mask & a) | andnot(mask, b); }
inline vi32x4 swap_pairs(vi32x4 a) { return {a.l[1], a.l[0], a.l[3], a.l[2]}; }
inline vi32x4 swap_pairs64(vi32x4 a) { return {a.l[2], a.l[3], a.l[0], a.l[1]}; }
inline vi32x4 select_alpha(vi32x4 rgb, vi32x4 a) { return {rgb.l[0], rgb.l[1], rgb.l[2], a.l[3]}; }
inline int movemask(vi32x4 mask) {
  int m = 0;
  for (int i = 0; i < 4; ++i) m |= (mask.l[i] < 0 ? 1 : 0) << i;
  return m;
}
inline vi32x4 pair_sums(vi32x4 a, vi32x4 b) {
  const auto add = [](std::int32_t x, std::int32_t y) {
    return std::int32_t(std::uint32_t(x) + std::uint32_t(y));
  };
  return {add(a.l[0], a.l[1]), add(a.l[2], a.l[3]), add(b.l[0], b.l[1]), add(b.l[2], b.l[3])};
}
inline vi32x4 even_lanes(vi32x4 a, vi32x4 b) { return {a.l[0], a.l[2], b.l[0], b.l[2]}; }
inline std::int32_t sum_lanes(vi32x4 a) {
  return std::int32_t(std::uint32_t(a.l[0]) + std::uint32_t(a.l[1]) + std::uint32_t(a.l[2]) +
                      std::uint32_t(a.l[3]));
}
inline std::int32_t sum_lanes02(vi32x4 a) {
  return std::int32_t(std::uint32_t(a.l[0]) + std::uint32_t(a.l[2]));
}
/// Clamped to 0..255, as SSE2's saturating packs.
inline void store_u8x4(vi32x4 a, std::uint8_t* out) {
  for (int i = 0; i < 4; ++i) out[i] = std::uint8_t(a.l[i] < 0 ? 0 : a.l[i] > 255 ? 255 : a.l[i]);
}

struct vi64x2 {
  std::int64_t l[2] = {0, 0};
  vi64x2() = default;
  explicit vi64x2(std::int64_t a) : l{a, a} {}
  vi64x2(std::int64_t lo, std::int64_t hi) : l{lo, hi} {}
};
inline vi64x2 load_i64x2(const std::int64_t* p) { return {p[0], p[1]}; }
inline vi64x2 operator+(vi64x2 a, vi64x2 b) {
  return {std::int64_t(std::uint64_t(a.l[0]) + std::uint64_t(b.l[0])),
          std::int64_t(std::uint64_t(a.l[1]) + std::uint64_t(b.l[1]))};
}
inline vi64x2 operator|(vi64x2 a, vi64x2 b) { return {a.l[0] | b.l[0], a.l[1] | b.l[1]}; }
inline int movemask(vi64x2 a) { return (a.l[0] < 0 ? 1 : 0) | (a.l[1] < 0 ? 2 : 0); }

#endif

}  // namespace TESSERA_SIMD_ISA
}  // namespace tessera::simd
