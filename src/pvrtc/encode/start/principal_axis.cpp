// Principal-axis initial endpoints for the refinement of Quality::normal / high.
//
// Intensity dilation (the paper's method, Quality::fast) labels extrema by luma only, so two
// colours of similar brightness, e.g. both sides of the wrap-around seam of a texture, end up
// averaged into one muddy pair of endpoints that refinement cannot pull apart again. Here each
// block's endpoints come from its bilinear footprint (the 8x4-block-wide texel window its
// colours reach, tent-weighted, wrapping): the texels are split by the sign of their projection
// on the principal axis of their colours and each half's weighted mean becomes one endpoint;
// the brighter half is B (high), as in the paper, so neighbouring blocks blend consistently.
// Where the two halves are about equally bright that order is arbitrary, and
// `orient_endpoints` (below) sets it from the neighbouring blocks instead.
#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "pvrtc/encode/encode_internal.h"

namespace tessera::pvrtc::detail {

namespace {

// One block's endpoints (see the file comment): NCH channels (3, or 4 with alpha) span the
// covariance; writes 4 floats each to low and high.
template <int NCH>
void principal_block(const EncoderState& s, int bx, int by, float* low, float* high) {
  const Grid& g = s.g;
  const int bw = g.bw, wm = g.pw - 1, hm = g.ph - 1;
  // Texel (u, v) of the window (u in 1..2bw-1, v in 1..7) has weight
  // wy(v) wx(u) = (v < 4 ? v : 8 - v) (u < bw ? u : 2bw - u).
  const int x0 = bx * bw - bw / 2;
  // Calls fn(texel, weight) for every texel of the window, in the same order each time.
  auto for_each_texel = [&](auto&& fn) {
    for (int v = 1; v < 8; ++v) {
      const int wy = v < 4 ? v : 8 - v;
      const std::uint8_t* row =
          &s.target[std::size_t((by * 4 - 2 + v) & hm) * std::size_t(g.pw) * 4];
      for (int u = 1; u < 2 * bw; ++u) {
        fn(row + std::size_t((x0 + u) & wm) * 4, std::int32_t(wy * (u < bw ? u : 2 * bw - u)));
      }
    }
  };
  // Weighted first and second moments in integers: exact, so the mean is the same
  // double as summing in doubles (the sums stay below 2^31: at most 7 x 15 texels
  // of weight <= 32 times 255^2), and one pass instead of two.
  std::int32_t wsum_i = 0, sum[4] = {0, 0, 0, 0};
  std::int32_t m2[4][4] = {};
  for_each_texel([&](const std::uint8_t* t, std::int32_t wt) {
    wsum_i += wt;
    std::int32_t wtc[4];
    for (int c = 0; c < 4; ++c) {
      wtc[c] = wt * t[c];
      sum[c] += wtc[c];
    }
    for (int a = 0; a < NCH; ++a) {
      for (int b = a; b < NCH; ++b) m2[a][b] += wtc[a] * t[b];
    }
  });
  const double wsum = double(wsum_i);
  double mean[4];
  for (int c = 0; c < 4; ++c) mean[c] = double(sum[c]) / wsum;
  double cov[4][4] = {};
  for (int a = 0; a < NCH; ++a) {
    for (int b = a; b < NCH; ++b) {
      cov[a][b] = cov[b][a] = double(m2[a][b]) - double(sum[a]) * double(sum[b]) / wsum;
    }
  }
  // Power iteration for the principal axis.
  double axis[4] = {0.2126, 0.7152, 0.0722, 0.5};
  principal_axis(cov, NCH, axis, 1e-12);  // degenerate: the last good axis stays
  // Split by the side of the mean along the axis; the halves' sums are exact integers.
  std::int32_t half[2][5] = {};  // [p >= 0]: weighted rgba sums, weight sum
  for_each_texel([&](const std::uint8_t* t, std::int32_t wt) {
    double p = 0;
    for (int a = 0; a < NCH; ++a) p += (t[a] - mean[a]) * axis[a];
    std::int32_t* acc = half[p < 0 ? 0 : 1];
    for (int c = 0; c < 4; ++c) acc[c] += wt * t[c];
    acc[4] += wt;
  });
  double lo[4], hi[4];
  for (int c = 0; c < 4; ++c) {
    lo[c] = half[0][4] > 0 ? double(half[0][c]) / double(half[0][4]) : mean[c];
    hi[c] = half[1][4] > 0 ? double(half[1][c]) / double(half[1][4]) : mean[c];
  }
  const double ylo = 0.2126 * lo[0] + 0.7152 * lo[1] + 0.0722 * lo[2];
  const double yhi = 0.2126 * hi[0] + 0.7152 * hi[1] + 0.0722 * hi[2];
  const bool swap = ylo > yhi;
  for (int c = 0; c < 4; ++c) {
    low[c] = float(swap ? hi[c] : lo[c]);
    high[c] = float(swap ? lo[c] : hi[c]);
  }
}

}  // namespace

void principal_endpoints(const EncoderState& s, std::vector<float>& low, std::vector<float>& high) {
  const Grid& g = s.g;
  low.assign(g.blocks() * 4, 0.0f);
  high.assign(g.blocks() * 4, 0.0f);
  parallel_for(0, g.nby, 4,
               [&](std::int64_t by0, std::int64_t by1) {
                 for (int by = int(by0); by < int(by1); ++by) {
                   for (int bx = 0; bx < g.nbx; ++bx) {
                     const std::size_t bi =
                         (std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx)) * 4;
                     if (s.alpha_mode) {
                       principal_block<4>(s, bx, by, &low[bi], &high[bi]);
                     } else {
                       principal_block<3>(s, bx, by, &low[bi], &high[bi]);
                     }
                   }
                 }
               },
               {s.threads});
}

// Consistent endpoint orientation (see encode_internal.h). Neighbouring blocks blend their A
// images and their B images separately, so a texel between two blocks can only reach a colour
// both blocks store on the same side. The start above orders each pair by luma, which is
// arbitrary where the two colours are about equally bright (hue edges, the wrap-around seam of
// a texture that does not tile): there the order is set by the neighbours instead.
//
// 1. Regions. Ambiguous pairs are grouped into regions by a breadth-first walk (raster-order
//    seeds, neighbours in a fixed order): a neighbour joins when its pair clearly matches the
//    current block's one way round (the better orientation's squared colour distance at most
//    half the other's) and takes that orientation, so a region is oriented consistently from
//    one end to the other: decisions between neighbours alone can leave a long run of
//    ambiguous blocks in two halves oriented against each other (a domain wall, each block
//    agreeing with two of its three neighbours; docs/benchmarks/pvrtc_history.md, "Start").
// 2. Each region as a whole is swapped when that brings it closer to the blocks around it.
// 3. A few serial raster passes swap single ambiguous blocks where that brings the pair closer
//    to its four neighbours' (a clean-up).
// Deterministic (serial) and cheap: a few flops per block and neighbour.
void orient_endpoints(const Grid& g, int nch, std::vector<float>& low, std::vector<float>& high) {
  // A pair counts as ambiguous when its luma difference is under 0.3 of its colour distance.
  constexpr double kAmbiguous = 0.3;
  // A neighbour joins a region when its better orientation is at most this fraction of the
  // other (not sensitive: see docs/benchmarks/pvrtc_history.md).
  constexpr double kClearMatch = 0.5;
  constexpr int kPasses = 4;  // clean-up passes over all four (wrapping) neighbours
  const std::size_t nb = g.blocks();
  auto d2 = [&](const float* p, const float* q) {
    double d = 0;
    for (int c = 0; c < nch; ++c) d += double(p[c] - q[c]) * double(p[c] - q[c]);
    return d;
  };
  auto ambiguous = [&](std::size_t i) {
    const float* lo = &low[i * 4];
    const float* hi = &high[i * 4];
    const double dy =
        0.2126 * (hi[0] - lo[0]) + 0.7152 * (hi[1] - lo[1]) + 0.0722 * (hi[2] - lo[2]);
    return dy * dy < kAmbiguous * kAmbiguous * d2(lo, hi);
  };
  // The four wrapping neighbours: left, right, up, down.
  auto neighbours = [&](std::size_t i, std::size_t out[4]) {
    const int bx = int(i % std::size_t(g.nbx)), by = int(i / std::size_t(g.nbx));
    const std::size_t row = std::size_t(by) * std::size_t(g.nbx);
    out[0] = row + std::size_t((bx + g.nbx - 1) & (g.nbx - 1));
    out[1] = row + std::size_t((bx + 1) & (g.nbx - 1));
    out[2] = std::size_t((by + g.nby - 1) & (g.nby - 1)) * std::size_t(g.nbx) + std::size_t(bx);
    out[3] = std::size_t((by + 1) & (g.nby - 1)) * std::size_t(g.nbx) + std::size_t(bx);
  };
  // Squared colour distances of block i's pair to block k's as it is (keep) and swapped.
  auto distances = [&](std::size_t i, std::size_t k, double& keep, double& swap) {
    const float* lo = &low[i * 4];
    const float* hi = &high[i * 4];
    const float* nl = &low[k * 4];
    const float* nh = &high[k * 4];
    keep = d2(lo, nl) + d2(hi, nh);
    swap = d2(hi, nl) + d2(lo, nh);
  };
  auto swap_pair = [&](std::size_t i) {
    for (int c = 0; c < 4; ++c) std::swap(low[i * 4 + c], high[i * 4 + c]);
  };

  std::vector<std::uint8_t> amb(nb);
  for (std::size_t i = 0; i < nb; ++i) amb[i] = ambiguous(i) ? 1 : 0;
  // Steps 1 and 2: region[i] is the region's index + 1 once block i joined one.
  std::vector<std::uint32_t> region(nb, 0);
  std::vector<std::size_t> members;
  std::uint32_t next = 0;
  for (std::size_t seed = 0; seed < nb; ++seed) {
    if (!amb[seed] || region[seed] != 0) continue;
    const std::uint32_t id = ++next;
    members.clear();
    members.push_back(seed);
    region[seed] = id;
    for (std::size_t q = 0; q < members.size(); ++q) {
      const std::size_t u = members[q];
      std::size_t nbrs[4];
      neighbours(u, nbrs);
      for (const std::size_t v : nbrs) {
        if (!amb[v] || region[v] != 0) continue;
        double keep, swap;
        distances(v, u, keep, swap);
        if (std::min(keep, swap) > kClearMatch * std::max(keep, swap)) continue;
        if (swap < keep) swap_pair(v);
        region[v] = id;
        members.push_back(v);
      }
    }
    double keep_sum = 0, swap_sum = 0;
    for (const std::size_t u : members) {
      std::size_t nbrs[4];
      neighbours(u, nbrs);
      for (const std::size_t v : nbrs) {
        if (region[v] == id) continue;
        double keep, swap;
        distances(u, v, keep, swap);
        keep_sum += keep;
        swap_sum += swap;
      }
    }
    if (swap_sum < keep_sum) {
      for (const std::size_t u : members) swap_pair(u);
    }
  }
  // Step 3.
  for (int pass = 0; pass < kPasses; ++pass) {
    for (std::size_t i = 0; i < nb; ++i) {
      if (!ambiguous(i)) continue;
      std::size_t nbrs[4];
      neighbours(i, nbrs);
      double keep = 0, swap = 0;
      for (const std::size_t k : nbrs) {
        double kk, ss;
        distances(i, k, kk, ss);
        keep += kk;
        swap += ss;
      }
      if (swap < keep) swap_pair(i);
    }
  }
}

bool split_pairs(const float (*px)[4], int n, int nch, bool translucent, SplitPairs& out) {
  float mean[4] = {0, 0, 0, 0};
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < 4; ++c) mean[c] += px[i][c] / float(n);
  }
  float cov[4][4] = {};
  for (int i = 0; i < n; ++i) {
    for (int a = 0; a < nch; ++a) {
      for (int b = 0; b < nch; ++b) cov[a][b] += (px[i][a] - mean[a]) * (px[i][b] - mean[b]);
    }
  }
  float axis[4] = {0.2126f, 0.7152f, 0.0722f, 0.5f};
  if (!principal_axis(cov, nch, axis, 1e-6f)) return false;
  float lo[4] = {0, 0, 0, 0}, hi[4] = {0, 0, 0, 0}, nlo = 0, nhi = 0;
  float pmin = 1e30f, pmax = -1e30f;
  int imin = 0, imax = 0;
  for (int i = 0; i < n; ++i) {
    float p = 0;
    for (int a = 0; a < nch; ++a) p += (px[i][a] - mean[a]) * axis[a];
    float* acc = p < 0 ? lo : hi;
    (p < 0 ? nlo : nhi) += 1;
    for (int c = 0; c < 4; ++c) acc[c] += px[i][c];
    if (p < pmin) {
      pmin = p;
      imin = i;
    }
    if (p > pmax) {
      pmax = p;
      imax = i;
    }
  }
  if (nlo == 0 || nhi == 0) return false;
  for (int c = 0; c < 4; ++c) {
    lo[c] /= nlo;
    hi[c] /= nhi;
  }
  const bool ta = translucent;
  out.pairs[0][0] = quantise_endpoint(lo, false, ta);
  out.pairs[0][1] = quantise_endpoint(hi, true, ta);
  out.pairs[1][0] = quantise_endpoint(hi, false, ta);
  out.pairs[1][1] = quantise_endpoint(lo, true, ta);
  out.pairs[2][0] = quantise_endpoint(px[imin], false, ta);
  out.pairs[2][1] = quantise_endpoint(px[imax], true, ta);
  out.pairs[3][0] = quantise_endpoint(px[imax], false, ta);
  out.pairs[3][1] = quantise_endpoint(px[imin], true, ta);
  out.low_mean_a = out.pairs[0][0];
  out.high_mean_b = out.pairs[0][1];
  out.low_extreme_a = out.pairs[2][0];
  out.high_extreme_b = out.pairs[2][1];
  return true;
}

}  // namespace tessera::pvrtc::detail
