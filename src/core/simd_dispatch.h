// simd_dispatch.h — part of the SIMD wrapper (see core/simd.h): what the run-time dispatch
// needs beyond the baseline backends. The CPU feature checks that choose between a baseline
// kernel and one built for a later instruction set (the -mavx2 *_avx2.cpp translation units,
// the SSSE3 routine below), and that routine itself: the baseline x86-64 build assumes SSE2
// only, so code that needs more is compiled for it alone (a separate translation unit, or a
// function with a target attribute) and called only after the check says yes.
#pragma once

#include <cstdint>
#include <cstring>

#include "core/simd_select.h"

#if defined(TESSERA_SIMD_X86_DISPATCH)  // defined by simd_select.h
#include <tmmintrin.h>
#endif

namespace tessera::simd {
inline namespace TESSERA_SIMD_ISA {

/// True where the CPU (and OS) can run AVX2 code; false on other CPUs and in builds without the
/// x86 vector backend. Computed once.
inline bool cpu_has_avx2() {
#if defined(TESSERA_SIMD_X86_DISPATCH)
  static const bool has = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") != 0;
  }();
  return has;
#else
  return false;
#endif
}

/// True where the CPU can run SSSE3 code (every x86-64 CPU since 2006); false elsewhere.
inline bool cpu_has_ssse3() {
#if defined(TESSERA_SIMD_X86_DISPATCH)
  static const bool has = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("ssse3") != 0;
  }();
  return has;
#else
  return false;
#endif
}

#if defined(TESSERA_SIMD_X86_DISPATCH)
/// The first `n / 16 * 16` texels of a packed RGB row to packed RGBA with alpha 255, sixteen a
/// step (three 16-byte loads, four byte shuffles); returns how many it did. SSSE3: call only
/// where cpu_has_ssse3().
__attribute__((target("ssse3"))) inline int rgb_to_rgba8_ssse3(const std::uint8_t* in, int n,
                                                               std::uint8_t* out) {
  const __m128i spread = _mm_setr_epi8(0, 1, 2, -1, 3, 4, 5, -1, 6, 7, 8, -1, 9, 10, 11, -1);
  const __m128i alpha = _mm_set1_epi32(static_cast<int>(0xff000000u));
  int x = 0;
  for (; x + 16 <= n; x += 16, in += 48, out += 64) {
    const __m128i a = _mm_loadu_si128(reinterpret_cast<const __m128i*>(in));
    const __m128i b = _mm_loadu_si128(reinterpret_cast<const __m128i*>(in + 16));
    const __m128i c = _mm_loadu_si128(reinterpret_cast<const __m128i*>(in + 32));
    const __m128i t[4] = {a, _mm_alignr_epi8(b, a, 12), _mm_alignr_epi8(c, b, 8),
                          _mm_srli_si128(c, 4)};
    for (int k = 0; k < 4; ++k) {
      _mm_storeu_si128(reinterpret_cast<__m128i*>(out + 16 * k),
                       _mm_or_si128(_mm_shuffle_epi8(t[k], spread), alpha));
    }
  }
  return x;
}
#endif

}  // namespace TESSERA_SIMD_ISA
}  // namespace tessera::simd
