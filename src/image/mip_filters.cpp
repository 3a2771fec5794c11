// Lanczos-3 and Kaiser mip levels: separable 2:1 windowed-sinc downsampling with wrapped edges.
#include "image/mip_filters.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace tessera::image::detail {

namespace {

constexpr double kRadius = 3.0;       // both kernels: zero from 3 texels of the smaller image
constexpr double kKaiserAlpha = 4.0;  // NVIDIA Texture Tools' KaiserFilter default

double sinc(double x) {
  if (std::abs(x) < 1e-9) return 1.0;
  const double px = std::numbers::pi * x;
  return std::sin(px) / px;
}

/// Modified Bessel function of the first kind, order 0: sum over k of ((x / 2)^k / k!)^2.
double bessel_i0(double x) {
  double sum = 1.0, term = 1.0;
  for (int k = 1; k < 100; ++k) {
    term *= (x / 2.0) / k;
    const double add = term * term;
    sum += add;
    if (add < sum * 1e-17) break;
  }
  return sum;
}

/// Source texels and normalised weights of one output texel.
struct Taps {
  std::vector<int> index;
  std::vector<double> weight;
};

/// Taps of each of the `dst` outputs of a side of `src` texels, wrapped: a source texel reached
/// more than once (small sides) holds the sum of its weights.
std::vector<Taps> wrapped_taps(int src, int dst, MipFilter filter) {
  std::vector<Taps> taps(static_cast<std::size_t>(dst));
  if (src == dst) {  // a side of 1: not filtered
    for (int i = 0; i < dst; ++i) taps[std::size_t(i)] = {{i}, {1.0}};
    return taps;
  }
  const double scale = double(src) / dst;  // 2 for even sides
  for (int i = 0; i < dst; ++i) {
    Taps& t = taps[std::size_t(i)];
    const double centre = (i + 0.5) * scale;  // in source texels
    const int lo = int(std::floor(centre - kRadius * scale));
    const int hi = int(std::ceil(centre + kRadius * scale));
    double sum = 0.0;
    for (int s = lo; s <= hi; ++s) {
      const double w = mip_kernel(filter, (s + 0.5 - centre) / scale);
      if (w == 0.0) continue;
      const int wrapped = ((s % src) + src) % src;
      const auto at = std::find(t.index.begin(), t.index.end(), wrapped);
      if (at == t.index.end()) {
        t.index.push_back(wrapped);
        t.weight.push_back(w);
      } else {
        t.weight[std::size_t(at - t.index.begin())] += w;
      }
      sum += w;
    }
    for (double& w : t.weight) w /= sum;
  }
  return taps;
}

/// 7 channels per texel: alpha-weighted colour (3), plain colour (3), alpha; the vertical pass
/// then finishes the alpha-weighted average exactly as a 2-D filter would.
constexpr int kWide = 7;

}  // namespace

double mip_kernel(MipFilter filter, double x) {
  const double ax = std::abs(x);
  if (ax >= kRadius) return 0.0;
  switch (filter) {
    case MipFilter::lanczos:
      return sinc(x) * sinc(x / kRadius);
    case MipFilter::kaiser: {
      const double t = x / kRadius;
      return sinc(x) * bessel_i0(kKaiserAlpha * std::sqrt(1.0 - t * t)) / bessel_i0(kKaiserAlpha);
    }
    case MipFilter::box:
      return ax < 0.5 ? 1.0 : 0.0;
  }
  return 0.0;
}

ImageRGBAF sinc_half(const ImageRGBAF& src, const SincHalfOptions& options) {
  const int sw = src.width, sh = src.height;
  const int dw = mip_dimension(sw, 1), dh = mip_dimension(sh, 1);
  const std::vector<Taps> tx = wrapped_taps(sw, dw, options.filter);
  const std::vector<Taps> ty = wrapped_taps(sh, dh, options.filter);

  // Horizontal pass: sw x sh -> dw x sh, 7 channels.
  std::vector<float> mid(std::size_t(dw) * std::size_t(sh) * kWide);
  parallel_for(0, sh, 8,
               [&](std::int64_t y0, std::int64_t y1) {
                 for (std::int64_t y = y0; y < y1; ++y) {
                   for (int x = 0; x < dw; ++x) {
                     const Taps& t = tx[std::size_t(x)];
                     double acc[kWide] = {0, 0, 0, 0, 0, 0, 0};
                     for (std::size_t k = 0; k < t.index.size(); ++k) {
                       const float* p = src.at(t.index[k], int(y));
                       const double w = t.weight[k];
                       for (int c = 0; c < 3; ++c) {
                         acc[c] += w * p[3] * p[c];
                         acc[3 + c] += w * p[c];
                       }
                       acc[6] += w * p[3];
                     }
                     float* o = &mid[(std::size_t(y) * std::size_t(dw) + std::size_t(x)) * kWide];
                     for (int c = 0; c < kWide; ++c) o[c] = float(acc[c]);
                   }
                 }
               },
               {options.threads});

  // Vertical pass and the alpha-weighted average.
  ImageRGBAF dst(dw, dh);
  parallel_for(
      0, dh, 8,
      [&](std::int64_t y0, std::int64_t y1) {
        for (std::int64_t y = y0; y < y1; ++y) {
          const Taps& t = ty[std::size_t(y)];
          for (int x = 0; x < dw; ++x) {
            double acc[kWide] = {0, 0, 0, 0, 0, 0, 0};
            for (std::size_t k = 0; k < t.index.size(); ++k) {
              const float* p =
                  &mid[(std::size_t(t.index[k]) * std::size_t(dw) + std::size_t(x)) * kWide];
              for (int c = 0; c < kWide; ++c) acc[c] += t.weight[k] * p[c];
            }
            float* o = dst.at(x, int(y));
            const bool use_alpha = options.premultiply && acc[6] > 1e-4;
            for (int c = 0; c < 3; ++c) {
              const double v = use_alpha ? acc[c] / acc[6] : acc[3 + c];
              o[c] = float(options.clamp_colour ? std::clamp(v, 0.0, 1.0) : v);
            }
            o[3] = float(std::clamp(acc[6], 0.0, 1.0));
          }
        }
      },
      {options.threads});
  return dst;
}

}  // namespace tessera::image::detail
