// Helpers shared by the 4-lane wrapper tests (simd_test.cpp, simd_int_test.cpp): lane views of
// vf4 / vint4 and a fixed pseudo-random sequence of edge and generated values.
#pragma once

#include <cstdint>

#include "core/simd.h"

namespace simd_test {

namespace simd = tessera::simd;
using tessera::simd::vf4;
using tessera::simd::vint4;

struct Lanes {
  float f[4];
};
inline Lanes lanes(vf4 a) {
  Lanes r;
  simd::storef4(a, r.f);
  return r;
}
struct ILanes {
  std::int32_t i[4];
};
inline ILanes lanes(vint4 a) {
  ILanes r;
  simd::store4(a, r.i);
  return r;
}

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
    static constexpr std::int32_t kEdge[] = {0,     1,      -1,     2,      255,    256,
                                             -255,  -256,   32767,  32768,  -32768, -32769,
                                             65535, 65536,  46340,  -46341, 1 << 30,
                                             INT32_MAX,     INT32_MIN,      INT32_MIN + 1};
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
};

}  // namespace simd_test
