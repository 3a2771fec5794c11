// tessera/metrics.h — image quality metrics shared by every experiment.
//
// Definitions (each pinned by tests, SSIM and PSNR cross-checked against scikit-image):
//  * MSE over RGB: mean over pixels of the mean of the three squared channel differences, on
//    8-bit values. PSNR = 10 log10(255^2 / MSE); +infinity when MSE == 0.
//  * Alpha MSE/PSNR: the same on the alpha channel alone, reported when either image has alpha.
//  * SSIM (Wang et al. 2004) on Rec.709 luma Y = 0.2126 R + 0.7152 G + 0.0722 B computed in
//    floating point from the 8-bit values (not rounded), 11x11 Gaussian window with sigma 1.5
//    (normalised), K1 = 0.01, K2 = 0.03, L = 255, population (not sample) covariances, the
//    'valid' region only (no padding), and the mean of the SSIM map. Equals
//    skimage.metrics.structural_similarity(gaussian_weights=True, sigma=1.5,
//    use_sample_covariance=False, data_range=255).
//  * Premultiplied MSE/PSNR (optional): the same over R, G, B of c * a / 255 (unrounded).
//  * Angular error (optional, normal maps): per texel the angle between the two normalised
//    vectors 2 c / 255 - 1; mean, 99th percentile (nearest rank: the ceil(0.99 n)-th smallest)
//    and maximum, in degrees.
//  * Error CDF (Toth 2013, Figure 5): per-pixel 2-norm of the linear-RGB difference; for each
//    threshold x, the fraction of counted pixels whose error is >= x.
//
// All functions are deterministic (identical results for any thread count) and thread-safe.
// Tests: tests/unit/metrics_test.cpp, ssim_exact_test.cpp.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "tessera/core.h"

namespace tessera::metrics {

/// Full-reference comparison of two equally sized 8-bit images.
struct ImageComparison {
  double mse_rgb = 0.0;     ///< Mean squared error over R, G, B (8-bit units squared).
  double psnr_rgb = 0.0;    ///< dB, peak 255; +infinity for identical RGB.
  bool has_alpha = false;   ///< Whether either input has alpha (then the alpha fields are set).
  double mse_alpha = 0.0;   ///< Mean squared error of alpha.
  double psnr_alpha = 0.0;  ///< dB, peak 255; +infinity for identical alpha.
  double ssim_gray = 1.0;   ///< Mean SSIM on Rec.709 luma (see header comment). Spelt like
                            ///< the documented JSON / Python key `ssim_gray`, which it fills.
  int max_abs = 0;          ///< Largest absolute difference over all compared channels.

  /// With `CompareOptions::premultiplied`: the error of colour x alpha, what a renderer that
  /// blends shows. Each channel is c * a / 255 (not rounded) for both images, an image without
  /// alpha counting as opaque; MSE and PSNR (peak 255) over R, G, B as above. Colour under
  /// alpha 0 in both images does not count.
  bool has_premultiplied = false;
  double mse_premultiplied = 0.0;
  double psnr_premultiplied = 0.0;  ///< dB; +infinity when colour x alpha is identical.

  /// With `CompareOptions::normal`: both images' RGB read as vectors (2 c / 255 - 1) and
  /// normalised (a zero vector counts as +Z), the angle between them per texel, in degrees
  /// (alpha is ignored). The mean is over all texels.
  bool has_normal = false;
  double angular_error_mean_deg = 0.0;
  double angular_error_p99_deg = 0.0;  ///< 99th percentile (nearest rank).
  double angular_error_max_deg = 0.0;
};

/// Options for `compare_images`.
struct CompareOptions {
  bool compute_ssim = true;    ///< SSIM is the expensive part; skip it when not needed.
  int threads = 0;             ///< 0 = all hardware threads.
  bool premultiplied = false;  ///< Also the error of colour x alpha (`psnr_premultiplied`).
  bool normal = false;         ///< Also the angular error of normal maps (`angular_error_*`).
};

/// Compares `a` against `b`. Fails with `size_mismatch` when their sizes differ.
Result<ImageComparison> compare_images(const ImageRGBA8& a, const ImageRGBA8& b,
                                       const CompareOptions& options = {});

/// PSNR in dB for a given MSE and peak value (+infinity when mse == 0).
double psnr_from_mse(double mse, double peak = 255.0);

/// Rec.709 luma of an 8-bit image as floats on the 0..255 scale, row-major.
std::vector<float> luma709(const ImageRGBA8& image);

/// Options of `ssim_plane` and `ssim_map`.
struct SsimOptions {
  double data_range = 255.0;  ///< L: the planes' values lie on a 0..data_range scale.
  int threads = 0;            ///< 0 = all hardware threads; results do not depend on it.
};

/// Mean SSIM of two luma planes of `width` x `height` (values on a 0..`options.data_range`
/// scale), with the window and constants of the header comment. Images smaller than 11x11 have
/// no valid window: their SSIM is the global SSIM of the whole image (uniform weights).
double ssim_plane(std::span<const float> a, std::span<const float> b, int width, int height,
                  const SsimOptions& options = {});

/// SSIM map over the valid region ((width-10) x (height-10) values), for heatmaps.
std::vector<float> ssim_map(std::span<const float> a, std::span<const float> b, int width,
                            int height, const SsimOptions& options = {});

/// Mean SSIM on Rec.709 luma of two 8-bit images (sizes must match, else an error).
Result<double> ssim_gray(const ImageRGBA8& a, const ImageRGBA8& b, const Parallel& parallel = {});

/// Error CDF of Toth 2013, Figure 5. `a` and `b` are linear RGB (alpha ignored). For each
/// threshold x in `thresholds`, returns the fraction of counted pixels with
/// ||a - b||_2 >= x. When `mask` is non-empty (one byte per pixel), only pixels with a non-zero
/// mask byte are counted. An empty set of counted pixels gives all zeros.
Result<std::vector<double>> error_cdf(const ImageRGBAF& a, const ImageRGBAF& b,
                                      std::span<const double> thresholds,
                                      std::span<const std::uint8_t> mask = {});

/// Per-pixel 2-norm of the linear-RGB difference (the quantity `error_cdf` counts), computed in
/// single precision as a shader would: sqrtf(dr*dr + dg*dg + db*db) with float differences.
Result<std::vector<float>> error_norms(const ImageRGBAF& a, const ImageRGBAF& b);

/// The error CDF of `error_cdf` accumulated over several image pairs (Toth 2013, Figure 5 counts
/// the pixels of every frame of an orbit): `fractions()` equals `error_cdf` over the counted
/// pixels of all added pairs taken together, without keeping them (memory is one counter per
/// threshold). Also keeps the mean error and the number of counted pixels. Not thread-safe;
/// results do not depend on the thread count of anything that produced the images.
class ErrorCdfAccumulator {
 public:
  /// `thresholds` must be ascending (checked by `add`).
  explicit ErrorCdfAccumulator(std::vector<double> thresholds = {});

  /// Counts the pixels of one pair (`mask` as in `error_cdf`: empty = every pixel). Fails on a
  /// size mismatch or unsorted thresholds, leaving the accumulator unchanged.
  Status add(const ImageRGBAF& a, const ImageRGBAF& b, std::span<const std::uint8_t> mask = {});

  const std::vector<double>& thresholds() const { return thresholds_; }
  /// For each threshold x: counted pixels with error >= x, divided by `counted()` (all zeros
  /// when nothing was counted).
  std::vector<double> fractions() const;
  /// Mean error over the counted pixels (0 when none), summed in pixel order.
  double mean() const { return counted_ ? sum_ / double(counted_) : 0.0; }
  std::uint64_t counted() const { return counted_; }

 private:
  std::vector<double> thresholds_;
  std::vector<std::uint64_t> bins_;  ///< bins_[t]: errors in [thresholds[t], thresholds[t+1]).
  std::uint64_t counted_ = 0;
  double sum_ = 0.0;
};

/// Colour maps for heatmaps.
enum class ColourMap { inferno, viridis, grey };

/// Maps t in [0, 1] (clamped) to an 8-bit RGB colour of `map`.
void colour_map_rgb(ColourMap map, float t, std::uint8_t rgb[3]);

/// Colours a scalar field of `width` x `height` values: value / scale in [0, 1] through `map`.
ImageRGBA8 heatmap(std::span<const float> values, int width, int height, float scale,
                   ColourMap map = ColourMap::inferno);

/// Difference heatmap of two 8-bit images: the per-pixel maximum absolute channel difference
/// (over RGB, and alpha when either image has alpha) divided by `scale` (8-bit units; e.g. 32
/// saturates at a difference of 32) through `map`. Fails on a size mismatch.
Result<ImageRGBA8> difference_heatmap(const ImageRGBA8& a, const ImageRGBA8& b, float scale = 64.0f,
                                      ColourMap map = ColourMap::inferno);

}  // namespace tessera::metrics
