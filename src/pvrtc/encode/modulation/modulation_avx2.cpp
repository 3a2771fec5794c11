// modulation_avx2.cpp — the 4 bpp brute-force modulation kernel of modulation_kernel.h on
// AVX2: four blocks (16 texels a row) a step instead of two, the same operations lane for
// lane, so the same bits and errors (ties to the earlier candidate included).
//
// Compiled with -mavx2 (src/CMakeLists.txt) and called only after the run-time CPU check in
// modulation.cpp. So that no AVX2 code can stand in for baseline code elsewhere, this file
// includes no header with inline functions or templates of external linkage (avx2_common.h's
// helpers have internal linkage; not simd.h,
// modulation_kernel.h or the standard containers) and keeps its helpers in an anonymous
// namespace; it exports `block_row_errors_avx2` only.
#include "pvrtc/encode/modulation/modulation_avx2.h"

#if defined(TESSERA_HAVE_AVX2_KERNELS) && !defined(__AVX2__)
#error "modulation_avx2.cpp must be compiled with -mavx2 where TESSERA_HAVE_AVX2_KERNELS is set"
#endif

#if defined(__AVX2__)

#include <immintrin.h>

#include <cstring>

#include "pvrtc/encode/avx2_common.h"

namespace tessera::pvrtc::detail {

namespace {

/// Lanes: 16-bit values of texels 0-7 (low 128 bits) and 8-15 (high); the 32-bit sums that
/// come from them hold texels 0-3 and 8-11 (`lo`: blocks 0 and 2) or 4-7 and 12-15 (`hi`:
/// blocks 1 and 3).

/// Sum of squares of (dr, dg, db, da) per texel.
inline void sq4(__m256i dr, __m256i dg, __m256i db, __m256i da, __m256i& lo, __m256i& hi) {
  const __m256i rg0 = _mm256_unpacklo_epi16(dr, dg), rg1 = _mm256_unpackhi_epi16(dr, dg);
  const __m256i ba0 = _mm256_unpacklo_epi16(db, da), ba1 = _mm256_unpackhi_epi16(db, da);
  lo = _mm256_add_epi32(_mm256_madd_epi16(rg0, rg0), _mm256_madd_epi16(ba0, ba0));
  hi = _mm256_add_epi32(_mm256_madd_epi16(rg1, rg1), _mm256_madd_epi16(ba1, ba1));
}

/// ((a * ka + b * kb) >> 3) - t, 16-bit lanes: the decoder's blend of weights kb / 8.
inline __m256i blend8(__m256i a, __m256i b, __m256i ka, __m256i kb, __m256i t) {
  const __m256i s = _mm256_add_epi16(_mm256_mullo_epi16(a, ka), _mm256_mullo_epi16(b, kb));
  return _mm256_sub_epi16(_mm256_srli_epi16(s, 3), t);
}

/// The candidate's key: error * 4 + rank (the minimum keeps the earliest of equal errors).
inline __m256i key(__m256i e, int rank) {
  return _mm256_or_si256(_mm256_slli_epi32(e, 2), _mm256_set1_epi32(rank));
}

/// Scores blocks bx .. bx + 3 (texel rows from `t`, 64 bytes each) into out[0..3].
template <bool kAlpha, bool kExtra>
inline void block_quad_errors(const std::uint16_t* const v[4], const std::uint8_t* const t[4],
                              std::size_t vstride, int bx, BlockModAvx2 out[4]) {
  constexpr int nch = kAlpha ? 4 : 3;
  // Bilinear taps (as simd::taps8, twice): from p[0..5], left = p0 p0 p1 p1 p1 p1 p2 p2 |
  // p2 p2 p3 p3 p3 p3 p4 p4 and right = the same indices + 1, as byte shuffles.
  const __m256i tap_left = _mm256_setr_epi8(0, 1, 0, 1, 2, 3, 2, 3, 2, 3, 2, 3, 4, 5, 4, 5,  //
                                            4, 5, 4, 5, 6, 7, 6, 7, 6, 7, 6, 7, 8, 9, 8, 9);
  const __m256i tap_right = _mm256_setr_epi8(2, 3, 2, 3, 4, 5, 4, 5, 4, 5, 4, 5, 6, 7, 6, 7,  //
                                             6, 7, 6, 7, 8, 9, 8, 9, 8, 9, 8, 9, 10, 11, 10, 11);
  const __m256i w_left = _mm256_setr_epi16(2, 1, 4, 3, 2, 1, 4, 3, 2, 1, 4, 3, 2, 1, 4, 3);
  const __m256i w_right = _mm256_setr_epi16(2, 3, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1);
  const __m256i k3 = _mm256_set1_epi16(3), k5 = _mm256_set1_epi16(5);
  const __m256i three = _mm256_set1_epi32(3), zero = _mm256_setzero_si256();
  __m256i err0[2], bits0[2], err1[2], bits1[2], err1p[2], bits1p[2];
  for (int h = 0; h < 2; ++h) {
    err0[h] = bits0[h] = err1[h] = bits1[h] = err1p[h] = bits1p[h] = zero;
  }
  __m256i clear = zero;  // 16-bit lanes: all ones where some row's target alpha < 128
  for (int j = 0; j < 4; ++j) {
    __m256i tv[4];
    load_channels(t[j], tv);
    __m256i d0[4], d3[4], d5[4], d8[4], d4[4];
    for (int c = 0; c < nch; ++c) {
      __m256i up[2];
      for (int img = 0; img < 2; ++img) {
        const std::uint16_t* p = v[j] + std::size_t(img * 4 + c) * vstride + std::size_t(bx);
        const __m256i x =
            _mm256_broadcastsi128_si256(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)));
        const __m256i L = _mm256_shuffle_epi8(x, tap_left), R = _mm256_shuffle_epi8(x, tap_right);
        const __m256i w =
            _mm256_add_epi16(_mm256_mullo_epi16(L, w_left), _mm256_mullo_epi16(R, w_right));
        up[img] = c < 3 ? _mm256_add_epi16(_mm256_srli_epi16(w, 6), _mm256_srli_epi16(w, 1))
                        : _mm256_add_epi16(_mm256_srli_epi16(w, 4), w);
      }
      const __m256i a = up[0], b = up[1], tc = tv[c];
      d0[c] = _mm256_sub_epi16(a, tc);
      d8[c] = _mm256_sub_epi16(b, tc);
      d3[c] = blend8(a, b, k5, k3, tc);
      d5[c] = blend8(a, b, k3, k5, tc);
      if constexpr (kExtra) {
        d4[c] = _mm256_sub_epi16(_mm256_srli_epi16(_mm256_add_epi16(a, b), 1), tc);
      }
    }
    if constexpr (!kAlpha) {
      d0[3] = d3[3] = d5[3] = d8[3] = d4[3] = zero;
    } else {
      clear = _mm256_or_si256(clear, _mm256_cmpgt_epi16(_mm256_set1_epi16(128), tv[3]));
    }
    __m256i e0[2], e3[2], e5[2], e8[2];
    sq4(d0[0], d0[1], d0[2], d0[3], e0[0], e0[1]);
    sq4(d3[0], d3[1], d3[2], d3[3], e3[0], e3[1]);
    sq4(d5[0], d5[1], d5[2], d5[3], e5[0], e5[1]);
    sq4(d8[0], d8[1], d8[2], d8[3], e8[0], e8[1]);
    __m256i e4[2], e4p[2];
    if constexpr (kExtra) {
      sq4(d4[0], d4[1], d4[2], d4[3], e4[0], e4[1]);
      if constexpr (kAlpha) {
        // Punch-through: alpha decodes to 0, so its error is the target alpha squared.
        sq4(d4[0], d4[1], d4[2], tv[3], e4p[0], e4p[1]);
      } else {
        e4p[0] = e4[0];
        e4p[1] = e4[1];
      }
    }
    const __m128i row_shift = _mm_cvtsi32_si128(8 * j);
    for (int h = 0; h < 2; ++h) {
      // Mode 0: codes 0..3 are weights 0, 3, 5, 8.
      __m256i k = _mm256_slli_epi32(e0[h], 2);
      k = _mm256_min_epi32(k, key(e3[h], 1));
      k = _mm256_min_epi32(k, key(e5[h], 2));
      k = _mm256_min_epi32(k, key(e8[h], 3));
      err0[h] = _mm256_add_epi32(err0[h], _mm256_srli_epi32(k, 2));
      bits0[h] = _mm256_or_si256(bits0[h], _mm256_sll_epi32(_mm256_and_si256(k, three), row_shift));
      if constexpr (kExtra) {
        // Mode 1 ranks 0, 1, 2, 3 = codes 0 (weight 0), 1 (4), 3 (8), 2 (4, punch-through):
        // code = rank ^ (rank >> 1).
        __m256i k1 = _mm256_slli_epi32(e0[h], 2);
        k1 = _mm256_min_epi32(k1, key(e4[h], 1));
        k1 = _mm256_min_epi32(k1, key(e8[h], 2));
        const __m256i k1p = _mm256_min_epi32(k1, key(e4p[h], 3));
        const __m256i r1 = _mm256_and_si256(k1, three), r1p = _mm256_and_si256(k1p, three);
        err1[h] = _mm256_add_epi32(err1[h], _mm256_srli_epi32(k1, 2));
        bits1[h] = _mm256_or_si256(
            bits1[h], _mm256_sll_epi32(_mm256_xor_si256(r1, _mm256_srli_epi32(r1, 1)), row_shift));
        err1p[h] = _mm256_add_epi32(err1p[h], _mm256_srli_epi32(k1p, 2));
        bits1p[h] = _mm256_or_si256(
            bits1p[h],
            _mm256_sll_epi32(_mm256_xor_si256(r1p, _mm256_srli_epi32(r1p, 1)), row_shift));
      }
    }
  }
  // Per block: the sum of its 4 column errors and its 4 column codes (byte j: row j) at bit
  // 2 * column, as `modk::finish`. The column codes do not overlap, so OR = add: two
  // horizontal adds give lanes (err B0, err B1, bits B0, bits B1 | the same for B2, B3).
  const __m256i col_shift = _mm256_setr_epi32(0, 2, 4, 6, 0, 2, 4, 6);
  auto fold = [&](const __m256i e[2], const __m256i b[2], std::uint32_t r[8]) {
    const __m256i es = _mm256_hadd_epi32(e[0], e[1]);
    const __m256i bs =
        _mm256_hadd_epi32(_mm256_sllv_epi32(b[0], col_shift), _mm256_sllv_epi32(b[1], col_shift));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(r), _mm256_hadd_epi32(es, bs));
  };
  std::uint32_t r0[8], r1[8] = {}, r1p[8] = {};
  fold(err0, bits0, r0);
  if constexpr (kExtra) {
    fold(err1, bits1, r1);
    fold(err1p, bits1p, r1p);
  }
  const std::uint32_t clear_bytes = std::uint32_t(_mm256_movemask_epi8(clear));
  for (int q = 0; q < 4; ++q) {
    const int e = (q >> 1) * 4 + (q & 1), b = e + 2;
    out[q].bits0 = r0[b];
    out[q].err0 = r0[e];
    out[q].bits1 = r1[b];
    out[q].err1 = r1[e];
    out[q].bits1p = r1p[b];
    out[q].err1p = r1p[e];
    out[q].any_clear = (clear_bytes >> (8 * q)) & 0xffu ? 1u : 0u;  // texels 4q .. 4q + 3
  }
}

template <bool kAlpha, bool kExtra>
void block_row(const std::uint16_t* const v[4], const std::uint8_t* const t[4], std::size_t vstride,
               int nbx, BlockModAvx2* out) {
  int bx = 0;
  for (; bx + 4 <= nbx; bx += 4) {
    const std::uint8_t* tq[4];
    for (int j = 0; j < 4; ++j) tq[j] = t[j] + std::size_t(bx) * 16;
    block_quad_errors<kAlpha, kExtra>(v, tq, vstride, bx, out + bx);
  }
  if (bx < nbx) {
    // 1-3 blocks left (textures 8 texels wide): their texels copied into a full step, the
    // rest zero; the taps read elements bx .. bx + 7 < vstride.
    const int n = nbx - bx;
    alignas(32) std::uint8_t buf[4][64] = {};
    const std::uint8_t* tq[4];
    for (int j = 0; j < 4; ++j) {
      std::memcpy(buf[j], t[j] + std::size_t(bx) * 16, std::size_t(n) * 16);
      tq[j] = buf[j];
    }
    BlockModAvx2 quad[4];
    block_quad_errors<kAlpha, kExtra>(v, tq, vstride, bx, quad);
    for (int q = 0; q < n; ++q) out[bx + q] = quad[q];
  }
}

}  // namespace

void block_row_errors_avx2(const std::uint16_t* const v[4], const std::uint8_t* const t[4],
                           std::size_t vstride, int nbx, bool alpha, bool extra,
                           BlockModAvx2* out) {
  if (alpha) {
    extra ? block_row<true, true>(v, t, vstride, nbx, out)
          : block_row<true, false>(v, t, vstride, nbx, out);
  } else {
    extra ? block_row<false, true>(v, t, vstride, nbx, out)
          : block_row<false, false>(v, t, vstride, nbx, out);
  }
}

}  // namespace tessera::pvrtc::detail

#else  // no AVX2 kernels in this build: modulation_avx2_supported() is false

namespace tessera::pvrtc::detail {

void block_row_errors_avx2(const std::uint16_t* const*, const std::uint8_t* const*, std::size_t,
                           int, bool, bool, BlockModAvx2*) {}

}  // namespace tessera::pvrtc::detail

#endif
