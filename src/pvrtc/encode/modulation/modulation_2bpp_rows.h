// modulation_2bpp_rows.h — the per-block-row arithmetic of the three 2 bpp modulation passes
// (modulation_2bpp.cpp says what they compute), written once over the SIMD wrapper's 16-bit lane
// types: one step scores kLanes<V> / 8 horizontally adjacent blocks, compiled with vu16x8 (one
// block, 8 texels a row) in the baseline (modulation_2bpp.cpp) and with vu16x16 (two blocks, the
// first in the low half) in modulation_2bpp_avx2.cpp. Same operations lane for lane, and the
// 8-lane operations used here work per half, so the halves never mix until the per-block sums:
// the same maps, bits, modes and errors (ties included) whichever width runs. What differs with
// the lane count (constant patterns, tap and target loads, map stores, per-block sums and
// halves) is a small overload on the vector type.
//
// Included by the -mavx2 translation unit: everything here is a template, a class or an inline
// function in an anonymous namespace (internal linkage), so no AVX2-compiled copy can stand in
// for a baseline one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

#include "core/simd.h"
#include "pvrtc/encode/modulation/modulation_2bpp_avx2.h"

namespace tessera::pvrtc::detail {
namespace {

// ---- what differs with the lane count ----

/// The 8-lane pattern `l` in every block's 8 lanes.
template <class V>
V mod2_pattern(const std::uint16_t l[8]);
template <>
[[maybe_unused]] inline simd::vu16x8 mod2_pattern<simd::vu16x8>(const std::uint16_t l[8]) {
  return simd::load_u16x8(l);
}
template <>
[[maybe_unused]] inline simd::vu16x16 mod2_pattern<simd::vu16x16>(const std::uint16_t l[8]) {
  const simd::vu16x8 x = simd::load_u16x8(l);
  return simd::vu16x16(x, x);
}

/// Left and right taps of the step's blocks from the column sums p[0 ..] (block bx + b at
/// p[b + 1]): per block b, left = p[b] x4 p[b + 1] x4, right = p[b + 1] x4 p[b + 2] x4.
[[maybe_unused]] inline void mod2_taps(const std::uint16_t* p, simd::vu16x8& left,
                                       simd::vu16x8& right) {
  const simd::vi32x4 p1(p[1]);
  left = simd::narrow16(simd::vi32x4(p[0]), p1);
  right = simd::narrow16(p1, simd::vi32x4(p[2]));
}
[[maybe_unused]] inline void mod2_taps(const std::uint16_t* p, simd::vu16x16& left,
                                       simd::vu16x16& right) {
  using u16 = std::uint16_t;
  // Byte pairs 2k, 2k + 1 of p[0..3] (in both halves).
  alignas(32) static constexpr u16 kLeft[16] = {0x100, 0x100, 0x100, 0x100, 0x302, 0x302,
                                                0x302, 0x302, 0x302, 0x302, 0x302, 0x302,
                                                0x504, 0x504, 0x504, 0x504};
  alignas(32) static constexpr u16 kRight[16] = {0x302, 0x302, 0x302, 0x302, 0x504, 0x504,
                                                 0x504, 0x504, 0x504, 0x504, 0x504, 0x504,
                                                 0x706, 0x706, 0x706, 0x706};
  std::uint64_t e;
  std::memcpy(&e, p, 8);
  const simd::vu16x16 q = simd::broadcast64(e);
  left = simd::shuffle_bytes(q, simd::load_u16x16(kLeft));
  right = simd::shuffle_bytes(q, simd::load_u16x16(kRight));
}

/// The lanes (each 0..255) as bytes, in order.
[[maybe_unused]] inline void mod2_store_bytes(simd::vu16x8 v, std::uint8_t* p) {
  simd::store_u8x8(v, p);
}
[[maybe_unused]] inline void mod2_store_bytes(simd::vu16x16 v, std::uint8_t* p) {
  simd::store_u8x16(v, p);
}

/// Block h of the step's lanes.
[[maybe_unused]] inline simd::vu16x8 mod2_block(simd::vu16x8 v, int) { return v; }
[[maybe_unused]] inline simd::vu16x8 mod2_block(simd::vu16x16 v, int h) {
  return h ? simd::high(v) : simd::low(v);
}

/// The lanes of block 0 from v0, those of block 1 from v1.
[[maybe_unused]] inline simd::vu16x8 mod2_blocks(simd::vu16x8 v0, simd::vu16x8) { return v0; }
[[maybe_unused]] inline simd::vu16x16 mod2_blocks(simd::vu16x16 v0, simd::vu16x16 v1) {
  return simd::vu16x16(simd::low(v0), simd::high(v1));
}

/// Per block, the sum of its four 32-bit lanes (wrapping).
[[maybe_unused]] inline void mod2_block_sums(simd::vi32x4 x, std::uint32_t* out) {
  std::int32_t l[4];
  simd::store4(x, l);
  out[0] = std::uint32_t(l[0]) + std::uint32_t(l[1]) + std::uint32_t(l[2]) + std::uint32_t(l[3]);
}
[[maybe_unused]] inline void mod2_block_sums(simd::vi32x8 x, std::uint32_t* out) {
  out[0] = std::uint32_t(simd::sum_lanes(simd::low(x)));
  out[1] = std::uint32_t(simd::sum_lanes(simd::high(x)));
}

// ---- the passes ----

/// Constants shared by the passes, the same in every block's 8 lanes.
template <class V>
struct Mod2Consts {
  V wl, wr;   // horizontal bilinear weights of the 8 texels (left / right taps)
  V even[2];  // lanes x with (x ^ row) even, by row parity
  V lanebit;  // 1, 2, 4, ..., 128
  V k1, k2, k3, k4, k5, k8;
  // Lanes of the neighbour vectors that refer to a restricted texel of the block itself, per
  // row: (0,0) for every variant, (4,2) too for H/V only. C: the row itself, L: the left
  // neighbours (x - 1), R: right, U: up (row - 1), D: down (row + 1).
  V c0[4], l0[4], u0[4], c12[4], l12[4], r12[4], u12[4], d12[4];

  /// Mask of up to two lanes (lane < 0: none).
  static V lanes(int lane0, int lane1 = -1) {
    std::uint16_t l[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    if (lane0 >= 0) l[lane0] = 0xffff;
    if (lane1 >= 0) l[lane1] = 0xffff;
    return mod2_pattern<V>(l);
  }

  Mod2Consts() {
    using u16 = std::uint16_t;
    const u16 wl8[8] = {4, 3, 2, 1, 8, 7, 6, 5}, wr8[8] = {4, 5, 6, 7, 0, 1, 2, 3};
    const u16 ev0[8] = {0xffff, 0, 0xffff, 0, 0xffff, 0, 0xffff, 0};
    const u16 ev1[8] = {0, 0xffff, 0, 0xffff, 0, 0xffff, 0, 0xffff};
    const u16 bit8[8] = {1, 2, 4, 8, 16, 32, 64, 128};
    wl = mod2_pattern<V>(wl8);
    wr = mod2_pattern<V>(wr8);
    even[0] = mod2_pattern<V>(ev0);
    even[1] = mod2_pattern<V>(ev1);
    lanebit = mod2_pattern<V>(bit8);
    k1 = V(u16{1});
    k2 = V(u16{2});
    k3 = V(u16{3});
    k4 = V(u16{4});
    k5 = V(u16{5});
    k8 = V(u16{8});
    for (int j = 0; j < 4; ++j) {
      c0[j] = lanes(j == 0 ? 0 : -1);
      l0[j] = lanes(j == 0 ? 1 : -1);
      u0[j] = lanes(j == 1 ? 0 : -1);
      c12[j] = lanes(j == 0 ? 0 : j == 2 ? 4 : -1);
      l12[j] = lanes(j == 0 ? 1 : j == 2 ? 5 : -1);
      r12[j] = lanes(j == 2 ? 3 : -1);
      u12[j] = lanes(j == 1 ? 0 : -1, j == 3 ? 4 : -1);
      d12[j] = lanes(j == 1 ? 4 : -1);
    }
  }
};

/// Squared error of (v[c] - t[c]) summed over the channels (alpha only when kAlpha): texels
/// 0-3 (lo) and 4-7 (hi) of each block.
template <bool kAlpha, class V, class VI>
inline void mod2_sq_err(const V v[4], const V t[4], VI& lo, VI& hi) {
  const V dr = v[0] - t[0], dg = v[1] - t[1], db = v[2] - t[2];
  V da;
  if constexpr (kAlpha) da = v[3] - t[3];
  const V rg0 = simd::zip_lo(dr, dg), rg1 = simd::zip_hi(dr, dg);
  const V ba0 = simd::zip_lo(db, da), ba1 = simd::zip_hi(db, da);
  lo = simd::madd(rg0, rg0) + simd::madd(ba0, ba0);
  hi = simd::madd(rg1, rg1) + simd::madd(ba1, ba1);
}

/// Error of the blend (a (8 - m) + b m) / 8 with per-lane weights m, texels 0-3 and 4-7 of each
/// block summed.
template <bool kAlpha, class V>
inline auto mod2_blend_err(const Mod2Consts<V>& k, const V a[4], const V b[4], const V t[4], V m) {
  constexpr int nch = kAlpha ? 4 : 3;
  const V im = k.k8 - m;
  V v[4];
  for (int c = 0; c < nch; ++c) v[c] = simd::srl<3>(simd::mullo(a[c], im) + simd::mullo(b[c], m));
  decltype(simd::madd(V(), V())) lo, hi;
  mod2_sq_err<kAlpha>(v, t, lo, hi);
  return lo + hi;
}

/// Map byte -> weight of its greedy code (0, 3, 5, 8) and of its A/B choice (0 or 8).
template <class V>
inline V mod2_greedy_weight(const Mod2Consts<V>& k, V bytes) {
  const V c = bytes & k.k3;
  return simd::mullo(c, k.k3) - simd::srl<1>(c);
}
template <class V>
inline V mod2_ab_weight(const Mod2Consts<V>& k, V bytes) {
  const V f = bytes & k.k4;
  return f + f;
}

/// Upscaled A (a) and B (b) and the target (t) of texel row j of the step's blocks from bx on.
/// The column sums are of 4 rows (weights 4 - d, d) and the taps weigh 8 (weights sum to 32):
/// the decoder's expansion of 5-bit colour / 4-bit alpha, as `upscale_rows`.
template <bool kAlpha, class V>
inline void mod2_load_row(const Mod2Consts<V>& k, const Mod2Row& r, int bx, int j, V a[4], V b[4],
                          V t[4]) {
  constexpr int nch = kAlpha ? 4 : 3;
  simd::load_texel_planes<nch>(r.t[j] + std::size_t(bx) * 32, t);
  for (int c = 0; c < nch; ++c) {
    for (int img = 0; img < 2; ++img) {
      V L, R;
      mod2_taps(r.v[j] + std::size_t(img * 4 + c) * r.vstride + std::size_t(bx), L, R);
      const V w = simd::mullo(L, k.wl) + simd::mullo(R, k.wr);
      (img == 0 ? a : b)[c] =
          c < 3 ? simd::srl<7>(w) + simd::srl<2>(w) : simd::srl<5>(w) + simd::srl<1>(w);
    }
  }
}

/// Pass 1 of one block row: greedy map rows (`out`), mode-0 bits (`mod`) and errors (`err0`).
template <bool kAlpha, class V>
void mod2_pass1(const Mod2Row& r) {
  using VI = decltype(simd::madd(V(), V()));
  constexpr int nb = simd::kLanes<V> / 8;  // blocks a step
  const Mod2Consts<V> k;
  const VI one(1), three(3);
  for (int bx = 0; bx < r.nbx; bx += nb) {
    VI acc_err, acc_bits;
    for (int j = 0; j < 4; ++j) {
      V a[4], b[4], t[4], v3[4], v5[4];
      mod2_load_row<kAlpha>(k, r, bx, j, a, b, t);
      for (int c = 0; c < (kAlpha ? 4 : 3); ++c) {
        v3[c] = simd::srl<3>(simd::mullo(a[c], k.k5) + simd::mullo(b[c], k.k3));
        v5[c] = simd::srl<3>(simd::mullo(a[c], k.k3) + simd::mullo(b[c], k.k5));
      }
      VI e0[2], e3[2], e5[2], e8[2];
      mod2_sq_err<kAlpha>(a, t, e0[0], e0[1]);
      mod2_sq_err<kAlpha>(v3, t, e3[0], e3[1]);
      mod2_sq_err<kAlpha>(v5, t, e5[0], e5[1]);
      mod2_sq_err<kAlpha>(b, t, e8[0], e8[1]);
      VI code[2], bit[2];
      for (int h = 0; h < 2; ++h) {
        // First minimum via (error * 4 + rank), as the scalar scan.
        VI q = simd::sll<2>(e0[h]);
        q = simd::min(q, simd::sll<2>(e3[h]) | one);
        q = simd::min(q, simd::sll<2>(e5[h]) | VI(2));
        q = simd::min(q, simd::sll<2>(e8[h]) | three);
        code[h] = q & three;
        const VI q0 = simd::min(simd::sll<1>(e0[h]), simd::sll<1>(e8[h]) | one);
        bit[h] = q0 & one;
        acc_err += simd::srl<1>(q0);
      }
      mod2_store_bytes(
          simd::narrow16(code[0] | simd::sll<2>(bit[0]), code[1] | simd::sll<2>(bit[1])),
          r.out[j] + std::size_t(bx) * 8);
      // Row j's 8 bits into byte j (each sum is below 256).
      acc_bits += simd::sll_bytes(simd::madd(simd::narrow16(bit[0], bit[1]), k.lanebit), j);
    }
    mod2_block_sums(acc_err, r.err0 + bx);
    mod2_block_sums(acc_bits, r.mod + bx);
  }
}

/// Stored values in raster order of the checkerboard, 2 bits each, from the greedy map rows
/// in[1..4] (texel rows 0-3 of the block, at element x): greedy codes, texel (0,0) restricted
/// to 0/3 (only its high bit is stored; bit 0 flags the H/V-only variants), and (4,2) too for
/// H/V only (bit 20, its low bit, tells V from H). variant: 0 H+V, 1 H only, 2 V only.
inline std::uint32_t mod2_interpolated_bits(const std::uint8_t* const in[6], std::size_t x,
                                            int variant) {
  std::uint32_t bits = 0;
  for (int j = 0; j < 4; ++j) {
    const std::uint8_t* cur = in[j + 1] + x;
    for (int i = 0; i < 4; ++i) {
      bits |= std::uint32_t(cur[(j & 1) + 2 * i] & 3) << (8 * j + 2 * i);
    }
  }
  const std::uint8_t* row0 = in[1] + x;
  const std::uint8_t* row2 = in[3] + x;
  bits = (bits & ~3u) | ((row0[0] & 4) ? 2u : 0u);
  if (variant > 0) {
    bits = (bits & ~(3u << 20)) | ((row2[4] & 4) ? (2u << 20) : 0u) | 1u;
    if (variant == 2) bits |= 1u << 20;
  } else {
    bits &= ~(1u << 20);
  }
  return bits;
}

/// Pass 2 of one block row: the three interpolated variants scored against the greedy map
/// (`in`), the choice (`mode`, `mod`) and the decoded weight of every stored texel (`out`).
template <bool kAlpha, class V>
void mod2_pass2(const Mod2Row& r) {
  using VI = decltype(simd::madd(V(), V()));
  constexpr int nb = simd::kLanes<V> / 8;
  const Mod2Consts<V> k;
  for (int bx = 0; bx < r.nbx; bx += nb) {
    const std::size_t x0 = std::size_t(bx) * 8;
    VI acc[3];
    V c0[4], c12[4], cab[4];
    for (int j = 0; j < 4; ++j) {
      const std::uint8_t* cur = r.in[j + 1] + x0;
      const V bc = simd::load_widen_as<V>(cur), bl = simd::load_widen_as<V>(cur - 1),
              br = simd::load_widen_as<V>(cur + 1), bu = simd::load_widen_as<V>(r.in[j] + x0),
              bd = simd::load_widen_as<V>(r.in[j + 2] + x0);
      const V cg = mod2_greedy_weight(k, bc), lg = mod2_greedy_weight(k, bl),
              rg = mod2_greedy_weight(k, br), ug = mod2_greedy_weight(k, bu),
              dg = mod2_greedy_weight(k, bd);
      const V ca = mod2_ab_weight(k, bc), la = mod2_ab_weight(k, bl), ra = mod2_ab_weight(k, br),
              ua = mod2_ab_weight(k, bu), da = mod2_ab_weight(k, bd);
      cab[j] = ca;
      c0[j] = simd::select(k.c0[j], ca, cg);
      c12[j] = simd::select(k.c12[j], ca, cg);
      const V l0 = simd::select(k.l0[j], la, lg), u0 = simd::select(k.u0[j], ua, ug);
      const V l12 = simd::select(k.l12[j], la, lg), r12 = simd::select(k.r12[j], ra, rg),
              u12 = simd::select(k.u12[j], ua, ug), d12 = simd::select(k.d12[j], da, dg);
      const V ev = k.even[j & 1];
      const V m0 = simd::select(ev, c0[j], simd::srl<2>(((u0 + dg) + (l0 + rg)) + k.k2));
      const V m1 = simd::select(ev, c12[j], simd::srl<1>((l12 + r12) + k.k1));
      const V m2 = simd::select(ev, c12[j], simd::srl<1>((u12 + d12) + k.k1));
      V a[4], b[4], t[4];
      mod2_load_row<kAlpha>(k, r, bx, j, a, b, t);
      acc[0] += mod2_blend_err<kAlpha>(k, a, b, t, m0);
      acc[1] += mod2_blend_err<kAlpha>(k, a, b, t, m1);
      acc[2] += mod2_blend_err<kAlpha>(k, a, b, t, m2);
    }
    std::uint32_t e[3][nb];
    for (int v = 0; v < 3; ++v) mod2_block_sums(acc[v], e[v]);
    for (int h = 0; h < nb; ++h) {
      const int bi = bx + h;
      const std::size_t xh = x0 + std::size_t(h) * 8;
      std::uint32_t best = r.err0[bi];
      int variant = -1;
      for (int v = 0; v < 3; ++v) {
        if (e[v][h] < best) {
          best = e[v][h];
          variant = v;
        }
      }
      if (variant < 0) {
        r.mode[bi] = 0;  // r.mod[bi]: the mode-0 bits from pass 1
        for (int j = 0; j < 4; ++j) simd::store_u8x8(mod2_block(cab[j], h), r.out[j] + xh);
        continue;
      }
      // Stored values: the greedy codes, with (0,0) and for H/V only (4,2) restricted.
      const std::uint32_t bits = mod2_interpolated_bits(r.in, xh, variant);
      const std::uint8_t* row2 = r.in[3] + xh;
      r.mode[bi] = 1;
      r.mod[bi] = bits;
      for (int j = 0; j < 4; ++j) {
        simd::store_u8x8(mod2_block(variant == 0 ? c0[j] : c12[j], h), r.out[j] + xh);
      }
      // H+V: the low bit of (4,2) is not stored (bit 20 was cleared): it decodes as
      // greedy code & 2.
      if (variant == 0) r.out[2][xh + 4] = (row2[4] & 2) ? 5 : 0;
    }
  }
}

/// Variant of a mode-1 block from its bits: 0 H+V, 1 H only, 2 V only.
inline int mod2_variant_of(std::uint32_t bits) {
  return (bits & 1) ? ((bits & (1u << 20)) ? 2 : 1) : 0;
}

/// Pass 3 of one block row: the exact error of the decode from the decoded map (`in`), `mode`,
/// `mod` and `err0`: mode-0 blocks are exact from pass 1, mode-1 blocks are rescored with the
/// weights their neighbours actually decode to. Reads the column sums only for steps with a
/// mode-1 block.
template <bool kAlpha, class V>
std::uint64_t mod2_pass3(const Mod2Row& r) {
  using VI = decltype(simd::madd(V(), V()));
  constexpr int nb = simd::kLanes<V> / 8;
  const Mod2Consts<V> k;
  std::uint64_t total = 0;
  for (int bx = 0; bx < r.nbx; bx += nb) {
    // Variant per block (-1: mode 0). A mode-0 block is scored as a mode-1 neighbour's
    // variant, and its score dropped.
    int variant[nb];
    int any = -1;
    for (int h = 0; h < nb; ++h) {
      variant[h] = r.mode[bx + h] != 0 ? mod2_variant_of(r.mod[bx + h]) : -1;
      if (variant[h] >= 0) any = variant[h];
    }
    if (any < 0) {
      for (int h = 0; h < nb; ++h) total += r.err0[bx + h];
      continue;
    }
    bool same = true;
    int v[nb];
    for (int h = 0; h < nb; ++h) {
      v[h] = variant[h] < 0 ? any : variant[h];
      same = same && v[h] == v[0];
    }
    const std::size_t x0 = std::size_t(bx) * 8;
    VI acc;
    for (int j = 0; j < 4; ++j) {
      const std::uint8_t* cur = r.in[j + 1] + x0;
      const V wc = simd::load_widen_as<V>(cur);
      const auto interp_of = [&](int var) {
        if (var == 0) {
          return simd::srl<2>(
              ((simd::load_widen_as<V>(cur - 1) + simd::load_widen_as<V>(cur + 1)) +
               (simd::load_widen_as<V>(r.in[j] + x0) + simd::load_widen_as<V>(r.in[j + 2] + x0))) +
              k.k2);
        }
        if (var == 1) {
          return simd::srl<1>((simd::load_widen_as<V>(cur - 1) + simd::load_widen_as<V>(cur + 1)) +
                              k.k1);
        }
        return simd::srl<1>(
            (simd::load_widen_as<V>(r.in[j] + x0) + simd::load_widen_as<V>(r.in[j + 2] + x0)) +
            k.k1);
      };
      const V interp = same ? interp_of(v[0]) : mod2_blocks(interp_of(v[0]), interp_of(v[nb - 1]));
      const V m = simd::select(k.even[j & 1], wc, interp);
      V a[4], b[4], t[4];
      mod2_load_row<kAlpha>(k, r, bx, j, a, b, t);
      acc += mod2_blend_err<kAlpha>(k, a, b, t, m);
    }
    std::uint32_t e[nb];
    mod2_block_sums(acc, e);
    for (int h = 0; h < nb; ++h) total += variant[h] >= 0 ? e[h] : r.err0[bx + h];
  }
  return total;
}

}  // namespace
}  // namespace tessera::pvrtc::detail
