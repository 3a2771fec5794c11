// Initial PVRTC endpoints by intensity dilation (Krajcevski & Manocha 2014, §2-3).
//
// 1. Intensity: Rec.709 luma (CIE Y) with alpha premultiplied when alpha is meaningful.
// 2. Labelling: a texel is a local maximum (minimum) when no 8-neighbour (wrapping) is brighter
//    (darker). Uniform areas are therefore both, exactly as the paper describes.
// 3. Dilation: each extremum image is dilated three times with a 3x3 kernel; an empty texel
//    next to several filled ones takes their average (rounded).
// 4. Block colours: the mean over the block's texels of the dilated image, where texels still
//    empty take the block's own extreme (brightest / darkest) texel colour.
//
// Everything runs fused in bands of block rows (with a 4-texel halo above and below), so each
// thread's working set stays in cache; bands write only their own blocks, so the output does not
// depend on the thread count.
#include <algorithm>
#include <cstring>

#include "pvrtc/encode_internal.h"
#include "pvrtc/simd.h"

namespace tessera::pvrtc::detail {

namespace {

constexpr int kDilations = 3;
constexpr int kHalo = kDilations + 1;  // rows of intensity needed above/below a band

// Rounded mean of n filled neighbours: floor(x / n) for x < 2400 and 2 <= n <= 9 equals
// mulhi(x, ceil(65536 / n)) (the error term stays below 1 / 9); n == 1 is passed through.
constexpr std::uint16_t kRecip16[10] = {0, 0, 32768, 21846, 16384, 13108, 10923, 9363, 8192, 7282};

// Planar extremum image of a band: colour planes and the filled flag (0/1), u8 each; rows are
// padded by 8 bytes so 8-wide loads at the row end stay inside the buffer.
struct BandPlanes {
  std::vector<std::uint8_t> p[5];
};

// One 3x3 dilation pass over local rows [r0, r1) (all 0 <= r0 - 1 and r1 + 1 <= rows): empty
// texels next to filled ones take the rounded mean of the filled neighbours.
void dilate_band(int w, const BandPlanes& src, BandPlanes& dst, int nplanes, int r0, int r1,
                 std::vector<std::uint16_t>& hs) {
  using simd::vu16x8;
  const int hr0 = r0 - 1, hr1 = r1 + 1, hrows = hr1 - hr0;
  const std::size_t W = std::size_t(w);
  hs.resize(5 * std::size_t(hrows) * W + 8);
  const int wv = w >= 10 ? ((w - 2) / 8) * 8 : 0;  // texels [1, 1 + wv) done 8 at a time
  for (int k = 0; k < 5; ++k) {
    if (k < 4 && k >= nplanes) continue;
    for (int r = hr0; r < hr1; ++r) {
      const std::uint8_t* in = &src.p[k][std::size_t(r) * W];
      std::uint16_t* out = &hs[(std::size_t(k) * std::size_t(hrows) + std::size_t(r - hr0)) * W];
      for (int x = 1; x < 1 + wv; x += 8) {
        simd::store_u16x8(
            simd::load_u8x8(in + x - 1) + simd::load_u8x8(in + x) + simd::load_u8x8(in + x + 1),
            out + x);
      }
      auto edge = [&](int x) {
        out[x] = std::uint16_t(in[(x - 1) & (w - 1)] + in[x] + in[(x + 1) & (w - 1)]);
      };
      edge(0);
      for (int x = 1 + wv; x < w; ++x) edge(x);
    }
  }
  auto hrow = [&](int k, int r) {
    return &hs[(std::size_t(k) * std::size_t(hrows) + std::size_t(r - hr0)) * W];
  };
  const vu16x8 one(1), zero(0);
  const int w8 = (w / 8) * 8;
  for (int r = r0; r < r1; ++r) {
    const std::size_t row = std::size_t(r) * W;
    const std::uint8_t* f = &src.p[4][row];
    std::uint8_t* fo = &dst.p[4][row];
    const std::uint16_t *n0 = hrow(4, r - 1), *n1 = hrow(4, r), *n2 = hrow(4, r + 1);
    for (int x = 0; x < w8; x += 8) {
      const vu16x8 n =
          simd::load_u16x8(n0 + x) + simd::load_u16x8(n1 + x) + simd::load_u16x8(n2 + x);
      vu16x8 rcv = zero;
      for (std::uint16_t k = 2; k < 10; ++k) {
        rcv = rcv | (simd::cmpeq(n, vu16x8(k)) & vu16x8(kRecip16[k]));
      }
      const vu16x8 hv = simd::srl<1>(n);
      const vu16x8 single = simd::cmpeq(n, one);
      const vu16x8 fv = simd::load_u8x8(f + x);
      const vu16x8 filled = simd::cmpeq(fv, one);
      simd::store_u8x8(simd::select(simd::cmpeq(n, zero), fv, one), fo + x);
      for (int k = 0; k < nplanes; ++k) {
        const vu16x8 sum = simd::load_u16x8(hrow(k, r - 1) + x) + simd::load_u16x8(hrow(k, r) + x) +
                           simd::load_u16x8(hrow(k, r + 1) + x);
        const vu16x8 avg = simd::select(single, sum, simd::mulhi(sum + hv, rcv));
        simd::store_u8x8(simd::select(filled, simd::load_u8x8(&src.p[k][row] + x), avg),
                         &dst.p[k][row] + x);
      }
    }
    for (int x = w8; x < w; ++x) {
      const std::uint32_t n = std::uint32_t(n0[x]) + n1[x] + n2[x];
      fo[x] = std::uint8_t(f[x] | (n != 0));
      for (int k = 0; k < nplanes; ++k) {
        const std::uint32_t sum =
            std::uint32_t(hrow(k, r - 1)[x]) + hrow(k, r)[x] + hrow(k, r + 1)[x];
        const std::uint32_t avg = n == 1 ? sum : ((sum + n / 2) * kRecip16[n]) >> 16;
        dst.p[k][row + std::size_t(x)] = f[x] ? src.p[k][row + std::size_t(x)] : std::uint8_t(avg);
      }
    }
  }
}

}  // namespace

void dilation_endpoints(const EncoderState& s, std::vector<float>& low, std::vector<float>& high) {
  const Grid& g = s.g;
  const std::uint8_t* t = s.target.data();
  const int w = g.pw, wm = g.pw - 1, hm = g.ph - 1, bw = g.bw;
  const std::size_t W = std::size_t(w);
  const int nplanes = s.alpha_mode ? 4 : 3;  // alpha is 255 everywhere otherwise
  low.assign(g.blocks() * 4, 0.0f);
  high.assign(g.blocks() * 4, 0.0f);
  parallel_for(
      0, g.nby, 4,
      [&](std::int64_t by0, std::int64_t by1) {
        const int Y0 = int(by0) * 4, Y1 = int(by1) * 4, R = Y1 - Y0;
        // Intensity of rows [Y0 - kHalo, Y1 + kHalo): Rec.709 luma (weights sum 65536), times
        // alpha / 255 in alpha mode.
        const int irows = R + 2 * kHalo;
        std::vector<std::int32_t> inten(std::size_t(irows) * W);
        for (int r = 0; r < irows; ++r) {
          const std::uint8_t* src = t + std::size_t((Y0 - kHalo + r) & hm) * W * 4;
          std::int32_t* out = &inten[std::size_t(r) * W];
          for (int x = 0; x < w; ++x) {
            const std::uint8_t* p = src + std::size_t(x) * 4;
            std::int32_t y = 13933 * p[0] + 46871 * p[1] + 4732 * p[2];
            if (s.alpha_mode) y = std::int32_t((std::int64_t(y) * p[3]) / 255);
            out[x] = y;
          }
        }
        // Labels for rows [Y0 - kDilations, Y1 + kDilations): local plane row r is texel row
        // Y0 - kDilations + r, intensity row r + 1.
        const int prows = R + 2 * kDilations;
        BandPlanes pl[2][2];  // [max/min][ping/pong]
        for (auto& kk : pl) {
          for (BandPlanes& p : kk) {
            for (int k = 0; k < 5; ++k) {
              if (k < 4 && k >= nplanes) continue;
              p.p[k].assign(std::size_t(prows) * W + 8, 0);
            }
          }
        }
        // Separable 3x3 max / min of the intensity (horizontal pass per row, then vertical):
        // a texel is a local maximum (minimum) when it equals the max (min) of its 3x3.
        std::vector<std::int32_t> hmax(std::size_t(irows) * W), hmin(std::size_t(irows) * W);
        for (int r = 0; r < irows; ++r) {
          const std::int32_t* in = &inten[std::size_t(r) * W];
          std::int32_t* mx = &hmax[std::size_t(r) * W];
          std::int32_t* mn = &hmin[std::size_t(r) * W];
          for (int x = 1; x + 1 < w; ++x) {
            mx[x] = std::max(std::max(in[x - 1], in[x]), in[x + 1]);
            mn[x] = std::min(std::min(in[x - 1], in[x]), in[x + 1]);
          }
          for (int x : {0, w - 1}) {
            const std::int32_t l = in[(x - 1) & wm], c = in[x], rr = in[(x + 1) & wm];
            mx[x] = std::max(std::max(l, c), rr);
            mn[x] = std::min(std::min(l, c), rr);
          }
        }
        std::vector<std::uint8_t> lab(W);
        for (int r = 0; r < prows; ++r) {
          const std::size_t r0 = std::size_t(r) * W, r1 = r0 + W, r2 = r1 + W;
          const std::int32_t* v = &inten[r1];
          for (int x = 0; x < w; ++x) {
            const std::size_t i0 = r0 + std::size_t(x), i1 = r1 + std::size_t(x),
                              i2 = r2 + std::size_t(x);
            const std::int32_t m = std::max(std::max(hmax[i0], hmax[i1]), hmax[i2]);
            const std::int32_t n = std::min(std::min(hmin[i0], hmin[i1]), hmin[i2]);
            lab[std::size_t(x)] = std::uint8_t((m == v[x] ? 1 : 0) | (n == v[x] ? 2 : 0));
          }
          const std::uint8_t* src = t + std::size_t((Y0 - kDilations + r) & hm) * W * 4;
          for (int x = 0; x < w; ++x) {
            if (!lab[std::size_t(x)]) continue;
            const std::size_t i = std::size_t(r) * W + std::size_t(x);
            for (int k = 0; k < 2; ++k) {
              if (!(lab[std::size_t(x)] & (1 << k))) continue;
              for (int c = 0; c < nplanes; ++c)
                pl[k][0].p[c][i] = src[std::size_t(x) * 4 + std::size_t(c)];
              pl[k][0].p[4][i] = 1;
            }
          }
        }
        std::vector<std::uint16_t> hs;
        for (int pass = 0; pass < kDilations; ++pass) {
          const int src = pass & 1, dst = src ^ 1;
          for (int k = 0; k < 2; ++k) {
            dilate_band(w, pl[k][src], pl[k][dst], nplanes, pass + 1, prows - pass - 1, hs);
          }
        }
        const int fin = kDilations & 1;
        for (int by = int(by0); by < int(by1); ++by) {
          for (int bx = 0; bx < g.nbx; ++bx) {
            // The block's own brightest and darkest texels (filler for empty texels).
            int xmax = 0, ymax = 0, xmin = 0, ymin = 0;
            std::int32_t vmax = -1, vmin = 1 << 30;
            for (int y = by * 4; y < by * 4 + 4; ++y) {
              const std::int32_t* row = &inten[std::size_t(y - Y0 + kHalo) * W];
              for (int x = bx * bw; x < bx * bw + bw; ++x) {
                if (row[x] > vmax) {
                  vmax = row[x];
                  xmax = x;
                  ymax = y;
                }
                if (row[x] < vmin) {
                  vmin = row[x];
                  xmin = x;
                  ymin = y;
                }
              }
            }
            const std::uint8_t* fill_c[2] = {t + (std::size_t(ymax) * W + std::size_t(xmax)) * 4,
                                             t + (std::size_t(ymin) * W + std::size_t(xmin)) * 4};
            std::uint32_t sum[2][4] = {};
            for (int y = by * 4; y < by * 4 + 4; ++y) {
              const std::size_t row = std::size_t(y - Y0 + kDilations) * W;
              for (int x = bx * bw; x < bx * bw + bw; ++x) {
                const std::size_t i = row + std::size_t(x);
                for (int k = 0; k < 2; ++k) {
                  const BandPlanes& p = pl[k][fin];
                  if (p.p[4][i]) {
                    for (int ch = 0; ch < nplanes; ++ch) sum[k][ch] += p.p[ch][i];
                  } else {
                    for (int ch = 0; ch < nplanes; ++ch) sum[k][ch] += fill_c[k][ch];
                  }
                }
              }
            }
            if (nplanes == 3) sum[0][3] = sum[1][3] = 255u * std::uint32_t(4 * bw);
            const float inv = 1.0f / float(4 * bw);
            const std::size_t b = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
            for (int ch = 0; ch < 4; ++ch) {
              high[b * 4 + std::size_t(ch)] = float(sum[0][ch]) * inv;
              low[b * 4 + std::size_t(ch)] = float(sum[1][ch]) * inv;
            }
          }
        }
      },
      s.threads);
}

}  // namespace tessera::pvrtc::detail
