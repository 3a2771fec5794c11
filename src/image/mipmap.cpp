// Mip chains (2x2 box or windowed sinc, gamma-correct, alpha-weighted, or as normal vectors)
// and Lanczos-3 resampling.
#include <algorithm>
#include <cmath>

#include "image/mip_filters.h"
#include "image/normal_kernel.h"
#include "image/texel_loops.h"
#include "tessera/image_mipmap.h"

namespace tessera::image {

namespace {

/// Working image: colour in the filtering space (linear light when sRGB), not premultiplied,
/// alpha in [0, 1].
using Work = ImageRGBAF;

using detail::for_each_texel;
using detail::map_texels;

Work to_work(const ImageRGBA8& img, const MipmapOptions& o) {
  Work w(img.width, img.height);
  map_texels(img, w, {o.threads}, [&](const std::uint8_t* s, float* d) {
    for (int c = 0; c < 3; ++c) d[c] = o.srgb ? srgb8_to_linear(s[c]) : s[c] / 255.0f;
    d[3] = s[3] / 255.0f;
  });
  return w;
}

std::uint8_t quantise_unit(float v) {
  return std::uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

/// The 8-bit image of `w`: colour through `colour(float) -> std::uint8_t` per channel, alpha
/// quantised (255 where `has_alpha` is false).
template <class Colour>
ImageRGBA8 to_rgba8(const Work& w, bool has_alpha, int threads, Colour colour) {
  ImageRGBA8 img(w.width, w.height);
  img.has_alpha = has_alpha;
  map_texels(w, img, {threads}, [&](const float* s, std::uint8_t* d) {
    for (int c = 0; c < 3; ++c) d[c] = colour(s[c]);
    d[3] = has_alpha ? quantise_unit(s[3]) : 255;
  });
  return img;
}

ImageRGBA8 from_work(const Work& w, bool has_alpha, const MipmapOptions& o) {
  return to_rgba8(w, has_alpha, o.threads,
                  [&](float v) { return o.srgb ? linear_to_srgb8(v) : quantise_unit(v); });
}

/// Normal maps: RGB as unit vectors (decoded, normalised; zero becomes +Z), alpha in [0, 1].
Work to_normal_work(const ImageRGBA8& img, int threads) {
  Work w(img.width, img.height);
  map_texels(img, w, {threads}, [](const std::uint8_t* s, float* d) {
    for (int c = 0; c < 3; ++c) d[c] = float(detail::decode_normal(s[c]));
    detail::normalise_or_z(d);
    d[3] = s[3] / 255.0f;
  });
  return w;
}

/// Scales every vector of a filtered normal-map level back to unit length (zero becomes +Z).
void renormalise(Work& w, int threads) {
  for_each_texel(w, {threads}, [](float* p) { detail::normalise_or_z(p); });
}

/// Normal maps: each vector stored as in `normalise_normals`, alpha as in `from_work`.
ImageRGBA8 from_normal_work(const Work& w, bool has_alpha, int threads) {
  return to_rgba8(w, has_alpha, threads, [](float v) { return detail::encode_normal(v); });
}

/// Accumulates texels with weights: alpha-weighted colour, plain colour and alpha.
struct Accum {
  double pc[3] = {0, 0, 0};  // sum w * a * c
  double c[3] = {0, 0, 0};   // sum w * c
  double a = 0;              // sum w * a
  double w = 0;              // sum w

  void add(const float* t, double weight) {
    for (int k = 0; k < 3; ++k) {
      pc[k] += weight * t[3] * t[k];
      c[k] += weight * t[k];
    }
    a += weight * t[3];
    w += weight;
  }
  void store(float* out, bool premultiply) const {
    const double inv_w = w != 0 ? 1.0 / w : 0.0;
    const bool use_alpha = premultiply && a > 1e-7 * std::abs(w);
    for (int k = 0; k < 3; ++k) {
      out[k] = float(use_alpha ? pc[k] / a : c[k] * inv_w);
    }
    out[3] = float(std::clamp(a * inv_w, 0.0, 1.0));
  }
};

Work box_half(const Work& src, bool premultiply, int threads) {
  const int w = mip_dimension(src.width, 1), h = mip_dimension(src.height, 1);
  const int fx = src.width > 1 ? 2 : 1, fy = src.height > 1 ? 2 : 1;
  Work dst(w, h);
  parallel_for(0, h, 8,
               [&](std::int64_t y0, std::int64_t y1) {
                 for (std::int64_t y = y0; y < y1; ++y) {
                   for (int x = 0; x < w; ++x) {
                     Accum acc;
                     for (int dy = 0; dy < fy; ++dy) {
                       const int sy = std::min(int(y) * fy + dy, src.height - 1);
                       for (int dx = 0; dx < fx; ++dx) {
                         const int sx = std::min(x * fx + dx, src.width - 1);
                         acc.add(src.at(sx, sy), 1.0);
                       }
                     }
                     acc.store(dst.at(x, int(y)), premultiply);
                   }
                 }
               },
               {threads});
  return dst;
}

/// Taps of one output coordinate: first source index and normalised weights.
struct Taps {
  int first = 0;
  std::vector<double> weights;
};

std::vector<Taps> make_taps(int src, int dst) {
  const double scale = double(src) / dst;
  const double stretch = std::max(scale, 1.0);  // widen the kernel when minifying
  const double support = 3.0 * stretch;
  std::vector<Taps> taps(static_cast<std::size_t>(dst));
  for (int i = 0; i < dst; ++i) {
    const double centre = (i + 0.5) * scale;  // in source texel units
    const int lo = int(std::floor(centre - support));
    const int hi = int(std::ceil(centre + support));
    Taps& t = taps[std::size_t(i)];
    t.first = lo;
    double sum = 0;
    for (int s = lo; s <= hi; ++s) {
      const double wgt = detail::mip_kernel(MipFilter::lanczos, (s + 0.5 - centre) / stretch);
      t.weights.push_back(wgt);
      sum += wgt;
    }
    for (double& wgt : t.weights) wgt /= sum;
  }
  return taps;
}

/// 7-channel intermediate: alpha-weighted colour (3), plain colour (3), alpha (1), so the
/// vertical pass can finish the alpha-weighted average exactly as a 2D filter would.
/// 28 bytes per texel of the (target width x source height) image.
struct Wide {
  int width = 0, height = 0;
  std::vector<float> v;  // width * height * 7
  float* at(int x, int y) { return &v[(std::size_t(y) * width + x) * 7]; }
  const float* at(int x, int y) const { return &v[(std::size_t(y) * width + x) * 7]; }
};

}  // namespace

const char* mip_filter_name(MipFilter filter) {
  switch (filter) {
    case MipFilter::box:
      return "box";
    case MipFilter::lanczos:
      return "lanczos";
    case MipFilter::kaiser:
      return "kaiser";
  }
  return "unknown";
}

int nearest_power_of_two(int size) {
  if (size <= 1) return 1;
  int lo = 1;
  while (lo * 2 <= size && lo < (1 << 30)) lo *= 2;
  if (lo == size || lo >= (1 << 30)) return lo;
  const int hi = lo * 2;
  return (size - lo < hi - size) ? lo : hi;
}

Result<std::vector<ImageRGBA8>> generate_mipmaps(const ImageRGBA8& image,
                                                 const MipmapOptions& options) {
  if (image.empty()) {
    return Status::error(ErrorCode::invalid_argument, "generate_mipmaps: empty image");
  }
  // Normal maps: RGB are vectors, neither sRGB nor weighted by alpha.
  const bool normal = options.normal_map;
  const bool premultiply = !normal && options.premultiply && image.has_alpha;
  int count = mip_level_count(image.width, image.height);
  if (options.max_levels > 0) count = std::min(count, options.max_levels);
  std::vector<ImageRGBA8> chain;
  chain.reserve(std::size_t(count));
  chain.push_back(image);
  if (count == 1) return chain;
  Work work = normal ? to_normal_work(image, options.threads) : to_work(image, options);
  const detail::SincHalfOptions sinc{options.filter, premultiply, !normal, options.threads};
  for (int level = 1; level < count; ++level) {
    work = options.filter == MipFilter::box ? box_half(work, premultiply, options.threads)
                                            : detail::sinc_half(work, sinc);
    if (normal) {
      renormalise(work, options.threads);
      chain.push_back(from_normal_work(work, image.has_alpha, options.threads));
    } else {
      chain.push_back(from_work(work, image.has_alpha, options));
    }
  }
  return chain;
}

Result<ImageRGBA8> resize_image(const ImageRGBA8& image, int width, int height,
                                const MipmapOptions& options) {
  if (image.empty()) return Status::error(ErrorCode::invalid_argument, "resize_image: empty image");
  if (Status s = check_image_size(width, height, "resize_image target"); !s.ok()) return s;
  if (width == image.width && height == image.height) return image;
  const bool premultiply = options.premultiply && image.has_alpha;
  const Work src = to_work(image, options);
  const std::vector<Taps> tx = make_taps(image.width, width);
  const std::vector<Taps> ty = make_taps(image.height, height);

  // Horizontal pass: src.width x src.height -> width x src.height (7 channels).
  Wide mid{width, image.height, std::vector<float>(std::size_t(width) * image.height * 7)};
  parallel_for(0, image.height, 8,
               [&](std::int64_t y0, std::int64_t y1) {
                 for (std::int64_t y = y0; y < y1; ++y) {
                   for (int x = 0; x < width; ++x) {
                     const Taps& t = tx[std::size_t(x)];
                     double acc[7] = {0, 0, 0, 0, 0, 0, 0};
                     for (std::size_t k = 0; k < t.weights.size(); ++k) {
                       const int sx = std::clamp(t.first + int(k), 0, image.width - 1);
                       const float* p = src.at(sx, int(y));
                       const double wgt = t.weights[k];
                       for (int c = 0; c < 3; ++c) {
                         acc[c] += wgt * p[3] * p[c];
                         acc[3 + c] += wgt * p[c];
                       }
                       acc[6] += wgt * p[3];
                     }
                     float* o = mid.at(x, int(y));
                     for (int c = 0; c < 7; ++c) o[c] = float(acc[c]);
                   }
                 }
               },
               {options.threads});

  // Vertical pass and normalisation.
  Work dst(width, height);
  parallel_for(0, height, 8,
               [&](std::int64_t y0, std::int64_t y1) {
                 for (std::int64_t y = y0; y < y1; ++y) {
                   const Taps& t = ty[std::size_t(y)];
                   for (int x = 0; x < width; ++x) {
                     double acc[7] = {0, 0, 0, 0, 0, 0, 0};
                     for (std::size_t k = 0; k < t.weights.size(); ++k) {
                       const int sy = std::clamp(t.first + int(k), 0, image.height - 1);
                       const float* p = mid.at(x, sy);
                       for (int c = 0; c < 7; ++c) acc[c] += t.weights[k] * p[c];
                     }
                     float* o = dst.at(x, int(y));
                     const bool use_alpha = premultiply && acc[6] > 1e-4;
                     for (int c = 0; c < 3; ++c)
                       o[c] = float(use_alpha ? acc[c] / acc[6] : acc[3 + c]);
                     o[3] = float(std::clamp(acc[6], 0.0, 1.0));
                   }
                 }
               },
               {options.threads});
  return from_work(dst, image.has_alpha, options);
}

}  // namespace tessera::image
