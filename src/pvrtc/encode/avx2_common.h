// avx2_common.h — small AVX2 helpers shared by the *_avx2.cpp translation units, and only by
// them (it needs -mavx2). Everything here lives in an anonymous namespace: internal linkage, so
// every AVX2 translation unit has its own copy and the linker can never let one stand in for
// baseline code elsewhere (the rule the *_avx2.cpp files state for what they include).
#pragma once

#if !defined(__AVX2__)
#error "avx2_common.h is for translation units compiled with -mavx2"
#endif

#include <immintrin.h>

#include <cstdint>

namespace tessera::pvrtc::detail {
namespace {

/// Unaligned 256-bit load.
inline __m256i load256(const void* p) {
  return _mm256_loadu_si256(static_cast<const __m256i*>(p));
}

/// The four values (16-bit) in every texel's four lanes.
inline __m256i broadcast4(const std::int32_t v[4]) {
  const std::uint64_t x = std::uint64_t(std::uint16_t(v[0])) |
                          std::uint64_t(std::uint16_t(v[1])) << 16 |
                          std::uint64_t(std::uint16_t(v[2])) << 32 |
                          std::uint64_t(std::uint16_t(v[3])) << 48;
  return _mm256_set1_epi64x(static_cast<long long>(x));
}

/// Sum of the eight 32-bit lanes.
inline std::uint32_t sum8(__m256i a) {
  __m128i s = _mm_add_epi32(_mm256_castsi256_si128(a), _mm256_extracti128_si256(a, 1));
  s = _mm_add_epi32(s, _mm_shuffle_epi32(s, _MM_SHUFFLE(1, 0, 3, 2)));
  s = _mm_add_epi32(s, _mm_shuffle_epi32(s, _MM_SHUFFLE(2, 3, 0, 1)));
  return std::uint32_t(_mm_cvtsi128_si32(s));
}

/// The 16 RGBA8 texels of one row (64 bytes at p) as one vector of 16-bit lanes per channel
/// (ch[0] R ... ch[3] A): texels 0-7 in the low 128 bits, 8-15 in the high.
inline void load_channels(const std::uint8_t* p, __m256i ch[4]) {
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
  ch[0] = _mm256_unpacklo_epi8(rg, zero);
  ch[1] = _mm256_unpackhi_epi8(rg, zero);
  ch[2] = _mm256_unpacklo_epi8(ba, zero);
  ch[3] = _mm256_unpackhi_epi8(ba, zero);
}

}  // namespace
}  // namespace tessera::pvrtc::detail
