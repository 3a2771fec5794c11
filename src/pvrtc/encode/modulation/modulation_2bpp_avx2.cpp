// modulation_2bpp_avx2.cpp — the three 2 bpp modulation passes (modulation_2bpp_rows.h, written
// once for both widths) with the SIMD wrapper's 8-lane types (core/simd_avx2.h): two blocks a
// step (block bx in the low half, bx + 1 in the high) instead of one, the same operations lane
// for lane, so the same maps, bits, modes and errors (ties included).
//
// Compiled with -mavx2 (src/CMakeLists.txt), which gives the wrapper its AVX2 backend, and
// called only after the run-time CPU check in modulation_2bpp.cpp. So that no AVX2 code can
// stand in for baseline code elsewhere, the wrapper's functions compiled here live in their own
// inline namespace (simd_select.h); otherwise this file includes no header with inline functions
// or templates of external linkage (modulation_2bpp_rows.h's have internal linkage,
// modulation_2bpp_avx2.h holds plain declarations; not encode_internal.h or the standard
// containers); it exports the three `mod2_pass*_row_avx2` functions only.
#include "pvrtc/encode/modulation/modulation_2bpp_avx2.h"

#if defined(TESSERA_HAVE_AVX2_KERNELS) && !defined(__AVX2__)
#error "modulation_2bpp_avx2.cpp needs -mavx2 where TESSERA_HAVE_AVX2_KERNELS is set"
#endif

#if defined(__AVX2__)

#include "core/simd.h"
#include "pvrtc/encode/modulation/modulation_2bpp_rows.h"

namespace tessera::pvrtc::detail {

void mod2_pass1_row_avx2(const Mod2Row& r, bool alpha) {
  alpha ? mod2_pass1<true, simd::vu16x16>(r) : mod2_pass1<false, simd::vu16x16>(r);
}

void mod2_pass2_row_avx2(const Mod2Row& r, bool alpha) {
  alpha ? mod2_pass2<true, simd::vu16x16>(r) : mod2_pass2<false, simd::vu16x16>(r);
}

std::uint64_t mod2_pass3_row_avx2(const Mod2Row& r, bool alpha) {
  return alpha ? mod2_pass3<true, simd::vu16x16>(r) : mod2_pass3<false, simd::vu16x16>(r);
}

}  // namespace tessera::pvrtc::detail

#else  // no AVX2 in this build: never called (the dispatch checks TESSERA_HAVE_AVX2_KERNELS)

namespace tessera::pvrtc::detail {

void mod2_pass1_row_avx2(const Mod2Row&, bool) {}
void mod2_pass2_row_avx2(const Mod2Row&, bool) {}
std::uint64_t mod2_pass3_row_avx2(const Mod2Row&, bool) { return 0; }

}  // namespace tessera::pvrtc::detail

#endif
