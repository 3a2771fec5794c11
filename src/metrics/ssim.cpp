// SSIM (Wang et al. 2004) with an 11x11 Gaussian window, valid region, as scikit-image computes
// it with gaussian_weights=True, sigma=1.5, use_sample_covariance=False.
//
// Layout and order. The Gaussian window is separable: a horizontal 11-tap pass turns each input
// row into five moment rows (mean of a, of b, of a*a, b*b, a*b), and a vertical 11-tap pass over
// 11 such rows gives the window moments of one output row. The moments are kept as structure of
// arrays (per tile of kTile columns, each moment's values contiguous), so every loop over x is a
// plain loop the compiler vectorises (2 doubles per SSE2 / NEON vector) without intrinsics.
// Vectorising across x leaves each element's arithmetic untouched: every moment starts at 0 and
// adds its 11 terms with k ascending, a product being formed as (w[k] * a) * b, ssim_value is one
// expression, and the build's -ffp-contract=off fuses nothing. So every map value and every sum
// is the same double as in the scalar, array-of-structs form this replaced, whose order
// tests/unit/ssim_exact_test.cpp keeps as its reference (compared with EXPECT_EQ).
//
// Work split. The mean is the sum of per-band sums over bands of kBand output rows, added in band
// order (as parallel_sum does), each band summing its values row by row, x ascending: the double
// result is independent of the thread count and of how bands are grouped into tasks. A task runs
// up to kMaxBandsPerTask consecutive bands with one ring of 11 horizontal rows, so an input row is
// filtered once per task rather than once per band (a band needs 10 rows past its own) and the
// buffers are allocated once per task; fewer bands per task where there would otherwise be fewer
// than two tasks per thread.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
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
constexpr int kMoments = 5;  // mean a, mean b, mean a*a, mean b*b, mean a*b
constexpr int kBand = 32;    // output rows per partial sum; fixes the summation order
// Most bands one task runs with one ring (any value gives the same result).
constexpr int kMaxBandsPerTask = 4;
constexpr int kTile = 128;  // output columns per tile of a ring row
// Pitch of a tile's moment rows and padding per ring row, in doubles: one cache line more than a
// power of two, so the 55 rows the vertical pass reads at once do not share a few L1 sets.
constexpr int kPitch = kTile + 8;
constexpr int kRowPad = 8;

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

double ssim_value(double ux, double uy, double uxx, double uyy, double uxy, double c1, double c2) {
  const double vx = uxx - ux * ux;
  const double vy = uyy - uy * uy;
  const double vxy = uxy - ux * uy;
  return ((2.0 * ux * uy + c1) * (2.0 * vxy + c2)) / ((ux * ux + uy * uy + c1) * (vx + vy + c2));
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

/// Horizontal pass of columns [x0, x0 + n) of one input row (`da`, `db`: the row as doubles,
/// from x0) into the moments of a (`h` + 0, + 2 kPitch) and the cross moment (`h` + 4 kPitch),
/// `h` being the row's tile. The fold over K unrolls the 11 taps in ascending order, so the
/// loop over t is the one the compiler vectorises.
template <std::size_t... K>
void filter_row_a(const double* __restrict da, const double* __restrict db, int n,
                  double* __restrict h, const Weights& weights, std::index_sequence<K...>) {
  const Weights w = weights;  // a local copy: no store can alias it
  for (int t = 0; t < n; ++t) {
    double mx = 0, mxx = 0, mxy = 0;
    (
        [&] {
          const double va = da[t + int(K)], vb = db[t + int(K)], wk = w[K];
          mx += wk * va;
          mxx += wk * va * va;
          mxy += wk * va * vb;
        }(),
        ...);
    h[t] = mx;
    h[2 * kPitch + t] = mxx;
    h[4 * kPitch + t] = mxy;
  }
}

/// The moments of b (`h` + kPitch, + 3 kPitch), as filter_row_a. Two passes rather than one keep
/// every value in a register (the single pass spills on SSE2's 16 registers).
template <std::size_t... K>
void filter_row_b(const double* __restrict db, int n, double* __restrict h, const Weights& weights,
                  std::index_sequence<K...>) {
  const Weights w = weights;
  for (int t = 0; t < n; ++t) {
    double my = 0, myy = 0;
    (
        [&] {
          const double vb = db[t + int(K)], wk = w[K];
          my += wk * vb;
          myy += wk * vb * vb;
        }(),
        ...);
    h[kPitch + t] = my;
    h[3 * kPitch + t] = myy;
  }
}

/// Vertical pass of one tile: the five window moments of columns t < n from the tiles of the
/// 11 horizontal rows `rows` (k ascending, each moment from 0: w[k] * h), their SSIM added to
/// `sum` in column order and, with kMap, stored in map[t]. The five moment sums are
/// independent, so they keep the pipeline busy, and the serial `sum` overlaps with them.
template <bool kMap, std::size_t... K>
double window_tile(const std::array<const double*, kWindow>& rows, int n, const Weights& weights,
                   double c1, double c2, double sum, double* __restrict map,
                   std::index_sequence<K...>) {
  const Weights w = weights;  // local copies: no store can alias them
  const std::array<const double*, kWindow> r = rows;
  for (int t = 0; t < n; ++t) {
    double m0 = 0, m1 = 0, m2 = 0, m3 = 0, m4 = 0;
    ((m0 += w[K] * r[K][t]), ...);
    ((m1 += w[K] * r[K][kPitch + t]), ...);
    ((m2 += w[K] * r[K][2 * kPitch + t]), ...);
    ((m3 += w[K] * r[K][3 * kPitch + t]), ...);
    ((m4 += w[K] * r[K][4 * kPitch + t]), ...);
    const double s = ssim_value(m0, m1, m2, m3, m4, c1, c2);
    if constexpr (kMap) map[t] = s;
    sum += s;
  }
  return sum;
}

/// Luma of one RGBA8 pixel, as luma709 computes it (float, on the 0..255 scale).
float luma709_pixel(const std::uint8_t* p) {
  return 0.2126f * float(p[0]) + 0.7152f * float(p[1]) + 0.0722f * float(p[2]);
}

/// The input rows of two float planes of `width` values per row.
struct PlaneRows {
  const float* a;
  const float* b;
  int width;
  void load(int y, double* da, double* db) const {
    const float* ra = a + std::size_t(y) * std::size_t(width);
    const float* rb = b + std::size_t(y) * std::size_t(width);
    for (int x = 0; x < width; ++x) {
      da[x] = ra[x];
      db[x] = rb[x];
    }
  }
};

/// The input rows of the luma709 planes of two RGBA8 images of `width` pixels per row, made row
/// by row rather than as whole planes first (two plane-sized allocations fewer).
struct LumaRows {
  const std::uint8_t* a;
  const std::uint8_t* b;
  int width;
  void load(int y, double* da, double* db) const {
    const std::size_t row = std::size_t(y) * std::size_t(width) * 4;
    for (int x = 0; x < width; ++x) {
      da[x] = luma709_pixel(a + row + std::size_t(x) * 4);
      db[x] = luma709_pixel(b + row + std::size_t(x) * 4);
    }
  }
};

/// One task's rolling state: the converted input rows and a ring of kWindow horizontal rows.
/// A ring row is split in tiles of kTile columns, each tile holding its kMoments moment rows
/// kPitch doubles apart (mean a, mean b, mean a*a, mean b*b, mean a*b), so window_tile
/// reads all five moments at constant offsets from one pointer per row.
class Ring {
 public:
  Ring(int width, int ow)
      : ow_(ow),
        tiles_((ow + kTile - 1) / kTile),
        row_(std::size_t(tiles_) * std::size_t(kMoments * kPitch) + std::size_t(kRowPad)),
        da_(std::size_t(width)),
        db_(std::size_t(width)),
        h_(std::size_t(kWindow) * row_) {}

  /// Filters input row `y` of `rows` (PlaneRows or LumaRows) into its slot.
  template <class Rows>
  void filter(const Rows& rows, int y) {
    rows.load(y, da_.data(), db_.data());
    for (int j = 0; j < tiles_; ++j) {
      const int x0 = j * kTile, n = std::min(kTile, ow_ - x0);
      double* h = tile(y, j);
      filter_row_a(&da_[std::size_t(x0)], &db_[std::size_t(x0)], n, h, weights(),
                   std::make_index_sequence<kWindow>{});
      filter_row_b(&db_[std::size_t(x0)], n, h, weights(), std::make_index_sequence<kWindow>{});
    }
  }

  /// Tile `j` of input row `y` (valid while y is among the last kWindow rows filtered).
  const double* tile(int y, int j) const {
    return &h_[std::size_t(y % kWindow) * row_ + std::size_t(j) * std::size_t(kMoments * kPitch)];
  }
  double* tile(int y, int j) {
    return const_cast<double*>(static_cast<const Ring&>(*this).tile(y, j));
  }
  int tiles() const { return tiles_; }

 private:
  int ow_, tiles_;
  std::size_t row_;  // doubles per ring row
  std::vector<double> da_, db_, h_;
};

/// Output rows [y0, y1) of the valid region of `rows` (y0 a multiple of kBand): adds each value
/// to band_sums[y / kBand - y0 / kBand] (row by row, x ascending) and, when `out` is not null,
/// stores it as float at out[(y - y0) * (width - 10) + x].
template <class Rows>
void ssim_rows(const Rows& rows, int y0, int y1, double c1, double c2, float* out,
               double* band_sums) {
  const Weights& w = weights();
  const int ow = rows.width - 2 * kRadius;
  Ring ring(rows.width, ow);
  for (int y = y0; y < y0 + 2 * kRadius; ++y) ring.filter(rows, y);
  alignas(16) double s[kTile];
  for (int y = y0; y < y1; ++y) {
    ring.filter(rows, y + 2 * kRadius);
    double& sum = band_sums[y / kBand - y0 / kBand];
    for (int j = 0; j < ring.tiles(); ++j) {
      const int x0 = j * kTile, n = std::min(kTile, ow - x0);
      std::array<const double*, kWindow> tiles{};
      for (int k = 0; k < kWindow; ++k) tiles[std::size_t(k)] = ring.tile(y + k, j);
      if (out) {
        sum = window_tile<true>(tiles, n, w, c1, c2, sum, s, std::make_index_sequence<kWindow>{});
        float* o = out + std::size_t(y - y0) * std::size_t(ow) + std::size_t(x0);
        for (int t = 0; t < n; ++t) o[t] = float(s[t]);
      } else {
        sum = window_tile<false>(tiles, n, w, c1, c2, sum, nullptr,
                                 std::make_index_sequence<kWindow>{});
      }
    }
  }
}

double ssim_constant(double k, double data_range) { return (k * data_range) * (k * data_range); }

/// Output rows per task for `oh` output rows on `threads` threads (0 = all hardware threads): a
/// multiple of kBand, so that tasks hold whole bands.
std::int64_t task_rows(int oh, int threads) {
  const int hardware = default_thread_count();
  const int t = threads > 0 ? std::min(threads, hardware) : hardware;
  const int bands = (oh + kBand - 1) / kBand;
  return std::int64_t(kBand) * std::clamp(bands / (2 * t), 1, kMaxBandsPerTask);
}

/// Mean SSIM over the valid region of `rows` (at least kWindow x kWindow): the band sums added
/// in band order, divided by the value count.
template <class Rows>
double ssim_mean(const Rows& rows, int height, double c1, double c2, int threads) {
  const int oh = height - 2 * kRadius;
  const int ow = rows.width - 2 * kRadius;
  std::vector<double> band_sums(std::size_t((oh + kBand - 1) / kBand), 0.0);
  parallel_for(0, oh, task_rows(oh, threads),
               [&](std::int64_t y0, std::int64_t y1) {
                 ssim_rows(rows, int(y0), int(y1), c1, c2, nullptr,
                           &band_sums[std::size_t(y0 / kBand)]);
               },
               {threads});
  double sum = 0.0;
  for (double v : band_sums) sum += v;
  return sum / (double(oh) * double(ow));
}

}  // namespace

double ssim_plane(std::span<const float> a, std::span<const float> b, int width, int height,
                  const SsimOptions& options) {
  const double c1 = ssim_constant(kK1, options.data_range);
  const double c2 = ssim_constant(kK2, options.data_range);
  if (width < kWindow || height < kWindow) return ssim_global(a, b, c1, c2);
  return ssim_mean(PlaneRows{a.data(), b.data(), width}, height, c1, c2, options.threads);
}

std::vector<float> ssim_map(std::span<const float> a, std::span<const float> b, int width,
                            int height, const SsimOptions& options) {
  if (width < kWindow || height < kWindow) return {};
  const double c1 = ssim_constant(kK1, options.data_range);
  const double c2 = ssim_constant(kK2, options.data_range);
  const int oh = height - 2 * kRadius;
  const int ow = width - 2 * kRadius;
  std::vector<float> map(std::size_t(oh) * std::size_t(ow));
  std::vector<double> band_sums(std::size_t((oh + kBand - 1) / kBand), 0.0);
  parallel_for(0, oh, task_rows(oh, options.threads),
               [&](std::int64_t y0, std::int64_t y1) {
                 ssim_rows(PlaneRows{a.data(), b.data(), width}, int(y0), int(y1), c1, c2,
                           &map[std::size_t(y0) * std::size_t(ow)],
                           &band_sums[std::size_t(y0 / kBand)]);
               },
               {options.threads});
  return map;
}

std::vector<float> luma709(const ImageRGBA8& image) {
  std::vector<float> y(image.pixel_count());
  for (std::size_t i = 0; i < y.size(); ++i) y[i] = luma709_pixel(&image.pixels[i * 4]);
  return y;
}

Result<double> ssim_gray(const ImageRGBA8& a, const ImageRGBA8& b, const Parallel& parallel) {
  if (a.width != b.width || a.height != b.height) {
    return Status::error(ErrorCode::size_mismatch, "SSIM: images differ in size");
  }
  if (a.width < kWindow || a.height < kWindow) {
    const std::vector<float> ya = luma709(a), yb = luma709(b);
    return ssim_plane(ya, yb, a.width, a.height,
                      {.data_range = 255.0, .threads = parallel.threads});
  }
  return ssim_mean(LumaRows{a.pixels.data(), b.pixels.data(), a.width}, a.height,
                   ssim_constant(kK1, 255.0), ssim_constant(kK2, 255.0), parallel.threads);
}

}  // namespace tessera::metrics
