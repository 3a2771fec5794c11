// Status names, image size limits, image views and sRGB conversion.
#include "tessera/core.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "core/simd_dispatch.h"

namespace tessera {

const char* error_code_name(ErrorCode code) {
  switch (code) {
    case ErrorCode::ok:
      return "ok";
    case ErrorCode::invalid_argument:
      return "invalid_argument";
    case ErrorCode::io_error:
      return "io_error";
    case ErrorCode::corrupt_data:
      return "corrupt_data";
    case ErrorCode::unsupported:
      return "unsupported";
    case ErrorCode::too_large:
      return "too_large";
    case ErrorCode::size_mismatch:
      return "size_mismatch";
    case ErrorCode::out_of_memory:
      return "out_of_memory";
    case ErrorCode::device_lost:
      return "device_lost";
  }
  return "unknown";
}

double total_wall_ms(const std::vector<PassTime>& passes) {
  double t = 0.0;
  for (const PassTime& p : passes) t += p.wall_ms;
  return t;
}

double total_gpu_ms(const std::vector<PassTime>& passes) {
  double t = 0.0;
  for (const PassTime& p : passes) t += p.gpu_ms;
  return t;
}

std::string size_text(std::int64_t width, std::int64_t height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

Status check_image_size(std::int64_t width, std::int64_t height, const std::string& what) {
  if (width <= 0 || height <= 0) {
    return Status::error(ErrorCode::corrupt_data,
                         what + ": invalid image size " + size_text(width, height));
  }
  if (width > kMaxImageDimension || height > kMaxImageDimension ||
      std::uint64_t(width) * std::uint64_t(height) > kMaxImagePixels) {
    return Status::error(ErrorCode::too_large,
                         what + ": image size " + size_text(width, height) +
                             " exceeds the limit (" + std::to_string(kMaxImageDimension) +
                             " per side, " + std::to_string(kMaxImagePixels >> 20) + " Mpx)");
  }
  return Status::success();
}

Status check_view(const ImageView8& view, const std::string& what) {
  if (view.data == nullptr) {
    return Status::error(ErrorCode::invalid_argument, what + ": image view has no pixels");
  }
  if (view.channels != 3 && view.channels != 4) {
    return Status::error(
        ErrorCode::invalid_argument,
        what + ": image view has " + std::to_string(view.channels) + " channels (3 or 4 needed)");
  }
  if (view.has_alpha && view.channels != 4) {
    return Status::error(ErrorCode::invalid_argument,
                         what + ": image view has alpha but 3 channels");
  }
  return check_image_size(view.width, view.height, what);
}

namespace {

/// One row of `n` texels `stride` bytes apart, `C` channels each, to packed RGBA. A constant
/// stride lets the compiler vectorise the common packed layouts.
template <int C, std::ptrdiff_t kStride>
void row_to_rgba8(const std::uint8_t* in, std::ptrdiff_t stride, int n, std::uint8_t* out,
                  bool opaque) {
  if constexpr (kStride != 0) stride = kStride;
  for (int x = 0; x < n; ++x, in += stride, out += 4) {
    out[0] = in[0];
    out[1] = in[1];
    out[2] = in[2];
    out[3] = C == 4 && !opaque ? in[3] : std::uint8_t{255};
  }
}

/// A packed RGB row to packed RGBA with alpha 255: sixteen texels a step with SSSE3, else four
/// (three little-endian words in, four out: a third of the byte loop's loads and stores).
void rgb_row_to_rgba8(const std::uint8_t* in, int n, std::uint8_t* out) {
  constexpr std::uint32_t kRgb = 0x00ffffffu, kAlpha = 0xff000000u;
  int x = 0;
#if defined(TESSERA_SIMD_X86_DISPATCH)
  if (simd::cpu_has_ssse3()) {
    x = simd::rgb_to_rgba8_ssse3(in, n, out);
    in += std::ptrdiff_t(x) * 3;
    out += std::ptrdiff_t(x) * 4;
  }
#endif
  for (; x + 4 <= n; x += 4, in += 12, out += 16) {
    std::uint32_t w[3];
    std::memcpy(w, in, 12);
    const std::uint32_t o[4] = {(w[0] & kRgb) | kAlpha, ((w[0] >> 24) | (w[1] << 8)) | kAlpha,
                                ((w[1] >> 16) | (w[2] << 16)) | kAlpha, (w[2] >> 8) | kAlpha};
    std::memcpy(out, o, 16);
  }
  row_to_rgba8<3, 3>(in, 3, n - x, out, true);
}

/// A packed RGBA row with alpha forced to 255: whole texels or-ed as little-endian words
/// (vectorises).
void rgba_row_opaque(const std::uint8_t* in, int n, std::uint8_t* out) {
  for (int x = 0; x < n; ++x, in += 4, out += 4) {
    std::uint32_t v;
    std::memcpy(&v, in, 4);
    v |= 0xff000000u;
    std::memcpy(out, &v, 4);
  }
}

}  // namespace

bool all_opaque(const ImageView8& view) {
  if (view.channels != 4) return true;
  if (!view.packed_rgba()) {
    for (int y = 0; y < view.height; ++y) {
      const std::uint8_t* p = view.at(0, y) + 3;
      for (int x = 0; x < view.width; ++x, p += view.pixel_stride) {
        if (*p != 255) return false;
      }
    }
    return true;
  }
  // Two texels a step: their alpha bytes are the top bytes of each little-endian half.
  constexpr std::uint64_t kAlpha2 = 0xff000000ff000000ull;
  const std::uint8_t* p = view.data;
  const std::size_t n = view.pixel_count() * 4;
  std::uint64_t all = kAlpha2;
  std::size_t i = 0;
  for (; i + 8 <= n && all == kAlpha2; i += 8) {
    std::uint64_t v;
    std::memcpy(&v, p + i, 8);
    all &= v | ~kAlpha2;
  }
  bool opaque = all == kAlpha2;
  for (i += 3; i < n && opaque; i += 4) opaque = p[i] == 255;
  return opaque;
}

void copy_to_rgba8(const ImageView8& view, std::uint8_t* out, bool opaque) {
  const std::size_t row_bytes = std::size_t(view.width) * 4;
  if (view.packed_rgba() && !opaque) {
    std::memcpy(out, view.data, row_bytes * std::size_t(view.height));
    return;
  }
  for (int y = 0; y < view.height; ++y, out += row_bytes) {
    const std::uint8_t* in = view.at(0, y);
    if (view.channels == 4 && view.pixel_stride == 4 && !opaque) {
      std::memcpy(out, in, row_bytes);
    } else if (view.channels == 4 && view.pixel_stride == 4) {
      rgba_row_opaque(in, view.width, out);
    } else if (view.channels == 3 && view.pixel_stride == 3) {
      rgb_row_to_rgba8(in, view.width, out);
    } else if (view.channels == 4) {
      row_to_rgba8<4, 0>(in, view.pixel_stride, view.width, out, opaque);
    } else {
      row_to_rgba8<3, 0>(in, view.pixel_stride, view.width, out, true);
    }
  }
}

ImageRGBA8 to_image(const ImageView8& view) {
  ImageRGBA8 image(view.width, view.height);
  image.has_alpha = view.has_alpha;
  copy_to_rgba8(view, image.pixels.data());
  return image;
}

float srgb_to_linear(float s) {
  s = std::clamp(s, 0.0f, 1.0f);
  if (s <= 0.04045f) return s / 12.92f;
  return float(std::pow((double(s) + 0.055) / 1.055, 2.4));
}

float linear_to_srgb(float l) {
  l = std::clamp(l, 0.0f, 1.0f);
  if (l <= 0.0031308f) return l * 12.92f;
  return float(1.055 * std::pow(double(l), 1.0 / 2.4) - 0.055);
}

namespace {
const std::array<float, 256>& srgb8_table() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[i] = srgb_to_linear(float(i) / 255.0f);
    return t;
  }();
  return table;
}
}  // namespace

float srgb8_to_linear(std::uint8_t v) { return srgb8_table()[v]; }

std::uint8_t linear_to_srgb8(float linear) {
  // Not NaN-propagating: NaN maps to 0 through the clamp inside linear_to_srgb.
  if (!(linear == linear)) linear = 0.0f;
  return std::uint8_t(std::lround(linear_to_srgb(linear) * 255.0f));
}

ImageRGBAF to_linear(const ImageRGBA8& srgb, const Parallel& parallel) {
  ImageRGBAF out(srgb.width, srgb.height);
  const auto& table = srgb8_table();
  parallel_for(
      0, srgb.height, 16,
      [&](std::int64_t y0, std::int64_t y1) {
        for (std::int64_t y = y0; y < y1; ++y) {
          for (int x = 0; x < srgb.width; ++x) {
            const std::uint8_t* s = srgb.at(x, int(y));
            float* d = out.at(x, int(y));
            d[0] = table[s[0]];
            d[1] = table[s[1]];
            d[2] = table[s[2]];
            d[3] = float(s[3]) / 255.0f;
          }
        }
      },
      parallel);
  return out;
}

ImageRGBA8 to_srgb8(const ImageRGBAF& linear, const Parallel& parallel) {
  ImageRGBA8 out(linear.width, linear.height);
  parallel_for(
      0, linear.height, 16,
      [&](std::int64_t y0, std::int64_t y1) {
        for (std::int64_t y = y0; y < y1; ++y) {
          for (int x = 0; x < linear.width; ++x) {
            const float* s = linear.at(x, int(y));
            std::uint8_t* d = out.at(x, int(y));
            d[0] = linear_to_srgb8(s[0]);
            d[1] = linear_to_srgb8(s[1]);
            d[2] = linear_to_srgb8(s[2]);
            const float a = std::clamp(s[3] == s[3] ? s[3] : 0.0f, 0.0f, 1.0f);
            d[3] = std::uint8_t(std::lround(a * 255.0f));
          }
        }
      },
      parallel);
  return out;
}

int mip_level_count(int width, int height) {
  int size = width > height ? width : height;
  if (size <= 0) return 0;
  int levels = 1;
  while (size > 1) {
    size >>= 1;
    ++levels;
  }
  return levels;
}

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

double median(std::vector<double> values) {
  values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return std::isnan(v); }),
               values.end());
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace tessera
