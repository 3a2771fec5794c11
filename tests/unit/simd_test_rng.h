// The pseudo-random lane values of the SIMD wrapper tests (simd_test.cpp, simd_int_test.cpp and
// simd_wide_test.cpp): splitmix64 with edge values mixed in (the limits of each lane type, the
// values where 16- and 32-bit products and sums wrap), a fixed sequence on every platform.
#pragma once

#include <cstdint>
#include <limits>

namespace simd_test {

/// splitmix64: a fixed sequence on every platform.
struct Rng {
  std::uint64_t s;
  std::uint32_t next() {
    std::uint64_t z = (s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return std::uint32_t(z ^ (z >> 31));
  }
  std::int32_t i32() {
    static constexpr std::int32_t kEdge[] = {
        0,      1,      -1,    2,     255,   256,    -255,    -256,      32767,     32768,
        -32768, -32769, 65535, 65536, 46340, -46341, 1 << 30, INT32_MAX, INT32_MIN, INT32_MIN + 1};
    const std::uint32_t r = next();
    switch (r & 3) {
      case 0:
        return kEdge[(r >> 2) % (sizeof(kEdge) / sizeof(kEdge[0]))];
      case 1:
        return std::int32_t((r >> 2) % 1024) - 384;  // around 0..255
      default:
        return std::int32_t(next());
    }
  }
  std::uint16_t u16() {
    static constexpr std::uint16_t kEdge[] = {0, 1, 2, 255, 256, 0x7fff, 0x8000, 0x8001, 0xffff};
    const std::uint32_t r = next();
    switch (r & 3) {
      case 0:
        return kEdge[(r >> 2) % (sizeof(kEdge) / sizeof(kEdge[0]))];
      case 1:
        return std::uint16_t((r >> 2) % 512);
      default:
        return std::uint16_t(r >> 16);
    }
  }
  float f32() {
    static constexpr float kEdge[] = {0.0f,          -0.0f, 1.0f,   -1.5f, 8388608.0f,
                                      2147483648.0f, -3e9f, 1e-40f, 255.5f};
    const std::uint32_t r = next();
    if ((r & 3) == 0) return kEdge[(r >> 2) % (sizeof(kEdge) / sizeof(kEdge[0]))];
    if ((r & 3) == 1) return std::numeric_limits<float>::quiet_NaN();
    return float(std::int32_t(next()) % 100000) * 0.37f;
  }
};

}  // namespace simd_test
