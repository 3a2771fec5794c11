// Principal-axis initial endpoints for the refinement of Quality::normal / high.
//
// Intensity dilation (the paper's method, Quality::fast) labels extrema by luma only, so two
// colours of similar brightness, e.g. both sides of the wrap-around seam of a texture, end up
// averaged into one muddy pair of endpoints that refinement cannot pull apart again. Here each
// block's endpoints come from its bilinear footprint (the 8x4-block-wide texel window its
// colours reach, tent-weighted, wrapping): the texels are split by the sign of their projection
// on the principal axis of their colours and each half's weighted mean becomes one endpoint;
// the brighter half is B (high), as in the paper, so neighbouring blocks blend consistently.
#include <cstdint>

#include "pvrtc/encode_internal.h"

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
  parallel_for(
      0, g.nby, 4,
      [&](std::int64_t by0, std::int64_t by1) {
        for (int by = int(by0); by < int(by1); ++by) {
          for (int bx = 0; bx < g.nbx; ++bx) {
            const std::size_t bi = (std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx)) * 4;
            if (s.alpha_mode) {
              principal_block<4>(s, bx, by, &low[bi], &high[bi]);
            } else {
              principal_block<3>(s, bx, by, &low[bi], &high[bi]);
            }
          }
        }
      },
      s.threads);
}

}  // namespace tessera::pvrtc::detail
