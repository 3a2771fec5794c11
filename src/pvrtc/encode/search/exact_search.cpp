// The exact searches on 4 bpp endpoints: `reseed` (before the least-squares refinement:
// endpoint pairs from a block's own texels) and `search_endpoints_4bpp` (after it: greedy +-1
// and neighbour-copy moves of each block's endpoint codes), each keeping a change only where the
// exactly decoded error of the block's 7x7-texel window drops.
// Where: steps "reseed" and 4 of docs/architecture.md's PVRTC table (the step-by-step
// walkthrough is there, "The exact endpoint search"); driven by passes.cpp per schedule.cpp.
// Pieces: the window evaluators (exact_search_kernel.h, _evaluators.h, _avx2.cpp), the moves
// (exact_search_moves.h), the window layout (exact_search_window.h).
// Exact and deterministic: integer sums, the 2x2 block colouring of the refinement, every kept
// move the same whatever the thread count or evaluator width.
#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "core/check.h"
#include "core/simd.h"
#include "pvrtc/encode/encode_internal.h"
#include "pvrtc/encode/search/exact_search_kernel.h"
#include "pvrtc/encode/search/exact_search_moves.h"

namespace tessera::pvrtc::detail {

namespace {

std::atomic<bool> g_baseline_only{false};

// The window evaluators, chosen once per reseed() / search_endpoints_4bpp() call:
// exact_search_kernel.h's (the evaluators of exact_search_evaluators.h with 4 lanes: SSE2, NEON or
// scalar through simd.h) or exact_search_avx2.cpp's (the same with 8 lanes) where
// exact_search_avx2_active(). Same integers. kWeighted: alpha-weighted colour error (a template
// flag, so that the unweighted search does no per-texel scaling at all; the AVX2 entry points
// read lw.weighted).
template <bool kWeighted>
struct Evaluators {
  bool avx2 = exact_search_avx2_active();
  std::uint32_t local(const LocalWindow& lw, const Rgba5& a, const Rgba5& b,
                      std::uint32_t bound) const {
    if (!avx2) {
      if constexpr (kWeighted) return local_error_weighted(lw, a, b, bound);
      return local_error_simd(lw, a, b, bound);
    }
    const std::int32_t va[4] = {a.r, a.g, a.b, a.a}, vb[4] = {b.r, b.g, b.b, b.a};
    return local_error_avx2(lw, va, vb, bound);
  }
  /// No bound; each texel's error to texel_err[0 .. 52).
  std::uint32_t local_store(const LocalWindow& lw, const Rgba5& a, const Rgba5& b,
                            std::uint32_t* texel_err) const {
    if (avx2) {
      const std::int32_t va[4] = {a.r, a.g, a.b, a.a}, vb[4] = {b.r, b.g, b.b, b.a};
      return local_error_store_avx2(lw, va, vb, texel_err);
    }
    if constexpr (kWeighted) return local_error_simd_t<true, true, true>(lw, a, b, 0, texel_err);
    return lw.nch == 4 ? local_error_simd_t<true, true>(lw, a, b, 0, texel_err)
                       : local_error_simd_t<false, true>(lw, a, b, 0, texel_err);
  }
  std::uint32_t planar(const PlanarWindow& pw, int c, std::int32_t av, std::int32_t bv,
                       std::uint32_t bound) const {
    if (avx2) return planar_error_avx2(pw, c, av, bv, bound);
    return planar_error_t<kWeighted>(pw, c, av, bv, bound);
  }
  void refresh(PlanarWindow& pw, const Rgba5& a, const Rgba5& b) const {
    planar_refresh_t<kWeighted>(pw, a, b);
  }
};

struct Window {
  const EncoderState* s;
  const std::vector<Rgba5>* ea;
  const std::vector<Rgba5>* eb;
  const std::vector<std::uint8_t>* modes;
  int nch;
  int alpha_weight;  ///< The squared alpha error counts this many times (1 or 2).
};

// The exact search counts the squared alpha error twice. Alpha PSNR is over one channel and
// RGB PSNR over three, so alpha error costs more dB per unit; the final modulation choice stays
// unweighted. Weight 3 traded too much RGB (docs/benchmarks/pvrtc_history.md).
constexpr int kSearchAlphaWeight = 2;

// Candidate endpoint pairs for block (bx, by) from its own 4x4 texels: their principal-axis
// split (`split_pairs`: the half means and the two extreme texels, both orientations), then
// the block's current A or B with the brighter / darker extreme or half mean. Writes up to 8
// (A, B) field pairs; returns the count.
int reseed_candidates(const EncoderState& s, int bx, int by, std::uint16_t out[8][2]) {
  const Grid& g = s.g;
  float px[16][4];
  for (int i = 0; i < 16; ++i) {
    const std::uint8_t* t =
        &s.target[(std::size_t(by * 4 + i / 4) * std::size_t(g.pw) + std::size_t(bx * 4 + i % 4)) *
                  4];
    for (int c = 0; c < 4; ++c) px[i][c] = float(t[c]);
  }
  SplitPairs sp;
  if (!split_pairs(px, 16, s.alpha_mode ? 4 : 3, s.alpha_mode, sp)) return 0;
  for (int k = 0; k < 4; ++k) {
    out[k][0] = sp.pairs[k][0];
    out[k][1] = sp.pairs[k][1];
  }
  const std::size_t j = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
  out[4][0] = s.ca[j];
  out[4][1] = sp.high_extreme_b;
  out[5][0] = sp.low_extreme_a;
  out[5][1] = s.cb[j];
  out[6][0] = s.ca[j];
  out[6][1] = sp.high_mean_b;
  out[7][0] = sp.low_mean_a;
  out[7][1] = s.cb[j];
  return 8;
}

// Reorders the window's texels in the SIMD layout: slot i takes texel order[i] (slots 0-48;
// the zero pads stay). The error is an integer sum, so the order changes only where
// the bounded evaluation stops, never a result below the bound.
// kRows 7: seven arrays of 8-byte rows (one per texel), the first 49 rows permuted, in one
// pass; 8: the colour scales too (alpha-weighted windows).
template <int kRows>
void permute_rows(LocalWindow& lw, const std::uint8_t* order) {
  void* const rows[8] = {lw.rest16_a, lw.rest16_b, lw.own16,  lw.t16,
                         lw.bias35,   lw.bias4,    lw.bias4p, lw.scale16};
  std::uint64_t tmp[kRows][49];
  for (int r = 0; r < kRows; ++r) std::memcpy(tmp[r], rows[r], sizeof(tmp[r]));
  for (int i = 0; i < 49; ++i) {
    const int o = order[i];
    TESSERA_DCHECK(o >= 0 && o < 49);  // a texel of the 7x7 window
    for (int r = 0; r < kRows; ++r) {
      std::memcpy(static_cast<char*>(rows[r]) + 8 * i, &tmp[r][o], 8);
    }
  }
}
void permute_local(LocalWindow& lw, const std::uint8_t* order) {
  if (lw.weighted) {
    permute_rows<8>(lw, order);
  } else {
    permute_rows<7>(lw, order);
  }
}

// Block j's bilinear weight on the window's texels where no neighbour wraps onto j itself:
// (1 2 3 4 3 2 1) across times down, in the channel lanes (alpha lane too when [1]).
struct OwnTable {
  std::uint16_t v[2][49][4];
  constexpr OwnTable() : v{} {
    constexpr int kW[7] = {1, 2, 3, 4, 3, 2, 1};
    for (int al = 0; al < 2; ++al) {
      for (int k = 0; k < 49; ++k) {
        for (int c = 0; c < 4; ++c) {
          v[al][k][c] = std::uint16_t(c < 3 || al ? kW[k / 7] * kW[k % 7] : 0);
        }
      }
    }
  }
};
constexpr OwnTable kOwnTable;

// slot_of: the slot of each window texel (raster order, 0-48) where the window is to be laid
// out in another order (the evaluators' sums are integers: any order gives the same results
// below the bound); nullptr: raster order.
template <bool kWeighted>
void build_local(const Window& w, int bx, int by, LocalWindow& lw,
                 const std::uint8_t* slot_of = nullptr) {
  using simd::vu16x8;
  const EncoderState& s = *w.s;
  const Grid& g = s.g;
  const std::size_t j = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
  lw.nch = w.nch;
  lw.punch = s.punch;
  lw.weighted = kWeighted;
  TESSERA_DCHECK(kWeighted == s.weighted() && (!kWeighted || lw.nch == 4));  // alpha mode only
  for (int c = 0; c < 8; ++c) lw.weight16[c] = std::uint16_t((c & 3) == 3 ? w.alpha_weight : 1);
  // The 3x3 blocks around j (wrapping) that the window's texels read: A in lanes 0-3, B in
  // lanes 4-7 (channels past nch zero); block j itself (also where the wrap lands on it) is
  // zero there and its bilinear weight goes to `own` instead.
  alignas(16) std::uint16_t nb[3][3][8];
  bool is_own[3][3];
  for (int dy = 0; dy < 3; ++dy) {
    for (int dx = 0; dx < 3; ++dx) {
      const std::size_t k = std::size_t((by + dy - 1) & (g.nby - 1)) * std::size_t(g.nbx) +
                            std::size_t((bx + dx - 1) & (g.nbx - 1));
      is_own[dy][dx] = k == j;
      const Rgba5& a = (*w.ea)[k];
      const Rgba5& b = (*w.eb)[k];
      const std::int32_t va[4] = {a.r, a.g, a.b, a.a}, vb[4] = {b.r, b.g, b.b, b.a};
      for (int c = 0; c < 4; ++c) {
        const bool used = k != j && c < lw.nch;
        nb[dy][dx][c] = used ? std::uint16_t(va[c]) : 0;
        nb[dy][dx][4 + c] = used ? std::uint16_t(vb[c]) : 0;
      }
    }
  }
  bool own_centre_only = true;  // usual: only the centre block is j (then kOwnTable)
  for (int q = 0; q < 9; ++q) own_centre_only &= q == 4 || !is_own[q / 3][q % 3];
  // Window row / column r (texel by*4 - 1 + r) interpolates neighbour rows (r < 3 ? 0 : 1) and
  // the next with weights 4 - d and d, d = (r + 1) & 3 (the decoder's axis_tap); separably:
  // each row's three vertical mixes first (16-bit lanes, all sums below 2^9).
  constexpr std::int32_t kExclude = 1 << 24;
  const std::uint16_t amask = lw.nch == 4 ? 0xffff : 0;
  const std::uint64_t amask64 = lw.nch == 4 ? ~0ull : 0x0000ffffffffffffull;
  const std::int32_t punch_bias = lw.punch ? 0 : kExclude;
  int k = 0;
  for (int r = 0; r < 7; ++r) {
    const int y = (by * 4 - 1 + r) & (g.ph - 1);
    const int n0y = r < 3 ? 0 : 1, dy = (r + 1) & 3;
    const vu16x8 wy0{std::uint16_t(4 - dy)}, wy1{std::uint16_t(dy)};
    vu16x8 v[3];
    int own_v[3];
    for (int c = 0; c < 3; ++c) {
      v[c] = simd::mullo(simd::load_u16x8(nb[n0y][c]), wy0) +
             simd::mullo(simd::load_u16x8(nb[n0y + 1][c]), wy1);
      own_v[c] = (is_own[n0y][c] ? 4 - dy : 0) + (is_own[n0y + 1][c] ? dy : 0);
    }
    const std::uint8_t* trow = &s.target[std::size_t(y) * std::size_t(g.pw) * 4];
    const std::uint8_t* mrow = &(*w.modes)[std::size_t(y >> 2) * std::size_t(g.nbx)];
    for (int q = 0; q < 7; ++q, ++k) {
      const int x = (bx * 4 - 1 + q) & (g.pw - 1);
      const int sl = slot_of != nullptr ? slot_of[k] : k;  // where texel k goes
      const int n0x = q < 3 ? 0 : 1, dx = (q + 1) & 3;
      const vu16x8 rest = simd::mullo(v[n0x], vu16x8(std::uint16_t(4 - dx))) +
                          simd::mullo(v[n0x + 1], vu16x8(std::uint16_t(dx)));
      alignas(16) std::uint16_t r8[8];
      simd::store_u16x8(rest, r8);
      std::memcpy(lw.rest16_a[sl], r8, 8);
      std::memcpy(lw.rest16_b[sl], r8 + 4, 8);
      if (!own_centre_only) {
        const std::uint16_t own = std::uint16_t((4 - dx) * own_v[n0x] + dx * own_v[n0x + 1]);
        const std::uint16_t own4[4] = {own, own, own, std::uint16_t(own & amask)};
        std::memcpy(lw.own16[sl], own4, 8);
      }
      const std::uint8_t* t = trow + std::size_t(x) * 4;
      if constexpr (std::endian::native == std::endian::little) {
        // The four bytes spread to 16-bit lanes (alpha lane masked for RGB).
        std::uint32_t t32;
        std::memcpy(&t32, t, 4);
        std::uint64_t v64 = t32;
        v64 = (v64 | (v64 << 16)) & 0x0000ffff0000ffffull;
        v64 = (v64 | (v64 << 8)) & 0x00ff00ff00ff00ffull;
        v64 &= amask64;
        std::memcpy(lw.t16[sl], &v64, 8);
      } else {
        const std::uint16_t t4[4] = {t[0], t[1], t[2], std::uint16_t(t[3] & amask)};
        std::memcpy(lw.t16[sl], t4, 8);
      }
      if constexpr (kWeighted) {
        const std::uint16_t sc =
            s.colour_scale[std::size_t(y) * std::size_t(g.pw) + std::size_t(x)];
        const std::uint16_t sc4[4] = {sc, sc, sc, 16};
        std::memcpy(lw.scale16[sl], sc4, 8);
      }
      const bool m1 = mrow[x >> 2] != 0;
      const std::int32_t b35 = m1 ? kExclude : 0, b4 = m1 ? 0 : kExclude,
                         b4p = m1 ? punch_bias : kExclude;
      std::int32_t* p35 = &lw.bias35[sl / 2][(sl & 1) * 2];
      std::int32_t* p4 = &lw.bias4[sl / 2][(sl & 1) * 2];
      std::int32_t* p4p = &lw.bias4p[sl / 2][(sl & 1) * 2];
      p35[0] = p35[1] = b35;
      p4[0] = p4[1] = b4;
      p4p[0] = p4p[1] = b4p;
    }
  }
  if (own_centre_only && slot_of == nullptr) {
    std::memcpy(lw.own16, kOwnTable.v[lw.nch == 4 ? 1 : 0], sizeof(kOwnTable.v[0]));
  } else if (own_centre_only) {
    for (int t = 0; t < 49; ++t) {
      std::memcpy(lw.own16[slot_of[t]], kOwnTable.v[lw.nch == 4 ? 1 : 0][t], 8);
    }
  }
  for (int q = 49; q < 56; ++q) {  // texels 49-55: the zero pad (error 0)
    for (int c = 0; c < 4; ++c) {
      lw.rest16_a[q][c] = lw.rest16_b[q][c] = lw.own16[q][c] = lw.t16[q][c] = 0;
      if constexpr (kWeighted) lw.scale16[q][c] = 0;
    }
  }
  for (int c = 2; c < 4; ++c) {
    lw.bias35[24][c] = 0;
    lw.bias4[24][c] = 0;
    lw.bias4p[24][c] = kExclude;
  }
  for (int p = 25; p < 28; ++p) {  // pads
    for (int c = 0; c < 4; ++c) lw.bias35[p][c] = lw.bias4[p][c] = lw.bias4p[p][c] = 0;
  }
}

// The slots 0-48 by decreasing texel error (bit length; slot order within a class): a
// counting sort on the error's bit length (33 classes, largest first). A window laid out in
// this order for the block's current pair lets a worse candidate reach the bound after fewer
// texels.
void order_by_error(const std::uint32_t* err, std::uint8_t* order) {
  int key[49], start[34] = {};
  for (int i = 0; i < 49; ++i) {
    key[i] = 32 - std::countl_zero(err[i]);
    ++start[32 - key[i] + 1];
  }
  for (int c = 1; c < 34; ++c) start[c] += start[c - 1];
  for (int i = 0; i < 49; ++i) order[start[32 - key[i]]++] = std::uint8_t(i);
}

}  // namespace

int reseed(EncoderState& s, std::uint32_t min_error, std::vector<std::uint8_t>& changed) {
  return reseed(s, min_error, changed, 1);
}

namespace {

template <bool kWeighted>
int reseed_t(EncoderState& s, std::uint32_t min_error, std::vector<std::uint8_t>& changed,
             int alpha_weight) {
  const Grid& g = s.g;
  std::vector<Rgba5> ea(g.blocks()), eb(g.blocks());
  for (std::size_t i = 0; i < g.blocks(); ++i) {
    ea[i] = expand_a(s.ca[i]);
    eb[i] = expand_b(s.cb[i]);
  }
  const Window w{&s, &ea, &eb, &s.mode, s.alpha_mode ? 4 : 3, alpha_weight};
  // A repeat pass visits only blocks with a block changed by the previous pass in their 3x3
  // neighbourhood: elsewhere the window and the candidates are as before.
  std::vector<std::uint8_t> active(g.blocks(), 1);
  if (changed.size() == g.blocks()) {
    for (int by = 0; by < g.nby; ++by) {
      for (int bx = 0; bx < g.nbx; ++bx) {
        std::uint8_t any = 0;
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            any |= changed[std::size_t((by + dy) & (g.nby - 1)) * std::size_t(g.nbx) +
                           std::size_t((bx + dx) & (g.nbx - 1))];
          }
        }
        active[std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx)] = any;
      }
    }
  }
  changed.assign(g.blocks(), 0);
  const Evaluators<kWeighted> ev;
  for_each_block_2x2(g, s.threads, [&](int bx, int by) {
    const std::size_t j = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
    if (!active[j]) return;
    LocalWindow lw;
    build_local<kWeighted>(w, bx, by, lw);
    auto eval = [&](const Rgba5& a, const Rgba5& b, std::uint32_t bound) {
      return ev.local(lw, a, b, bound);
    };
    // Eight candidates only: reordering the texels would cost more than it saves.
    std::uint32_t best = ev.local(lw, ea[j], eb[j], std::numeric_limits<std::uint32_t>::max());
    if (best <= min_error) return;
    std::uint16_t cand[8][2];
    const int n = reseed_candidates(s, bx, by, cand);
    int pick = -1;
    for (int k = 0; k < n; ++k) {
      const std::uint32_t e = eval(expand_a(cand[k][0]), expand_b(cand[k][1]), best);
      if (e < best) {
        best = e;
        pick = k;
      }
    }
    if (pick < 0) return;
    s.ca[j] = cand[pick][0];
    s.cb[j] = cand[pick][1];
    ea[j] = expand_a(s.ca[j]);
    eb[j] = expand_b(s.cb[j]);
    changed[j] = 1;
  });
  int count = 0;
  for (std::uint8_t c : changed) count += c;
  return count;
}

}  // namespace

int reseed(EncoderState& s, std::uint32_t min_error, std::vector<std::uint8_t>& changed,
           int alpha_weight) {
  if (s.g.format != Format::pvrtc1_4bpp) return 0;
  return s.weighted() ? reseed_t<true>(s, min_error, changed, alpha_weight)
                      : reseed_t<false>(s, min_error, changed, alpha_weight);
}

bool exact_search_avx2_active() {
#if defined(TESSERA_NO_SIMD)
  return false;  // the scalar build stays scalar (the AVX2 kernels are still built and tested)
#else
  return avx2_kernels_usable() && !g_baseline_only.load(std::memory_order_relaxed);
#endif
}

bool set_exact_search_baseline_only(bool on) { return g_baseline_only.exchange(on); }

void search_endpoints_4bpp(EncoderState& s, int rounds, int passes, std::uint32_t min_error) {
  search_endpoints_4bpp(s, rounds, passes, min_error, EndpointSearchOptions{});
}

namespace {

// What the block visits of one search_endpoints_4bpp call share.
template <bool kWeighted>
struct BlockSearch {
  const EncoderState& s;
  const Window& w;
  const Evaluators<kWeighted>& ev;
  /// Each block's texels by decreasing error under its pair at its first visit (texel indices,
  /// raster 0-48; valid where has_order): later visits build their window in that order
  /// without sorting again (the texels that err most change little while the search
  /// converges; re-sorting each visit cost more than it saved).
  std::vector<std::uint8_t>& orders;
  std::vector<std::uint8_t>& has_order;
  int passes;
  std::uint32_t min_error;
  bool neighbour_moves;
};

// Lays out block j's window (in its error order, sorting at the first visit) and returns its
// exact error under the block's current pair.
template <bool kWeighted>
std::uint32_t block_window(const BlockSearch<kWeighted>& bs, int bx, int by, std::size_t j,
                           LocalWindow& lw) {
  const Window& w = bs.w;
  std::uint8_t* order = &bs.orders[j * 49];
  if (bs.has_order[j]) {
    std::uint8_t slot_of[49];
    for (int i = 0; i < 49; ++i) slot_of[order[i]] = std::uint8_t(i);
    build_local<kWeighted>(w, bx, by, lw, slot_of);
    return bs.ev.local(lw, (*w.ea)[j], (*w.eb)[j], std::numeric_limits<std::uint32_t>::max());
  }
  build_local<kWeighted>(w, bx, by, lw);
  std::uint32_t err[52];
  const std::uint32_t best = bs.ev.local_store(lw, (*w.ea)[j], (*w.eb)[j], err);
  if (best <= bs.min_error) return best;  // skipped: no order needed
  order_by_error(err, order);
  permute_local(lw, order);
  bs.has_order[j] = 1;
  return best;
}

// One visit of block (bx, by): the greedy descent over the moves of its endpoint pair (and,
// with neighbour moves, its neighbours' A, B or both). Returns the best pair found in
// (pair_a, pair_b); false where the block is skipped or keeps its pair.
template <bool kWeighted>
bool search_block(const BlockSearch<kWeighted>& bs, int bx, int by, std::uint16_t& pair_a,
                  std::uint16_t& pair_b) {
  const EncoderState& s = bs.s;
  const Grid& g = s.g;
  const Evaluators<kWeighted>& ev = bs.ev;
  const std::size_t j = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
  LocalWindow lw;
  std::uint32_t best = block_window(bs, bx, by, j, lw);
  if (best <= bs.min_error) return false;
  std::uint16_t cur_a = s.ca[j], cur_b = s.cb[j];
  // Candidates differing from the current pair in one colour channel only (most
  // of the +-1 moves) go to the channel-planar evaluator; its per-pair tables are
  // built when first needed after each change of the current pair.
  PlanarWindow pw;
  bool planar_built = false;
  unsigned planar_valid = 0;  // bit 0: planar_refresh; bit 1 + c: planar_rest(c)
  Rgba5 cur5a = (*bs.w.ea)[j], cur5b = (*bs.w.eb)[j];
  // c: the one colour channel the candidate changes, else -1 (then the general evaluator).
  auto eval = [&](const Rgba5& a, const Rgba5& b, int c, std::uint32_t bound) {
    if (c < 0) return ev.local(lw, a, b, bound);
    if (!planar_built) {
      build_planar(lw, pw);
      planar_built = true;
    }
    if (!(planar_valid & 1u)) {
      ev.refresh(pw, cur5a, cur5b);
      planar_valid = 1;
    }
    if (!(planar_valid & (2u << c))) {
      planar_rest(pw, c);
      planar_valid |= 2u << c;
    }
    const std::int32_t va[3] = {a.r, a.g, a.b}, vb[3] = {b.r, b.g, b.b};
    return ev.planar(pw, c, va[c], vb[c], bound);
  };
  PairCodes codes(cur_a, cur_b);
  auto take = [&](std::uint16_t na, std::uint16_t nb) {
    cur_a = na;
    cur_b = nb;
    cur5a = expand_a(na);
    cur5b = expand_b(nb);
    codes = PairCodes(na, nb);
    planar_valid = 0;
  };
  SeenPairs seen;
  seen.check_insert((std::uint32_t(cur_a) << 16) | cur_b);
  bool improved = true;
  for (int pass = 0; pass < bs.passes && improved; ++pass) {
    improved = false;
    for (int mv = 0; mv < kMoves; ++mv) {
      std::uint16_t na, nb;
      if (!codes.moved(mv, na, nb)) continue;
      const std::uint32_t key = (std::uint32_t(na) << 16) | nb;
      if (seen.check_insert(key)) continue;
      const std::uint32_t e = eval(expand_a(na), expand_b(nb), kMoveTable.planar[mv], best);
      if (e < best) {
        best = e;
        take(na, nb);
        improved = true;
      }
    }
    if (!bs.neighbour_moves) continue;  // next pass
    // Copy moves: a neighbour's A, its B, or both (edges that cross several
    // blocks want the same pair on both sides; the 2x2 colouring keeps the
    // neighbours fixed while this class is searched, so this is deterministic).
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if (dx == 0 && dy == 0) continue;
        const std::size_t k = std::size_t((by + dy) & (g.nby - 1)) * std::size_t(g.nbx) +
                              std::size_t((bx + dx) & (g.nbx - 1));
        const std::uint16_t cand[3][2] = {{s.ca[k], cur_b}, {cur_a, s.cb[k]}, {s.ca[k], s.cb[k]}};
        for (const auto& c : cand) {
          if (seen.check_insert((std::uint32_t(c[0]) << 16) | c[1])) continue;
          const Rgba5 a = expand_a(c[0]), b = expand_b(c[1]);
          const std::uint32_t e =
              eval(a, b, single_colour_channel(a, b, cur5a, cur5b, lw.nch), best);
          if (e < best) {
            best = e;
            take(c[0], c[1]);
            improved = true;
          }
        }
      }
    }
  }
  pair_a = cur_a;
  pair_b = cur_b;
  return cur_a != s.ca[j] || cur_b != s.cb[j];
}

// The latest step stamp of `changed_at` in the 3x3 blocks around (bx, by) (wrapping).
int latest_change_around(const Grid& g, const std::vector<int>& changed_at, int bx, int by) {
  int latest = -1;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      latest =
          std::max(latest, changed_at[std::size_t((by + dy) & (g.nby - 1)) * std::size_t(g.nbx) +
                                      std::size_t((bx + dx) & (g.nbx - 1))]);
    }
  }
  return latest;
}

template <bool kWeighted>
void search_endpoints_4bpp_t(EncoderState& s, int rounds, int passes, std::uint32_t min_error,
                             const EndpointSearchOptions& options) {
  const Grid& g = s.g;
  std::vector<Rgba5> ea(g.blocks()), eb(g.blocks());
  for (std::size_t i = 0; i < g.blocks(); ++i) {
    ea[i] = expand_a(s.ca[i]);
    eb[i] = expand_b(s.cb[i]);
  }
  const Window w{&s, &ea, &eb, &s.mode, s.alpha_mode ? 4 : 3, kSearchAlphaWeight};
  // A block's search depends only on the endpoints in its 3x3 neighbourhood (and the modes,
  // fixed here): once it has been searched, it is searched again only after one of those
  // changed (step stamps: phase 4 * round + colour class). Skipping is exact, so rounds can run
  // to convergence at a fraction of the cost.
  std::vector<int> changed_at(g.blocks(), -1), searched_at(g.blocks(), -2);
  // Seeded: the first round searches only the seed blocks; the rest wait for a changed
  // neighbour.
  if (options.seeds != nullptr) {
    for (std::size_t j = 0; j < g.blocks(); ++j) {
      if (!(*options.seeds)[j]) searched_at[j] = 0;
    }
  }
  std::vector<std::uint8_t> orders(g.blocks() * 49), has_order(g.blocks(), 0);
  const Evaluators<kWeighted> ev;
  const BlockSearch<kWeighted> bs{s,         w,      ev,        orders,
                                  has_order, passes, min_error, options.neighbour_moves};
  double searched_total = 0, searched_before = 0;  // for the progress reports
  for (int round = 0; round < rounds; ++round) {
    std::vector<std::uint8_t> any_change(std::size_t(g.nby / 2), 0);
    for_each_block_2x2(g, s.threads, [&](int bx, int by) {
      const int step = 4 * round + (bx & 1) + 2 * (by & 1);  // the colour class's phase
      const std::size_t j = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
      if (latest_change_around(g, changed_at, bx, by) < searched_at[j]) return;
      searched_at[j] = step;
      std::uint16_t a, b;
      if (!search_block(bs, bx, by, a, b)) return;
      s.ca[j] = a;
      s.cb[j] = b;
      ea[j] = expand_a(a);
      eb[j] = expand_b(b);
      changed_at[j] = step;
      any_change[std::size_t(by / 2)] = 1;
    });
    if (s.progress.active()) {
      // Blocks searched this round (stamped with one of its steps): the round's share of work.
      const double searched = double(std::count_if(searched_at.begin(), searched_at.end(),
                                                   [&](int t) { return t >= 4 * round; }));
      searched_total += searched;
      s.progress.at(round + 1 == rounds
                        ? 1.0
                        : convergence_fraction(searched_total, searched, searched_before));
      searched_before = searched;
    }
    if (std::find(any_change.begin(), any_change.end(), 1) == any_change.end()) break;
  }
  // The windows were scored with every texel's best code within its block's mode: re-choosing
  // the modulation (and mode) of every block reproduces or improves on that.
  choose_modulation(s);
}

}  // namespace

void search_endpoints_4bpp(EncoderState& s, int rounds, int passes, std::uint32_t min_error,
                           const EndpointSearchOptions& options) {
  if (s.g.format != Format::pvrtc1_4bpp || rounds <= 0) return;
  if (s.weighted()) {
    search_endpoints_4bpp_t<true>(s, rounds, passes, min_error, options);
  } else {
    search_endpoints_4bpp_t<false>(s, rounds, passes, min_error, options);
  }
}

}  // namespace tessera::pvrtc::detail
