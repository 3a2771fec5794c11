// 2 bpp modulation choice as planar SIMD passes (16-bit lanes, one 8-texel block row per
// vector, through simd.h), bit-identical with the scalar search it replaced:
//
// Per block, mode 0 (direct: each texel A or B, 1 bit) or mode 1 (2-bit values on the
// checkerboard (x ^ y even), the other texels interpolated from their stored neighbours: H+V,
// H only or V only), whichever has the smaller estimated error (ties: mode 0, then H+V, H, V).
// The estimate takes the stored values as the greedy best of the four weights per texel, except
// texel (0,0) (and (4,2) for H/V only), which can only hold 0 or 3 (the better of A and B), and
// takes the neighbouring blocks' values as their greedy values.
//
//   pass 1: per texel the greedy code and the better of A/B (the "map", one byte per texel,
//           rows with wrap-around guard bytes), per block the mode-0 bits and error;
//   pass 2: per block the three interpolated variants scored from the map, the choice, and the
//           decoded weight of every stored texel (a second map) for pass 3;
//   pass 3: the exact error of the decode: mode-0 blocks are exact from pass 1, mode-1 blocks
//           are rescored with the weights their neighbours actually decode to.
//
// The upscaled endpoint images are formed on the fly from per-row column sums, as the decoder's
// `upscale_rows` (weights of a 2 bpp texel sum to 32).
//
// Where the CPU has AVX2 (checked once per call), the per-block-row arithmetic of the three
// passes runs in modulation_2bpp_avx2.cpp instead, two blocks a step (rows of an even number of
// blocks: every 2 bpp grid, nbx being a power of two >= 2); allocation, threading and the rest
// stay here. Same output.
#include "pvrtc/encode/modulation/modulation_2bpp.h"

#include <atomic>
#include <vector>

#include "core/simd.h"
#include "pvrtc/encode/modulation/modulation_2bpp_avx2.h"
#include "pvrtc/encode/modulation/modulation_2bpp_bits.h"
#include "pvrtc/encode/modulation/modulation_2bpp_blends.h"

namespace tessera::pvrtc::detail {

namespace {

using simd::vint4;
using simd::vu16x8;

constexpr int kGuard = 8;  // bytes before and after each map row (one is used each side)

std::atomic<bool> g_baseline_only{false};

/// The AVX2 passes run here (checked once per call): built with them (src/CMakeLists.txt gives
/// *_avx2.cpp -mavx2 on x86-64), the CPU has AVX2 and a row holds an even number of blocks. Not
/// with TESSERA_NO_SIMD (scalar build).
bool use_avx2(const Grid& g) {
#if defined(TESSERA_NO_SIMD)
  (void)g;
  return false;
#else
  return avx2_kernels_usable() && g.nbx >= 2 && g.nbx % 2 == 0 &&
         !g_baseline_only.load(std::memory_order_relaxed);
#endif
}

inline vu16x8 lanes8(int a, int b, int c, int d, int e, int f, int g, int h) {
  return simd::narrow16(vint4(a, b, c, d), vint4(e, f, g, h));
}

/// Single-lane mask (lane < 0: none).
inline vu16x8 lane_mask(int lane) {
  int l[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  if (lane >= 0) l[lane] = -1;
  return lanes8(l[0], l[1], l[2], l[3], l[4], l[5], l[6], l[7]);
}

inline vu16x8 lane_mask2(int lane0, int lane1) {
  int l[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  if (lane0 >= 0) l[lane0] = -1;
  if (lane1 >= 0) l[lane1] = -1;
  return lanes8(l[0], l[1], l[2], l[3], l[4], l[5], l[6], l[7]);
}

inline std::uint32_t hsum(vint4 v) {
  std::int32_t l[4];
  simd::store4(v, l);
  return std::uint32_t(l[0]) + std::uint32_t(l[1]) + std::uint32_t(l[2]) + std::uint32_t(l[3]);
}

/// Constants shared by the passes.
struct Consts {
  vu16x8 wl, wr;       // horizontal bilinear weights of the 8 texels (left / right sums)
  vu16x8 even[2];      // lanes x with (x ^ row) even, by row parity
  vu16x8 lanebit;      // 1, 2, 4, ..., 128
  vu16x8 k1, k2, k3, k4, k5, k8, kff;
  // Lanes of the neighbour vectors that refer to a restricted texel of the block itself, per
  // row: (0,0) for every variant, (4,2) too for H/V only. C: the row itself, L: the left
  // neighbours (x - 1), R: right, U: up (row - 1), D: down (row + 1).
  vu16x8 c0[4], l0[4], u0[4], c12[4], l12[4], r12[4], u12[4], d12[4];
  Consts() {
    wl = lanes8(4, 3, 2, 1, 8, 7, 6, 5);
    wr = lanes8(4, 5, 6, 7, 0, 1, 2, 3);
    even[0] = lanes8(-1, 0, -1, 0, -1, 0, -1, 0);
    even[1] = lanes8(0, -1, 0, -1, 0, -1, 0, -1);
    lanebit = lanes8(1, 2, 4, 8, 16, 32, 64, 128);
    k1 = vu16x8(1);
    k2 = vu16x8(2);
    k3 = vu16x8(3);
    k4 = vu16x8(4);
    k5 = vu16x8(5);
    k8 = vu16x8(8);
    kff = vu16x8(0xff);
    for (int j = 0; j < 4; ++j) {
      c0[j] = lane_mask(j == 0 ? 0 : -1);
      l0[j] = lane_mask(j == 0 ? 1 : -1);
      u0[j] = lane_mask(j == 1 ? 0 : -1);
      c12[j] = lane_mask(j == 0 ? 0 : j == 2 ? 4 : -1);
      l12[j] = lane_mask(j == 0 ? 1 : j == 2 ? 5 : -1);
      r12[j] = lane_mask(j == 2 ? 3 : -1);
      u12[j] = lane_mask2(j == 1 ? 0 : -1, j == 3 ? 4 : -1);
      d12[j] = lane_mask(j == 1 ? 4 : -1);
    }
  }
};

/// One block row: per texel row the column sums of the endpoint images (8 planes, image * 4 +
/// channel, `vstride` apart; element bx + 1 holds block bx, element 0 the last block and
/// element nbx + 1 the first) and the target row.
struct Row2 {
  const std::uint16_t* v[4] = {};
  const std::uint8_t* t[4] = {};
  std::size_t vstride = 0;
};

/// Per-thread column-sum buffer for one block row.
class ColumnSums {
 public:
  ColumnSums(const Grid& g, const std::vector<std::uint16_t>& ep, bool alpha)
      : g_(g), ep_(ep), alpha_(alpha), vstride_(std::size_t(g.nbx) + 8),
        vp_(4 * 8 * vstride_, 0) {}

  void fill(const EncoderState& s, int by, Row2& r) {
    const std::size_t nb = g_.blocks();
    for (int j = 0; j < 4; ++j) {
      const AxisTap ty = axis_tap(by * 4 + j, 4, g_.ph);
      const std::uint16_t wy0 = std::uint16_t(4 - ty.d), wy1 = std::uint16_t(ty.d);
      for (int k = 0; k < 8; ++k) {
        if ((k & 3) == 3 && !alpha_) continue;
        const std::uint16_t* e0 =
            &ep_[std::size_t(k) * nb + std::size_t(ty.b0) * std::size_t(g_.nbx)];
        const std::uint16_t* e1 =
            &ep_[std::size_t(k) * nb + std::size_t(ty.b1) * std::size_t(g_.nbx)];
        std::uint16_t* v = &vp_[(std::size_t(j) * 8 + std::size_t(k)) * vstride_];
        for (int bx = 0; bx < g_.nbx; ++bx) v[bx + 1] = std::uint16_t(e0[bx] * wy0 + e1[bx] * wy1);
        v[0] = v[g_.nbx];
        v[g_.nbx + 1] = v[1];
      }
      r.v[j] = &vp_[std::size_t(j) * 8 * vstride_];
      r.t[j] = &s.target[std::size_t(by * 4 + j) * std::size_t(g_.pw) * 4];
    }
    r.vstride = vstride_;
  }

 private:
  const Grid& g_;
  const std::vector<std::uint16_t>& ep_;
  bool alpha_;
  std::size_t vstride_;
  std::vector<std::uint16_t> vp_;
};

/// Calls fn(by, cs, r) for every block row, rows in parallel; each worker has its own column-sum
/// buffer `cs` and row view `r` (which fn fills with `cs.fill(s, by, r)` when it needs them).
template <class Fn>
void for_each_block_row(const EncoderState& s, const std::vector<std::uint16_t>& ep, bool alpha,
                        Fn&& fn) {
  parallel_for(
      0, s.g.nby, 4,
      [&](std::int64_t by0, std::int64_t by1) {
        ColumnSums cs(s.g, ep, alpha);
        Row2 r;
        for (int by = int(by0); by < int(by1); ++by) fn(by, cs, r);
      },
      {s.threads});
}

/// Upscaled A (a) and B (b) and the target (t) of texel row j of block bx, per channel.
template <bool kAlpha>
inline void load_row(const Consts& k, const Row2& r, int bx, int j, vu16x8 a[4], vu16x8 b[4],
                     vu16x8 t[4]) {
  constexpr int nch = kAlpha ? 4 : 3;
  const std::uint8_t* tp = r.t[j] + std::size_t(bx) * 32;
  const vint4 t0 = simd::load_texels4(tp), t1 = simd::load_texels4(tp + 16);
  for (int c = 0; c < nch; ++c) {
    t[c] = simd::channel16(t0, t1, c);
    for (int img = 0; img < 2; ++img) {
      const std::uint16_t* p = r.v[j] + std::size_t(img * 4 + c) * r.vstride + bx;
      const vint4 p1(p[1]);
      const vu16x8 L = simd::narrow16(vint4(p[0]), p1), R = simd::narrow16(p1, vint4(p[2]));
      const vu16x8 w = simd::mullo(L, k.wl) + simd::mullo(R, k.wr);
      const vu16x8 u = c < 3 ? simd::srl<7>(w) + simd::srl<2>(w) : simd::srl<5>(w) + simd::srl<1>(w);
      (img == 0 ? a : b)[c] = u;
    }
  }
}

// sq_err, blend_err, greedy_weight, ab_weight: modulation_2bpp_blends.h.

struct Maps {
  std::size_t stride = 0;
  std::vector<std::uint8_t> greedy;   // pass 1: greedy code | (B better than A) << 2
  std::vector<std::uint8_t> decoded;  // pass 2: decoded weight of each stored texel
  std::uint8_t* row(std::vector<std::uint8_t>& m, int y) {
    return &m[std::size_t(y) * stride + kGuard];
  }
};

inline void fill_guards(std::uint8_t* row, int pw) {
  row[-1] = row[pw - 1];
  row[pw] = row[0];
}

template <bool kAlpha>
std::uint64_t choose_2bpp_impl(EncoderState& s) {
  const Grid& g = s.g;
  const std::size_t nb = g.blocks();
  const Consts k;
  // Expanded endpoints, planar: plane (image * 4 + channel), one u16 per block.
  std::vector<std::uint16_t> ep(8 * nb);
  for (std::size_t i = 0; i < nb; ++i) {
    const Rgba5 a = expand_a(s.ca[i]), b = expand_b(s.cb[i]);
    const std::int32_t v[8] = {a.r, a.g, a.b, a.a, b.r, b.g, b.b, b.a};
    for (int c = 0; c < 8; ++c) ep[std::size_t(c) * nb + i] = std::uint16_t(v[c]);
  }
  Maps maps;
  maps.stride = std::size_t(g.pw) + 2 * kGuard;
  maps.greedy.assign(maps.stride * std::size_t(g.ph), 0);
  maps.decoded.assign(maps.stride * std::size_t(g.ph), 0);
  std::vector<std::uint32_t> err0(nb);
  const int hm = g.ph - 1;
  const bool avx2 = use_avx2(g);
  // Block row `by` for the AVX2 passes: map rows by * 4 - 1 .. by * 4 + 4 of `in`, by * 4 ..
  // by * 4 + 3 of `out`.
  const auto avx2_row = [&](int by, const Row2& r, std::vector<std::uint8_t>* in,
                            std::vector<std::uint8_t>* out) {
    Mod2RowAvx2 m{};
    const std::size_t b0 = std::size_t(by) * std::size_t(g.nbx);
    for (int j = 0; j < 4; ++j) {
      m.v[j] = r.v[j];
      m.t[j] = r.t[j];
      m.out[j] = out ? maps.row(*out, by * 4 + j) : nullptr;
    }
    for (int j = -1; j <= 4; ++j) m.in[j + 1] = in ? maps.row(*in, (by * 4 + j) & hm) : nullptr;
    m.vstride = r.vstride;
    m.nbx = g.nbx;
    m.err0 = &err0[b0];
    m.mod = &s.mod[b0];
    m.mode = &s.mode[b0];
    return m;
  };

  // Pass 1: greedy codes, A/B choice, mode 0.
  for_each_block_row(s, ep, kAlpha, [&](int by, ColumnSums& cs, Row2& r) {
    cs.fill(s, by, r);
    if (avx2) mod2_pass1_row_avx2(avx2_row(by, r, nullptr, &maps.greedy), kAlpha);
    for (int bx = 0; bx < (avx2 ? 0 : g.nbx); ++bx) {
      vint4 acc_err, acc_bits;
      for (int j = 0; j < 4; ++j) {
        vu16x8 a[4], b[4], t[4], v3[4], v5[4];
        load_row<kAlpha>(k, r, bx, j, a, b, t);
        for (int c = 0; c < (kAlpha ? 4 : 3); ++c) {
          v3[c] = simd::srl<3>(simd::mullo(a[c], k.k5) + simd::mullo(b[c], k.k3));
          v5[c] = simd::srl<3>(simd::mullo(a[c], k.k3) + simd::mullo(b[c], k.k5));
        }
        vint4 e0[2], e3[2], e5[2], e8[2];
        sq_err<kAlpha>(a, t, e0[0], e0[1]);
        sq_err<kAlpha>(v3, t, e3[0], e3[1]);
        sq_err<kAlpha>(v5, t, e5[0], e5[1]);
        sq_err<kAlpha>(b, t, e8[0], e8[1]);
        vint4 code[2], bit[2];
        for (int h = 0; h < 2; ++h) {
          // First minimum via (error * 4 + rank), as the scalar scan.
          vint4 q = simd::sll<2>(e0[h]);
          q = simd::min(q, simd::sll<2>(e3[h]) | vint4(1));
          q = simd::min(q, simd::sll<2>(e5[h]) | vint4(2));
          q = simd::min(q, simd::sll<2>(e8[h]) | vint4(3));
          code[h] = q & vint4(3);
          const vint4 q0 = simd::min(simd::sll<1>(e0[h]), simd::sll<1>(e8[h]) | vint4(1));
          bit[h] = q0 & vint4(1);
          acc_err += simd::srl<1>(q0);
        }
        const std::size_t x0 = std::size_t(bx) * 8;
        simd::store_u8x8(simd::narrow16(code[0] | simd::sll<2>(bit[0]),
                                        code[1] | simd::sll<2>(bit[1])),
                         maps.row(maps.greedy, by * 4 + j) + x0);
        acc_bits += simd::sll_bytes(simd::madd(simd::narrow16(bit[0], bit[1]), k.lanebit), j);
      }
      const std::size_t bi = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
      err0[bi] = hsum(acc_err);
      s.mod[bi] = hsum(acc_bits);
    }
    for (int j = 0; j < 4; ++j) fill_guards(maps.row(maps.greedy, by * 4 + j), g.pw);
  });

  // Pass 2: the interpolated variants against the greedy map; the choice.
  for_each_block_row(s, ep, kAlpha, [&](int by, ColumnSums& cs, Row2& r) {
    cs.fill(s, by, r);
    const std::uint8_t* rows[6];
    for (int j = -1; j <= 4; ++j) rows[j + 1] = maps.row(maps.greedy, (by * 4 + j) & hm);
    if (avx2) mod2_pass2_row_avx2(avx2_row(by, r, &maps.greedy, &maps.decoded), kAlpha);
    for (int bx = 0; bx < (avx2 ? 0 : g.nbx); ++bx) {
      const std::size_t x0 = std::size_t(bx) * 8;
      vint4 acc[3];
      vu16x8 c0[4], c12[4], cab[4];
      for (int j = 0; j < 4; ++j) {
        const std::uint8_t* cur = rows[j + 1] + x0;
        const vu16x8 bc = simd::load_u8x8(cur), bl = simd::load_u8x8(cur - 1),
                     br = simd::load_u8x8(cur + 1), bu = simd::load_u8x8(rows[j] + x0),
                     bd = simd::load_u8x8(rows[j + 2] + x0);
        const vu16x8 cg = greedy_weight(k, bc), lg = greedy_weight(k, bl),
                     rg = greedy_weight(k, br), ug = greedy_weight(k, bu),
                     dg = greedy_weight(k, bd);
        const vu16x8 ca = ab_weight(k, bc), la = ab_weight(k, bl), ra = ab_weight(k, br),
                     ua = ab_weight(k, bu), da = ab_weight(k, bd);
        cab[j] = ca;
        c0[j] = simd::select(k.c0[j], ca, cg);
        c12[j] = simd::select(k.c12[j], ca, cg);
        const vu16x8 l0 = simd::select(k.l0[j], la, lg), u0 = simd::select(k.u0[j], ua, ug);
        const vu16x8 l12 = simd::select(k.l12[j], la, lg),
                     r12 = simd::select(k.r12[j], ra, rg),
                     u12 = simd::select(k.u12[j], ua, ug),
                     d12 = simd::select(k.d12[j], da, dg);
        const vu16x8 ev = k.even[j & 1];
        const vu16x8 m0 = simd::select(ev, c0[j], simd::srl<2>(u0 + dg + l0 + rg + k.k2));
        const vu16x8 m1 = simd::select(ev, c12[j], simd::srl<1>(l12 + r12 + k.k1));
        const vu16x8 m2 = simd::select(ev, c12[j], simd::srl<1>(u12 + d12 + k.k1));
        vu16x8 a[4], b[4], t[4];
        load_row<kAlpha>(k, r, bx, j, a, b, t);
        acc[0] += blend_err<kAlpha>(k, a, b, t, m0);
        acc[1] += blend_err<kAlpha>(k, a, b, t, m1);
        acc[2] += blend_err<kAlpha>(k, a, b, t, m2);
      }
      const std::size_t bi = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
      std::uint32_t best = err0[bi];
      int variant = -1;
      for (int v = 0; v < 3; ++v) {
        const std::uint32_t e = hsum(acc[v]);
        if (e < best) {
          best = e;
          variant = v;
        }
      }
      if (variant < 0) {
        s.mode[bi] = 0;  // s.mod[bi]: the mode-0 bits from pass 1
        for (int j = 0; j < 4; ++j) {
          simd::store_u8x8(cab[j], maps.row(maps.decoded, by * 4 + j) + x0);
        }
        continue;
      }
      // Stored values: the greedy codes, with (0,0) and for H/V only (4,2) restricted
      // (modulation_2bpp_bits.h).
      const std::uint32_t bits = interpolated_bits(rows, x0, variant);
      const std::uint8_t* row2 = rows[3] + x0;
      s.mode[bi] = 1;
      s.mod[bi] = bits;
      for (int j = 0; j < 4; ++j) {
        simd::store_u8x8(variant == 0 ? c0[j] : c12[j],
                         maps.row(maps.decoded, by * 4 + j) + x0);
      }
      // H+V: the low bit of (4,2) is not stored (bit 20 was cleared): it decodes as
      // greedy code & 2.
      if (variant == 0) {
        maps.row(maps.decoded, by * 4 + 2)[x0 + 4] = (row2[4] & 2) ? 5 : 0;
      }
    }
    for (int j = 0; j < 4; ++j) fill_guards(maps.row(maps.decoded, by * 4 + j), g.pw);
  });

  // Pass 3: exact error of the decode.
  std::vector<std::uint64_t> row_err(std::size_t(g.nby), 0);
  for_each_block_row(s, ep, kAlpha, [&](int by, ColumnSums& cs, Row2& r) {
    const std::size_t b0 = std::size_t(by) * std::size_t(g.nbx);
    std::uint64_t total = 0;
    bool any1 = false;
    for (int bx = 0; bx < g.nbx; ++bx) any1 |= s.mode[b0 + std::size_t(bx)] != 0;
    if (any1) cs.fill(s, by, r);
    if (avx2) {
      row_err[std::size_t(by)] =
          mod2_pass3_row_avx2(avx2_row(by, r, &maps.decoded, nullptr), kAlpha);
      return;
    }
    const std::uint8_t* rows[6];
    for (int j = -1; j <= 4; ++j) rows[j + 1] = maps.row(maps.decoded, (by * 4 + j) & hm);
    for (int bx = 0; bx < g.nbx; ++bx) {
      const std::size_t bi = b0 + std::size_t(bx);
      if (s.mode[bi] == 0) {
        total += err0[bi];
        continue;
      }
      const std::uint32_t bits = s.mod[bi];
      const int variant = (bits & 1) ? ((bits & (1u << 20)) ? 2 : 1) : 0;
      const std::size_t x0 = std::size_t(bx) * 8;
      vint4 acc;
      for (int j = 0; j < 4; ++j) {
        const std::uint8_t* cur = rows[j + 1] + x0;
        const vu16x8 wc = simd::load_u8x8(cur);
        vu16x8 interp;
        if (variant == 0) {
          interp = simd::srl<2>(simd::load_u8x8(cur - 1) + simd::load_u8x8(cur + 1) +
                                simd::load_u8x8(rows[j] + x0) +
                                simd::load_u8x8(rows[j + 2] + x0) + k.k2);
        } else if (variant == 1) {
          interp = simd::srl<1>(simd::load_u8x8(cur - 1) + simd::load_u8x8(cur + 1) + k.k1);
        } else {
          interp = simd::srl<1>(simd::load_u8x8(rows[j] + x0) +
                                simd::load_u8x8(rows[j + 2] + x0) + k.k1);
        }
        const vu16x8 m = simd::select(k.even[j & 1], wc, interp);
        vu16x8 a[4], b[4], t[4];
        load_row<kAlpha>(k, r, bx, j, a, b, t);
        acc += blend_err<kAlpha>(k, a, b, t, m);
      }
      total += hsum(acc);
    }
    row_err[std::size_t(by)] = total;
  });
  std::uint64_t total = 0;
  for (std::uint64_t e : row_err) total += e;
  return total;
}

}  // namespace

std::uint64_t choose_modulation_2bpp(EncoderState& s) {
  return s.alpha_mode ? choose_2bpp_impl<true>(s) : choose_2bpp_impl<false>(s);
}

bool set_modulation_2bpp_baseline_only(bool on) { return g_baseline_only.exchange(on); }

}  // namespace tessera::pvrtc::detail
