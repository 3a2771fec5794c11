// dilation_rows.h — row kernels of the intensity dilation written once over the SIMD wrapper's
// types and compiled per instruction set: with the 4-lane types in dilation.cpp (the baseline
// kernels) and with the 8-lane ones in dilation_avx2.cpp. Same operations lane for lane, so the
// same rows whichever width runs.
//
// Included by the -mavx2 translation unit: everything here is a template in an anonymous
// namespace (internal linkage), so no AVX2-compiled copy can stand in for a baseline one.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/simd.h"

namespace tessera::pvrtc::detail {
namespace {

/// Sets the wrap-around pad elements next to a row of w elements (x = -1 and x = w).
template <typename T>
inline void wrap_pad(T* row, int w) {
  row[-1] = row[w - 1];
  row[w] = row[0];
}

/// DilationKernels::label_row over float vectors VF (simd::vf4 or vf8): the vertical 3-max /
/// 3-min of each column into `mx` / `mn`, then each texel's label from the horizontal ones.
template <class VF>
void label_row_t(const float* i0, const float* i1, const float* i2, int w, float* mx, float* mn,
                 std::uint8_t* out) {
  using namespace simd;
  using VI = decltype(cmpeq(VF(), VF()));
  constexpr int n = kLanes<VF>;
  for (int x = 0; x < w; x += n) {
    const VF a = load_as<VF>(i0 + x), c = load_as<VF>(i1 + x), d = load_as<VF>(i2 + x);
    store(max(max(a, c), d), mx + x);
    store(min(min(a, c), d), mn + x);
  }
  wrap_pad(mx, w);
  wrap_pad(mn, w);
  const VI one(1), two(2);
  for (int x = 0; x < w; x += n) {
    const VF v = load_as<VF>(i1 + x);
    const VF m = max(max(load_as<VF>(mx + x - 1), load_as<VF>(mx + x)), load_as<VF>(mx + x + 1));
    const VF s = min(min(load_as<VF>(mn + x - 1), load_as<VF>(mn + x)), load_as<VF>(mn + x + 1));
    // A texel whose 3x3 neighbourhood has one intensity (m == s) is neither.
    const VI l = (cmpeq(m, v) & one) | (cmpeq(s, v) & two);
    store_bytes(andnot(cmpeq(m, s), l), out + x);
  }
}

/// DilationKernels::accumulate_row over byte vectors VU8 (simd::vu8x16 or vu8x32).
template <class VU8>
void accumulate_row_t(int planes, int w, const std::uint8_t* row, std::size_t stride,
                      std::uint16_t* acc, std::size_t astride, bool first) {
  using namespace simd;
  using VU16 = decltype(widen_lo(VU8()));
  constexpr int n = kLanes<VU8>, h = n / 2;
  for (int k = 0; k < planes; ++k) {
    const std::uint8_t* p = row + std::size_t(k) * stride;
    std::uint16_t* a = acc + std::size_t(k) * astride;
    for (int x = 0; x < w; x += n) {
      const VU8 v = load_as<VU8>(p + x);
      if (first) {
        store(widen_lo(v), a + x);
        store(widen_hi(v), a + x + h);
      } else {
        store(load_as<VU16>(a + x) + widen_lo(v), a + x);
        store(load_as<VU16>(a + x + h) + widen_hi(v), a + x + h);
      }
    }
  }
}

}  // namespace
}  // namespace tessera::pvrtc::detail
