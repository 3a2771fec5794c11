// MSE / PSNR / max error, image comparison and the error CDF of Toth 2013.
#include "tessera/metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <vector>

#include "image/normal_kernel.h"

namespace tessera::metrics {

namespace {
Status size_mismatch(const char* what, int aw, int ah, int bw, int bh) {
  return Status::error(ErrorCode::size_mismatch, std::string(what) + ": image sizes differ (" +
                                                     std::to_string(aw) + "x" + std::to_string(ah) +
                                                     " vs " + std::to_string(bw) + "x" +
                                                     std::to_string(bh) + ")");
}

constexpr std::int64_t kGrain = 1 << 14;

/// Colour x alpha: sum over texels and R, G, B of (ca * aa - cb * ab)^2, in 8-bit units times
/// 255 (integers, so exact within each chunk); an image without alpha counts as opaque.
double premultiplied_sse(const ImageRGBA8& a, const ImageRGBA8& b, int threads) {
  return parallel_sum(0, std::int64_t(a.pixel_count()), kGrain,
                      [&](std::int64_t i0, std::int64_t i1) {
                        std::int64_t s = 0;
                        for (std::int64_t i = i0; i < i1; ++i) {
                          const int alpha_a = a.has_alpha ? a.pixels[i * 4 + 3] : 255;
                          const int alpha_b = b.has_alpha ? b.pixels[i * 4 + 3] : 255;
                          for (int c = 0; c < 3; ++c) {
                            const std::int64_t d = int(a.pixels[i * 4 + c]) * alpha_a -
                                                   int(b.pixels[i * 4 + c]) * alpha_b;
                            s += d * d;
                          }
                        }
                        return double(s);
                      },
                      {threads});
}

/// The angle in degrees between the normals texel `i` of `a` and `b` hold.
double normal_angle_deg(const ImageRGBA8& a, const ImageRGBA8& b, std::size_t i) {
  double u[3], v[3];
  for (int c = 0; c < 3; ++c) {
    u[c] = image::detail::decode_normal(a.pixels[i * 4 + std::size_t(c)]);
    v[c] = image::detail::decode_normal(b.pixels[i * 4 + std::size_t(c)]);
  }
  image::detail::normalise_or_z(u);
  image::detail::normalise_or_z(v);
  const double cross[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                           u[0] * v[1] - u[1] * v[0]};
  const double sine = std::sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]);
  const double cosine = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
  // atan2 keeps small angles accurate where acos(cosine) would lose them.
  return std::atan2(sine, cosine) * (180.0 / std::numbers::pi);
}

/// Fills the angular error fields of `r` (mean summed in texel order, p99 by nearest rank).
void angular_errors(const ImageRGBA8& a, const ImageRGBA8& b, int threads, ImageComparison& r) {
  const std::int64_t n = std::int64_t(a.pixel_count());
  std::vector<double> angles(static_cast<std::size_t>(n));
  parallel_for(0, n, kGrain,
               [&](std::int64_t i0, std::int64_t i1) {
                 for (std::int64_t i = i0; i < i1; ++i) {
                   angles[std::size_t(i)] = normal_angle_deg(a, b, std::size_t(i));
                 }
               },
               {threads});
  const double sum = parallel_sum(0, n, kGrain,
                                  [&](std::int64_t i0, std::int64_t i1) {
                                    double s = 0.0;
                                    for (std::int64_t i = i0; i < i1; ++i)
                                      s += angles[std::size_t(i)];
                                    return s;
                                  },
                                  {threads});
  r.has_normal = true;
  r.angular_error_mean_deg = sum / double(n);
  r.angular_error_max_deg = *std::max_element(angles.begin(), angles.end());
  // Nearest rank: the ceil(0.99 n)-th smallest angle.
  const std::int64_t rank = (99 * n + 99) / 100;
  const auto at = angles.begin() + (rank - 1);
  std::nth_element(angles.begin(), at, angles.end());
  r.angular_error_p99_deg = *at;
}

}  // namespace

double psnr_from_mse(double mse, double peak) {
  if (mse <= 0.0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(peak * peak / mse);
}

Result<ImageComparison> compare_images(const ImageRGBA8& a, const ImageRGBA8& b,
                                       const CompareOptions& options) {
  if (a.width != b.width || a.height != b.height) {
    return size_mismatch("compare", a.width, a.height, b.width, b.height);
  }
  ImageComparison r;
  r.has_alpha = a.has_alpha || b.has_alpha;
  const std::int64_t n = std::int64_t(a.pixel_count());
  r.has_premultiplied = options.premultiplied;
  r.has_normal = options.normal;
  if (n == 0) return r;
  // Sums of squared 8-bit differences are integers: exact in double up to 2^53.
  const double sse_rgb = parallel_sum(0, n, kGrain,
                                      [&](std::int64_t i0, std::int64_t i1) {
                                        std::int64_t s = 0;
                                        for (std::int64_t i = i0; i < i1; ++i) {
                                          for (int c = 0; c < 3; ++c) {
                                            const int d =
                                                int(a.pixels[i * 4 + c]) - int(b.pixels[i * 4 + c]);
                                            s += d * d;
                                          }
                                        }
                                        return double(s);
                                      },
                                      {options.threads});
  const double sse_alpha = parallel_sum(0, n, kGrain,
                                        [&](std::int64_t i0, std::int64_t i1) {
                                          std::int64_t s = 0;
                                          for (std::int64_t i = i0; i < i1; ++i) {
                                            const int d =
                                                int(a.pixels[i * 4 + 3]) - int(b.pixels[i * 4 + 3]);
                                            s += d * d;
                                          }
                                          return double(s);
                                        },
                                        {options.threads});
  const int channels = r.has_alpha ? 4 : 3;
  int max_abs = 0;
  for (std::int64_t i = 0; i < n; ++i) {
    for (int c = 0; c < channels; ++c) {
      max_abs = std::max(max_abs, std::abs(int(a.pixels[i * 4 + c]) - int(b.pixels[i * 4 + c])));
    }
  }
  r.max_abs = max_abs;
  r.mse_rgb = sse_rgb / (3.0 * double(n));
  r.psnr_rgb = psnr_from_mse(r.mse_rgb);
  if (r.has_alpha) {
    r.mse_alpha = sse_alpha / double(n);
    r.psnr_alpha = psnr_from_mse(r.mse_alpha);
  }
  if (options.premultiplied) {
    r.mse_premultiplied =
        premultiplied_sse(a, b, options.threads) / (255.0 * 255.0 * 3.0 * double(n));
    r.psnr_premultiplied = psnr_from_mse(r.mse_premultiplied);
  }
  if (options.normal) angular_errors(a, b, options.threads, r);
  if (options.compute_ssim) r.ssim_gray = *ssim_gray(a, b, {options.threads});
  return r;
}

Result<std::vector<float>> error_norms(const ImageRGBAF& a, const ImageRGBAF& b) {
  if (a.width != b.width || a.height != b.height) {
    return size_mismatch("error norms", a.width, a.height, b.width, b.height);
  }
  std::vector<float> e(a.pixel_count());
  for (std::size_t i = 0; i < e.size(); ++i) {
    const float* pa = &a.pixels[i * 4];
    const float* pb = &b.pixels[i * 4];
    const float dr = pa[0] - pb[0], dg = pa[1] - pb[1], db = pa[2] - pb[2];
    e[i] = std::sqrt(dr * dr + dg * dg + db * db);
  }
  return e;
}

Result<std::vector<double>> error_cdf(const ImageRGBAF& a, const ImageRGBAF& b,
                                      std::span<const double> thresholds,
                                      std::span<const std::uint8_t> mask) {
  Result<std::vector<float>> norms = error_norms(a, b);
  if (!norms) return norms.status();
  if (!mask.empty() && mask.size() != norms->size()) {
    return Status::error(ErrorCode::size_mismatch, "error CDF: mask size differs from image");
  }
  std::vector<float> counted;
  counted.reserve(norms->size());
  for (std::size_t i = 0; i < norms->size(); ++i) {
    if (mask.empty() || mask[i]) counted.push_back((*norms)[i]);
  }
  std::sort(counted.begin(), counted.end());
  std::vector<double> cdf(thresholds.size(), 0.0);
  if (counted.empty()) return cdf;
  for (std::size_t t = 0; t < thresholds.size(); ++t) {
    // Count of values >= x: everything from the first element not less than x.
    const auto first = std::lower_bound(counted.begin(), counted.end(), thresholds[t],
                                        [](float v, double x) { return double(v) < x; });
    cdf[t] = double(counted.end() - first) / double(counted.size());
  }
  return cdf;
}

ErrorCdfAccumulator::ErrorCdfAccumulator(std::vector<double> thresholds)
    : thresholds_(std::move(thresholds)), bins_(thresholds_.size(), 0) {}

Status ErrorCdfAccumulator::add(const ImageRGBAF& a, const ImageRGBAF& b,
                                std::span<const std::uint8_t> mask) {
  if (!std::is_sorted(thresholds_.begin(), thresholds_.end())) {
    return Status::error(ErrorCode::invalid_argument, "error CDF: thresholds not ascending");
  }
  Result<std::vector<float>> norms = error_norms(a, b);
  if (!norms) return norms.status();
  if (!mask.empty() && mask.size() != norms->size()) {
    return Status::error(ErrorCode::size_mismatch, "error CDF: mask size differs from image");
  }
  for (std::size_t i = 0; i < norms->size(); ++i) {
    if (!mask.empty() && !mask[i]) continue;
    const float v = (*norms)[i];
    ++counted_;
    sum_ += double(v);
    // The last threshold not above v: v counts towards it and every smaller one (a NaN error
    // towards none, as in `error_cdf`).
    const auto above = std::upper_bound(thresholds_.begin(), thresholds_.end(), v,
                                        [](float e, double x) { return !(double(e) >= x); });
    if (above != thresholds_.begin()) ++bins_[std::size_t(above - thresholds_.begin()) - 1];
  }
  return Status::success();
}

std::vector<double> ErrorCdfAccumulator::fractions() const {
  std::vector<double> f(bins_.size(), 0.0);
  std::uint64_t at_or_above = 0;
  for (std::size_t t = bins_.size(); t-- > 0;) {
    at_or_above += bins_[t];
    f[t] = counted_ ? double(at_or_above) / double(counted_) : 0.0;
  }
  return f;
}

}  // namespace tessera::metrics
