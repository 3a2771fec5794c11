// Exact local search on 2 bpp endpoints (high quality).
//
// At 2 bpp the least-squares refinement (least_squares_refinement.cpp) stalls short of
// PVRTexTool's best: given pvrtcbest's own endpoints, our modulation choice and descent decode
// them better than PVRTexTool's modulation does, so what was missing were the endpoints. This
// search works as the 4 bpp one (exact_search.cpp), on the 2 bpp geometry: a block's A and B reach
// the 15x7 texels x in [8 bx - 3, 8 bx + 11], y in [4 by - 1, 4 by + 5] (bilinear weights summing
// to 32), and a candidate pair is scored over that window with the other blocks' endpoints fixed
// and every texel taking its best weight among those its block's mode allows: {0, 8} in direct
// blocks; in interpolated blocks {0, 3, 5, 8} on the stored checkerboard texels ({0, 8} at texel
// (0, 0), whose low bit is the variant flag) and {0, 3, 4, 5, 8} on the interpolated ones. The last
// set is a relaxation: an interpolated texel's weight is the mean of its stored neighbours, which
// the score does not tie together. So after the search the modulation is chosen again and descended
// exactly (modulation_2bpp*.cpp), the least-squares refinement runs once more, and the whole
// result is kept only where its exact total error is below the one before the search.
//
// Candidates per block visit: principal-axis pairs of the block's own 8x4 texels and of its
// 15x7 window (`split_pairs`), each neighbour's A, B or both, then the +-1 code moves of
// exact_search_moves.h until a sweep improves nothing. Blocks are visited in the 2x2 colouring
// (deterministic for any thread count); after the first round a block is searched again only
// when an endpoint in its 3x3 neighbourhood changed (its score depends on nothing else).
// Window errors are integer sums over the texels in decreasing order of their error under the
// current pair, stopping at the best so far, as in exact_search.cpp; the evaluator is written
// once over the lane types (exact_search_2bpp_evaluator.h): four texels a step, or eight where
// the CPU has AVX2 (exact_search_2bpp_avx2.cpp; the same integers).
#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <vector>

#include "core/simd.h"
#include "pvrtc/encode/encode_internal.h"
#include "pvrtc/encode/search/exact_search_2bpp_evaluator.h"
#include "pvrtc/encode/search/exact_search_moves.h"
#include "pvrtc/encode/search/exact_search_window.h"

namespace tessera::pvrtc::detail {

namespace {

constexpr int kWindowW = Window2::kWidth, kWindowH = Window2::kHeight;
constexpr int kTexels = Window2::kTexels;  // 105
constexpr int kSlots = Window2::kSlots;    // 112
constexpr std::int32_t kExclude = Window2::kExclude;
// The squared alpha error counts twice in the window score, as in the 4 bpp search.
constexpr int kAlphaWeight = 2;
// Round bound; rounds stop earlier once no block changed.
constexpr int kMaxRounds = 16;
// Sweeps of the move list per block visit (each sweep after one that improved).
constexpr int kMovePasses = 4;
// Shares of `search_endpoints_2bpp`'s time, for the progress reports (seconds per megapixel on
// one thread, as passes.cpp's costs): the search rounds (every block, or seeded after the
// crossover), the modulation choice and its 3 descent sweeps, the refinement, the last 2
// descent sweeps.
constexpr double kSearchShare = 4.0, kSeededSearchShare = 1.9, kDescentShare = 0.6,
                 kRefineShare = 0.33, kFinalShare = 0.45;

// The bounded window error of the endpoint codes (ca, cb) (exact_search_2bpp_evaluator.h: the
// decoder's arithmetic, four texels a step); `avx2` (exact_search_avx2_active(), read once per
// search): the same evaluator with the 8-lane types (exact_search_2bpp_avx2.cpp), the same
// integers. Takes the codes, not the expanded endpoints: passed by reference, those would be
// split into eight scalar arguments for this one hot call.
std::uint32_t eval(const Window2& w, std::uint16_t ca, std::uint16_t cb, std::uint32_t bound,
                   bool avx2) {
  const Rgba5 a = expand_a(ca), b = expand_b(cb);
  const std::int32_t va[4] = {a.r, a.g, a.b, a.a}, vb[4] = {b.r, b.g, b.b, b.a};
  if (avx2) return window2_error_avx2(w, va, vb, bound);
  return window2_error_bounded<simd::vu16x8>(w, va, vb, bound);
}

// Fills the window of block (bx, by) from the expanded endpoints of every block.
void build_window(const EncoderState& s, const std::vector<Rgba5>& ea, const std::vector<Rgba5>& eb,
                  int bx, int by, Window2& w) {
  const Grid& g = s.g;
  const std::size_t j = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
  const int nch = s.alpha_mode ? 4 : 3;
  w.nch = nch;
  for (int c = 0; c < 8; ++c) w.weight16[c] = std::uint16_t((c & 3) == 3 ? kAlphaWeight : 1);
  int k = 0;
  for (int wy = 0; wy < kWindowH; ++wy) {
    const int y = (by * 4 - 1 + wy) & (g.ph - 1);
    const AxisTap ty = axis_tap(y, 4, g.ph);
    const std::uint8_t* trow = &s.target[std::size_t(y) * std::size_t(g.pw) * 4];
    for (int wx = 0; wx < kWindowW; ++wx, ++k) {
      const int x = (bx * 8 - 3 + wx) & (g.pw - 1);
      const AxisTap tx = axis_tap(x, 8, g.pw);
      const std::size_t r0 = std::size_t(ty.b0) * std::size_t(g.nbx);
      const std::size_t r1 = std::size_t(ty.b1) * std::size_t(g.nbx);
      const std::size_t blk[4] = {r0 + std::size_t(tx.b0), r0 + std::size_t(tx.b1),
                                  r1 + std::size_t(tx.b0), r1 + std::size_t(tx.b1)};
      const std::int32_t wt[4] = {(8 - tx.d) * (4 - ty.d), tx.d * (4 - ty.d), (8 - tx.d) * ty.d,
                                  tx.d * ty.d};
      std::int32_t ra[4] = {0, 0, 0, 0}, rb[4] = {0, 0, 0, 0}, own = 0;
      for (int i = 0; i < 4; ++i) {
        if (blk[i] == j) {
          own += wt[i];
          continue;
        }
        const Rgba5& pa = ea[blk[i]];
        const Rgba5& pb = eb[blk[i]];
        const std::int32_t va[4] = {pa.r, pa.g, pa.b, pa.a}, vb[4] = {pb.r, pb.g, pb.b, pb.a};
        for (int c = 0; c < 4; ++c) {
          ra[c] += wt[i] * va[c];
          rb[c] += wt[i] * vb[c];
        }
      }
      const std::uint8_t* t = trow + std::size_t(x) * 4;
      for (int c = 0; c < 4; ++c) {
        const bool used = c < nch;
        w.rest_a[k][c] = used ? std::uint16_t(ra[c]) : 0;
        w.rest_b[k][c] = used ? std::uint16_t(rb[c]) : 0;
        w.own[k][c] = used ? std::uint16_t(own) : 0;
        w.t[k][c] = used ? std::uint16_t(t[c]) : 0;
      }
      // The blends the texel's block mode allows (see the file comment).
      const bool interpolated_block =
          s.mode[std::size_t(y >> 2) * std::size_t(g.nbx) + std::size_t(x >> 3)] != 0;
      std::int32_t b35 = kExclude, b4 = kExclude;  // direct: A or B
      if (interpolated_block) {
        if (((x ^ y) & 1) != 0) {
          b35 = b4 = 0;  // interpolated texel
        } else if ((x & 7) != 0 || (y & 3) != 0) {
          b35 = 0;  // stored texel other than (0, 0)
        }
      }
      w.bias35[k] = b35;
      w.bias4[k] = b4;
    }
  }
  for (; k < kSlots; ++k) {
    for (int c = 0; c < 4; ++c) w.rest_a[k][c] = w.rest_b[k][c] = w.own[k][c] = w.t[k][c] = 0;
    w.bias35[k] = w.bias4[k] = 0;
  }
}

// Reorders the window's texels by decreasing error (bit length) under (a, b), the block's
// current pair, so that a worse candidate reaches the bound sooner; returns the window error
// under (a, b). The sum is of integers, so the order changes only where a bounded evaluation
// stops, never a result below the bound.
std::uint32_t order_window(Window2& w, const Rgba5& a, const Rgba5& b, bool avx2) {
  alignas(32) std::uint32_t err[kSlots];
  const std::int32_t va[4] = {a.r, a.g, a.b, a.a}, vb[4] = {b.r, b.g, b.b, b.a};
  const std::uint32_t total = avx2 ? window2_error_store_avx2(w, va, vb, err)
                                   : window2_error_stored<simd::vu16x8>(w, va, vb, err);
  int key[kTexels], start[34] = {};
  for (int i = 0; i < kTexels; ++i) {
    key[i] = 32 - std::countl_zero(err[i]);
    ++start[32 - key[i] + 1];
  }
  for (int c = 1; c < 34; ++c) start[c] += start[c - 1];
  std::uint8_t order[kTexels];
  for (int i = 0; i < kTexels; ++i) order[start[32 - key[i]]++] = std::uint8_t(i);
  const Window2 src = w;
  for (int i = 0; i < kTexels; ++i) {
    const int o = order[i];
    std::memcpy(w.rest_a[i], src.rest_a[o], 8);
    std::memcpy(w.rest_b[i], src.rest_b[o], 8);
    std::memcpy(w.own[i], src.own[o], 8);
    std::memcpy(w.t[i], src.t[o], 8);
    w.bias35[i] = src.bias35[o];
    w.bias4[i] = src.bias4[o];
  }
  return total;
}

// Principal-axis candidate pairs from the block's own 8x4 texels and from its 15x7 window.
// Writes up to 8 (A, B) field pairs; returns the count.
int seed_candidates(const EncoderState& s, int bx, int by, std::uint16_t out[8][2]) {
  const Grid& g = s.g;
  const int nch = s.alpha_mode ? 4 : 3;
  float px[kTexels][4];
  int n = 0;
  for (int area = 0; area < 2; ++area) {
    const int w = area == 0 ? 8 : kWindowW, h = area == 0 ? 4 : kWindowH;
    const int x0 = area == 0 ? bx * 8 : bx * 8 - 3, y0 = area == 0 ? by * 4 : by * 4 - 1;
    for (int i = 0; i < w * h; ++i) {
      const int x = (x0 + i % w) & (g.pw - 1), y = (y0 + i / w) & (g.ph - 1);
      const std::uint8_t* t = &s.target[(std::size_t(y) * std::size_t(g.pw) + std::size_t(x)) * 4];
      for (int c = 0; c < 4; ++c) px[i][c] = float(t[c]);
    }
    SplitPairs sp;
    if (!split_pairs(px, w * h, nch, s.alpha_mode, sp)) continue;
    for (int k = 0; k < 4; ++k, ++n) {
      out[n][0] = sp.pairs[k][0];
      out[n][1] = sp.pairs[k][1];
    }
  }
  return n;
}

// The search rounds (see the file comment); returns the number of block changes. `seeds`
// (optional): the first round searches only the flagged blocks.
int search(EncoderState& s, const std::vector<std::uint8_t>* seeds) {
  const Grid& g = s.g;
  std::vector<Rgba5> ea(g.blocks()), eb(g.blocks());
  for (std::size_t i = 0; i < g.blocks(); ++i) {
    ea[i] = expand_a(s.ca[i]);
    eb[i] = expand_b(s.cb[i]);
  }
  // Step stamps (4 * round + colour class): a block is searched again only after a block in
  // its 3x3 neighbourhood changed since its last search.
  std::vector<int> changed_at(g.blocks(), -1), searched_at(g.blocks(), -2);
  std::vector<int> changes_per_row(std::size_t(g.nby), 0);
  const bool avx2 = exact_search_avx2_active();
  if (seeds != nullptr) {
    for (std::size_t j = 0; j < g.blocks(); ++j) {
      if (!(*seeds)[j]) searched_at[j] = 0;  // waits for a changed neighbour
    }
  }
  double searched_total = 0, searched_before = 0;  // for the progress reports
  for (int round = 0; round < kMaxRounds; ++round) {
    std::vector<std::uint8_t> any_change(std::size_t(g.nby / 2), 0);
    for_each_block_2x2(g, s.threads, [&](int bx, int by) {
      const int step = 4 * round + (bx & 1) + 2 * (by & 1);
      const std::size_t j = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
      int latest = -1;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          latest = std::max(latest,
                            changed_at[std::size_t((by + dy) & (g.nby - 1)) * std::size_t(g.nbx) +
                                       std::size_t((bx + dx) & (g.nbx - 1))]);
        }
      }
      if (latest < searched_at[j]) return;
      searched_at[j] = step;
      Window2 w;
      build_window(s, ea, eb, bx, by, w);
      std::uint32_t best = order_window(w, ea[j], eb[j], avx2);
      if (best == 0) return;
      std::uint16_t cur_a = s.ca[j], cur_b = s.cb[j];
      SeenPairs seen;
      seen.check_insert((std::uint32_t(cur_a) << 16) | cur_b);
      bool improved = false;
      auto consider = [&](std::uint16_t na, std::uint16_t nb) {
        if (seen.check_insert((std::uint32_t(na) << 16) | nb)) return;
        const std::uint32_t e = eval(w, na, nb, best, avx2);
        if (e < best) {
          best = e;
          cur_a = na;
          cur_b = nb;
          improved = true;
        }
      };
      if (round == 0) {  // the seeds do not depend on the neighbours: once is enough
        std::uint16_t cand[8][2];
        const int n = seed_candidates(s, bx, by, cand);
        for (int k = 0; k < n; ++k) consider(cand[k][0], cand[k][1]);
      }
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          if (dx == 0 && dy == 0) continue;
          const std::size_t k = std::size_t((by + dy) & (g.nby - 1)) * std::size_t(g.nbx) +
                                std::size_t((bx + dx) & (g.nbx - 1));
          consider(s.ca[k], s.cb[k]);
          consider(s.ca[k], cur_b);
          consider(cur_a, s.cb[k]);
        }
      }
      for (int pass = 0; pass < kMovePasses; ++pass) {
        improved = false;
        for (int mv = 0; mv < kMoves; ++mv) {
          std::uint16_t na, nb;
          if (!PairCodes(cur_a, cur_b).moved(mv, na, nb)) continue;
          consider(na, nb);
        }
        if (!improved) break;
      }
      if (cur_a == s.ca[j] && cur_b == s.cb[j]) return;
      s.ca[j] = cur_a;
      s.cb[j] = cur_b;
      ea[j] = expand_a(cur_a);
      eb[j] = expand_b(cur_b);
      changed_at[j] = step;
      any_change[std::size_t(by / 2)] = 1;
      ++changes_per_row[std::size_t(by)];
    });
    if (s.progress.active()) {
      // Blocks searched this round (stamped with one of its steps): the round's share of work.
      const double searched = double(std::count_if(searched_at.begin(), searched_at.end(),
                                                   [&](int t) { return t >= 4 * round; }));
      searched_total += searched;
      s.progress.at(convergence_fraction(searched_total, searched, searched_before));
      searched_before = searched;
    }
    if (std::find(any_change.begin(), any_change.end(), 1) == any_change.end()) break;
  }
  int total = 0;
  for (int c : changes_per_row) total += c;
  return total;
}

}  // namespace

std::uint32_t window_error_2bpp(const EncoderState& s, int bx, int by, std::uint16_t ca,
                                std::uint16_t cb, std::uint32_t bound, bool ordered) {
  const Grid& g = s.g;
  std::vector<Rgba5> ea(g.blocks()), eb(g.blocks());
  for (std::size_t i = 0; i < g.blocks(); ++i) {
    ea[i] = expand_a(s.ca[i]);
    eb[i] = expand_b(s.cb[i]);
  }
  Window2 w;
  build_window(s, ea, eb, bx, by, w);
  const std::size_t j = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
  const bool avx2 = exact_search_avx2_active();
  if (ordered) order_window(w, ea[j], eb[j], avx2);
  return eval(w, ca, cb, bound, avx2);
}

std::uint64_t search_endpoints_2bpp(EncoderState& s, std::uint64_t error) {
  return search_endpoints_2bpp(s, error, nullptr);
}

std::uint64_t search_endpoints_2bpp(EncoderState& s, std::uint64_t error,
                                    const std::vector<std::uint8_t>* seeds) {
  if (s.g.format != Format::pvrtc1_2bpp) return error;
  const std::vector<std::uint16_t> ca = s.ca, cb = s.cb;
  const std::vector<std::uint8_t> mode = s.mode;
  const std::vector<std::uint32_t> mod = s.mod;
  // Progress: the search rounds, the modulation and its descent, the refinement, the descent.
  const Progress whole = s.progress;
  const double search_share = seeds != nullptr ? kSeededSearchShare : kSearchShare;
  ProgressSteps steps(whole, search_share + kDescentShare + kRefineShare + kFinalShare);
  s.progress = steps.next(search_share);
  const int changes = search(s, seeds);
  s.progress = whole;
  if (changes == 0) return error;
  steps.next(kDescentShare);
  choose_modulation(s);
  std::uint64_t e = refine_modulation_2bpp(s, 3);
  s.progress = steps.next(kRefineShare);
  refine(s, 16, e);
  s.progress = whole;
  steps.next(kFinalShare);
  e = refine_modulation_2bpp(s, 2);
  if (e < error) return e;
  s.ca = ca;
  s.cb = cb;
  s.mode = mode;
  s.mod = mod;
  return error;
}

}  // namespace tessera::pvrtc::detail
