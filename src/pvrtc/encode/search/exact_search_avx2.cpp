// exact_search_avx2.cpp — the window evaluators of the 4 bpp exact search (exact_search_kernel.h)
// on AVX2: `local_error_avx2` four texels (16 lanes) a vector and 8 a step instead of two and four,
// `planar_error_avx2` 16 texels a step instead of 8. The same operations lane for lane, so the
// same per-texel errors; only the bound is checked less often (every 8 / 16 texels), which
// changes nothing below the bound.
//
// Compiled with -mavx2 (src/CMakeLists.txt) and called only after the run-time CPU check in
// exact_search.cpp. So that no AVX2 code can stand in for baseline code elsewhere, this file
// includes no header with inline functions or templates of external linkage (not simd.h,
// exact_search_kernel.h or pvrtc_kernel.h) and keeps its helpers in an anonymous namespace; it
// exports the three functions of exact_search_window.h only.
#include "pvrtc/encode/search/exact_search_window.h"

#if defined(TESSERA_HAVE_AVX2_KERNELS) && !defined(__AVX2__)
#error "exact_search_avx2.cpp must be compiled with -mavx2 where TESSERA_HAVE_AVX2_KERNELS is set"
#endif

#if defined(__AVX2__)

#include <immintrin.h>

#include "pvrtc/encode/avx2_common.h"

namespace tessera::pvrtc::detail {

namespace {

/// Squared errors of texels k .. k + 3's blends, lanes (texel RG, texel BA) x 4, as `pair_sq`
/// of local_error_simd_t: blends 0 (A), 8 (B), 3, 5, 4 and 4 with alpha punched through.
struct QuadSq {
  __m256i e0, e8, e3, e5, e4, e4p;
};

template <bool kAlpha>
inline void quad_sq(const LocalWindow& lw, int k, __m256i av, __m256i bv, __m256i aw,
                    QuadSq& o) {
  const __m256i own = load256(&lw.own16[k][0]);
  // Bilinear sums S (weights sum to 16); 8-bit colour (2S >> 7) + (2S >> 2), alpha
  // (2S >> 5) + (2S >> 1) (lanes 3 and 7 of each 128-bit half: _mm256_blend_epi16 0x88).
  const __m256i sa = _mm256_add_epi16(load256(&lw.rest16_a[k][0]), _mm256_mullo_epi16(own, av));
  const __m256i sb = _mm256_add_epi16(load256(&lw.rest16_b[k][0]), _mm256_mullo_epi16(own, bv));
  __m256i ua = _mm256_add_epi16(_mm256_srli_epi16(sa, 6), _mm256_srli_epi16(sa, 1));
  __m256i ub = _mm256_add_epi16(_mm256_srli_epi16(sb, 6), _mm256_srli_epi16(sb, 1));
  if constexpr (kAlpha) {
    ua = _mm256_blend_epi16(ua, _mm256_add_epi16(_mm256_srli_epi16(sa, 4), sa), 0x88);
    ub = _mm256_blend_epi16(ub, _mm256_add_epi16(_mm256_srli_epi16(sb, 4), sb), 0x88);
  }
  const __m256i t = load256(&lw.t16[k][0]);
  auto err = [&](__m256i v) {
    const __m256i d = _mm256_sub_epi16(v, t);
    return kAlpha ? _mm256_madd_epi16(d, _mm256_mullo_epi16(d, aw)) : _mm256_madd_epi16(d, d);
  };
  // Blends 4 (A + B) +- (A - B) >> 3 for m = 3, 5 (wrapping lanes, exact results) and
  // (A + B) >> 1 for m = 4, as the baseline.
  const __m256i sum = _mm256_add_epi16(ua, ub), sum2 = _mm256_add_epi16(sum, sum),
                sum4 = _mm256_add_epi16(sum2, sum2), diff = _mm256_sub_epi16(ua, ub);
  o.e0 = err(ua);
  o.e8 = err(ub);
  o.e3 = err(_mm256_srli_epi16(_mm256_add_epi16(sum4, diff), 3));
  o.e5 = err(_mm256_srli_epi16(_mm256_sub_epi16(sum4, diff), 3));
  const __m256i v4 = _mm256_srli_epi16(sum, 1);
  o.e4 = err(v4);
  if constexpr (kAlpha) o.e4p = err(_mm256_blend_epi16(v4, _mm256_setzero_si256(), 0x88));
}

/// Texels 8s .. 8s + 7 of a LocalWindow bias array (texel k at element 2k), in the lane order
/// of _mm256_hadd_epi32 of two quads: texels (0 1 4 5 | 2 3 6 7).
inline __m256i bias8(const std::int32_t (*rows)[4], int s) {
  const __m256 p = _mm256_castsi256_ps(load256(rows[4 * s]));
  const __m256 q = _mm256_castsi256_ps(load256(rows[4 * s + 2]));
  return _mm256_castps_si256(_mm256_shuffle_ps(p, q, _MM_SHUFFLE(2, 0, 2, 0)));
}

// Eight texels a step: the per-texel sums of two quads' lanes (texels 0 1 4 5 | 2 3 6 7), then
// the minimum over the blends. The baseline takes it in float lanes (SSE2 has no 32-bit
// integer min; exact there, see exact_search_kernel.h); AVX2 has one, and the exact integer minimum
// is the same number.
template <bool kAlpha, bool kStore>
std::uint32_t local_error_t(const LocalWindow& lw, const std::int32_t a[4],
                            const std::int32_t b[4], std::uint32_t bound,
                            std::uint32_t* texel_err) {
  const __m256i av = broadcast4(a), bv = broadcast4(b);
  const __m256i aw =
      _mm256_broadcastsi128_si256(_mm_loadu_si128(reinterpret_cast<const __m128i*>(lw.weight16)));
  __m256i acc = _mm256_setzero_si256();
  for (int s = 0; s < 7; ++s) {
    QuadSq x, y;
    quad_sq<kAlpha>(lw, 8 * s, av, bv, aw, x);
    quad_sq<kAlpha>(lw, 8 * s + 4, av, bv, aw, y);
    const __m256i b35 = bias8(lw.bias35, s);
    __m256i m4 = _mm256_add_epi32(_mm256_hadd_epi32(x.e4, y.e4), bias8(lw.bias4, s));
    if constexpr (kAlpha) {
      m4 = _mm256_min_epi32(
          m4, _mm256_add_epi32(_mm256_hadd_epi32(x.e4p, y.e4p), bias8(lw.bias4p, s)));
    }
    const __m256i m = _mm256_min_epi32(
        _mm256_min_epi32(
            _mm256_min_epi32(_mm256_hadd_epi32(x.e0, y.e0), _mm256_hadd_epi32(x.e8, y.e8)),
            _mm256_min_epi32(_mm256_add_epi32(_mm256_hadd_epi32(x.e3, y.e3), b35),
                             _mm256_add_epi32(_mm256_hadd_epi32(x.e5, y.e5), b35))),
        m4);
    acc = _mm256_add_epi32(acc, m);
    if constexpr (kStore) {
      // Back to texel order (64-bit units 0 2 1 3); the last step stores texels 48-51 only.
      const __m256i ordered = _mm256_permute4x64_epi64(m, _MM_SHUFFLE(3, 1, 2, 0));
      if (s < 6) {
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(texel_err + 8 * s), ordered);
      } else {
        _mm_storeu_si128(reinterpret_cast<__m128i*>(texel_err + 8 * s),
                         _mm256_castsi256_si128(ordered));
      }
    } else {
      if (sum8(acc) >= bound) break;
    }
  }
  return sum8(acc);
}

/// 16 texels (o .. o + 15; kTail: o .. o + 7) of channel c: the minimum over the slots of
/// (2^23 + d^2) + rest as planar_error, as two vectors of 8 float lanes (texels in order).
/// The 16-bit lanes are in the order (0-3 8-11 | 4-7 12-15) (loads permuted by 64-bit units),
/// so that each 128-bit half's low / high four lanes widen to texels 0-7 / 8-15.
template <bool kTail>
inline __m256i planar_group(const PlanarWindow& pw, int c, int o, __m256i a16, __m256i b16) {
  auto load = [&](const std::uint16_t* p) {
    __m256i v;
    if constexpr (kTail) {
      v = _mm256_inserti128_si256(_mm256_setzero_si256(),
                                  _mm_loadu_si128(reinterpret_cast<const __m128i*>(p)), 0);
    } else {
      v = load256(p);
    }
    return _mm256_permute4x64_epi64(v, _MM_SHUFFLE(3, 1, 2, 0));
  };
  const __m256i own = load(&pw.own[o]);
  const __m256i sa = _mm256_add_epi16(load(&pw.ra[c][o]), _mm256_mullo_epi16(own, a16));
  const __m256i sb = _mm256_add_epi16(load(&pw.rb[c][o]), _mm256_mullo_epi16(own, b16));
  const __m256i ua = _mm256_add_epi16(_mm256_srli_epi16(sa, 6), _mm256_srli_epi16(sa, 1));
  const __m256i ub = _mm256_add_epi16(_mm256_srli_epi16(sb, 6), _mm256_srli_epi16(sb, 1));
  const __m256i sum = _mm256_add_epi16(ua, ub), sum2 = _mm256_add_epi16(sum, sum),
                sum4 = _mm256_add_epi16(sum2, sum2), diff = _mm256_sub_epi16(ua, ub);
  const __m256i bl[5] = {ua, ub, _mm256_srli_epi16(_mm256_add_epi16(sum4, diff), 3),
                         _mm256_srli_epi16(_mm256_sub_epi16(sum4, diff), 3),
                         _mm256_srli_epi16(sum, 1)};
  const __m256i t = load(&pw.t[c][o]);
  const __m256i f2p23 = _mm256_set1_epi16(0x4b00);
  __m256 mlo = _mm256_setzero_ps(), mhi = _mm256_setzero_ps();
  for (int sl = 0; sl < PlanarWindow::kSlots; ++sl) {
    const __m256i d = _mm256_sub_epi16(bl[sl], t);
    const __m256i sq = _mm256_mullo_epi16(d, d);
    // (2^23 + d^2) + (total - e - 2^23): exact integers below 2^24.
    const __m256 lo = _mm256_add_ps(_mm256_castsi256_ps(_mm256_unpacklo_epi16(sq, f2p23)),
                                    _mm256_loadu_ps(&pw.rest[c][sl][o]));
    mlo = sl == 0 ? lo : _mm256_min_ps(mlo, lo);
    if constexpr (!kTail) {
      const __m256 hi = _mm256_add_ps(_mm256_castsi256_ps(_mm256_unpackhi_epi16(sq, f2p23)),
                                      _mm256_loadu_ps(&pw.rest[c][sl][o + 8]));
      mhi = sl == 0 ? hi : _mm256_min_ps(mhi, hi);
    }
  }
  if constexpr (kTail) return _mm256_cvttps_epi32(mlo);
  return _mm256_add_epi32(_mm256_cvttps_epi32(mlo), _mm256_cvttps_epi32(mhi));
}

}  // namespace

std::uint32_t local_error_avx2(const LocalWindow& lw, const std::int32_t a[4],
                               const std::int32_t b[4], std::uint32_t bound) {
  return lw.nch == 4 ? local_error_t<true, false>(lw, a, b, bound, nullptr)
                     : local_error_t<false, false>(lw, a, b, bound, nullptr);
}

std::uint32_t local_error_store_avx2(const LocalWindow& lw, const std::int32_t a[4],
                                     const std::int32_t b[4], std::uint32_t* texel_err) {
  return lw.nch == 4 ? local_error_t<true, true>(lw, a, b, 0, texel_err)
                     : local_error_t<false, true>(lw, a, b, 0, texel_err);
}

std::uint32_t planar_error_avx2(const PlanarWindow& pw, int c, std::int32_t av, std::int32_t bv,
                                std::uint32_t bound) {
  const __m256i a16 = _mm256_set1_epi16(static_cast<short>(av));
  const __m256i b16 = _mm256_set1_epi16(static_cast<short>(bv));
  __m256i acc = _mm256_setzero_si256();
  for (int o = 0; o < 48; o += 16) {
    acc = _mm256_add_epi32(acc, planar_group<false>(pw, c, o, a16, b16));
    if (sum8(acc) >= bound) return sum8(acc);
  }
  return sum8(_mm256_add_epi32(acc, planar_group<true>(pw, c, 48, a16, b16)));
}

}  // namespace tessera::pvrtc::detail

#else  // no AVX2 kernels in this build: polish_avx2_active() is false

namespace tessera::pvrtc::detail {

std::uint32_t local_error_avx2(const LocalWindow&, const std::int32_t*, const std::int32_t*,
                               std::uint32_t) {
  return 0;
}
std::uint32_t local_error_store_avx2(const LocalWindow&, const std::int32_t*,
                                     const std::int32_t*, std::uint32_t*) {
  return 0;
}
std::uint32_t planar_error_avx2(const PlanarWindow&, int, std::int32_t, std::int32_t,
                                std::uint32_t) {
  return 0;
}

}  // namespace tessera::pvrtc::detail

#endif
