// modulation_avx2.cpp — the 4 bpp brute-force modulation kernel of modulation_kernel.h over the
// SIMD wrapper's 8-lane types (core/simd_wide.h): four blocks (16 texels a row) a step instead
// of two, the same operations lane for lane, so the same bits and errors (ties to the earlier
// candidate included).
//
// Compiled with -mavx2 (src/CMakeLists.txt), which gives the wrapper its AVX2 backend, and
// called only after the run-time CPU check in modulation.cpp. So that no AVX2 code can stand
// in for baseline code elsewhere, the wrapper's functions compiled here live in their own
// inline namespace (simd_int.h); otherwise this file includes no header with inline functions
// or templates of external linkage (not modulation_kernel.h or the standard containers) and
// keeps its helpers in an anonymous namespace; it exports `block_row_errors_avx2` only.
#include "pvrtc/encode/modulation/modulation_avx2.h"

#if defined(TESSERA_HAVE_AVX2_KERNELS) && !defined(__AVX2__)
#error "modulation_avx2.cpp must be compiled with -mavx2 where TESSERA_HAVE_AVX2_KERNELS is set"
#endif

#if defined(__AVX2__)

#include <cstring>

#include "core/simd.h"

namespace tessera::pvrtc::detail {

namespace {

using namespace simd;
using u16 = std::uint16_t;

/// Lanes: 16-bit values of texels 0-7 (low half) and 8-15 (high); the 32-bit sums that come
/// from them hold texels 0-3 and 8-11 (`lo`: blocks 0 and 2) or 4-7 and 12-15 (`hi`: blocks 1
/// and 3).

/// Sum of squares of (dr, dg, db, da) per texel.
inline void sq4(vu16x16 dr, vu16x16 dg, vu16x16 db, vu16x16 da, vint8& lo, vint8& hi) {
  const vu16x16 rg0 = zip_lo(dr, dg), rg1 = zip_hi(dr, dg);
  const vu16x16 ba0 = zip_lo(db, da), ba1 = zip_hi(db, da);
  lo = madd(rg0, rg0) + madd(ba0, ba0);
  hi = madd(rg1, rg1) + madd(ba1, ba1);
}

/// ((a * ka + b * kb) >> 3) - t, 16-bit lanes: the decoder's blend of weights kb / 8.
inline vu16x16 blend8(vu16x16 a, vu16x16 b, vu16x16 ka, vu16x16 kb, vu16x16 t) {
  return srl<3>(mullo(a, ka) + mullo(b, kb)) - t;
}

/// The candidate's key: error * 4 + rank (the minimum keeps the earliest of equal errors).
inline vint8 key(vint8 e, int rank) { return sll<2>(e) | vint8(rank); }

/// Scores blocks bx .. bx + 3 (texel rows from `t`, 64 bytes each) into out[0..3].
template <bool kAlpha, bool kExtra>
inline void block_quad_errors(const std::uint16_t* const v[4], const std::uint8_t* const t[4],
                              std::size_t vstride, int bx, BlockModAvx2 out[4]) {
  constexpr int nch = kAlpha ? 4 : 3;
  // Bilinear taps (as simd::taps8, once per half): from p[0..5], left = p0 p0 p1 p1 p1 p1 p2
  // p2 | p2 p2 p3 p3 p3 p3 p4 p4 and right = the same indices + 1, as byte shuffles (byte
  // pairs 2k, 2k + 1 of p[0..7] in both halves).
  static constexpr u16 kTapLeft[16] = {0x100, 0x100, 0x302, 0x302, 0x302, 0x302, 0x504, 0x504,
                                       0x504, 0x504, 0x706, 0x706, 0x706, 0x706, 0x908, 0x908};
  static constexpr u16 kTapRight[16] = {0x302, 0x302, 0x504, 0x504, 0x504, 0x504, 0x706, 0x706,
                                        0x706, 0x706, 0x908, 0x908, 0x908, 0x908, 0xb0a, 0xb0a};
  static constexpr u16 kWLeft[16] = {2, 1, 4, 3, 2, 1, 4, 3, 2, 1, 4, 3, 2, 1, 4, 3};
  static constexpr u16 kWRight[16] = {2, 3, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1};
  const vu16x16 tap_left = load_u16x16(kTapLeft), tap_right = load_u16x16(kTapRight);
  const vu16x16 w_left = load_u16x16(kWLeft), w_right = load_u16x16(kWRight);
  const vu16x16 k3(u16{3}), k5(u16{5}), k128(u16{128}), zero;
  const vint8 three(3);
  vint8 err0[2], bits0[2], err1[2], bits1[2], err1p[2], bits1p[2];
  vu16x16 clear;  // all ones where some row's target alpha < 128
  for (int j = 0; j < 4; ++j) {
    vu16x16 tv[4];
    load_planes(t[j], tv);
    vu16x16 d0[4], d3[4], d5[4], d8[4], d4[4];
    for (int c = 0; c < nch; ++c) {
      vu16x16 up[2];
      for (int img = 0; img < 2; ++img) {
        const vu16x8 p = load_u16x8(v[j] + std::size_t(img * 4 + c) * vstride + std::size_t(bx));
        const vu16x16 x(p, p);
        const vu16x16 w = mullo(shuffle_bytes(x, tap_left), w_left) +
                          mullo(shuffle_bytes(x, tap_right), w_right);
        up[img] = c < 3 ? srl<6>(w) + srl<1>(w) : srl<4>(w) + w;
      }
      const vu16x16 a = up[0], b = up[1], tc = tv[c];
      d0[c] = a - tc;
      d8[c] = b - tc;
      d3[c] = blend8(a, b, k5, k3, tc);
      d5[c] = blend8(a, b, k3, k5, tc);
      if constexpr (kExtra) d4[c] = srl<1>(a + b) - tc;
    }
    if constexpr (!kAlpha) {
      d0[3] = d3[3] = d5[3] = d8[3] = d4[3] = zero;
    } else {
      clear = clear | cmpgt_s16(k128, tv[3]);
    }
    vint8 e0[2], e3[2], e5[2], e8[2];
    sq4(d0[0], d0[1], d0[2], d0[3], e0[0], e0[1]);
    sq4(d3[0], d3[1], d3[2], d3[3], e3[0], e3[1]);
    sq4(d5[0], d5[1], d5[2], d5[3], e5[0], e5[1]);
    sq4(d8[0], d8[1], d8[2], d8[3], e8[0], e8[1]);
    vint8 e4[2], e4p[2];
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
    for (int h = 0; h < 2; ++h) {
      // Mode 0: codes 0..3 are weights 0, 3, 5, 8.
      vint8 k = sll<2>(e0[h]);
      k = min(k, key(e3[h], 1));
      k = min(k, key(e5[h], 2));
      k = min(k, key(e8[h], 3));
      err0[h] += srl<2>(k);
      bits0[h] = bits0[h] | sll_bytes(k & three, j);
      if constexpr (kExtra) {
        // Mode 1 ranks 0, 1, 2, 3 = codes 0 (weight 0), 1 (4), 3 (8), 2 (4, punch-through):
        // code = rank ^ (rank >> 1).
        vint8 k1 = sll<2>(e0[h]);
        k1 = min(k1, key(e4[h], 1));
        k1 = min(k1, key(e8[h], 2));
        const vint8 k1p = min(k1, key(e4p[h], 3));
        const vint8 r1 = k1 & three, r1p = k1p & three;
        err1[h] += srl<2>(k1);
        bits1[h] = bits1[h] | sll_bytes(r1 ^ srl<1>(r1), j);
        err1p[h] += srl<2>(k1p);
        bits1p[h] = bits1p[h] | sll_bytes(r1p ^ srl<1>(r1p), j);
      }
    }
  }
  // Per block: the sum of its 4 column errors and its 4 column codes (byte j: row j) at bit
  // 2 * column, as `modk::finish`. The column codes do not overlap, so OR = add: two pair sums
  // (per half) give lanes (err B0, err B1, bits B0, bits B1 | the same for B2, B3).
  const vint8 col_shift(vint4(0, 2, 4, 6), vint4(0, 2, 4, 6));
  auto fold = [&](const vint8 e[2], const vint8 b[2], std::uint32_t r[8]) {
    const vint8 es = pair_sums(e[0], e[1]);
    const vint8 bs = pair_sums(sllv(b[0], col_shift), sllv(b[1], col_shift));
    store8(pair_sums(es, bs), reinterpret_cast<std::int32_t*>(r));
  };
  std::uint32_t r0[8], r1[8] = {}, r1p[8] = {};
  fold(err0, bits0, r0);
  if constexpr (kExtra) {
    fold(err1, bits1, r1);
    fold(err1p, bits1p, r1p);
  }
  const std::uint32_t clear_bytes = movemask_bytes(clear);
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
