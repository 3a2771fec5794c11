// tessera/core.h — status codes, results, images, colour conversion and parallel loops.
//
// Everything else in tessera is built on the types in this header:
//  * `Status` / `Result<T>`: the library never throws across its boundary; every fallible call
//    returns a status with an error code and a one-line human-readable message.
//  * `ImageRGBA8` / `ImageRGBAF`: tightly packed, row-major, top-down RGBA images;
//    `ImageView8`: 8-bit RGB or RGBA pixels someone else owns, any strides (what the PVRTC
//    encoder reads in place, e.g. a numpy array).
//  * sRGB <-> linear conversion with the exact IEC 61966-2-1 piecewise curve.
//  * `parallel_for`: the one parallel loop, with an explicit thread count. Callers write each
//    output element from exactly one iteration, so results are identical for any thread count.
//
// API conventions every public header follows (nodiscard statuses, thread counts, options
// structs, one namespace per system): docs/architecture.md, "Conventions".
// Tests: tests/unit/core_test.cpp (Status, images, sRGB), file_write_test.cpp (atomic writes).
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace tessera {

// ---------------------------------------------------------------------------------------------
// Errors
// ---------------------------------------------------------------------------------------------

/// Error categories. The CLI maps every non-ok code to exit status 1 ("bad input").
enum class ErrorCode {
  ok = 0,
  invalid_argument,  ///< A parameter is out of range (caller error).
  io_error,          ///< A file could not be opened, read, written or renamed.
  corrupt_data,      ///< A file is truncated or its contents are inconsistent.
  unsupported,       ///< A valid file uses a feature tessera does not implement.
  too_large,         ///< A size exceeds tessera's limits (checked before allocating).
  size_mismatch,     ///< Two inputs that must have equal sizes do not.
  out_of_memory,     ///< Host or device memory ran out (VK_ERROR_OUT_OF_*_MEMORY, a full pool).
  device_lost,       ///< The GPU device was lost (VK_ERROR_DEVICE_LOST): recreate the device.
};

/// Short lowercase name of an error code ("io_error", ...).
const char* error_code_name(ErrorCode code);

/// Outcome of a fallible operation: a code and, on error, a one-line message that names the
/// file (when there is one) and the problem.
struct [[nodiscard]] Status {
  ErrorCode code = ErrorCode::ok;
  std::string message;

  bool ok() const { return code == ErrorCode::ok; }
  static Status success() { return {}; }
  static Status error(ErrorCode c, std::string msg) { return {c, std::move(msg)}; }
};

/// A value or an error status (a minimal `std::expected`).
template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : value_(std::move(value)) {}          // NOLINT(google-explicit-constructor)
  Result(Status status) : status_(std::move(status)) {}  // NOLINT(google-explicit-constructor)

  bool ok() const { return value_.has_value(); }
  explicit operator bool() const { return ok(); }
  const Status& status() const { return status_; }
  T& value() & { return *value_; }
  const T& value() const& { return *value_; }
  T&& value() && { return std::move(*value_); }
  T* operator->() { return &*value_; }
  const T* operator->() const { return &*value_; }
  T& operator*() & { return *value_; }
  const T& operator*() const& { return *value_; }

 private:
  std::optional<T> value_;
  Status status_;
};

// ---------------------------------------------------------------------------------------------
// Threads
// ---------------------------------------------------------------------------------------------

/// The thread count of an operation whose only knob it is (see the conventions above); options
/// structs carry the same `int threads` member instead.
struct Parallel {
  int threads = 0;  ///< 0 = all hardware threads, 1 = the calling thread only; results never
                    ///< depend on it.
};

/// Times of one named pass of a renderer (GPU or CPU), in milliseconds; NaN where not measured:
/// the CPU has no GPU time, a Vulkan profile has GPU timestamps only (its commands run after the
/// record returns), a GL driver's impossible GL_TIME_ELAPSED reads NaN.
struct PassTime {
  std::string pass;
  /// Host time: on GL from the pass's dispatch to the end of a closing glFinish; on the CPU the
  /// pass's call.
  double wall_ms = std::numeric_limits<double>::quiet_NaN();
  /// GPU time: GL_TIME_ELAPSED, or the difference of Vulkan timestamps.
  double gpu_ms = std::numeric_limits<double>::quiet_NaN();
};
/// The sums of the passes' times (NaN when one of them is NaN; 0 for no pass).
double total_wall_ms(const std::vector<PassTime>& passes);
double total_gpu_ms(const std::vector<PassTime>& passes);

// ---------------------------------------------------------------------------------------------
// Images
// ---------------------------------------------------------------------------------------------

/// Largest width or height tessera accepts for any image.
inline constexpr int kMaxImageDimension = 1 << 16;
/// Largest pixel count tessera accepts for any image (256 Mpx = 1 GiB as RGBA8).
inline constexpr std::uint64_t kMaxImagePixels = std::uint64_t{1} << 28;

/// "WIDTHxHEIGHT" ("640x480"): how messages and reports write an image's size.
std::string size_text(std::int64_t width, std::int64_t height);

/// Checks `width` x `height` against the limits above before anything is allocated.
/// `what` names the source (usually a file path) for the error message.
Status check_image_size(std::int64_t width, std::int64_t height, const std::string& what);

/// 8-bit RGBA image, 4 bytes per pixel, rows top to bottom, no padding.
struct ImageRGBA8 {
  int width = 0;
  int height = 0;
  /// True when the source had an alpha channel (or alpha was otherwise meaningful). Metrics
  /// report alpha PSNR separately when either compared image has alpha.
  bool has_alpha = false;
  std::vector<std::uint8_t> pixels;  ///< width * height * 4 bytes.

  ImageRGBA8() = default;
  /// Allocates a zero-filled image. Sizes must already be checked (see `check_image_size`).
  ImageRGBA8(int w, int h) : width(w), height(h), pixels(std::size_t(w) * std::size_t(h) * 4) {}

  std::size_t pixel_count() const { return std::size_t(width) * std::size_t(height); }
  std::uint8_t* at(int x, int y) { return &pixels[(std::size_t(y) * width + x) * 4]; }
  const std::uint8_t* at(int x, int y) const { return &pixels[(std::size_t(y) * width + x) * 4]; }
  bool empty() const { return width == 0 || height == 0; }
};

/// A read-only view of 8-bit RGB or RGBA pixels that someone else owns (a numpy array, a mapped
/// file, an engine's staging buffer), so that an encoder can read them where they are. Each
/// texel is `channels` consecutive bytes, R, G, B (, A); texel (x, y) starts at
/// `data + y * row_stride + x * pixel_stride` (strides in bytes, either may be negative, e.g. a
/// vertically flipped view). The owner keeps the bytes alive and unchanged while a call reads
/// them.
struct ImageView8 {
  const std::uint8_t* data = nullptr;
  int width = 0;
  int height = 0;
  int channels = 4;                 ///< 3 (RGB: alpha is 255) or 4 (RGBA).
  std::ptrdiff_t pixel_stride = 4;  ///< Bytes from one texel to the next along x.
  std::ptrdiff_t row_stride = 0;    ///< Bytes from one row to the next.
  /// As `ImageRGBA8::has_alpha`: whether the alpha channel is meaningful (false for RGB).
  bool has_alpha = false;

  /// A view of all of `image` (RGBA, packed).
  static ImageView8 of(const ImageRGBA8& image) {
    return {image.pixels.data(), image.width, image.height, 4, 4, std::ptrdiff_t(image.width) * 4,
            image.has_alpha};
  }
  const std::uint8_t* at(int x, int y) const {
    return data + std::ptrdiff_t(y) * row_stride + std::ptrdiff_t(x) * pixel_stride;
  }
  /// True when the texels are packed RGBA rows with no gaps (the layout of `ImageRGBA8`).
  bool packed_rgba() const {
    return channels == 4 && pixel_stride == 4 && row_stride == std::ptrdiff_t(width) * 4;
  }
  std::size_t pixel_count() const { return std::size_t(width) * std::size_t(height); }
};

/// Checks a view: pixels present, 3 or 4 channels, `has_alpha` only with 4, and the size within
/// the limits above (strides are the owner's: any value, 0 for a broadcast, is read as given).
/// `what` names the source.
Status check_view(const ImageView8& view, const std::string& what);

/// Writes the view's texels as packed RGBA rows (width * height * 4 bytes) to `out`: alpha 255
/// for RGB views, and for every texel when `opaque`. The view must pass `check_view`.
void copy_to_rgba8(const ImageView8& view, std::uint8_t* out, bool opaque = false);

/// True when every texel's alpha is 255: always for RGB views; for RGBA ones every alpha byte is
/// read (packed rows two texels a step), whatever `has_alpha` says.
bool all_opaque(const ImageView8& view);

/// Copies a view into an owned RGBA image (alpha 255 for RGB), keeping `has_alpha`. The view
/// must pass `check_view`.
ImageRGBA8 to_image(const ImageView8& view);

/// Floating-point RGBA image, 4 floats per pixel, rows top to bottom. The colour space is the
/// caller's convention (tessera uses linear RGB unless a function says otherwise).
struct ImageRGBAF {
  int width = 0;
  int height = 0;
  std::vector<float> pixels;  ///< width * height * 4 floats.

  ImageRGBAF() = default;
  ImageRGBAF(int w, int h) : width(w), height(h), pixels(std::size_t(w) * std::size_t(h) * 4) {}

  std::size_t pixel_count() const { return std::size_t(width) * std::size_t(height); }
  float* at(int x, int y) { return &pixels[(std::size_t(y) * width + x) * 4]; }
  const float* at(int x, int y) const { return &pixels[(std::size_t(y) * width + x) * 4]; }
  bool empty() const { return width == 0 || height == 0; }
};

// ---------------------------------------------------------------------------------------------
// Colour
// ---------------------------------------------------------------------------------------------

/// Exact sRGB decoding curve (IEC 61966-2-1): x/12.92 below 0.04045, else ((x+0.055)/1.055)^2.4.
/// Input and output in [0, 1]; values outside are clamped.
float srgb_to_linear(float srgb);
/// Exact sRGB encoding curve, the inverse of `srgb_to_linear`. Clamps to [0, 1].
float linear_to_srgb(float linear);
/// Table lookup of `srgb_to_linear(v / 255)` for an 8-bit value.
float srgb8_to_linear(std::uint8_t v);
/// Encodes linear [0, 1] to the nearest 8-bit sRGB value (round to nearest).
std::uint8_t linear_to_srgb8(float linear);

/// Converts 8-bit sRGB colour to linear float; alpha is mapped linearly to [0, 1].
ImageRGBAF to_linear(const ImageRGBA8& srgb, const Parallel& parallel = {});
/// Converts linear float colour to 8-bit sRGB (rounded); alpha is mapped linearly.
ImageRGBA8 to_srgb8(const ImageRGBAF& linear, const Parallel& parallel = {});

// ---------------------------------------------------------------------------------------------
// Parallelism
// ---------------------------------------------------------------------------------------------

/// Number of worker threads `threads == 0` stands for (the hardware concurrency).
/// Size of mip level `level` of a side of `size` texels (the GL rule): max(size >> level, 1),
/// for level >= 0. The one copy of this rule: textures, mip chains and PVRTC files use it.
inline int mip_dimension(int size, int level) {
  const int s = level >= 31 ? 0 : size >> level;
  return s > 0 ? s : 1;
}

/// Levels of the full mip chain of a width x height image, level 0 included:
/// floor(log2(max(width, height))) + 1, and 0 when max(width, height) <= 0.
int mip_level_count(int width, int height);

int default_thread_count();

/// Milliseconds elapsed on the steady clock since `t0`.
double ms_since(std::chrono::steady_clock::time_point t0);

/// Median of `values`, NaN values left out: the middle value, or the mean of the middle two for
/// an even count; 0 when no value is left. The one median of the timings and benchmarks.
double median(std::vector<double> values);

/// Runs `body(begin_i, end_i)` over disjoint sub-ranges covering [begin, end), each at most
/// `grain` long, on up to `parallel.threads` threads (0 = all hardware threads, 1 = the calling
/// thread only). Sub-range boundaries are multiples of `grain` from `begin`, independent of the
/// thread count, so a body that writes only its own outputs gives identical results for any
/// thread count.
/// Blocks until all iterations finished. Thread-safe; may be nested.
void parallel_for(std::int64_t begin, std::int64_t end, std::int64_t grain,
                  const std::function<void(std::int64_t, std::int64_t)>& body,
                  const Parallel& parallel = {});

/// Deterministic parallel sum: evaluates `chunk(begin_i, end_i)` on the same fixed sub-ranges
/// as `parallel_for` and adds the partial sums in index order, so the result is bit-identical
/// for any thread count.
double parallel_sum(std::int64_t begin, std::int64_t end, std::int64_t grain,
                    const std::function<double(std::int64_t, std::int64_t)>& chunk,
                    const Parallel& parallel = {});

}  // namespace tessera
