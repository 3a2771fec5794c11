// modulation_kernel.h — the 4 bpp brute-force modulation kernel for two horizontally adjacent
// blocks (8 texels a row, 4 rows), planar 16-bit SIMD through simd.h.
//
// The upscaled endpoint images are formed on the fly from per-row column sums (the bilinear sum
// of a texel is linear between block centres, exactly as `upscale_rows`), every blend of both
// modes is scored per texel with the exact decoder arithmetic, and the best code per texel is the
// minimum of (error * 4 + rank): ties keep the earlier candidate, as a scalar first-minimum scan.
#pragma once

#include <cstdint>

#include "core/simd.h"
#include "pvrtc/encode/colour_scale_kernel.h"
#include "pvrtc/format/pvrtc_kernel.h"

namespace tessera::pvrtc::detail {

/// Inputs of one block row: for each of its 4 texel rows, the column sums of the endpoint
/// images (`v[row]`: 8 planes, image * 4 + channel, `vstride` apart; element bx + 1 holds block
/// bx, element 0 the last block and element nbx + 1 the first: wrap-around) and the target row.
struct ModRow4 {
  const std::uint16_t* v[4] = {};
  const std::uint8_t* t[4] = {};
  /// Alpha-weighted colour error only: each texel row's colour scales (one byte a texel, 0..16,
  /// `EncoderState::colour_scale`).
  const std::uint8_t* w[4] = {};
  std::size_t vstride = 0;
};

/// Best modulation of one block: mode 0, mode 1 without and with punch-through.
struct BlockMod {
  std::uint32_t bits0 = 0, err0 = 0, bits1 = 0, err1 = 0, bits1p = 0, err1p = 0;
  bool any_clear = false;  ///< Some target alpha < 128 (alpha mode only).
};

namespace modk {

using simd::vint4;
using simd::vu16x8;

/// Sum of squares of (dr, dg, db, da) for texels 0-3 (lo) and 4-7 (hi).
inline void sq4(vu16x8 dr, vu16x8 dg, vu16x8 db, vu16x8 da, vint4& lo, vint4& hi) {
  const vu16x8 rg0 = simd::zip_lo(dr, dg), rg1 = simd::zip_hi(dr, dg);
  const vu16x8 ba0 = simd::zip_lo(db, da), ba1 = simd::zip_hi(db, da);
  lo = simd::madd(rg0, rg0) + simd::madd(ba0, ba0);
  hi = simd::madd(rg1, rg1) + simd::madd(ba1, ba1);
}

/// Running per-block results over the 4 rows (lanes = the block's 4 columns).
struct Acc {
  vint4 err0, bits0, err1, bits1, err1p, bits1p;
};

inline void finish(const Acc& a, bool extra, BlockMod& m) {
  std::int32_t l[6][4];
  simd::store4(a.err0, l[0]);
  simd::store4(a.bits0, l[1]);
  if (extra) {
    simd::store4(a.err1, l[2]);
    simd::store4(a.bits1, l[3]);
    simd::store4(a.err1p, l[4]);
    simd::store4(a.bits1p, l[5]);
  }
  auto bits = [](const std::int32_t* b) {
    return std::uint32_t(b[0]) | (std::uint32_t(b[1]) << 2) | (std::uint32_t(b[2]) << 4) |
           (std::uint32_t(b[3]) << 6);
  };
  auto sum = [](const std::int32_t* e) { return std::uint32_t(e[0] + e[1] + e[2] + e[3]); };
  m.err0 = sum(l[0]);
  m.bits0 = bits(l[1]);
  if (extra) {
    m.err1 = sum(l[2]);
    m.bits1 = bits(l[3]);
    m.err1p = sum(l[4]);
    m.bits1p = bits(l[5]);
  }
}

}  // namespace modk

/// Scores blocks bx and bx + 1 of a block row. kAlpha: alpha is a fourth channel (and the
/// punch-through blend is scored); kExtra: also mode 1 (weights 0, 4, 8) and punch-through;
/// kWeighted (with kAlpha only): every colour difference is scaled by its texel's colour scale
/// (`scale_diff16`, magnitudes never grow, so the u16 / madd ranges below still hold).
template <bool kAlpha, bool kExtra, bool kWeighted = false>
inline void block_pair_errors(const ModRow4& r, int bx, BlockMod out[2]) {
  using namespace modk;
  constexpr int nch = kAlpha ? 4 : 3;
  const vint4 three(3);
  const vu16x8 w_left = simd::narrow16(vint4(2, 1, 4, 3), vint4(2, 1, 4, 3));
  const vu16x8 w_right = simd::narrow16(vint4(2, 3, 0, 1), vint4(2, 3, 0, 1));
  const vu16x8 k3(3), k5(5), zero(0);
  Acc acc[2];
  bool clear[2] = {false, false};
  for (int j = 0; j < 4; ++j) {
    const std::uint8_t* tp = r.t[j] + std::size_t(bx) * 16;
    const vint4 t0 = simd::load_texels4(tp), t1 = simd::load_texels4(tp + 16);
    static_assert(kAlpha || !kWeighted);
    vu16x8 scale;
    if constexpr (kWeighted) scale = simd::load_u8x8(r.w[j] + std::size_t(bx) * 4);
    vu16x8 d0[4], d3[4], d5[4], d8[4], d4[4], tv[4];
    for (int c = 0; c < nch; ++c) {
      const vu16x8 t = simd::channel16(t0, t1, c);
      tv[c] = t;
      vu16x8 up[2];
      for (int img = 0; img < 2; ++img) {
        vu16x8 L, R;
        simd::taps8(r.v[j] + std::size_t(img * 4 + c) * r.vstride + bx, L, R);
        const vu16x8 w = simd::mullo(L, w_left) + simd::mullo(R, w_right);
        up[img] = c < 3 ? simd::srl<6>(w) + simd::srl<1>(w) : simd::srl<4>(w) + w;
      }
      const vu16x8 a = up[0], b = up[1];
      d0[c] = a - t;
      d8[c] = b - t;
      d3[c] = simd::srl<3>(simd::mullo(a, k5) + simd::mullo(b, k3)) - t;
      d5[c] = simd::srl<3>(simd::mullo(a, k3) + simd::mullo(b, k5)) - t;
      if constexpr (kExtra) d4[c] = simd::srl<1>(a + b) - t;
      if constexpr (kWeighted) {
        if (c < 3) {
          d0[c] = scale_diff16(d0[c], scale);
          d8[c] = scale_diff16(d8[c], scale);
          d3[c] = scale_diff16(d3[c], scale);
          d5[c] = scale_diff16(d5[c], scale);
          if constexpr (kExtra) d4[c] = scale_diff16(d4[c], scale);
        }
      }
    }
    if constexpr (!kAlpha) {
      d0[3] = d3[3] = d5[3] = d8[3] = d4[3] = zero;
    } else {
      clear[0] |= ((tp[3] & tp[7] & tp[11] & tp[15]) & 0x80) == 0;
      clear[1] |= ((tp[19] & tp[23] & tp[27] & tp[31]) & 0x80) == 0;
    }
    vint4 e0[2], e3[2], e5[2], e8[2];
    sq4(d0[0], d0[1], d0[2], d0[3], e0[0], e0[1]);
    sq4(d3[0], d3[1], d3[2], d3[3], e3[0], e3[1]);
    sq4(d5[0], d5[1], d5[2], d5[3], e5[0], e5[1]);
    sq4(d8[0], d8[1], d8[2], d8[3], e8[0], e8[1]);
    vint4 e4[2], e4p[2];
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
      vint4 k = simd::sll<2>(e0[h]);
      k = simd::min(k, simd::sll<2>(e3[h]) | vint4(1));
      k = simd::min(k, simd::sll<2>(e5[h]) | vint4(2));
      k = simd::min(k, simd::sll<2>(e8[h]) | vint4(3));
      acc[h].err0 += simd::srl<2>(k);
      acc[h].bits0 = acc[h].bits0 | simd::sll_bytes(k & three, j);
      if constexpr (kExtra) {
        // Mode 1 ranks 0, 1, 2, 3 = codes 0 (weight 0), 1 (4), 3 (8), 2 (4, punch-through):
        // code = rank ^ (rank >> 1).
        vint4 k1 = simd::sll<2>(e0[h]);
        k1 = simd::min(k1, simd::sll<2>(e4[h]) | vint4(1));
        k1 = simd::min(k1, simd::sll<2>(e8[h]) | vint4(2));
        const vint4 k1p = simd::min(k1, simd::sll<2>(e4p[h]) | vint4(3));
        const vint4 r1 = k1 & three, r1p = k1p & three;
        acc[h].err1 += simd::srl<2>(k1);
        acc[h].bits1 = acc[h].bits1 | simd::sll_bytes(r1 ^ simd::srl<1>(r1), j);
        acc[h].err1p += simd::srl<2>(k1p);
        acc[h].bits1p = acc[h].bits1p | simd::sll_bytes(r1p ^ simd::srl<1>(r1p), j);
      }
    }
  }
  for (int h = 0; h < 2; ++h) {
    finish(acc[h], kExtra, out[h]);
    out[h].any_clear = clear[h];
  }
}

}  // namespace tessera::pvrtc::detail
