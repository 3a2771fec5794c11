// Status names, image size limits and sRGB conversion.
#include <algorithm>
#include <array>
#include <cmath>

#include "tessera/core.h"

namespace tessera {

const char* error_code_name(ErrorCode code) {
  switch (code) {
    case ErrorCode::ok: return "ok";
    case ErrorCode::invalid_argument: return "invalid_argument";
    case ErrorCode::io_error: return "io_error";
    case ErrorCode::corrupt_data: return "corrupt_data";
    case ErrorCode::unsupported: return "unsupported";
    case ErrorCode::too_large: return "too_large";
    case ErrorCode::size_mismatch: return "size_mismatch";
  }
  return "unknown";
}

Status check_image_size(std::int64_t width, std::int64_t height, const std::string& what) {
  if (width <= 0 || height <= 0) {
    return Status::error(ErrorCode::corrupt_data, what + ": invalid image size " +
                                                      std::to_string(width) + "x" +
                                                      std::to_string(height));
  }
  if (width > kMaxImageDimension || height > kMaxImageDimension ||
      std::uint64_t(width) * std::uint64_t(height) > kMaxImagePixels) {
    return Status::error(ErrorCode::too_large,
                         what + ": image size " + std::to_string(width) + "x" +
                             std::to_string(height) + " exceeds the limit (" +
                             std::to_string(kMaxImageDimension) + " per side, " +
                             std::to_string(kMaxImagePixels >> 20) + " Mpx)");
  }
  return Status::success();
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
