// modulation_2bpp_avx2.cpp — the three 2 bpp modulation passes of modulation_2bpp.cpp over the
// SIMD wrapper's 8-lane types (core/simd_wide.h): two blocks a step (block bx in the low half,
// bx + 1 in the high), the same operations lane for lane as the baseline's one block row per
// 4-lane vector (the 8-lane operations that work per half are those 4-lane ones; the per-texel
// errors and weights are the baseline's own code, modulation_2bpp_blends.h), so the same maps,
// bits, modes and errors (ties included). The halves never mix until the per-block sums.
//
// Compiled with -mavx2 (src/CMakeLists.txt), which gives the wrapper its AVX2 backend, and
// called only after the run-time CPU check in modulation_2bpp.cpp. So that no AVX2 code can
// stand in for baseline code elsewhere, the wrapper's functions compiled here live in their own
// inline namespace (simd_int.h); otherwise this file includes no header with inline functions
// or templates of external linkage (modulation_2bpp_bits.h's and modulation_2bpp_blends.h's
// helpers have internal linkage; not encode_internal.h or the standard containers) and keeps its helpers in an anonymous
// namespace; it exports the three `mod2_pass*_row_avx2` functions only.
#include "pvrtc/encode/modulation/modulation_2bpp_avx2.h"

#if defined(TESSERA_HAVE_AVX2_KERNELS) && !defined(__AVX2__)
#error "modulation_2bpp_avx2.cpp needs -mavx2 where TESSERA_HAVE_AVX2_KERNELS is set"
#endif

#if defined(__AVX2__)

#include <cstring>

#include "core/simd.h"
#include "pvrtc/encode/modulation/modulation_2bpp_bits.h"
#include "pvrtc/encode/modulation/modulation_2bpp_blends.h"

namespace tessera::pvrtc::detail {

namespace {

using namespace simd;
using u16 = std::uint16_t;

/// Sixteen 16-bit lanes, the pattern `l` (8 lanes) in both halves.
vu16x16 twice(const u16 l[8]) {
  const vu16x8 x = load_u16x8(l);
  return vu16x16(x, x);
}

/// Mask of up to two lanes (lane < 0: none) in both halves, as modulation_2bpp.cpp's
/// lane_mask / lane_mask2.
vu16x16 lane_mask2(int lane0, int lane1) {
  u16 l[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  if (lane0 >= 0) l[lane0] = 0xffff;
  if (lane1 >= 0) l[lane1] = 0xffff;
  return twice(l);
}

/// Constants shared by the passes (those of modulation_2bpp.cpp, in both halves).
struct Consts {
  vu16x16 wl, wr, even[2], lanebit, k1, k2, k3, k4, k5, k8;
  vu16x16 tap_l, tap_r;  // column-sum element shuffles: left / right taps of both blocks
  vu16x16 c0[4], l0[4], u0[4], c12[4], l12[4], r12[4], u12[4], d12[4];
  Consts() {
    const u16 wl8[8] = {4, 3, 2, 1, 8, 7, 6, 5}, wr8[8] = {4, 5, 6, 7, 0, 1, 2, 3};
    const u16 ev0[8] = {0xffff, 0, 0xffff, 0, 0xffff, 0, 0xffff, 0};
    const u16 ev1[8] = {0, 0xffff, 0, 0xffff, 0, 0xffff, 0, 0xffff};
    const u16 bit8[8] = {1, 2, 4, 8, 16, 32, 64, 128};
    wl = twice(wl8);
    wr = twice(wr8);
    even[0] = twice(ev0);
    even[1] = twice(ev1);
    lanebit = twice(bit8);
    k1 = vu16x16(u16{1});
    k2 = vu16x16(u16{2});
    k3 = vu16x16(u16{3});
    k4 = vu16x16(u16{4});
    k5 = vu16x16(u16{5});
    k8 = vu16x16(u16{8});
    // From the 4 elements p[0..3] (in both halves; byte pairs 0-1 .. 6-7): block 0 takes
    // p0 x4 p1 x4 (left) and p1 x4 p2 x4 (right), block 1 the same one element on.
    const u16 tl[16] = {0x100, 0x100, 0x100, 0x100, 0x302, 0x302, 0x302, 0x302,
                        0x302, 0x302, 0x302, 0x302, 0x504, 0x504, 0x504, 0x504};
    const u16 tr[16] = {0x302, 0x302, 0x302, 0x302, 0x504, 0x504, 0x504, 0x504,
                        0x504, 0x504, 0x504, 0x504, 0x706, 0x706, 0x706, 0x706};
    tap_l = load_u16x16(tl);
    tap_r = load_u16x16(tr);
    for (int j = 0; j < 4; ++j) {
      c0[j] = lane_mask2(j == 0 ? 0 : -1, -1);
      l0[j] = lane_mask2(j == 0 ? 1 : -1, -1);
      u0[j] = lane_mask2(j == 1 ? 0 : -1, -1);
      c12[j] = lane_mask2(j == 0 ? 0 : j == 2 ? 4 : -1, -1);
      l12[j] = lane_mask2(j == 0 ? 1 : j == 2 ? 5 : -1, -1);
      r12[j] = lane_mask2(j == 2 ? 3 : -1, -1);
      u12[j] = lane_mask2(j == 1 ? 0 : -1, j == 3 ? 4 : -1);
      d12[j] = lane_mask2(j == 1 ? 4 : -1, -1);
    }
  }
};

/// Per half, the sum of its four 32-bit lanes (wrapping, as the baseline's hsum).
inline void hsum2(vint8 x, std::uint32_t& h0, std::uint32_t& h1) {
  h0 = std::uint32_t(sum_lanes(low(x)));
  h1 = std::uint32_t(sum_lanes(high(x)));
}

/// Upscaled A (a) and B (b) and the target (t) of texel row j of blocks bx and bx + 1.
template <bool kAlpha>
inline void load_row(const Consts& k, const Mod2RowAvx2& r, int bx, int j, vu16x16 a[4],
                     vu16x16 b[4], vu16x16 t[4]) {
  constexpr int nch = kAlpha ? 4 : 3;
  load_planes(r.t[j] + std::size_t(bx) * 32, t);
  for (int c = 0; c < nch; ++c) {
    for (int img = 0; img < 2; ++img) {
      const u16* p = r.v[j] + std::size_t(img * 4 + c) * r.vstride + bx;
      std::uint64_t e;
      std::memcpy(&e, p, 8);
      const vu16x16 q = broadcast64(e);
      const vu16x16 w = mullo(shuffle_bytes(q, k.tap_l), k.wl) + mullo(shuffle_bytes(q, k.tap_r), k.wr);
      (img == 0 ? a : b)[c] = c < 3 ? srl<7>(w) + srl<2>(w) : srl<5>(w) + srl<1>(w);
    }
  }
}

// sq_err, blend_err, greedy_weight, ab_weight: modulation_2bpp_blends.h.

inline vint8 key(vint8 e, int rank) { return sll<2>(e) | vint8(rank); }

template <bool kAlpha>
void pass1(const Mod2RowAvx2& r) {
  const Consts k;
  const vint8 one(1), three(3);
  for (int bx = 0; bx < r.nbx; bx += 2) {
    vint8 acc_err, acc_bits;
    for (int j = 0; j < 4; ++j) {
      vu16x16 a[4], b[4], t[4], v3[4], v5[4];
      load_row<kAlpha>(k, r, bx, j, a, b, t);
      for (int c = 0; c < (kAlpha ? 4 : 3); ++c) {
        v3[c] = srl<3>(mullo(a[c], k.k5) + mullo(b[c], k.k3));
        v5[c] = srl<3>(mullo(a[c], k.k3) + mullo(b[c], k.k5));
      }
      vint8 e0[2], e3[2], e5[2], e8[2];
      sq_err<kAlpha>(a, t, e0[0], e0[1]);
      sq_err<kAlpha>(v3, t, e3[0], e3[1]);
      sq_err<kAlpha>(v5, t, e5[0], e5[1]);
      sq_err<kAlpha>(b, t, e8[0], e8[1]);
      vint8 code[2], bit[2];
      for (int h = 0; h < 2; ++h) {
        // First minimum via (error * 4 + rank), as the scalar scan.
        vint8 q = sll<2>(e0[h]);
        q = min(q, key(e3[h], 1));
        q = min(q, key(e5[h], 2));
        q = min(q, key(e8[h], 3));
        code[h] = q & three;
        const vint8 q0 = min(sll<1>(e0[h]), sll<1>(e8[h]) | one);
        bit[h] = q0 & one;
        acc_err += srl<1>(q0);
      }
      const vu16x16 bytes = narrow16(code[0] | sll<2>(bit[0]), code[1] | sll<2>(bit[1]));
      store_u8x16(bytes, r.out[j] + std::size_t(bx) * 8);
      // Row j's 8 bits into byte j (the baseline's byte shift: each sum is below 256).
      acc_bits += sll_bytes(madd(narrow16(bit[0], bit[1]), k.lanebit), j);
    }
    hsum2(acc_err, r.err0[bx], r.err0[bx + 1]);
    hsum2(acc_bits, r.mod[bx], r.mod[bx + 1]);
  }
}

template <bool kAlpha>
void pass2(const Mod2RowAvx2& r) {
  const Consts k;
  for (int bx = 0; bx < r.nbx; bx += 2) {
    const std::size_t x0 = std::size_t(bx) * 8;
    vint8 acc[3];
    vu16x16 c0[4], c12[4], cab[4];
    for (int j = 0; j < 4; ++j) {
      const std::uint8_t* cur = r.in[j + 1] + x0;
      const vu16x16 bc = load_u8x16_u16(cur), bl = load_u8x16_u16(cur - 1),
                    br = load_u8x16_u16(cur + 1), bu = load_u8x16_u16(r.in[j] + x0),
                    bd = load_u8x16_u16(r.in[j + 2] + x0);
      const vu16x16 cg = greedy_weight(k, bc), lg = greedy_weight(k, bl),
                    rg = greedy_weight(k, br), ug = greedy_weight(k, bu),
                    dg = greedy_weight(k, bd);
      const vu16x16 ca = ab_weight(k, bc), la = ab_weight(k, bl), ra = ab_weight(k, br),
                    ua = ab_weight(k, bu), da = ab_weight(k, bd);
      cab[j] = ca;
      c0[j] = select(k.c0[j], ca, cg);
      c12[j] = select(k.c12[j], ca, cg);
      const vu16x16 l0 = select(k.l0[j], la, lg), u0 = select(k.u0[j], ua, ug);
      const vu16x16 l12 = select(k.l12[j], la, lg), r12 = select(k.r12[j], ra, rg),
                    u12 = select(k.u12[j], ua, ug), d12 = select(k.d12[j], da, dg);
      const vu16x16 ev = k.even[j & 1];
      const vu16x16 m0 = select(ev, c0[j], srl<2>(((u0 + dg) + (l0 + rg)) + k.k2));
      const vu16x16 m1 = select(ev, c12[j], srl<1>((l12 + r12) + k.k1));
      const vu16x16 m2 = select(ev, c12[j], srl<1>((u12 + d12) + k.k1));
      vu16x16 a[4], b[4], t[4];
      load_row<kAlpha>(k, r, bx, j, a, b, t);
      acc[0] += blend_err<kAlpha>(k, a, b, t, m0);
      acc[1] += blend_err<kAlpha>(k, a, b, t, m1);
      acc[2] += blend_err<kAlpha>(k, a, b, t, m2);
    }
    std::uint32_t e[3][2];
    for (int v = 0; v < 3; ++v) hsum2(acc[v], e[v][0], e[v][1]);
    for (int h = 0; h < 2; ++h) {
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
        for (int j = 0; j < 4; ++j) store_u8x8(h ? high(cab[j]) : low(cab[j]), r.out[j] + xh);
        continue;
      }
      // Stored values as modulation_2bpp.cpp's pass 2 (modulation_2bpp_bits.h).
      const std::uint32_t bits = interpolated_bits(r.in, xh, variant);
      const std::uint8_t* row2 = r.in[3] + xh;
      r.mode[bi] = 1;
      r.mod[bi] = bits;
      for (int j = 0; j < 4; ++j) {
        const vu16x16 m = variant == 0 ? c0[j] : c12[j];
        store_u8x8(h ? high(m) : low(m), r.out[j] + xh);
      }
      if (variant == 0) r.out[2][xh + 4] = (row2[4] & 2) ? 5 : 0;
    }
  }
}

/// Variant of a mode-1 block from its bits: 0 H+V, 1 H only, 2 V only.
inline int variant_of(std::uint32_t bits) { return (bits & 1) ? ((bits & (1u << 20)) ? 2 : 1) : 0; }

template <bool kAlpha>
std::uint64_t pass3(const Mod2RowAvx2& r) {
  const Consts k;
  const vu16x16 lo_half(vu16x8(u16{0xffff}), vu16x8());
  std::uint64_t total = 0;
  for (int bx = 0; bx < r.nbx; bx += 2) {
    const bool m0 = r.mode[bx] != 0, m1 = r.mode[bx + 1] != 0;
    if (!m0 && !m1) {
      total += r.err0[bx];
      total += r.err0[bx + 1];
      continue;
    }
    // A mode-0 block is scored as its neighbour's variant, and its score dropped.
    int v0 = m0 ? variant_of(r.mod[bx]) : -1, v1 = m1 ? variant_of(r.mod[bx + 1]) : -1;
    if (v0 < 0) v0 = v1;
    if (v1 < 0) v1 = v0;
    const std::size_t x0 = std::size_t(bx) * 8;
    vint8 acc;
    for (int j = 0; j < 4; ++j) {
      const std::uint8_t* cur = r.in[j + 1] + x0;
      const vu16x16 wc = load_u8x16_u16(cur);
      const auto interp_of = [&](int variant) {
        if (variant == 0) {
          return srl<2>(((load_u8x16_u16(cur - 1) + load_u8x16_u16(cur + 1)) +
                         (load_u8x16_u16(r.in[j] + x0) + load_u8x16_u16(r.in[j + 2] + x0))) +
                        k.k2);
        }
        if (variant == 1) {
          return srl<1>((load_u8x16_u16(cur - 1) + load_u8x16_u16(cur + 1)) + k.k1);
        }
        return srl<1>((load_u8x16_u16(r.in[j] + x0) + load_u8x16_u16(r.in[j + 2] + x0)) + k.k1);
      };
      const vu16x16 interp =
          v0 == v1 ? interp_of(v0) : select(lo_half, interp_of(v0), interp_of(v1));
      const vu16x16 m = select(k.even[j & 1], wc, interp);
      vu16x16 a[4], b[4], t[4];
      load_row<kAlpha>(k, r, bx, j, a, b, t);
      acc += blend_err<kAlpha>(k, a, b, t, m);
    }
    std::uint32_t e0, e1;
    hsum2(acc, e0, e1);
    total += m0 ? e0 : r.err0[bx];
    total += m1 ? e1 : r.err0[bx + 1];
  }
  return total;
}

}  // namespace

void mod2_pass1_row_avx2(const Mod2RowAvx2& r, bool alpha) {
  alpha ? pass1<true>(r) : pass1<false>(r);
}

void mod2_pass2_row_avx2(const Mod2RowAvx2& r, bool alpha) {
  alpha ? pass2<true>(r) : pass2<false>(r);
}

std::uint64_t mod2_pass3_row_avx2(const Mod2RowAvx2& r, bool alpha) {
  return alpha ? pass3<true>(r) : pass3<false>(r);
}

}  // namespace tessera::pvrtc::detail

#else  // no AVX2 in this build: never called (the dispatch checks TESSERA_HAVE_AVX2_KERNELS)

namespace tessera::pvrtc::detail {

void mod2_pass1_row_avx2(const Mod2RowAvx2&, bool) {}
void mod2_pass2_row_avx2(const Mod2RowAvx2&, bool) {}
std::uint64_t mod2_pass3_row_avx2(const Mod2RowAvx2&, bool) { return 0; }

}  // namespace tessera::pvrtc::detail

#endif
