// The face arrays' texel formats (tessera/faces_gpu.h): RGBA float texels to binary16, unorm8 and
// sRGB8 as every backend uploads them, computed here so GL and Vulkan store the same bytes.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "tessera/faces_gpu.h"

namespace tessera::faces {

namespace {

/// IEEE 754 binary32 to binary16, round to nearest even; infinities and NaNs kept, overflow to
/// infinity, subnormals exact.
std::uint16_t to_half(float f) {
  std::uint32_t x;
  std::memcpy(&x, &f, 4);
  const std::uint16_t sign = std::uint16_t((x >> 16) & 0x8000u);
  const std::uint32_t abs = x & 0x7fffffffu;
  if (abs >= 0x7f800000u) {  // inf or NaN (NaN keeps a payload bit)
    return std::uint16_t(sign | 0x7c00u | (abs > 0x7f800000u ? 0x200u : 0u));
  }
  if (abs >= 0x477ff000u) return std::uint16_t(sign | 0x7c00u);  // rounds past 65504
  if (abs < 0x38800000u) {               // below the smallest normal half: a subnormal (or zero)
    if (abs < 0x33000000u) return sign;  // below half the smallest subnormal
    const std::uint32_t mant = (abs & 0x7fffffu) | 0x800000u;
    const int shift = 126 - int(abs >> 23);  // 14..24 from the float's exponent
    const std::uint32_t q = mant >> (shift + 0), rem = mant & ((1u << shift) - 1u);
    // half subnormal = mant * 2^(e - 150) / 2^-24 = mant >> (126 - e)
    const std::uint32_t halfway = 1u << (shift - 1);
    std::uint32_t h = q;
    if (rem > halfway || (rem == halfway && (q & 1u))) ++h;
    return std::uint16_t(sign | h);
  }
  std::uint32_t h = ((abs >> 13) - (112u << 10));  // rebias the exponent (127 - 15 = 112)
  const std::uint32_t rem = abs & 0x1fffu;
  if (rem > 0x1000u || (rem == 0x1000u && (h & 1u))) ++h;  // may carry into the exponent
  return std::uint16_t(sign | h);
}

std::uint8_t to_unorm8(float v) {
  if (!(v > 0.0f)) return 0;  // NaN and negatives
  if (v >= 1.0f) return 255;
  return std::uint8_t(std::lround(v * 255.0f));
}

}  // namespace

std::size_t texel_bytes(TexelFormat format) {
  switch (format) {
    case TexelFormat::rgba32f:
      return 16;
    case TexelFormat::rgba16f:
      return 8;
    case TexelFormat::rgba8_unorm:
    case TexelFormat::rgba8_srgb:
      return 4;
  }
  return 16;
}

void convert_texels(const float* rgba, std::size_t texels, TexelFormat format, std::uint8_t* out) {
  const std::size_t n = texels * 4;
  switch (format) {
    case TexelFormat::rgba32f:
      std::memcpy(out, rgba, n * 4);
      return;
    case TexelFormat::rgba16f:
      for (std::size_t i = 0; i < n; ++i) {
        const std::uint16_t h = to_half(rgba[i]);
        out[2 * i] = std::uint8_t(h & 0xffu);
        out[2 * i + 1] = std::uint8_t(h >> 8);
      }
      return;
    case TexelFormat::rgba8_unorm:
      for (std::size_t i = 0; i < n; ++i) out[i] = to_unorm8(rgba[i]);
      return;
    case TexelFormat::rgba8_srgb:
      for (std::size_t i = 0; i < n; ++i) {
        const float v = rgba[i];
        out[i] = i % 4 == 3 ? to_unorm8(v) : linear_to_srgb8(std::isnan(v) ? 0.0f : v);
      }
      return;
  }
}

}  // namespace tessera::faces
