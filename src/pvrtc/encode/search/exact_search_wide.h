// exact_search_wide.h — a helper shared by the 8-lane window evaluators of the exact searches
// (exact_search_avx2.cpp, exact_search_2bpp_avx2.cpp), over the SIMD wrapper's 8-lane types.
// Internal linkage (anonymous namespace): each translation unit that includes it has its own
// copy, so an AVX2-compiled one can never stand in for baseline code elsewhere.
#pragma once

#include <cstdint>

#include "core/simd.h"

namespace tessera::pvrtc::detail {
namespace {

/// The endpoint's four values (r, g, b, a; 16-bit) in every texel's four lanes.
inline simd::vu16x16 broadcast_endpoint(const std::int32_t v[4]) {
  return simd::broadcast64(std::uint64_t(std::uint16_t(v[0])) |
                           std::uint64_t(std::uint16_t(v[1])) << 16 |
                           std::uint64_t(std::uint16_t(v[2])) << 32 |
                           std::uint64_t(std::uint16_t(v[3])) << 48);
}

}  // namespace
}  // namespace tessera::pvrtc::detail
