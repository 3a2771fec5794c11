// modulation_blends.h — the 4 bpp brute-force modulation kernel, written once over the SIMD
// wrapper's 16-bit lane types: one step scores the 4 texel rows of kLanes<V> / 4 horizontally
// adjacent blocks, compiled with vu16x8 (two blocks, 8 texels a row) in the baseline kernel
// (modulation_kernel.h) and with vu16x16 (four blocks, 16 texels) in modulation_avx2.cpp, as is
// the fold of a step's accumulators into per-block results (`mod_block_results`); the drivers
// only find each block's "some alpha below 128" their own way.
//
// The upscaled endpoint images are formed on the fly from per-row column sums (the bilinear sum
// of a texel is linear between block centres, exactly as `upscale_rows`), every blend of both
// modes is scored per texel with the exact decoder arithmetic, and the best code per texel is
// the minimum of (error * 4 + rank): ties keep the earlier candidate, as a scalar first-minimum
// scan. With alpha-weighted colour error (kWeighted) every colour difference is first scaled by
// its texel's colour scale (`scale_diff16`; magnitudes never grow, so the u16 / madd ranges
// still hold).
//
// Included by the -mavx2 translation unit: everything here is a template in an anonymous
// namespace (internal linkage), so no AVX2-compiled copy can stand in for a baseline one.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/simd.h"
#include "pvrtc/encode/colour_scale_kernel.h"

namespace tessera::pvrtc::detail {
namespace {

/// Running per-column results over a step's 4 rows (32-bit lanes, VI = decltype(madd(V, V))):
/// `lo` the columns of texels 0-3 of each 8-texel group (blocks 0, 2), `hi` those of texels
/// 4-7 (blocks 1, 3). err*: summed errors; bits*: the code of row j in byte j.
template <class VI>
struct ModAcc {
  VI err0, bits0, err1, bits1, err1p, bits1p;
};

/// Bilinear taps of a step's texels from the column sums p[0 ..] (block bx + b at p[b + 1]):
/// left = (p0 p0 p1 p1 p1 p1 p2 p2 | p2 p2 p3 p3 p3 p3 p4 p4) and right = the same indices + 1,
/// as many lanes as V has. The 4-lane form reads p[0..3], the 8-lane one p[0..7].
[[maybe_unused]] inline void mod_taps(const std::uint16_t* p, simd::vu16x8& left,
                                      simd::vu16x8& right) {
  simd::taps8(p, left, right);
}
[[maybe_unused]] inline void mod_taps(const std::uint16_t* p, simd::vu16x16& left,
                                      simd::vu16x16& right) {
  using u16 = std::uint16_t;
  // Byte pairs 2k, 2k + 1 of p[0..7] in both halves.
  alignas(32) static constexpr u16 kLeft[16] = {0x100, 0x100, 0x302, 0x302, 0x302, 0x302,
                                                0x504, 0x504, 0x504, 0x504, 0x706, 0x706,
                                                0x706, 0x706, 0x908, 0x908};
  alignas(32) static constexpr u16 kRight[16] = {0x302, 0x302, 0x504, 0x504, 0x504, 0x504,
                                                 0x706, 0x706, 0x706, 0x706, 0x908, 0x908,
                                                 0x908, 0x908, 0xb0a, 0xb0a};
  const simd::vu16x8 x8 = simd::load_u16x8(p);
  const simd::vu16x16 x(x8, x8);
  left = simd::shuffle_bytes(x, simd::load_u16x16(kLeft));
  right = simd::shuffle_bytes(x, simd::load_u16x16(kRight));
}

/// The step's colour scales (one byte a texel) as 16-bit lanes.
[[maybe_unused]] inline void mod_load_scales(const std::uint8_t* p, simd::vu16x8& out) {
  out = simd::load_u8x8(p);
}
[[maybe_unused]] inline void mod_load_scales(const std::uint8_t* p, simd::vu16x16& out) {
  out = simd::load_u8x16_u16(p);
}

/// Sum of squares of (dr, dg, db, da) per texel: texels 0-3 (lo) and 4-7 (hi) of each 8-lane
/// group.
template <class V, class VI>
inline void mod_sq4(V dr, V dg, V db, V da, VI& lo, VI& hi) {
  const V rg0 = simd::zip_lo(dr, dg), rg1 = simd::zip_hi(dr, dg);
  const V ba0 = simd::zip_lo(db, da), ba1 = simd::zip_hi(db, da);
  lo = simd::madd(rg0, rg0) + simd::madd(ba0, ba0);
  hi = simd::madd(rg1, rg1) + simd::madd(ba1, ba1);
}

/// The candidate's key: error * 4 + rank (the minimum keeps the earliest of equal errors).
template <class VI>
inline VI mod_key(VI e, int rank) {
  return simd::sll<2>(e) | VI(rank);
}

/// Scores one step: texel rows j = 0..3 of the blocks from bx on. `v[j]`: the column-sum planes
/// of row j (8 planes, image * 4 + channel, `vstride` apart; element bx + 1 holds block bx),
/// `t[j]`: the step's first target texel of row j, `w[j]` (kWeighted only): its colour scale.
/// kAlpha: alpha is a fourth channel (and the punch-through blend is scored); kExtra: also
/// mode 1 (weights 0, 4, 8) and punch-through. Fills acc; with kAlpha, `clear` is all ones in
/// the lanes of texels whose target alpha is below 128 in some row.
template <bool kAlpha, bool kExtra, bool kWeighted, class V, class VI>
inline void mod_step(const std::uint16_t* const v[4], const std::uint8_t* const t[4],
                     const std::uint8_t* const w[4], std::size_t vstride, int bx, ModAcc<VI> acc[2],
                     V& clear) {
  static_assert(kAlpha || !kWeighted);
  constexpr int nch = kAlpha ? 4 : 3;
  alignas(32) static constexpr std::uint16_t kWLeft[16] = {2, 1, 4, 3, 2, 1, 4, 3,
                                                           2, 1, 4, 3, 2, 1, 4, 3};
  alignas(32) static constexpr std::uint16_t kWRight[16] = {2, 3, 0, 1, 2, 3, 0, 1,
                                                            2, 3, 0, 1, 2, 3, 0, 1};
  const V w_left = simd::load_as<V>(kWLeft), w_right = simd::load_as<V>(kWRight);
  const V k3(std::uint16_t{3}), k5(std::uint16_t{5}), k128(std::uint16_t{128});
  const VI three(3);
  acc[0] = acc[1] = ModAcc<VI>{};
  clear = V();
  for (int j = 0; j < 4; ++j) {
    V tv[4];
    simd::load_texel_planes<nch>(t[j], tv);
    V scale;
    if constexpr (kWeighted) mod_load_scales(w[j], scale);
    V d0[4], d3[4], d5[4], d8[4], d4[4];
    for (int c = 0; c < nch; ++c) {
      V up[2];
      for (int img = 0; img < 2; ++img) {
        V L, R;
        mod_taps(v[j] + std::size_t(img * 4 + c) * vstride + std::size_t(bx), L, R);
        const V s = simd::mullo(L, w_left) + simd::mullo(R, w_right);
        up[img] = c < 3 ? simd::srl<6>(s) + simd::srl<1>(s) : simd::srl<4>(s) + s;
      }
      const V a = up[0], b = up[1], tc = tv[c];
      d0[c] = a - tc;
      d8[c] = b - tc;
      d3[c] = simd::srl<3>(simd::mullo(a, k5) + simd::mullo(b, k3)) - tc;
      d5[c] = simd::srl<3>(simd::mullo(a, k3) + simd::mullo(b, k5)) - tc;
      if constexpr (kExtra) d4[c] = simd::srl<1>(a + b) - tc;
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
      d0[3] = d3[3] = d5[3] = d8[3] = d4[3] = V();
    } else {
      clear = clear | simd::cmpgt_s16(k128, tv[3]);
    }
    VI e0[2], e3[2], e5[2], e8[2];
    mod_sq4(d0[0], d0[1], d0[2], d0[3], e0[0], e0[1]);
    mod_sq4(d3[0], d3[1], d3[2], d3[3], e3[0], e3[1]);
    mod_sq4(d5[0], d5[1], d5[2], d5[3], e5[0], e5[1]);
    mod_sq4(d8[0], d8[1], d8[2], d8[3], e8[0], e8[1]);
    VI e4[2], e4p[2];
    if constexpr (kExtra) {
      mod_sq4(d4[0], d4[1], d4[2], d4[3], e4[0], e4[1]);
      if constexpr (kAlpha) {
        // Punch-through: alpha decodes to 0, so its error is the target alpha squared.
        mod_sq4(d4[0], d4[1], d4[2], tv[3], e4p[0], e4p[1]);
      } else {
        e4p[0] = e4[0];
        e4p[1] = e4[1];
      }
    }
    for (int h = 0; h < 2; ++h) {
      // Mode 0: codes 0..3 are weights 0, 3, 5, 8.
      VI k = simd::sll<2>(e0[h]);
      k = simd::min(k, mod_key(e3[h], 1));
      k = simd::min(k, mod_key(e5[h], 2));
      k = simd::min(k, mod_key(e8[h], 3));
      acc[h].err0 += simd::srl<2>(k);
      acc[h].bits0 = acc[h].bits0 | simd::sll_bytes(k & three, j);
      if constexpr (kExtra) {
        // Mode 1 ranks 0, 1, 2, 3 = codes 0 (weight 0), 1 (4), 3 (8), 2 (4, punch-through):
        // code = rank ^ (rank >> 1).
        VI k1 = simd::sll<2>(e0[h]);
        k1 = simd::min(k1, mod_key(e4[h], 1));
        k1 = simd::min(k1, mod_key(e8[h], 2));
        const VI k1p = simd::min(k1, mod_key(e4p[h], 3));
        const VI r1 = k1 & three, r1p = k1p & three;
        acc[h].err1 += simd::srl<2>(k1);
        acc[h].bits1 = acc[h].bits1 | simd::sll_bytes(r1 ^ simd::srl<1>(r1), j);
        acc[h].err1p += simd::srl<2>(k1p);
        acc[h].bits1p = acc[h].bits1p | simd::sll_bytes(r1p ^ simd::srl<1>(r1p), j);
      }
    }
  }
}

/// The column codes of a step's blocks (32-bit lanes, one a column: the code of row j in byte j)
/// moved to bit 2 * column within each block's 4 lanes: a multiply on 4 lanes (SSE2 has no
/// per-lane shift; the lanes wrap, as the sums after), a per-lane shift on 8.
[[maybe_unused]] inline simd::vi32x4 mod_column_bits(simd::vi32x4 b) {
  return b * simd::vi32x4(1, 4, 16, 64);
}
[[maybe_unused]] inline simd::vi32x8 mod_column_bits(simd::vi32x8 b) {
  const simd::vi32x4 s(0, 2, 4, 6);
  return simd::sllv(b, simd::vi32x8(s, s));
}

/// The step's per-block results from its accumulators into out[0 .. kLanes<VI> / 2) (the
/// blocks from left to right; BlockMod or BlockModAvx2, any_clear not set): per block the sum
/// of its 4 column errors and its 4 column codes at bit 2 * column (the codes do not overlap,
/// so the sum is their OR). Two pair sums per 128-bit half give lanes (err P, err Q, bits P,
/// bits Q) for that half's blocks P (acc[0]) and Q (acc[1]): blocks 0, 1 in the low half, and
/// on 8 lanes 2, 3 in the high one, so block q's error is in lane 4 (q / 2) + q % 2 and its
/// bits two lanes on.
template <bool kExtra, class VI, class M>
inline void mod_block_results(const ModAcc<VI> acc[2], M* out) {
  constexpr int kN = simd::kLanes<VI>;
  auto fold = [](VI e0, VI e1, VI b0, VI b1, std::uint32_t r[kN]) {
    const VI es = simd::pair_sums(e0, e1);
    const VI bs = simd::pair_sums(mod_column_bits(b0), mod_column_bits(b1));
    simd::store(simd::pair_sums(es, bs), reinterpret_cast<std::int32_t*>(r));
  };
  alignas(32) std::uint32_t r0[kN], r1[kN] = {}, r1p[kN] = {};
  fold(acc[0].err0, acc[1].err0, acc[0].bits0, acc[1].bits0, r0);
  if constexpr (kExtra) {
    fold(acc[0].err1, acc[1].err1, acc[0].bits1, acc[1].bits1, r1);
    fold(acc[0].err1p, acc[1].err1p, acc[0].bits1p, acc[1].bits1p, r1p);
  }
  for (int q = 0; q < kN / 2; ++q) {
    const int e = (q >> 1) * 4 + (q & 1), b = e + 2;
    out[q].bits0 = r0[b];
    out[q].err0 = r0[e];
    out[q].bits1 = r1[b];
    out[q].err1 = r1[e];
    out[q].bits1p = r1p[b];
    out[q].err1p = r1p[e];
  }
}

}  // namespace
}  // namespace tessera::pvrtc::detail
