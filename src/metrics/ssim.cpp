// SSIM (Wang et al. 2004) with an 11x11 Gaussian window, valid region, as scikit-image computes
// it with gaussian_weights=True, sigma=1.5, use_sample_covariance=False.
#include <algorithm>
#include <array>
#include <cmath>

#include "tessera/metrics.h"

namespace tessera::metrics {

namespace {

constexpr int kRadius = 5;
constexpr int kWindow = 2 * kRadius + 1;
constexpr double kSigma = 1.5;
constexpr double kK1 = 0.01;
constexpr double kK2 = 0.03;

std::array<double, kWindow> gaussian_weights() {
  std::array<double, kWindow> w{};
  double sum = 0.0;
  for (int i = -kRadius; i <= kRadius; ++i) {
    w[i + kRadius] = std::exp(-0.5 * double(i * i) / (kSigma * kSigma));
    sum += w[i + kRadius];
  }
  for (double& v : w) v /= sum;
  return w;
}

double ssim_value(double ux, double uy, double uxx, double uyy, double uxy, double c1,
                  double c2) {
  const double vx = uxx - ux * ux;
  const double vy = uyy - uy * uy;
  const double vxy = uxy - ux * uy;
  return ((2.0 * ux * uy + c1) * (2.0 * vxy + c2)) /
         ((ux * ux + uy * uy + c1) * (vx + vy + c2));
}

/// Global SSIM with uniform weights, for images smaller than the window.
double ssim_global(std::span<const float> a, std::span<const float> b, double c1, double c2) {
  const double n = double(a.size());
  double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sx += a[i];
    sy += b[i];
    sxx += double(a[i]) * a[i];
    syy += double(b[i]) * b[i];
    sxy += double(a[i]) * b[i];
  }
  return ssim_value(sx / n, sy / n, sxx / n, syy / n, sxy / n, c1, c2);
}

/// Computes SSIM values of output rows [y0, y1) of the valid region into `out` (row-major,
/// (width - 10) per row, starting at out[0]). Returns their sum.
double ssim_rows(std::span<const float> a, std::span<const float> b, int width, int y0, int y1,
                 double c1, double c2, float* out) {
  static const std::array<double, kWindow> w = gaussian_weights();
  const int ow = width - 2 * kRadius;
  const int rows = (y1 - y0) + 2 * kRadius;
  // Horizontal pass for the input rows this band needs: 5 moments per output column.
  std::vector<double> h(std::size_t(rows) * ow * 5);
  for (int r = 0; r < rows; ++r) {
    const float* ra = &a[std::size_t(y0 + r) * width];
    const float* rb = &b[std::size_t(y0 + r) * width];
    double* hr = &h[std::size_t(r) * ow * 5];
    for (int x = 0; x < ow; ++x) {
      double mx = 0, my = 0, mxx = 0, myy = 0, mxy = 0;
      for (int k = 0; k < kWindow; ++k) {
        const double va = ra[x + k], vb = rb[x + k], wk = w[k];
        mx += wk * va;
        my += wk * vb;
        mxx += wk * va * va;
        myy += wk * vb * vb;
        mxy += wk * va * vb;
      }
      double* m = &hr[std::size_t(x) * 5];
      m[0] = mx;
      m[1] = my;
      m[2] = mxx;
      m[3] = myy;
      m[4] = mxy;
    }
  }
  double sum = 0.0;
  for (int y = 0; y < y1 - y0; ++y) {
    for (int x = 0; x < ow; ++x) {
      double m[5] = {0, 0, 0, 0, 0};
      for (int k = 0; k < kWindow; ++k) {
        const double* hm = &h[(std::size_t(y + k) * ow + x) * 5];
        for (int c = 0; c < 5; ++c) m[c] += w[k] * hm[c];
      }
      const double s = ssim_value(m[0], m[1], m[2], m[3], m[4], c1, c2);
      if (out) out[std::size_t(y) * ow + x] = float(s);
      sum += s;
    }
  }
  return sum;
}

}  // namespace

double ssim_plane(std::span<const float> a, std::span<const float> b, int width, int height,
                  const SsimOptions& options) {
  const double data_range = options.data_range;
  const double c1 = (kK1 * data_range) * (kK1 * data_range);
  const double c2 = (kK2 * data_range) * (kK2 * data_range);
  if (width < kWindow || height < kWindow) return ssim_global(a, b, c1, c2);
  const int oh = height - 2 * kRadius;
  const int ow = width - 2 * kRadius;
  const double sum = parallel_sum(
      0, oh, 32,
      [&](std::int64_t y0, std::int64_t y1) {
        return ssim_rows(a, b, width, int(y0), int(y1), c1, c2, nullptr);
      },
      {options.threads});
  return sum / (double(oh) * double(ow));
}

std::vector<float> ssim_map(std::span<const float> a, std::span<const float> b, int width,
                            int height, const SsimOptions& options) {
  if (width < kWindow || height < kWindow) return {};
  const double data_range = options.data_range;
  const double c1 = (kK1 * data_range) * (kK1 * data_range);
  const double c2 = (kK2 * data_range) * (kK2 * data_range);
  const int oh = height - 2 * kRadius;
  const int ow = width - 2 * kRadius;
  std::vector<float> map(std::size_t(oh) * ow);
  parallel_for(
      0, oh, 32,
      [&](std::int64_t y0, std::int64_t y1) {
        ssim_rows(a, b, width, int(y0), int(y1), c1, c2, &map[std::size_t(y0) * ow]);
      },
      {options.threads});
  return map;
}

std::vector<float> luma709(const ImageRGBA8& image) {
  std::vector<float> y(image.pixel_count());
  for (std::size_t i = 0; i < y.size(); ++i) {
    const std::uint8_t* p = &image.pixels[i * 4];
    y[i] = 0.2126f * float(p[0]) + 0.7152f * float(p[1]) + 0.0722f * float(p[2]);
  }
  return y;
}

Result<double> ssim_gray(const ImageRGBA8& a, const ImageRGBA8& b, const Parallel& parallel) {
  if (a.width != b.width || a.height != b.height) {
    return Status::error(ErrorCode::size_mismatch, "SSIM: images differ in size");
  }
  const std::vector<float> ya = luma709(a), yb = luma709(b);
  return ssim_plane(ya, yb, a.width, a.height,
                    {.data_range = 255.0, .threads = parallel.threads});
}

}  // namespace tessera::metrics
