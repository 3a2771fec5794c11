// modulation_2bpp.h — the 2 bpp modulation choice (direct 1-bit mode or the interpolated
// checkerboard modes, see modulation_2bpp.cpp).
#pragma once

#include <cstdint>

#include "pvrtc/encode/encode_internal.h"

namespace tessera::pvrtc::detail {

/// Chooses mode and modulation bits of every 2 bpp block for the current endpoints and returns
/// the total error of the exact decode of the result (as `total_error`).
std::uint64_t choose_modulation_2bpp(EncoderState& s);

}  // namespace tessera::pvrtc::detail
