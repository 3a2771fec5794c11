// exact_search_2bpp_avx2.cpp — the window evaluator of the 2 bpp exact endpoint search
// (exact_search_2bpp.cpp) over the SIMD wrapper's 8-lane types (core/simd_wide.h): four texels
// (16 lanes) a vector and eight a step instead of two and four. The per-texel blend errors are
// the baseline's own code (exact_search_2bpp_blends.h, compiled here with vu16x16), so the same
// per-texel errors; only the bound is checked less often (every 8 texels), which changes
// nothing below the bound.
//
// Compiled with -mavx2 (src/CMakeLists.txt), which gives the wrapper its AVX2 backend, and
// called only where polish_avx2_active(). So that no AVX2 code can stand in for baseline code
// elsewhere, the wrapper's functions compiled here live in their own inline namespace
// (simd_int.h); otherwise this file includes no header with inline functions or templates of
// external linkage (not pvrtc_kernel.h) and keeps its helpers in an anonymous namespace; it
// exports the two functions of exact_search_window.h for the 2 bpp window only.
#include "pvrtc/encode/search/exact_search_window.h"

#if defined(TESSERA_HAVE_AVX2_KERNELS) && !defined(__AVX2__)
#error "exact_search_2bpp_avx2.cpp needs -mavx2 where TESSERA_HAVE_AVX2_KERNELS is set"
#endif

#if defined(__AVX2__)

#include "core/simd.h"
#include "pvrtc/encode/search/exact_search_2bpp_blends.h"
#include "pvrtc/encode/search/exact_search_wide.h"

namespace tessera::pvrtc::detail {

namespace {

using namespace simd;

/// Squared errors of texels k .. k + 3's five blends, lanes (texel RG, texel BA) x 4: the
/// baseline's own blend_sq2 (exact_search_2bpp_blends.h), four texels a vector.
using QuadSq = BlendSq2<vu16x16>;
template <bool kAlpha>
inline void quad_sq(const Window2& w, int k, vu16x16 av, vu16x16 bv, vu16x16 aw, QuadSq& o) {
  blend_sq2<kAlpha>(w, k, av, bv, aw, o);
}

// Eight texels a step: the per-texel sums of two quads' lanes (pair_sums works per half:
// texels 0 1 4 5 | 2 3 6 7, the bias arrays permuted to match), then the minimum over the
// blends. The baseline takes it in float lanes (exact for the errors that can win, see
// exact_search_2bpp.cpp); the integer minimum is the same number.
template <bool kAlpha, bool kStore>
std::uint32_t window_error_t(const Window2& w, const std::int32_t a[4], const std::int32_t b[4],
                             std::uint32_t bound, std::uint32_t* texel_err) {
  const vu16x16 av = broadcast_endpoint(a), bv = broadcast_endpoint(b);
  const vu16x8 aw8 = load_u16x8(w.weight16);
  const vu16x16 aw(aw8, aw8);
  vint8 acc;
  for (int s = 0; s < Window2::kSlots / 8; ++s) {
    QuadSq x, y;
    quad_sq<kAlpha>(w, 8 * s, av, bv, aw, x);
    quad_sq<kAlpha>(w, 8 * s + 4, av, bv, aw, y);
    const vint8 b35 = permute64<0, 2, 1, 3>(load8(&w.bias35[8 * s]));
    const vint8 b4 = permute64<0, 2, 1, 3>(load8(&w.bias4[8 * s]));
    const vint8 m = min(min(min(pair_sums(x.e0, y.e0), pair_sums(x.e8, y.e8)),
                            min(pair_sums(x.e3, y.e3) + b35, pair_sums(x.e5, y.e5) + b35)),
                        pair_sums(x.e4, y.e4) + b4);
    acc += m;
    if constexpr (kStore) {
      // Back to texel order.
      store8(permute64<0, 2, 1, 3>(m), reinterpret_cast<std::int32_t*>(texel_err + 8 * s));
    } else {
      if (std::uint32_t(sum_lanes(acc)) >= bound) break;
    }
  }
  return std::uint32_t(sum_lanes(acc));
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
