// exact_search_2bpp_avx2.cpp — the window evaluator of the 2 bpp exact endpoint search
// (exact_search_2bpp_evaluator.h, written once for both widths) with the SIMD wrapper's 8-lane
// types (core/simd_avx2.h): four texels (16 lanes) a vector and eight a step instead of two and
// four. The same operations lane for lane, so the same per-texel errors; only the bound is
// checked less often (every 8 texels), which changes nothing below the bound.
//
// Compiled with -mavx2 (src/CMakeLists.txt), which gives the wrapper its AVX2 backend, and
// called only where exact_search_avx2_active(). So that no AVX2 code can stand in for baseline code
// elsewhere, the wrapper's functions compiled here live in their own inline namespace
// (simd_select.h); otherwise this file includes no header with inline functions or templates of
// external linkage (exact_search_2bpp_evaluator.h's have internal linkage; not pvrtc_kernel.h);
// it exports the two functions of exact_search_window.h for the 2 bpp window only.
#include "pvrtc/encode/search/exact_search_window.h"

#if defined(TESSERA_HAVE_AVX2_KERNELS) && !defined(__AVX2__)
#error "exact_search_2bpp_avx2.cpp needs -mavx2 where TESSERA_HAVE_AVX2_KERNELS is set"
#endif

#if defined(__AVX2__)

#include "core/simd.h"
#include "pvrtc/encode/search/exact_search_2bpp_evaluator.h"

namespace tessera::pvrtc::detail {

std::uint32_t window2_error_avx2(const Window2& w, const std::int32_t a[4], const std::int32_t b[4],
                                 std::uint32_t bound) {
  return window2_error_bounded<simd::vu16x16>(w, a, b, bound);
}

std::uint32_t window2_error_store_avx2(const Window2& w, const std::int32_t a[4],
                                       const std::int32_t b[4], std::uint32_t* texel_err) {
  return window2_error_stored<simd::vu16x16>(w, a, b, texel_err);
}

}  // namespace tessera::pvrtc::detail

#else  // no AVX2 kernels in this build: exact_search_avx2_active() is false

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
