// Shading drivers over the enlarged G-buffer: reference (all samples), default (one sample per
// pixel) and adaptive (Listing 1 of Hollander et al. 2013). Parallel over rows of output pixels;
// every pixel is written by one iteration, so results do not depend on the thread count.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/check.h"
#include "deferred_internal.h"

namespace tessera::deferred {

namespace {

void store(ImageRGBAF& img, int x, int y, const std::array<float, 3>& c) {
  float* o = img.at(x, y);
  o[0] = c[0];
  o[1] = c[1];
  o[2] = c[2];
  o[3] = 1.0f;
}

/// Luma used by the shading metric and FXAA: Rec.601 weights on sRGB-encoded clamped colour.
float luma_srgb(const std::array<float, 3>& linear) {
  return 0.299f * linear_to_srgb(linear[0]) + 0.587f * linear_to_srgb(linear[1]) +
         0.114f * linear_to_srgb(linear[2]);
}

constexpr int kRowGrain = 1;

}  // namespace

ImageRGBAF DeferredRenderer::shade_reference(const GBuffer& gb,
                                             const ShadingOptions& shading) const {
  const ShadeContext ctx(*this, gb, shading);
  const int m = gb.m, n = m * m, w = gb.width(), h = gb.height();
  const std::span<const std::uint8_t> order = sample_order(m);
  ImageRGBAF img(w, h);
  parallel_for(0, h, kRowGrain,
               [&](std::int64_t y0, std::int64_t y1) {
                 for (int y = int(y0); y < int(y1); ++y) {
                   for (int x = 0; x < w; ++x) {
                     std::array<float, 3> sum{0, 0, 0};
                     for (int p = 0; p < n; ++p) {
                       const int cell = order[std::size_t(p)];
                       const std::array<float, 3> c =
                           ctx.shade(m * x + cell % m, m * y + cell / m, 1.0f);
                       for (int k = 0; k < 3; ++k) sum[std::size_t(k)] += c[std::size_t(k)];
                     }
                     for (float& v : sum) v /= float(n);
                     store(img, x, y, sum);
                   }
                 }
               },
               {shading.threads});
  return img;
}

ImageRGBAF DeferredRenderer::shade_default(const GBuffer& gb, const ShadingOptions& shading) const {
  const ShadeContext ctx(*this, gb, shading);
  const int m = gb.m, w = gb.width(), h = gb.height();
  const int first = sample_order(m)[0];
  ImageRGBAF img(w, h);
  parallel_for(0, h, kRowGrain,
               [&](std::int64_t y0, std::int64_t y1) {
                 for (int y = int(y0); y < int(y1); ++y) {
                   for (int x = 0; x < w; ++x) {
                     store(img, x, y, ctx.shade(m * x + first % m, m * y + first / m, float(m)));
                   }
                 }
               },
               {shading.threads});
  return img;
}

namespace {

/// Pass 1 of shade_adaptive: the first sample of every window shaded into `image` (S), with its
/// light terms and its luma for the shading metric.
void shade_first_samples(const ShadeContext& ctx, const GBuffer& gb, int first, int threads,
                         ImageRGBAF& image, std::vector<LightTerms>& terms,
                         std::vector<float>& luma) {
  const int m = gb.m, w = gb.width(), h = gb.height();
  parallel_for(0, h, kRowGrain,
               [&](std::int64_t y0, std::int64_t y1) {
                 for (int y = int(y0); y < int(y1); ++y) {
                   for (int x = 0; x < w; ++x) {
                     const int gx = m * x + first % m, gy = m * y + first / m;
                     const float* s = gb.sample(gx, gy);
                     const std::size_t i = std::size_t(y) * std::size_t(w) + std::size_t(x);
                     std::array<float, 3> c = kBackground;
                     if (ctx.material(s) >= 0) {
                       terms[i] = ctx.lighting(gx, gy, s);
                       c = combine(ctx.albedo(s, float(m)), terms[i]);
                     }
                     store(image, x, y, c);
                     luma[i] = luma_srgb(c);
                   }
                 }
               },
               {threads});
}

/// Pass 2: the number of extra samples per pixel (the geometry and shading metrics).
std::vector<std::uint8_t> extra_sample_counts(const ShadeContext& ctx, const GBuffer& gb,
                                              const AdaptiveThresholds& a,
                                              const std::vector<float>& luma, int threads) {
  const int m = gb.m, n = m * m, w = gb.width(), h = gb.height();
  const int k_max = n - 1;
  std::vector<std::uint8_t> extra(std::size_t(w) * std::size_t(h), 0);
  parallel_for(0, h, kRowGrain,
               [&](std::int64_t y0, std::int64_t y1) {
                 std::vector<float> depths(static_cast<std::size_t>(n)),
                     normals(static_cast<std::size_t>(n) * 3);
                 for (int y = int(y0); y < int(y1); ++y) {
                   for (int x = 0; x < w; ++x) {
                     const std::size_t i = std::size_t(y) * std::size_t(w) + std::size_t(x);
                     if (a.force_k >= 0) {
                       extra[i] = std::uint8_t(std::min(a.force_k, k_max));
                       continue;
                     }
                     float k = 0.0f;
                     if (a.use_geometry) {
                       int background = 0;
                       for (int j = 0; j < m; ++j) {
                         for (int c = 0; c < m; ++c) {
                           const float* s = gb.sample(m * x + c, m * y + j);
                           const std::size_t q = std::size_t(j * m + c);
                           depths[q] = s[kChDepth];
                           const bool bg = ctx.material(s) < 0;
                           background += bg ? 1 : 0;
                           for (int d = 0; d < 3; ++d)
                             normals[q * 3 + std::size_t(d)] = bg ? 0.0f : s[kChNormal + d];
                         }
                       }
                       if (background > 0 && background < n) {
                         k = float(k_max);
                       } else if (background == 0) {
                         k = std::max(metric_depth(depths, a.c_depth),
                                      metric_normal(normals, a.c_normal, n));
                       }
                     }
                     if (a.use_shading && k < float(k_max)) {
                       auto l = [&](int xx, int yy) {
                         xx = std::clamp(xx, 0, w - 1);
                         yy = std::clamp(yy, 0, h - 1);
                         return luma[std::size_t(yy) * std::size_t(w) + std::size_t(xx)];
                       };
                       k = std::max(k,
                                    metric_shading(luma[i], l(x, y - 1), l(x, y + 1), l(x - 1, y),
                                                   l(x + 1, y), a.t_min, a.t_edge, a.c_shade, n));
                     }
                     extra[i] = std::uint8_t(std::clamp(int(std::lround(k)), 0, k_max));
                   }
                 }
               },
               {threads});
  return extra;
}

/// Pass 3: k more samples per pixel in index order, averaged with the first; `samples` gets
/// k + 1, `relookup` 1 where the first sample's albedo was looked up again.
void shade_extra_samples(const ShadeContext& ctx, const GBuffer& gb, const AdaptiveThresholds& a,
                         std::span<const std::uint8_t> order,
                         const std::vector<std::uint8_t>& extra,
                         const std::vector<LightTerms>& terms, int threads, ImageRGBAF& image,
                         std::vector<std::uint8_t>& samples, std::vector<std::uint8_t>& relookup) {
  const int m = gb.m, n = m * m, w = gb.width(), h = gb.height();
  parallel_for(
      0, h, kRowGrain,
      [&](std::int64_t y0, std::int64_t y1) {
        std::vector<int> mats(static_cast<std::size_t>(n));
        std::vector<float> scale(static_cast<std::size_t>(n));
        for (int y = int(y0); y < int(y1); ++y) {
          for (int x = 0; x < w; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(w) + std::size_t(x);
            const int k = extra[i];
            TESSERA_DCHECK(k >= 0 && k < n);  // k extra samples of the n = m x m window
            samples[i] = std::uint8_t(k + 1);
            if (k == 0) continue;  // S already holds the pixel
            // Texture-footprint scales (the material-boundary rule, see deferred.h).
            bool uniform = true, seam = false;
            for (int q = 0; q < n; ++q) {
              mats[std::size_t(q)] = ctx.material(gb.sample(m * x + q % m, m * y + q / m));
              uniform = uniform && mats[std::size_t(q)] == mats[0];
            }
            for (int q = 0; q < n && !seam; ++q) {
              const int cx = q % m, cy = q / m;
              const float* s = gb.sample(m * x + cx, m * y + cy);
              if (mats[std::size_t(q)] < 0) continue;
              // Right and down neighbours of the same material.
              for (int dir = 0; dir < 2 && !seam; ++dir) {
                const int nx = cx + (dir == 0), ny = cy + (dir == 1);
                if (nx >= m || ny >= m) continue;
                const int q2 = ny * m + nx;
                if (mats[std::size_t(q2)] != mats[std::size_t(q)]) continue;
                const float* t = gb.sample(m * x + nx, m * y + ny);
                const int ch = dir == 0 ? kChDuvDx : kChDuvDy;
                const float jump =
                    std::fabs(t[kChUv] - s[kChUv]) + std::fabs(t[kChUv + 1] - s[kChUv + 1]);
                const float predicted = 0.5f * (std::fabs(s[ch]) + std::fabs(s[ch + 1]) +
                                                std::fabs(t[ch]) + std::fabs(t[ch + 1]));
                seam = jump > a.seam_factor * predicted + 1e-6f;
              }
            }
            for (int p = 0; p <= k; ++p) {
              const int cell = order[std::size_t(p)];
              TESSERA_DCHECK(cell >= 0 && cell < n);  // a window index of the order (Figure 3)
              float sc = 1.0f;
              if (seam) {
                sc = 1.0f;
              } else if (uniform) {
                sc = std::sqrt(float(n) / float(k + 1));
              } else {
                int area = 0, shaded = 0;
                for (int q = 0; q < n; ++q) area += mats[std::size_t(q)] == mats[std::size_t(cell)];
                for (int r = 0; r <= k; ++r) {
                  shaded += mats[std::size_t(order[std::size_t(r)])] == mats[std::size_t(cell)];
                }
                sc = std::sqrt(float(area) / float(shaded));
              }
              scale[std::size_t(p)] = sc;
            }
            std::array<float, 3> sum{0, 0, 0};
            for (int p = 0; p <= k; ++p) {
              const int cell = order[std::size_t(p)];
              const int gx = m * x + cell % m, gy = m * y + cell / m;
              std::array<float, 3> c;
              if (p == 0) {
                // Reuse the light terms of S; only the albedo lookup sees the new footprint.
                const float* s = gb.sample(gx, gy);
                if (ctx.material(s) < 0) {
                  c = kBackground;
                } else {
                  c = combine(ctx.albedo(s, scale[0]), terms[i]);
                  relookup[i] = ctx.textured(s) ? 1 : 0;
                }
              } else {
                c = ctx.shade(gx, gy, scale[std::size_t(p)]);
              }
              for (int q = 0; q < 3; ++q) sum[std::size_t(q)] += c[std::size_t(q)];
            }
            for (float& v : sum) v /= float(k + 1);
            store(image, x, y, sum);
          }
        }
      },
      {threads});
}

}  // namespace

AdaptiveResult DeferredRenderer::shade_adaptive(const GBuffer& gb, const ShadingOptions& shading,
                                                const AdaptiveThresholds& a) const {
  const ShadeContext ctx(*this, gb, shading);
  const int m = gb.m, n = m * m, w = gb.width(), h = gb.height();
  const std::span<const std::uint8_t> order = sample_order(m);
  TESSERA_DCHECK(order.size() == std::size_t(n));  // every window cell once (Figure 3)
  const std::size_t npix = std::size_t(w) * std::size_t(h);
  AdaptiveResult res;
  res.image = ImageRGBAF(w, h);
  res.samples.assign(npix, 1);

  // Pass 1: shade the first sample of every window into S (colour, and its light terms).
  auto t0 = std::chrono::steady_clock::now();
  std::vector<LightTerms> terms(npix);
  std::vector<float> luma(npix);
  shade_first_samples(ctx, gb, order[0], shading.threads, res.image, terms, luma);
  res.ms_first = ms_since(t0);

  // Pass 2: the number of extra samples per pixel.
  t0 = std::chrono::steady_clock::now();
  const std::vector<std::uint8_t> extra = extra_sample_counts(ctx, gb, a, luma, shading.threads);
  res.ms_metric = ms_since(t0);

  // Pass 3: shade k more samples in index order and average them with the first.
  t0 = std::chrono::steady_clock::now();
  std::vector<std::uint8_t> relookup(npix, 0);
  shade_extra_samples(ctx, gb, a, order, extra, terms, shading.threads, res.image, res.samples,
                      relookup);
  res.ms_rest = ms_since(t0);
  for (std::size_t i = 0; i < npix; ++i) {
    res.samples_shaded += res.samples[i];
    res.extra_lookups += relookup[i];
  }
  return res;
}

}  // namespace tessera::deferred
