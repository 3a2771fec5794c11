// SSIM (Wang et al. 2004) with an 11x11 Gaussian window, valid region, as scikit-image computes
// it with gaussian_weights=True, sigma=1.5, use_sample_covariance=False.
//
// Layout and order. The Gaussian window is separable: a horizontal 11-tap pass turns each input
// row into five moment rows (mean of a, of b, of a*a, b*b, a*b), and a vertical 11-tap pass over
// 11 such rows gives the window moments of one output row. Each moment is a contiguous row of
// doubles (structure of arrays), so every loop over x is a plain loop the compiler vectorises
// (2 doubles per SSE2 / NEON vector) without intrinsics. Vectorising across x keeps each element's
// arithmetic untouched: every moment starts at 0 and adds its 11 terms with k ascending, a
// product being formed as (w[k] * a) * b, and ssim_value is one expression; with -ffp-contract=off
// (the build's) nothing is fused. So every map value and every sum is the same double as the
// scalar, array-of-structs form this replaced — tests/unit/ssim_exact_test.cpp keeps that form as
// its reference and compares with EXPECT_EQ.
//
// Work split. The mean is the sum of per-band sums over bands of kBand output rows, added in band
// order (as parallel_sum does), each band summing its values row by row, x ascending: the double
// result is independent of the thread count. A task runs kBandsPerTask consecutive bands with one
// ring of 11 horizontal rows, so an input row is filtered once per task rather than once per band
// (a band needs 10 rows past its own), and its buffers are allocated once per task.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "tessera/metrics.h"

namespace tessera::metrics {

namespace {

constexpr int kRadius = 5;
constexpr int kWindow = 2 * kRadius + 1;
constexpr double kSigma = 1.5;
constexpr double kK1 = 0.01;
constexpr double kK2 = 0.03;
constexpr int kMoments = 5;        // mean a, mean b, mean a*a, mean b*b, mean a*b
constexpr int kBand = 32;          // output rows per partial sum; fixes the summation order
constexpr int kBandsPerTask = 4;   // bands one task runs with one ring (any value: same result)
constexpr int kTile = 128;         // output columns per vertical step, kept on the stack

using Weights = std::array<double, kWindow>;

Weights gaussian_weights() {
  Weights w{};
  double sum = 0.0;
  for (int i = -kRadius; i <= kRadius; ++i) {
    w[i + kRadius] = std::exp(-0.5 * double(i * i) / (kSigma * kSigma));
    sum += w[i + kRadius];
  }
  for (double& v : w) v /= sum;
  return w;
}

const Weights& weights() {
  static const Weights w = gaussian_weights();
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

/// Horizontal pass of one input row (`da`, `db`: `ow + 10` values) into the moment rows of a
/// (`hx`, `hxx`) and the cross moment `hxy`. The fold over K unrolls the 11 taps in ascending
/// order, so the loop over x is the one the compiler vectorises.
template <std::size_t... K>
void filter_row_a(const double* __restrict da, const double* __restrict db, int ow,
                  double* __restrict hx, double* __restrict hxx, double* __restrict hxy,
                  const Weights& weights, std::index_sequence<K...>) {
  const Weights w = weights;  // a local copy: no store can alias it
  for (int x = 0; x < ow; ++x) {
    double mx = 0, mxx = 0, mxy = 0;
    (
        [&] {
          const double va = da[x + int(K)], vb = db[x + int(K)], wk = w[K];
          mx += wk * va;
          mxx += wk * va * va;
          mxy += wk * va * vb;
        }(),
        ...);
    hx[x] = mx;
    hxx[x] = mxx;
    hxy[x] = mxy;
  }
}

/// The moment rows of b (`hy`, `hyy`) of one input row, as filter_row_a.
template <std::size_t... K>
void filter_row_b(const double* __restrict db, int ow, double* __restrict hy,
                  double* __restrict hyy, const Weights& weights, std::index_sequence<K...>) {
  const Weights w = weights;
  for (int x = 0; x < ow; ++x) {
    double my = 0, myy = 0;
    (
        [&] {
          const double vb = db[x + int(K)], wk = w[K];
          my += wk * vb;
          myy += wk * vb * vb;
        }(),
        ...);
    hy[x] = my;
    hyy[x] = myy;
  }
}

/// Vertical pass of one moment over `n` columns: out[t] = sum over k ascending of
/// w[k] * rows[k][t], from 0.
template <std::size_t... K>
void filter_column(const std::array<const double*, kWindow>& rows, int n, const Weights& weights,
                   double* __restrict out, std::index_sequence<K...>) {
  const Weights w = weights;  // local copies: no store can alias them
  const std::array<const double*, kWindow> r = rows;
  for (int t = 0; t < n; ++t) {
    double m = 0;
    ((m += w[K] * r[K][t]), ...);
    out[t] = m;
  }
}

/// One task's rolling state: the converted input rows and a ring of kWindow horizontal rows,
/// each kMoments contiguous moment rows of `ow` doubles.
class Ring {
 public:
  Ring(int width, int ow)
      : ow_(ow), da_(std::size_t(width)), db_(std::size_t(width)),
        h_(std::size_t(kWindow) * kMoments * std::size_t(ow)) {}

  /// Filters input row `y` of the planes (row-major, `width` floats per row) into its slot.
  void filter(const float* a, const float* b, int width, int y) {
    const float* ra = a + std::size_t(y) * std::size_t(width);
    const float* rb = b + std::size_t(y) * std::size_t(width);
    for (int x = 0; x < width; ++x) {
      da_[std::size_t(x)] = ra[x];
      db_[std::size_t(x)] = rb[x];
    }
    double* h = moment(y, 0);
    const std::size_t n = std::size_t(ow_);
    filter_row_a(da_.data(), db_.data(), ow_, h, h + 2 * n, h + 4 * n, weights(),
                 std::make_index_sequence<kWindow>{});
    filter_row_b(db_.data(), ow_, h + n, h + 3 * n, weights(), std::make_index_sequence<kWindow>{});
  }

  /// Moment row `c` of input row `y` (valid while y is among the last kWindow rows filtered).
  double* moment(int y, int c) {
    return &h_[(std::size_t(y % kWindow) * kMoments + std::size_t(c)) * std::size_t(ow_)];
  }

 private:
  int ow_;
  std::vector<double> da_, db_, h_;
};

/// Output rows [y0, y1) of the valid region (y0 a multiple of kBand): adds each value to
/// band_sums[y / kBand - y0 / kBand] (row by row, x ascending) and, when `out` is not null,
/// stores it as float at out[(y - y0) * (width - 10) + x].
void ssim_rows(const float* a, const float* b, int width, int y0, int y1, double c1, double c2,
               float* out, double* band_sums) {
  const Weights& w = weights();
  const int ow = width - 2 * kRadius;
  Ring ring(width, ow);
  for (int y = y0; y < y0 + 2 * kRadius; ++y) ring.filter(a, b, width, y);
  alignas(16) double m[kMoments][kTile];
  alignas(16) double s[kTile];
  for (int y = y0; y < y1; ++y) {
    ring.filter(a, b, width, y + 2 * kRadius);
    double& sum = band_sums[y / kBand - y0 / kBand];
    for (int x0 = 0; x0 < ow; x0 += kTile) {
      const int n = std::min(kTile, ow - x0);
      for (int c = 0; c < kMoments; ++c) {
        std::array<const double*, kWindow> rows{};
        for (int k = 0; k < kWindow; ++k) rows[std::size_t(k)] = ring.moment(y + k, c) + x0;
        filter_column(rows, n, w, m[c], std::make_index_sequence<kWindow>{});
      }
      for (int t = 0; t < n; ++t) s[t] = ssim_value(m[0][t], m[1][t], m[2][t], m[3][t], m[4][t], c1, c2);
      if (out) {
        float* o = out + std::size_t(y - y0) * std::size_t(ow) + std::size_t(x0);
        for (int t = 0; t < n; ++t) o[t] = float(s[t]);
      }
      for (int t = 0; t < n; ++t) sum += s[t];
    }
  }
}

double constants_c(double k, double data_range) { return (k * data_range) * (k * data_range); }

}  // namespace

double ssim_plane(std::span<const float> a, std::span<const float> b, int width, int height,
                  const SsimOptions& options) {
  const double c1 = constants_c(kK1, options.data_range);
  const double c2 = constants_c(kK2, options.data_range);
  if (width < kWindow || height < kWindow) return ssim_global(a, b, c1, c2);
  const int oh = height - 2 * kRadius;
  const int ow = width - 2 * kRadius;
  std::vector<double> band_sums(std::size_t((oh + kBand - 1) / kBand), 0.0);
  parallel_for(
      0, oh, std::int64_t(kBand) * kBandsPerTask,
      [&](std::int64_t y0, std::int64_t y1) {
        ssim_rows(a.data(), b.data(), width, int(y0), int(y1), c1, c2, nullptr,
                  &band_sums[std::size_t(y0 / kBand)]);
      },
      {options.threads});
  double sum = 0.0;
  for (double v : band_sums) sum += v;
  return sum / (double(oh) * double(ow));
}

std::vector<float> ssim_map(std::span<const float> a, std::span<const float> b, int width,
                            int height, const SsimOptions& options) {
  if (width < kWindow || height < kWindow) return {};
  const double c1 = constants_c(kK1, options.data_range);
  const double c2 = constants_c(kK2, options.data_range);
  const int oh = height - 2 * kRadius;
  const int ow = width - 2 * kRadius;
  std::vector<float> map(std::size_t(oh) * std::size_t(ow));
  std::vector<double> band_sums(std::size_t((oh + kBand - 1) / kBand), 0.0);
  parallel_for(
      0, oh, std::int64_t(kBand) * kBandsPerTask,
      [&](std::int64_t y0, std::int64_t y1) {
        ssim_rows(a.data(), b.data(), width, int(y0), int(y1), c1, c2,
                  &map[std::size_t(y0) * std::size_t(ow)], &band_sums[std::size_t(y0 / kBand)]);
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
