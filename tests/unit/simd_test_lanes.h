// Helpers shared by the 4-lane wrapper tests (simd_test.cpp, simd_int_test.cpp): the wrapper's
// 4-lane types, lane views of vf32x4 / vi32x4, and (simd_test_rng.h) a fixed pseudo-random
// sequence of edge and generated values.
#pragma once

#include <cstdint>

#include "core/simd.h"
#include "simd_test_rng.h"

namespace simd_test {

namespace simd = tessera::simd;
using tessera::simd::vf32x4;
using tessera::simd::vi32x4;
using tessera::simd::vi64x2;
using tessera::simd::vu16x8;
using tessera::simd::vu8x16;

struct Lanes {
  float f[4];
};
inline Lanes lanes(vf32x4 a) {
  Lanes r;
  simd::storef4(a, r.f);
  return r;
}
struct ILanes {
  std::int32_t i[4];
};
inline ILanes lanes(vi32x4 a) {
  ILanes r;
  simd::store4(a, r.i);
  return r;
}

}  // namespace simd_test
