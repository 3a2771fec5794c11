// 2 bpp modulation by exact coordinate descent (high quality).
//
// The 2 bpp modulation choice (modulation_2bpp.cpp) takes every stored value of an
// interpolated block as the best weight for that texel alone, but each stored texel also sets
// the interpolated weight of up to four neighbours (the average of their stored neighbours,
// which may lie in the adjacent blocks). Here, with the endpoints fixed, each stored value is
// re-chosen to minimise the exact decoded error of the texel and of the interpolated texels
// that read it, and each interpolated block also tries the other two interpolation variants
// (H+V, H only, V only). Blocks are visited in a 2x2 colouring: blocks of one colour share no
// texel they read, so each colour is parallel and deterministic.
//
// A block's visit copies the stored weights and modes around it into a small region and
// tabulates, once, the error of each texel it can count at each of the nine weights (16-bit
// SIMD through simd.h, a running sum over the weight); every candidate is then scored from
// table lookups. Same integers as scoring each texel from the level, so the same output, in
// less time than scoring each candidate from the levels.
#include <cstdint>
#include <cstring>
#include <vector>

#include "core/simd.h"
#include "pvrtc/encode/encode_internal.h"

namespace tessera::pvrtc::detail {

namespace {

// The unpacked modulation of a level: stored values per texel and the mode of every block.
struct Mod2 {
  std::vector<std::uint8_t> value;  ///< 0..3 per texel (pw * ph); unused on interpolated texels
  std::vector<std::uint8_t> mode;   ///< 0 direct, 1 H+V, 2 H only, 3 V only, per block
};

// One block's visit works on a copy of the texels it can read: the block's 8x4 texels with a
// border of 2 (wrapped), region coordinates (x + 2, y + 2). The block's stored values and
// interpolated texels read stored weights up to 2 texels out, and the errors counted are those
// of texels up to 1 out (the interpolated neighbours of its stored texels): the inner 10x6
// texels, region 1..10 x 1..6. A level has at least 2x2 blocks (16x8 texels), so the 12x8
// region never holds one texel twice.
struct Region {
  static constexpr int kW = 12, kH = 8;
  static constexpr int kInner = 64;  ///< 60 inner texels, 4 zero pads
  std::uint8_t sw[kH][kW];           ///< stored weight (0, 3, 5, 8) of the texel's stored value
  std::uint8_t bm[kH][kW];  ///< mode of the texel's block (0 direct, 1 H+V, 2 H only, 3 V only)
  // Inner texel (rx, ry) at slot (ry - 1) * 10 + rx - 1, per channel (alpha zero if RGB): 8 A,
  // B - A (mod 2^16) and the target; A and B the upscaled endpoints.
  alignas(16) std::uint16_t a8[4][kInner], q[4][kInner], t[4][kInner];
  /// err[w][slot]: the texel's squared error at weight w (0..8), exactly the decoder's
  /// ((8 - w) A + w B) / 8 against the target, summed over the channels.
  alignas(16) std::int32_t err[9][kInner];

  static int slot(int rx, int ry) { return (ry - 1) * 10 + rx - 1; }

  /// Fills `err` from a8, q and t: (8 A + w (B - A)) / 8 = ((8 - w) A + w B) / 8 lies in
  /// 0..255, so 16-bit lanes and a running sum over w are exact.
  void tabulate() {
    using namespace simd;
    for (int g = 0; g < kInner; g += 8) {
      vu16x8 acc[4], dq[4], tt[4];
      for (int c = 0; c < 4; ++c) {
        acc[c] = load_u16x8(&a8[c][g]);
        dq[c] = load_u16x8(&q[c][g]);
        tt[c] = load_u16x8(&t[c][g]);
      }
      for (int w = 0; w <= 8; ++w) {
        vu16x8 d[4];
        for (int c = 0; c < 4; ++c) {
          d[c] = srl<3>(acc[c]) - tt[c];  // signed, |d| <= 255
          acc[c] = acc[c] + dq[c];
        }
        const vu16x8 rg_lo = zip_lo(d[0], d[1]), ba_lo = zip_lo(d[2], d[3]);
        const vu16x8 rg_hi = zip_hi(d[0], d[1]), ba_hi = zip_hi(d[2], d[3]);
        store4(madd(rg_lo, rg_lo) + madd(ba_lo, ba_lo), &err[w][g]);
        store4(madd(rg_hi, rg_hi) + madd(ba_hi, ba_hi), &err[w][g + 4]);
      }
    }
  }

  /// Error of inner texel (rx, ry) at weight w.
  std::uint32_t error(int rx, int ry, int w) const { return std::uint32_t(err[w][slot(rx, ry)]); }
  /// Weight of an interpolated texel under block mode m (1..3) from its stored neighbours.
  int interpolated_weight(int rx, int ry, int m) const {
    const int l = sw[ry][rx - 1], r = sw[ry][rx + 1];
    const int u = sw[ry - 1][rx], d = sw[ry + 1][rx];
    if (m == 1) return (u + d + l + r + 2) >> 2;
    if (m == 2) return (l + r + 1) >> 1;
    return (u + d + 1) >> 1;
  }
  /// Error of stored texel (rx, ry) at its current weight plus that of its interpolated
  /// neighbours (only even texels are read by any).
  std::uint32_t stored_cost(int rx, int ry) const {
    std::uint32_t e = error(rx, ry, sw[ry][rx]);
    if ((rx ^ ry) & 1) return e;
    static constexpr int kN[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};
    for (const auto& n : kN) {
      const int nx = rx + n[0], ny = ry + n[1];
      const int m = bm[ny][nx];
      if (m != 0) e += error(nx, ny, interpolated_weight(nx, ny, m));
    }
    return e;
  }
  /// Under block mode m (1..3): the error of the block's interpolated texels and of its texel
  /// (4, 2), what a change of interpolation variant alters.
  std::uint32_t variant_cost(int m) const {
    std::uint32_t e = error(6, 4, sw[4][6]);
    for (int y = 0; y < 4; ++y) {
      for (int x = (y & 1) ^ 1; x < 8; x += 2) {
        e += error(x + 2, y + 2, interpolated_weight(x + 2, y + 2, m));
      }
    }
    return e;
  }
};

class Descent {
 public:
  Descent(EncoderState& s, Mod2& md) : s_(s), g_(s.g), md_(md) {
    std::vector<Rgba5> ea(g_.blocks()), eb(g_.blocks());
    const std::vector<std::uint64_t> w = s.words();
    expand_endpoints(g_, w.data(), ea.data(), eb.data(), s.threads);
    ua_.resize(g_.texels() * 4);
    ub_.resize(g_.texels() * 4);
    upscale_rows(g_, ea.data(), 0, g_.ph, ua_.data());
    upscale_rows(g_, eb.data(), 0, g_.ph, ub_.data());
    nch_ = s.alpha_mode ? 4 : 3;
  }

  void block(int bx, int by) {
    Region r;
    load(bx, by, r);
    const std::size_t bi = std::size_t(by) * std::size_t(g_.nbx) + std::size_t(bx);
    std::uint8_t& mode = md_.mode[bi];
    auto val = [&](int x, int y) -> std::uint8_t& {
      return md_.value[std::size_t(by * 4 + y) * std::size_t(g_.pw) + std::size_t(bx * 8 + x)];
    };
    // Stored values, in raster order; a candidate replaces the current value only when its
    // cost is strictly lower.
    for (int y = 0; y < 4; ++y) {
      for (int x = 0; x < 8; ++x) {
        if (mode != 0 && ((x ^ y) & 1)) continue;  // interpolated
        const bool restricted = mode == 0 || (x == 0 && y == 0) || (x == 4 && y == 2 && mode != 1);
        std::uint8_t& v = val(x, y);
        std::uint8_t& sw = r.sw[y + 2][x + 2];
        const std::uint8_t cur = v;
        std::uint32_t best = r.stored_cost(x + 2, y + 2);
        std::uint8_t pick = cur;
        for (std::uint8_t c = 0; c < 4; ++c) {
          if (c == cur || (restricted && c != 0 && c != 3)) continue;
          sw = std::uint8_t(kMod4Mode0[c]);
          const std::uint32_t e = r.stored_cost(x + 2, y + 2);
          if (e < best) {
            best = e;
            pick = c;
          }
        }
        v = pick;
        sw = std::uint8_t(kMod4Mode0[pick]);
      }
    }
    if (mode == 0) return;
    // Interpolation variants (texel (4, 2) holds 0 or 3 under H / V only).
    const int cur_mode = mode;
    std::uint8_t& v42 = val(4, 2);
    const std::uint8_t cur42 = v42;
    std::uint32_t best = r.variant_cost(cur_mode);
    int pick_mode = cur_mode;
    std::uint8_t pick42 = cur42;
    for (int m = 1; m <= 3; ++m) {
      if (m == cur_mode) continue;  // the value pass above already chose (4, 2)
      for (std::uint8_t c42 = 0; c42 < 4; ++c42) {
        if (m != 1 && c42 != 0 && c42 != 3) continue;
        r.sw[4][6] = std::uint8_t(kMod4Mode0[c42]);
        const std::uint32_t e = r.variant_cost(m);
        if (e < best) {
          best = e;
          pick_mode = m;
          pick42 = c42;
        }
      }
    }
    mode = std::uint8_t(pick_mode);
    v42 = pick42;
  }

 private:
  // Copies what block (bx, by)'s visit reads into `r` (wrapping at the level's edges).
  void load(int bx, int by, Region& r) const {
    std::memset(r.a8, 0, sizeof(r.a8));
    std::memset(r.q, 0, sizeof(r.q));
    std::memset(r.t, 0, sizeof(r.t));
    const int x0 = bx * 8 - 2, y0 = by * 4 - 2;
    for (int ry = 0; ry < Region::kH; ++ry) {
      const int y = (y0 + ry) & (g_.ph - 1);
      const std::size_t row = std::size_t(y) * std::size_t(g_.pw);
      const std::uint8_t* mrow = &md_.mode[std::size_t(y >> 2) * std::size_t(g_.nbx)];
      const bool inner_row = ry >= 1 && ry <= 6;
      for (int rx = 0; rx < Region::kW; ++rx) {
        const int x = (x0 + rx) & (g_.pw - 1);
        r.sw[ry][rx] = std::uint8_t(kMod4Mode0[md_.value[row + std::size_t(x)]]);
        r.bm[ry][rx] = mrow[x >> 3];
        if (!inner_row || rx < 1 || rx > 10) continue;
        const std::size_t i = (row + std::size_t(x)) * 4;
        const int k = Region::slot(rx, ry);
        for (int c = 0; c < nch_; ++c) {
          const std::uint16_t a = ua_[i + std::size_t(c)], b = ub_[i + std::size_t(c)];
          r.a8[c][k] = std::uint16_t(8 * a);
          r.q[c][k] = std::uint16_t(b - a);
          r.t[c][k] = s_.target[i + std::size_t(c)];
        }
      }
    }
    r.tabulate();
  }

  EncoderState& s_;
  const Grid& g_;
  Mod2& md_;
  std::vector<std::uint8_t> ua_, ub_;
  int nch_ = 3;
};

}  // namespace

std::uint64_t refine_modulation_2bpp(EncoderState& s, int sweeps) {
  const Grid& g = s.g;
  if (g.format != Format::pvrtc1_2bpp || sweeps <= 0) return total_error(s);
  Mod2 md;
  md.value.assign(g.texels(), 0);
  md.mode.assign(g.blocks(), 0);
  for (int by = 0; by < g.nby; ++by) {
    for (int bx = 0; bx < g.nbx; ++bx) {
      const std::size_t bi = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
      std::uint8_t v[32];
      int mode = 0;
      unpack_2bpp_block(s.word(bi), v, mode);
      md.mode[bi] = std::uint8_t(mode);
      for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 8; ++x) {
          md.value[std::size_t(by * 4 + y) * std::size_t(g.pw) + std::size_t(bx * 8 + x)] =
              v[y * 8 + x];
        }
      }
    }
  }
  Descent d(s, md);
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    for_each_block_2x2(g, s.threads, [&](int bx, int by) { d.block(bx, by); });
  }
  for (int by = 0; by < g.nby; ++by) {
    for (int bx = 0; bx < g.nbx; ++bx) {
      const std::size_t bi = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
      std::uint8_t v[32];
      for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 8; ++x) {
          v[y * 8 + x] =
              md.value[std::size_t(by * 4 + y) * std::size_t(g.pw) + std::size_t(bx * 8 + x)];
        }
      }
      s.mod[bi] = pack_2bpp_block(v, md.mode[bi]);
      s.mode[bi] = md.mode[bi] != 0;
    }
  }
  return total_error(s);
}

}  // namespace tessera::pvrtc::detail
