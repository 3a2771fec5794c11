// exact_search_avx2.cpp — the window evaluators of the 4 bpp exact search
// (exact_search_evaluators.h, written once for both widths) with the SIMD wrapper's 8-lane types
// (core/simd_avx2.h): `local_error_lanes` four texels (16 lanes) a vector and 8 a step instead
// of two and four, `planar_error_lanes` 16 texels a step instead of 8, alpha-weighted colour
// error included. The same operations lane for lane, so the same per-texel errors; only the
// bound is checked less often (every 8 / 16 texels), which changes nothing below the bound.
//
// Compiled with -mavx2 (src/CMakeLists.txt), which gives the wrapper its AVX2 backend, and
// called only after the run-time CPU check in exact_search.cpp. So that no AVX2 code can stand
// in for baseline code elsewhere, the wrapper's functions compiled here live in their own
// inline namespace (simd_select.h); otherwise this file includes no header with inline functions
// or templates of external linkage (exact_search_evaluators.h's have internal linkage; not
// exact_search_kernel.h or pvrtc_kernel.h); it exports the three functions of
// exact_search_window.h only.
#include "pvrtc/encode/search/exact_search_window.h"

#if defined(TESSERA_HAVE_AVX2_KERNELS) && !defined(__AVX2__)
#error "exact_search_avx2.cpp must be compiled with -mavx2 where TESSERA_HAVE_AVX2_KERNELS is set"
#endif

#if defined(__AVX2__)

#include "core/simd.h"
#include "pvrtc/encode/search/exact_search_evaluators.h"

namespace tessera::pvrtc::detail {

std::uint32_t local_error_avx2(const LocalWindow& lw, const std::int32_t a[4],
                               const std::int32_t b[4], std::uint32_t bound) {
  using simd::vu16x16;
  if (lw.nch != 4) return local_error_lanes<false, false, false, vu16x16>(lw, a, b, bound, nullptr);
  return lw.weighted ? local_error_lanes<true, false, true, vu16x16>(lw, a, b, bound, nullptr)
                     : local_error_lanes<true, false, false, vu16x16>(lw, a, b, bound, nullptr);
}

std::uint32_t local_error_store_avx2(const LocalWindow& lw, const std::int32_t a[4],
                                     const std::int32_t b[4], std::uint32_t* texel_err) {
  using simd::vu16x16;
  if (lw.nch != 4) return local_error_lanes<false, true, false, vu16x16>(lw, a, b, 0, texel_err);
  return lw.weighted ? local_error_lanes<true, true, true, vu16x16>(lw, a, b, 0, texel_err)
                     : local_error_lanes<true, true, false, vu16x16>(lw, a, b, 0, texel_err);
}

std::uint32_t planar_error_avx2(const PlanarWindow& pw, int c, std::int32_t av, std::int32_t bv,
                                std::uint32_t bound) {
  return pw.weighted ? planar_error_lanes<true, simd::vu16x16>(pw, c, av, bv, bound)
                     : planar_error_lanes<false, simd::vu16x16>(pw, c, av, bv, bound);
}

}  // namespace tessera::pvrtc::detail

#else  // no AVX2 kernels in this build: exact_search_avx2_active() is false

namespace tessera::pvrtc::detail {

std::uint32_t local_error_avx2(const LocalWindow&, const std::int32_t*, const std::int32_t*,
                               std::uint32_t) {
  return 0;
}
std::uint32_t local_error_store_avx2(const LocalWindow&, const std::int32_t*, const std::int32_t*,
                                     std::uint32_t*) {
  return 0;
}
std::uint32_t planar_error_avx2(const PlanarWindow&, int, std::int32_t, std::int32_t,
                                std::uint32_t) {
  return 0;
}

}  // namespace tessera::pvrtc::detail

#endif
