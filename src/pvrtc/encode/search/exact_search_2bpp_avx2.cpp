// exact_search_2bpp_avx2.cpp — the window evaluator of the 2 bpp exact endpoint search
// (exact_search_2bpp.cpp) on AVX2: four texels (16 lanes) a vector and eight a step instead of two
// and four. The same operations lane for lane, so the same per-texel errors; only the bound is
// checked less often (every 8 texels), which changes nothing below the bound.
//
// Compiled with -mavx2 (src/CMakeLists.txt) and called only where polish_avx2_active(). So
// that no AVX2 code can stand in for baseline code elsewhere, this file includes no header with
// inline functions or templates of external linkage (not simd.h or pvrtc_kernel.h) and keeps
// its helpers in an anonymous namespace; it exports the two functions of exact_search_window.h for
// the 2 bpp window only.
#include "pvrtc/encode/search/exact_search_window.h"

#if defined(TESSERA_HAVE_AVX2_KERNELS) && !defined(__AVX2__)
#error "exact_search_2bpp_avx2.cpp needs -mavx2 where TESSERA_HAVE_AVX2_KERNELS is set"
#endif

#if defined(__AVX2__)

#include <immintrin.h>

#include "pvrtc/encode/avx2_common.h"

namespace tessera::pvrtc::detail {

namespace {

/// Squared errors of texels k .. k + 3's five blends, lanes (texel RG, texel BA) x 4.
struct QuadSq {
  __m256i e0, e8, e3, e5, e4;
};

// The decoder's arithmetic, as the baseline: 8-bit colour (S >> 7) + (S >> 2) and alpha
// (S >> 5) + (S >> 1) of the bilinear sum S (lanes 3 and 7 of each 128-bit half:
// _mm256_blend_epi16 0x88), blends 0 (A), 8 (B), 3 and 5 from 4 (A + B) +- (A - B) (wrapping
// lanes, exact results) and 4 from A + B.
template <bool kAlpha>
inline void quad_sq(const Window2& w, int k, __m256i av, __m256i bv, __m256i aw, QuadSq& o) {
  const __m256i own = load256(&w.own[k][0]);
  const __m256i sa = _mm256_add_epi16(load256(&w.rest_a[k][0]), _mm256_mullo_epi16(own, av));
  const __m256i sb = _mm256_add_epi16(load256(&w.rest_b[k][0]), _mm256_mullo_epi16(own, bv));
  __m256i ua = _mm256_add_epi16(_mm256_srli_epi16(sa, 7), _mm256_srli_epi16(sa, 2));
  __m256i ub = _mm256_add_epi16(_mm256_srli_epi16(sb, 7), _mm256_srli_epi16(sb, 2));
  if constexpr (kAlpha) {
    ua = _mm256_blend_epi16(
        ua, _mm256_add_epi16(_mm256_srli_epi16(sa, 5), _mm256_srli_epi16(sa, 1)), 0x88);
    ub = _mm256_blend_epi16(
        ub, _mm256_add_epi16(_mm256_srli_epi16(sb, 5), _mm256_srli_epi16(sb, 1)), 0x88);
  }
  const __m256i t = load256(&w.t[k][0]);
  auto err = [&](__m256i v) {
    const __m256i d = _mm256_sub_epi16(v, t);
    return kAlpha ? _mm256_madd_epi16(d, _mm256_mullo_epi16(d, aw)) : _mm256_madd_epi16(d, d);
  };
  const __m256i sum = _mm256_add_epi16(ua, ub), sum2 = _mm256_add_epi16(sum, sum),
                sum4 = _mm256_add_epi16(sum2, sum2), diff = _mm256_sub_epi16(ua, ub);
  o.e0 = err(ua);
  o.e8 = err(ub);
  o.e3 = err(_mm256_srli_epi16(_mm256_add_epi16(sum4, diff), 3));
  o.e5 = err(_mm256_srli_epi16(_mm256_sub_epi16(sum4, diff), 3));
  o.e4 = err(_mm256_srli_epi16(sum, 1));
}

// Eight texels a step: the per-texel sums of two quads' lanes (_mm256_hadd_epi32: texels
// 0 1 4 5 | 2 3 6 7, the bias arrays permuted to match), then the minimum over the blends.
// The baseline takes it in float lanes (exact for the errors that can win, see
// exact_search_2bpp.cpp); the integer minimum is the same number.
template <bool kAlpha, bool kStore>
std::uint32_t window_error_t(const Window2& w, const std::int32_t a[4], const std::int32_t b[4],
                             std::uint32_t bound, std::uint32_t* texel_err) {
  const __m256i av = broadcast4(a), bv = broadcast4(b);
  const __m256i aw =
      _mm256_broadcastsi128_si256(_mm_loadu_si128(reinterpret_cast<const __m128i*>(w.weight16)));
  const __m256i hadd_order = _mm256_setr_epi32(0, 1, 4, 5, 2, 3, 6, 7);
  __m256i acc = _mm256_setzero_si256();
  for (int s = 0; s < Window2::kSlots / 8; ++s) {
    QuadSq x, y;
    quad_sq<kAlpha>(w, 8 * s, av, bv, aw, x);
    quad_sq<kAlpha>(w, 8 * s + 4, av, bv, aw, y);
    const __m256i b35 = _mm256_permutevar8x32_epi32(load256(&w.bias35[8 * s]), hadd_order);
    const __m256i b4 = _mm256_permutevar8x32_epi32(load256(&w.bias4[8 * s]), hadd_order);
    const __m256i m = _mm256_min_epi32(
        _mm256_min_epi32(
            _mm256_min_epi32(_mm256_hadd_epi32(x.e0, y.e0), _mm256_hadd_epi32(x.e8, y.e8)),
            _mm256_min_epi32(_mm256_add_epi32(_mm256_hadd_epi32(x.e3, y.e3), b35),
                             _mm256_add_epi32(_mm256_hadd_epi32(x.e5, y.e5), b35))),
        _mm256_add_epi32(_mm256_hadd_epi32(x.e4, y.e4), b4));
    acc = _mm256_add_epi32(acc, m);
    if constexpr (kStore) {
      // Back to texel order (64-bit units 0 2 1 3).
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(texel_err + 8 * s),
                          _mm256_permute4x64_epi64(m, _MM_SHUFFLE(3, 1, 2, 0)));
    } else {
      if (sum8(acc) >= bound) break;
    }
  }
  return sum8(acc);
}

}  // namespace

std::uint32_t window2_error_avx2(const Window2& w, const std::int32_t a[4],
                                 const std::int32_t b[4], std::uint32_t bound) {
  return w.nch == 4 ? window_error_t<true, false>(w, a, b, bound, nullptr)
                    : window_error_t<false, false>(w, a, b, bound, nullptr);
}

std::uint32_t window2_error_store_avx2(const Window2& w, const std::int32_t a[4],
                                       const std::int32_t b[4], std::uint32_t* texel_err) {
  return w.nch == 4 ? window_error_t<true, true>(w, a, b, 0, texel_err)
                    : window_error_t<false, true>(w, a, b, 0, texel_err);
}

}  // namespace tessera::pvrtc::detail

#else  // no AVX2 kernels in this build: polish_avx2_active() is false

namespace tessera::pvrtc::detail {

std::uint32_t window2_error_avx2(const Window2&, const std::int32_t*, const std::int32_t*,
                                 std::uint32_t) {
  return 0;
}
std::uint32_t window2_error_store_avx2(const Window2&, const std::int32_t*, const std::int32_t*,
                                       std::uint32_t*) {
  return 0;
}

}  // namespace tessera::pvrtc::detail

#endif
