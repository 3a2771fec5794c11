// Initial PVRTC endpoints by intensity dilation (Krajcevski & Manocha 2014, §2-3).
//
// 1. Intensity: Rec.709 luma (CIE Y) with alpha premultiplied when alpha is meaningful.
// 2. Labelling: a texel is a local maximum (minimum) when no 8-neighbour (wrapping) is brighter
//    (darker). Uniform areas are therefore both, exactly as the paper describes.
// 3. Dilation: each extremum image is dilated three times with a 3x3 kernel; an empty texel
//    next to several filled ones takes their average (rounded).
// 4. Block colours: the mean over the block's texels of the dilated image, where texels still
//    empty take the block's own extreme (brightest / darkest) texel colour.
#include <algorithm>
#include <cstring>

#include "pvrtc/encode_internal.h"

namespace tessera::pvrtc::detail {

namespace {

constexpr int kDilations = 3;

// One 3x3 dilation pass on rows [y0, y1). `src`/`dst` hold RGBA, `fsrc`/`fdst` filled flags.
void dilate_rows(const Grid& g, const std::uint8_t* src, const std::uint8_t* fsrc,
                 std::uint8_t* dst, std::uint8_t* fdst, int y0, int y1) {
  const int w = g.pw, wm = g.pw - 1, hm = g.ph - 1;
  for (int y = y0; y < y1; ++y) {
    const std::size_t rows[3] = {std::size_t((y - 1) & hm) * std::size_t(w), std::size_t(y) * std::size_t(w),
                                 std::size_t((y + 1) & hm) * std::size_t(w)};
    for (int x = 0; x < w; ++x) {
      const std::size_t i = rows[1] + std::size_t(x);
      if (fsrc[i]) {
        std::memcpy(dst + i * 4, src + i * 4, 4);
        fdst[i] = 1;
        continue;
      }
      const std::size_t cols[3] = {std::size_t((x - 1) & wm), std::size_t(x), std::size_t((x + 1) & wm)};
      std::uint32_t sum[4] = {0, 0, 0, 0}, n = 0;
      for (std::size_t r : rows) {
        for (std::size_t c : cols) {
          const std::size_t j = r + c;
          if (!fsrc[j]) continue;
          ++n;
          for (int k = 0; k < 4; ++k) sum[k] += src[j * 4 + std::size_t(k)];
        }
      }
      if (n == 0) {
        fdst[i] = 0;
        continue;
      }
      for (int k = 0; k < 4; ++k) dst[i * 4 + std::size_t(k)] = std::uint8_t((sum[k] + n / 2) / n);
      fdst[i] = 1;
    }
  }
}

}  // namespace

void dilation_endpoints(const EncoderState& s, std::vector<float>& low, std::vector<float>& high) {
  const Grid& g = s.g;
  const std::size_t n = g.texels();
  const std::uint8_t* t = s.target.data();
  // Intensity, fixed point: Y * alpha with Rec.709 weights scaled to 2^16 * 255.
  std::vector<std::int32_t> inten(n);
  parallel_for(
      0, std::int64_t(n), 1 << 14,
      [&](std::int64_t i0, std::int64_t i1) {
        for (std::int64_t i = i0; i < i1; ++i) {
          const std::uint8_t* p = t + i * 4;
          std::int32_t y = 13933 * p[0] + 46871 * p[1] + 4732 * p[2];  // sum 65536
          if (s.alpha_mode) y = std::int32_t((std::int64_t(y) * p[3]) / 255);
          inten[std::size_t(i)] = y;
        }
      },
      s.threads);
  // Labels and initial extremum images.
  std::vector<std::uint8_t> img[2][2];  // [max/min][ping/pong]
  std::vector<std::uint8_t> fill[2][2];
  for (int k = 0; k < 2; ++k) {
    for (int b = 0; b < 2; ++b) {
      img[k][b].assign(n * 4, 0);
      fill[k][b].assign(n, 0);
    }
  }
  const int w = g.pw, wm = g.pw - 1, hm = g.ph - 1;
  parallel_for(
      0, g.ph, 16,
      [&](std::int64_t y0, std::int64_t y1) {
        for (int y = int(y0); y < int(y1); ++y) {
          const std::size_t rows[3] = {std::size_t((y - 1) & hm) * std::size_t(w),
                                       std::size_t(y) * std::size_t(w),
                                       std::size_t((y + 1) & hm) * std::size_t(w)};
          for (int x = 0; x < w; ++x) {
            const std::size_t i = rows[1] + std::size_t(x);
            const std::int32_t v = inten[i];
            bool is_max = true, is_min = true;
            const std::size_t cols[3] = {std::size_t((x - 1) & wm), std::size_t(x),
                                         std::size_t((x + 1) & wm)};
            for (std::size_t r : rows) {
              for (std::size_t c : cols) {
                const std::int32_t u = inten[r + c];
                is_max &= u <= v;
                is_min &= u >= v;
              }
            }
            if (is_max) {
              std::memcpy(&img[0][0][i * 4], t + i * 4, 4);
              fill[0][0][i] = 1;
            }
            if (is_min) {
              std::memcpy(&img[1][0][i * 4], t + i * 4, 4);
              fill[1][0][i] = 1;
            }
          }
        }
      },
      s.threads);
  for (int pass = 0; pass < kDilations; ++pass) {
    const int src = pass & 1, dst = src ^ 1;
    parallel_for(
        0, g.ph, 16,
        [&](std::int64_t y0, std::int64_t y1) {
          for (int k = 0; k < 2; ++k) {
            dilate_rows(g, img[k][src].data(), fill[k][src].data(), img[k][dst].data(),
                        fill[k][dst].data(), int(y0), int(y1));
          }
        },
        s.threads);
  }
  const int fin = kDilations & 1;
  low.assign(g.blocks() * 4, 0.0f);
  high.assign(g.blocks() * 4, 0.0f);
  const int bw = g.bw;
  parallel_for(
      0, g.nby, 4,
      [&](std::int64_t by0, std::int64_t by1) {
        for (int by = int(by0); by < int(by1); ++by) {
          for (int bx = 0; bx < g.nbx; ++bx) {
            // The block's own brightest and darkest texels (filler for empty texels).
            std::size_t imax = 0, imin = 0;
            std::int32_t vmax = -1, vmin = 1 << 30;
            for (int y = 0; y < 4; ++y) {
              for (int x = 0; x < bw; ++x) {
                const std::size_t i = std::size_t(by * 4 + y) * std::size_t(w) + std::size_t(bx * bw + x);
                if (inten[i] > vmax) {
                  vmax = inten[i];
                  imax = i;
                }
                if (inten[i] < vmin) {
                  vmin = inten[i];
                  imin = i;
                }
              }
            }
            std::uint32_t sum[2][4] = {};
            for (int y = 0; y < 4; ++y) {
              for (int x = 0; x < bw; ++x) {
                const std::size_t i = std::size_t(by * 4 + y) * std::size_t(w) + std::size_t(bx * bw + x);
                for (int k = 0; k < 2; ++k) {
                  const std::uint8_t* c =
                      fill[k][fin][i] ? &img[k][fin][i * 4] : t + (k == 0 ? imax : imin) * 4;
                  for (int ch = 0; ch < 4; ++ch) sum[k][ch] += c[ch];
                }
              }
            }
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
