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
#include <cstdint>
#include <vector>

#include "pvrtc/encode_internal.h"

namespace tessera::pvrtc::detail {

namespace {

// The unpacked modulation of a level: stored values per texel and the mode of every block.
struct Mod2 {
  const Grid* g = nullptr;
  std::vector<std::uint8_t> value;  ///< 0..3 per texel (pw * ph); unused on interpolated texels
  std::vector<std::uint8_t> mode;   ///< 0 direct, 1 H+V, 2 H only, 3 V only, per block

  int block_mode(int x, int y) const {
    return mode[std::size_t(y >> 2) * std::size_t(g->nbx) + std::size_t(x >> 3)];
  }
  int stored_weight(int x, int y) const {
    return kMod4Mode0[value[std::size_t(y & (g->ph - 1)) * std::size_t(g->pw) +
                            std::size_t(x & (g->pw - 1))]];
  }
  bool interpolated(int x, int y) const { return ((x ^ y) & 1) && block_mode(x, y) != 0; }
  /// Effective weight of texel (x, y) (in range), exactly as `modulation_map`.
  int weight(int x, int y) const {
    const int m = block_mode(x, y);
    if (m == 0 || ((x ^ y) & 1) == 0) return stored_weight(x, y);
    const int l = stored_weight(x - 1, y), r = stored_weight(x + 1, y);
    const int u = stored_weight(x, y - 1), d = stored_weight(x, y + 1);
    if (m == 1) return (u + d + l + r + 2) / 4;
    if (m == 2) return (l + r + 1) / 2;
    return (u + d + 1) / 2;
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

  /// Squared error of texel (x, y) (wrapped) with its current weight.
  std::uint32_t texel_error(int x, int y) const {
    x &= g_.pw - 1;
    y &= g_.ph - 1;
    const int m = md_.weight(x, y);
    const std::size_t i = (std::size_t(y) * std::size_t(g_.pw) + std::size_t(x)) * 4;
    std::uint32_t e = 0;
    for (int c = 0; c < nch_; ++c) {
      const int v = (ua_[i + std::size_t(c)] * (8 - m) + ub_[i + std::size_t(c)] * m) / 8;
      const int d = v - s_.target[i + std::size_t(c)];
      e += std::uint32_t(d * d);
    }
    return e;
  }

  /// Error of texel (x, y) and of its interpolated neighbours (those that read its value).
  std::uint32_t stored_cost(int x, int y) const {
    std::uint32_t e = texel_error(x, y);
    if ((x ^ y) & 1) return e;  // an odd texel is read by no one
    static constexpr int kN[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};
    for (const auto& n : kN) {
      const int nx = (x + n[0]) & (g_.pw - 1), ny = (y + n[1]) & (g_.ph - 1);
      if (md_.interpolated(nx, ny)) e += texel_error(nx, ny);
    }
    return e;
  }

  /// Error of the block's interpolated texels and of texel (4, 2) (what a variant change
  /// alters).
  std::uint32_t variant_cost(int bx, int by) const {
    std::uint32_t e = texel_error(bx * 8 + 4, by * 4 + 2);
    for (int y = 0; y < 4; ++y) {
      for (int x = (y & 1) ^ 1; x < 8; x += 2) e += texel_error(bx * 8 + x, by * 4 + y);
    }
    return e;
  }

  void block(int bx, int by) {
    const std::size_t bi = std::size_t(by) * std::size_t(g_.nbx) + std::size_t(bx);
    std::uint8_t& mode = md_.mode[bi];
    auto val = [&](int x, int y) -> std::uint8_t& {
      return md_.value[std::size_t(by * 4 + y) * std::size_t(g_.pw) + std::size_t(bx * 8 + x)];
    };
    // Stored values.
    for (int y = 0; y < 4; ++y) {
      for (int x = 0; x < 8; ++x) {
        if (mode != 0 && ((x ^ y) & 1)) continue;  // interpolated
        const bool restricted =
            mode == 0 || (x == 0 && y == 0) || (x == 4 && y == 2 && mode != 1);
        std::uint8_t& v = val(x, y);
        const std::uint8_t cur = v;
        std::uint32_t best = stored_cost(bx * 8 + x, by * 4 + y);
        std::uint8_t pick = cur;
        for (std::uint8_t c = 0; c < 4; ++c) {
          if (c == cur || (restricted && c != 0 && c != 3)) continue;
          v = c;
          const std::uint32_t e = stored_cost(bx * 8 + x, by * 4 + y);
          if (e < best) {
            best = e;
            pick = c;
          }
        }
        v = pick;
      }
    }
    if (mode == 0) return;
    // Interpolation variants (texel (4, 2) holds 0 or 3 under H / V only).
    const int cur_mode = mode;
    std::uint8_t& v42 = val(4, 2);
    const std::uint8_t cur42 = v42;
    std::uint32_t best = variant_cost(bx, by);
    int pick_mode = cur_mode;
    std::uint8_t pick42 = cur42;
    for (int m = 1; m <= 3; ++m) {
      if (m == cur_mode) continue;  // the value pass above already chose (4, 2)
      for (std::uint8_t c42 = 0; c42 < 4; ++c42) {
        if (m != 1 && c42 != 0 && c42 != 3) continue;
        mode = std::uint8_t(m);
        v42 = c42;
        const std::uint32_t e = variant_cost(bx, by);
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
  md.g = &g;
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
