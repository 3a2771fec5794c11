// The one definition of how normal maps store vectors, shared by `image::normalise_normals`
// and the normal-map mip chains: a component v in [-1, 1] is stored as round((v + 1) * 127.5)
// and read back as 2 c / 255 - 1; a vector shorter than 1e-6 counts as +Z.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace tessera::image::detail {

/// Shorter than this, a vector has no direction: it becomes +Z.
inline constexpr double kMinNormalLength = 1e-6;

/// 2 c / 255 - 1.
inline double decode_normal(std::uint8_t c) { return 2.0 * c / 255.0 - 1.0; }

/// round((v + 1) * 127.5), clamped to [0, 255] (0 becomes 128, 1 becomes 255).
inline std::uint8_t encode_normal(double v) {
  return std::uint8_t(std::clamp(std::lround((v + 1.0) * 127.5), 0L, 255L));
}

/// Scales `v` to unit length; a vector shorter than `kMinNormalLength` (or NaN) becomes +Z.
template <typename T>
void normalise_or_z(T v[3]) {
  const double len = std::sqrt(double(v[0]) * v[0] + double(v[1]) * v[1] + double(v[2]) * v[2]);
  if (!(len >= kMinNormalLength)) {
    v[0] = T(0);
    v[1] = T(0);
    v[2] = T(1);
    return;
  }
  for (int c = 0; c < 3; ++c) v[c] = T(v[c] / len);
}

}  // namespace tessera::image::detail
