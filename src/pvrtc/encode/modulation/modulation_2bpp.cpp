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
// The per-block-row arithmetic of the passes is written once (modulation_2bpp_rows.h) and runs
// here over the 4-lane types (one block a step), or where the CPU has AVX2 (checked once per
// call) in modulation_2bpp_avx2.cpp over the 8-lane ones (two blocks a step; rows of an even
// number of blocks: every 2 bpp grid, nbx being a power of two >= 2). Allocation, the maps,
// threading and the choice of width stay here. Same output.
#include "pvrtc/encode/modulation/modulation_2bpp.h"

#include <atomic>
#include <vector>

#include "core/simd.h"
#include "pvrtc/encode/modulation/modulation_2bpp_avx2.h"
#include "pvrtc/encode/modulation/modulation_2bpp_rows.h"
#include "pvrtc/encode/modulation/planar_endpoints.h"

namespace tessera::pvrtc::detail {

namespace {

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

/// Per-thread column-sum buffer for one block row.
class ColumnSums {
 public:
  ColumnSums(const Grid& g, const std::vector<std::uint16_t>& ep, bool alpha)
      : g_(g), ep_(ep), alpha_(alpha), vstride_(std::size_t(g.nbx) + 8), vp_(4 * 8 * vstride_, 0) {}

  /// The column sums and target rows of block row `by` into r.v, r.t and r.vstride.
  void fill(const EncoderState& s, int by, Mod2Row& r) {
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

/// Calls fn(by, cs) for every block row, rows in parallel; each worker has its own column-sum
/// buffer `cs` (which fn fills with `cs.fill` when it needs the sums).
template <class Fn>
void for_each_block_row(const EncoderState& s, const std::vector<std::uint16_t>& ep, bool alpha,
                        Fn&& fn) {
  parallel_for(0, s.g.nby, 4,
               [&](std::int64_t by0, std::int64_t by1) {
                 ColumnSums cs(s.g, ep, alpha);
                 for (int by = int(by0); by < int(by1); ++by) fn(by, cs);
               },
               {s.threads});
}

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
  const std::vector<std::uint16_t> ep = planar_endpoints(s);
  Maps maps;
  maps.stride = std::size_t(g.pw) + 2 * kGuard;
  maps.greedy.assign(maps.stride * std::size_t(g.ph), 0);
  maps.decoded.assign(maps.stride * std::size_t(g.ph), 0);
  std::vector<std::uint32_t> err0(nb);
  const int hm = g.ph - 1;
  const bool avx2 = use_avx2(g);
  // Block row `by` of the passes: map rows by * 4 - 1 .. by * 4 + 4 of `in`, by * 4 .. by * 4 + 3
  // of `out` (the column sums and target rows: `ColumnSums::fill`).
  const auto row_of = [&](int by, std::vector<std::uint8_t>* in, std::vector<std::uint8_t>* out) {
    Mod2Row m{};
    const std::size_t b0 = std::size_t(by) * std::size_t(g.nbx);
    for (int j = 0; j < 4; ++j) m.out[j] = out ? maps.row(*out, by * 4 + j) : nullptr;
    for (int j = -1; j <= 4; ++j) m.in[j + 1] = in ? maps.row(*in, (by * 4 + j) & hm) : nullptr;
    m.nbx = g.nbx;
    m.err0 = &err0[b0];
    m.mod = &s.mod[b0];
    m.mode = &s.mode[b0];
    return m;
  };

  // Pass 1: greedy codes, A/B choice, mode 0.
  for_each_block_row(s, ep, kAlpha, [&](int by, ColumnSums& cs) {
    Mod2Row m = row_of(by, nullptr, &maps.greedy);
    cs.fill(s, by, m);
    if (avx2) {
      mod2_pass1_row_avx2(m, kAlpha);
    } else {
      mod2_pass1<kAlpha, simd::vu16x8>(m);
    }
    for (int j = 0; j < 4; ++j) fill_guards(maps.row(maps.greedy, by * 4 + j), g.pw);
  });

  // Pass 2: the interpolated variants against the greedy map; the choice.
  for_each_block_row(s, ep, kAlpha, [&](int by, ColumnSums& cs) {
    Mod2Row m = row_of(by, &maps.greedy, &maps.decoded);
    cs.fill(s, by, m);
    if (avx2) {
      mod2_pass2_row_avx2(m, kAlpha);
    } else {
      mod2_pass2<kAlpha, simd::vu16x8>(m);
    }
    for (int j = 0; j < 4; ++j) fill_guards(maps.row(maps.decoded, by * 4 + j), g.pw);
  });

  // Pass 3: exact error of the decode (the column sums only for rows with a mode-1 block).
  std::vector<std::uint64_t> row_err(std::size_t(g.nby), 0);
  for_each_block_row(s, ep, kAlpha, [&](int by, ColumnSums& cs) {
    Mod2Row m = row_of(by, &maps.decoded, nullptr);
    bool any1 = false;
    for (int bx = 0; bx < g.nbx; ++bx) any1 |= m.mode[bx] != 0;
    if (any1) cs.fill(s, by, m);
    row_err[std::size_t(by)] =
        avx2 ? mod2_pass3_row_avx2(m, kAlpha) : mod2_pass3<kAlpha, simd::vu16x8>(m);
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
