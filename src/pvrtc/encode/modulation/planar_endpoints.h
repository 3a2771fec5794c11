// planar_endpoints.h — the expanded endpoints of every block as planes: the input of the 4 bpp
// modulation choice (modulation.cpp) and of the 2 bpp one (modulation_2bpp.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include "pvrtc/encode/encode_internal.h"
#include "pvrtc/format/pvrtc_kernel.h"

namespace tessera::pvrtc::detail {

/// The endpoints of the blocks of `s` expanded to 8 bits (expand_a / expand_b), planar: plane
/// image * 4 + channel (A r, g, b, a, then B), one u16 per block.
inline std::vector<std::uint16_t> planar_endpoints(const EncoderState& s) {
  const std::size_t nb = s.g.blocks();
  std::vector<std::uint16_t> ep(8 * nb);
  for (std::size_t i = 0; i < nb; ++i) {
    const Rgba5 a = expand_a(s.ca[i]), b = expand_b(s.cb[i]);
    const std::int32_t v[8] = {a.r, a.g, a.b, a.a, b.r, b.g, b.b, b.a};
    for (int k = 0; k < 8; ++k) ep[std::size_t(k) * nb + i] = std::uint16_t(v[k]);
  }
  return ep;
}

}  // namespace tessera::pvrtc::detail
