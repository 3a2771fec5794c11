// Principal-axis initial endpoints for the refinement of Quality::normal / high.
//
// Intensity dilation (the paper's method, Quality::fast) labels extrema by luma only, so two
// colours of similar brightness, e.g. both sides of the wrap-around seam of a texture, end up
// averaged into one muddy pair of endpoints that refinement cannot pull apart again. Here each
// block's endpoints come from its bilinear footprint (the 8x4-block-wide texel window its
// colours reach, tent-weighted, wrapping): the texels are split by the sign of their projection
// on the principal axis of their colours and each half's weighted mean becomes one endpoint;
// the brighter half is B (high), as in the paper, so neighbouring blocks blend consistently.
#include <cmath>

#include "pvrtc/encode_internal.h"

namespace tessera::pvrtc::detail {

void principal_endpoints(const EncoderState& s, std::vector<float>& low, std::vector<float>& high) {
  const Grid& g = s.g;
  low.assign(g.blocks() * 4, 0.0f);
  high.assign(g.blocks() * 4, 0.0f);
  const int bw = g.bw, wm = g.pw - 1, hm = g.ph - 1;
  const int nch = s.alpha_mode ? 4 : 3;
  parallel_for(
      0, g.nby, 4,
      [&](std::int64_t by0, std::int64_t by1) {
        for (int by = int(by0); by < int(by1); ++by) {
          for (int bx = 0; bx < g.nbx; ++bx) {
            double mean[4] = {0, 0, 0, 0}, wsum = 0;
            double cov[4][4] = {};
            auto texel = [&](int u, int v, double& wt) {
              const int y = (by * 4 - 2 + v) & hm, x = (bx * bw - bw / 2 + u) & wm;
              wt = double(v < 4 ? v : 8 - v) * double(u < bw ? u : 2 * bw - u);
              return &s.target[(std::size_t(y) * std::size_t(g.pw) + std::size_t(x)) * 4];
            };
            for (int v = 1; v < 8; ++v) {
              for (int u = 1; u < 2 * bw; ++u) {
                double wt;
                const std::uint8_t* t = texel(u, v, wt);
                wsum += wt;
                for (int c = 0; c < 4; ++c) mean[c] += wt * t[c];
              }
            }
            for (double& m : mean) m /= wsum;
            for (int v = 1; v < 8; ++v) {
              for (int u = 1; u < 2 * bw; ++u) {
                double wt;
                const std::uint8_t* t = texel(u, v, wt);
                double d[4];
                for (int c = 0; c < 4; ++c) d[c] = t[c] - mean[c];
                for (int a = 0; a < nch; ++a) {
                  for (int b = 0; b < nch; ++b) cov[a][b] += wt * d[a] * d[b];
                }
              }
            }
            // Power iteration for the principal axis.
            double axis[4] = {0.2126, 0.7152, 0.0722, 0.5};
            for (int it = 0; it < 8; ++it) {
              double n[4] = {0, 0, 0, 0}, len = 0;
              for (int a = 0; a < nch; ++a) {
                for (int b = 0; b < nch; ++b) n[a] += cov[a][b] * axis[b];
                len += n[a] * n[a];
              }
              if (len < 1e-12) break;
              len = std::sqrt(len);
              for (int a = 0; a < nch; ++a) axis[a] = n[a] / len;
            }
            double lo[4] = {0, 0, 0, 0}, hi[4] = {0, 0, 0, 0}, wlo = 0, whi = 0;
            for (int v = 1; v < 8; ++v) {
              for (int u = 1; u < 2 * bw; ++u) {
                double wt;
                const std::uint8_t* t = texel(u, v, wt);
                double p = 0;
                for (int a = 0; a < nch; ++a) p += (t[a] - mean[a]) * axis[a];
                double* acc = p < 0 ? lo : hi;
                (p < 0 ? wlo : whi) += wt;
                for (int c = 0; c < 4; ++c) acc[c] += wt * t[c];
              }
            }
            for (int c = 0; c < 4; ++c) {
              lo[c] = wlo > 0 ? lo[c] / wlo : mean[c];
              hi[c] = whi > 0 ? hi[c] / whi : mean[c];
            }
            const double ylo = 0.2126 * lo[0] + 0.7152 * lo[1] + 0.0722 * lo[2];
            const double yhi = 0.2126 * hi[0] + 0.7152 * hi[1] + 0.0722 * hi[2];
            const bool swap = ylo > yhi;
            const std::size_t bi = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
            for (int c = 0; c < 4; ++c) {
              low[bi * 4 + std::size_t(c)] = float(swap ? hi[c] : lo[c]);
              high[bi * 4 + std::size_t(c)] = float(swap ? lo[c] : hi[c]);
            }
          }
        }
      },
      s.threads);
}

}  // namespace tessera::pvrtc::detail
