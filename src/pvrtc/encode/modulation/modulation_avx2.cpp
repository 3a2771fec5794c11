// modulation_avx2.cpp — the 4 bpp brute-force modulation kernel (modulation_blends.h, written
// once for both widths) with the SIMD wrapper's 8-lane types (core/simd_avx2.h): four blocks
// (16 texels a row) a step instead of two, the same operations lane for lane, so the same bits
// and errors (ties to the earlier candidate included), alpha-weighted colour error included.
//
// Compiled with -mavx2 (src/CMakeLists.txt), which gives the wrapper its AVX2 backend, and
// called only after the run-time CPU check in modulation.cpp. So that no AVX2 code can stand
// in for baseline code elsewhere, the wrapper's functions compiled here live in their own
// inline namespace (simd_select.h); otherwise this file includes no header with inline functions
// or templates of external linkage (modulation_blends.h's have internal linkage; not
// modulation_kernel.h or the standard containers) and keeps its helpers in an anonymous
// namespace; it exports `block_row_errors_avx2` only.
#include "pvrtc/encode/modulation/modulation_avx2.h"

#if defined(TESSERA_HAVE_AVX2_KERNELS) && !defined(__AVX2__)
#error "modulation_avx2.cpp must be compiled with -mavx2 where TESSERA_HAVE_AVX2_KERNELS is set"
#endif

#if defined(__AVX2__)

#include <cstring>

#include "core/simd.h"
#include "pvrtc/encode/modulation/modulation_blends.h"

namespace tessera::pvrtc::detail {

namespace {

using namespace simd;

/// Scores blocks bx .. bx + 3 (texel rows from `t`, 64 bytes each; colour scales from `w`, 16
/// bytes each, kWeighted only) into out[0..3].
template <bool kAlpha, bool kExtra, bool kWeighted>
inline void block_quad_errors(const std::uint16_t* const v[4], const std::uint8_t* const t[4],
                              const std::uint8_t* const w[4], std::size_t vstride, int bx,
                              BlockModAvx2 out[4]) {
  // Lanes: 16-bit values of texels 0-7 (low half) and 8-15 (high); the 32-bit sums hold texels
  // 0-3 and 8-11 (acc[0]: blocks 0 and 2) or 4-7 and 12-15 (acc[1]: blocks 1 and 3).
  ModAcc<vi32x8> acc[2];
  vu16x16 clear;  // all ones where some row's target alpha < 128
  mod_step<kAlpha, kExtra, kWeighted>(v, t, w, vstride, bx, acc, clear);
  mod_block_results<kExtra>(acc, out);
  const std::uint32_t clear_bytes = kAlpha ? movemask_bytes(clear) : 0u;
  for (int q = 0; q < 4; ++q) {
    out[q].any_clear = (clear_bytes >> (8 * q)) & 0xffu ? 1u : 0u;  // texels 4q .. 4q + 3
  }
}

template <bool kAlpha, bool kExtra, bool kWeighted>
void block_row(const std::uint16_t* const v[4], const std::uint8_t* const t[4],
               const std::uint8_t* const w[4], std::size_t vstride, int nbx, BlockModAvx2* out) {
  int bx = 0;
  const std::uint8_t* tq[4];
  const std::uint8_t* wq[4] = {};
  for (; bx + 4 <= nbx; bx += 4) {
    for (int j = 0; j < 4; ++j) {
      tq[j] = t[j] + std::size_t(bx) * 16;
      if constexpr (kWeighted) wq[j] = w[j] + std::size_t(bx) * 4;
    }
    block_quad_errors<kAlpha, kExtra, kWeighted>(v, tq, wq, vstride, bx, out + bx);
  }
  if (bx < nbx) {
    // 1-3 blocks left (textures 8 texels wide): their texels (and scales) copied into a full
    // step, the rest zero; the taps read elements bx .. bx + 7 < vstride.
    const int n = nbx - bx;
    alignas(32) std::uint8_t buf[4][64] = {};
    alignas(16) std::uint8_t wbuf[4][16] = {};
    for (int j = 0; j < 4; ++j) {
      std::memcpy(buf[j], t[j] + std::size_t(bx) * 16, std::size_t(n) * 16);
      tq[j] = buf[j];
      if constexpr (kWeighted) {
        std::memcpy(wbuf[j], w[j] + std::size_t(bx) * 4, std::size_t(n) * 4);
        wq[j] = wbuf[j];
      }
    }
    BlockModAvx2 quad[4];
    block_quad_errors<kAlpha, kExtra, kWeighted>(v, tq, wq, vstride, bx, quad);
    for (int q = 0; q < n; ++q) out[bx + q] = quad[q];
  }
}

}  // namespace

void block_row_errors_avx2(const std::uint16_t* const v[4], const std::uint8_t* const t[4],
                           const std::uint8_t* const w[4], std::size_t vstride, int nbx, bool alpha,
                           bool extra, BlockModAvx2* out) {
  if (alpha && w != nullptr) {
    extra ? block_row<true, true, true>(v, t, w, vstride, nbx, out)
          : block_row<true, false, true>(v, t, w, vstride, nbx, out);
  } else if (alpha) {
    extra ? block_row<true, true, false>(v, t, w, vstride, nbx, out)
          : block_row<true, false, false>(v, t, w, vstride, nbx, out);
  } else {
    extra ? block_row<false, true, false>(v, t, w, vstride, nbx, out)
          : block_row<false, false, false>(v, t, w, vstride, nbx, out);
  }
}

}  // namespace tessera::pvrtc::detail

#else  // no AVX2 kernels in this build: modulation_avx2_supported() is false

namespace tessera::pvrtc::detail {

void block_row_errors_avx2(const std::uint16_t* const*, const std::uint8_t* const*,
                           const std::uint8_t* const*, std::size_t, int, bool, bool,
                           BlockModAvx2*) {}

}  // namespace tessera::pvrtc::detail

#endif
