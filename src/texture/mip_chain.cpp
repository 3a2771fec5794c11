// Float mip chains for any size: exact area (box) downsampling with fractional weights at odd
// sizes, optionally alpha-weighted. Level sizes follow GL: max(1, floor(size / 2)).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "tessera/texture.h"

namespace tessera {

namespace {

/// For one axis, the source texels each destination texel covers and their weights: destination
/// texel d covers the source interval [d * s, (d + 1) * s) with s = src / dst, and source texel
/// i weighs |[i, i + 1) ∩ that interval| / s. Weights of one destination texel sum to 1, and
/// every source texel's weights sum to 1 / s over all destinations, so means are preserved.
struct AxisFilter {
  std::vector<int> first;     ///< First source texel of destination d.
  std::vector<int> count;     ///< Number of source texels of destination d.
  std::vector<double> weight; ///< kMaxSpan weights per destination.
  static constexpr int kMaxSpan = 4;  // s <= 3 (3 -> 1), so at most 4 texels are touched.

  AxisFilter(int src, int dst) : first(dst), count(dst), weight(std::size_t(dst) * kMaxSpan) {
    const double s = double(src) / double(dst);
    for (int d = 0; d < dst; ++d) {
      // d * src is an exact integer, so interval ends that fall on texel edges stay exact.
      const double lo = double(d) * src / dst;
      const double hi = double(d + 1) * src / dst;
      int i0 = int(std::floor(lo));
      int i1 = int(std::ceil(hi)) - 1;
      if (i1 > src - 1) i1 = src - 1;
      // Drop slivers that come only from rounding (overlap below 1e-12 texels).
      while (i0 < i1 && double(i0 + 1) - lo < 1e-12) ++i0;
      while (i1 > i0 && hi - double(i1) < 1e-12) --i1;
      first[d] = i0;
      count[d] = i1 - i0 + 1;
      for (int k = 0; k < count[d]; ++k) {
        const double a = std::max(lo, double(i0 + k));
        const double b = std::min(hi, double(i0 + k + 1));
        weight[std::size_t(d) * kMaxSpan + k] = (b - a) / s;
      }
    }
  }
};

}  // namespace

ImageRGBAF downsample_box(const ImageRGBAF& image, bool alpha_weighted, int threads) {
  if (image.empty()) return {};
  const int dw = TextureShape::level_size(image.width, 1);
  const int dh = TextureShape::level_size(image.height, 1);
  const AxisFilter fx(image.width, dw);
  const AxisFilter fy(image.height, dh);
  ImageRGBAF out(dw, dh);
  parallel_for(
      0, dh, 8,
      [&](std::int64_t y_begin, std::int64_t y_end) {
        for (std::int64_t yy = y_begin; yy < y_end; ++yy) {
          const int y = int(yy);
          for (int x = 0; x < dw; ++x) {
            double plain[3] = {0, 0, 0};  // sum w * c
            double pre[3] = {0, 0, 0};    // sum w * a * c
            double alpha = 0;             // sum w * a
            for (int j = 0; j < fy.count[y]; ++j) {
              const double wy = fy.weight[std::size_t(y) * AxisFilter::kMaxSpan + j];
              const int sy = fy.first[y] + j;
              for (int i = 0; i < fx.count[x]; ++i) {
                const double w = wy * fx.weight[std::size_t(x) * AxisFilter::kMaxSpan + i];
                const float* s = image.at(fx.first[x] + i, sy);
                for (int c = 0; c < 3; ++c) {
                  plain[c] += w * s[c];
                  pre[c] += w * s[3] * s[c];
                }
                alpha += w * s[3];
              }
            }
            float* d = out.at(x, y);
            const bool use_pre = alpha_weighted && alpha > 0.0;
            for (int c = 0; c < 3; ++c) d[c] = float(use_pre ? pre[c] / alpha : plain[c]);
            d[3] = float(alpha);
          }
        }
      },
      threads);
  return out;
}

std::vector<ImageRGBAF> build_mip_chain(const ImageRGBAF& image, bool alpha_weighted,
                                        int max_levels, int threads) {
  std::vector<ImageRGBAF> chain;
  if (image.empty()) return chain;
  int levels = TextureShape::full_level_count(image.width, image.height);
  if (max_levels > 0 && max_levels < levels) levels = max_levels;
  chain.reserve(std::size_t(levels));
  chain.push_back(image);
  for (int l = 1; l < levels; ++l) {
    chain.push_back(downsample_box(chain.back(), alpha_weighted, threads));
  }
  return chain;
}

}  // namespace tessera
