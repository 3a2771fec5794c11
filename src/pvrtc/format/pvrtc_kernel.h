// pvrtc_kernel.h — pure PVRTC1 block math shared by the decoder and the encoder.
//
// Nothing here loops over an image: these are the per-block / per-texel building blocks
// (endpoint packing, the PVRTexTool-exact bilinear upscale arithmetic, modulation weights,
// quantisation of 8-bit targets to endpoint codes). The drivers (decode.cpp, encode.cpp,
// dilation.cpp, least_squares_refinement.cpp) call them.
//
// Block word layout (little-endian u64): bits 0-31 modulation, bit 32 modulation mode,
// bits 33-47 colour A (bit 47 opaque flag), bits 48-63 colour B (bit 63 opaque flag).
// In this file an endpoint is handled as the 16-bit field `(word >> 32) & 0xffff` (A; bit 0 is
// the mode bit and is ignored) or `word >> 48` (B).
#pragma once

#include <algorithm>
#include <cstdint>

#include "core/check.h"
#include "tessera/pvrtc.h"

namespace tessera::pvrtc::detail {

/// An endpoint expanded to the decoder's working precision: r, g, b in 0..31, a in 0..15.
struct Rgba5 {
  std::int32_t r = 0, g = 0, b = 0, a = 0;
};

inline std::int32_t expand4to5(std::uint32_t v) { return std::int32_t((v << 1) | (v >> 3)); }
inline std::int32_t expand3to5(std::uint32_t v) { return std::int32_t((v << 2) | (v >> 1)); }

/// Expands colour A (16-bit field; bit 15 opaque flag, bit 0 ignored).
inline Rgba5 expand_a(std::uint32_t c) {
  Rgba5 o;
  if (c & 0x8000u) {
    o.r = std::int32_t((c >> 10) & 31);
    o.g = std::int32_t((c >> 5) & 31);
    o.b = expand4to5((c >> 1) & 15);
    o.a = 15;
  } else {
    o.a = std::int32_t((c >> 11) & 0xe);
    o.r = expand4to5((c >> 8) & 15);
    o.g = expand4to5((c >> 4) & 15);
    o.b = expand3to5((c >> 1) & 7);
  }
  return o;
}

/// Expands colour B (16-bit field; bit 15 opaque flag).
inline Rgba5 expand_b(std::uint32_t c) {
  Rgba5 o;
  if (c & 0x8000u) {
    o.r = std::int32_t((c >> 10) & 31);
    o.g = std::int32_t((c >> 5) & 31);
    o.b = std::int32_t(c & 31);
    o.a = 15;
  } else {
    o.a = std::int32_t((c >> 11) & 0xe);
    o.r = expand4to5((c >> 8) & 15);
    o.g = expand4to5((c >> 4) & 15);
    o.b = expand4to5(c & 15);
  }
  return o;
}

/// Channel codes of one endpoint before packing. `opaque` selects the RGB554/555 layouts,
/// otherwise ARGB3443 (A) / ARGB3444 (B); `a` is the 3-bit alpha code when translucent.
struct EndpointCodes {
  bool opaque = true;
  std::uint32_t r = 0, g = 0, b = 0, a = 0;
};

/// Bit depths of (r, g, b, a) for endpoint A (is_b false) or B.
inline void channel_bits(bool is_b, bool opaque, int bits[4]) {
  if (opaque) {
    bits[0] = 5;
    bits[1] = 5;
    bits[2] = is_b ? 5 : 4;
    bits[3] = 0;
  } else {
    bits[0] = 4;
    bits[1] = 4;
    bits[2] = is_b ? 4 : 3;
    bits[3] = 3;
  }
}

inline std::uint32_t pack_endpoint(bool is_b, const EndpointCodes& e) {
  if (e.opaque) {
    return 0x8000u | (e.r << 10) | (e.g << 5) | (is_b ? e.b : (e.b << 1));
  }
  return (e.a << 12) | (e.r << 8) | (e.g << 4) | (is_b ? e.b : (e.b << 1));
}

inline EndpointCodes unpack_endpoint(bool is_b, std::uint32_t c) {
  EndpointCodes e;
  e.opaque = (c & 0x8000u) != 0;
  if (e.opaque) {
    e.r = (c >> 10) & 31;
    e.g = (c >> 5) & 31;
    e.b = is_b ? (c & 31) : ((c >> 1) & 15);
  } else {
    e.a = (c >> 12) & 7;
    e.r = (c >> 8) & 15;
    e.g = (c >> 4) & 15;
    e.b = is_b ? (c & 15) : ((c >> 1) & 7);
  }
  return e;
}

/// 8-bit value a colour code of `bits` (3, 4 or 5) decodes to in a uniform region.
inline int code_level_rgb(std::uint32_t code, int bits) {
  std::int32_t e = bits == 5 ? std::int32_t(code) : bits == 4 ? expand4to5(code) : expand3to5(code);
  return (e << 3) | (e >> 2);
}
/// 8-bit alpha of a translucent 3-bit alpha code in a uniform region (a4 = 2 a3, 17 a4).
inline int code_level_alpha(std::uint32_t code) { return int(34 * code); }

/// Level of a channel code: channel 3 (alpha) uses `code_level_alpha`.
inline int code_level(std::uint32_t code, int bits, int channel) {
  return channel == 3 ? code_level_alpha(code) : code_level_rgb(code, bits);
}

/// Largest code whose level is <= `level` (0 if none), for a channel of `bits` bits.
inline std::uint32_t code_floor(float level, int bits, int channel) {
  const std::uint32_t maxc = (1u << bits) - 1;
  float f = level * float(maxc) / 255.0f;
  std::int32_t c = std::clamp(std::int32_t(f), 0, std::int32_t(maxc));
  while (c < std::int32_t(maxc) && float(code_level(std::uint32_t(c + 1), bits, channel)) <= level)
    ++c;
  while (c > 0 && float(code_level(std::uint32_t(c), bits, channel)) > level) --c;
  return std::uint32_t(c);
}

/// Nearest code to an 8-bit level (ties: the lower code), by search: the definition that the
/// encoder's table lookup `code_nearest_fast` below is tested against.
inline std::uint32_t code_nearest(float level, int bits, int channel) {
  const std::uint32_t maxc = (1u << bits) - 1;
  std::uint32_t c = code_floor(level, bits, channel);
  if (c < maxc) {
    const float d0 = level - float(code_level(c, bits, channel));
    const float d1 = float(code_level(c + 1, bits, channel)) - level;
    if (d1 < d0) ++c;
  }
  return c;
}

/// `code_nearest` by table: the nearest code is the number of codes c < max whose midpoint
/// (L(c) + L(c + 1)) / 2 lies strictly below the level (levels rise with the code; a level on
/// a midpoint keeps the lower code, as `code_nearest` does). With the midpoint sums integers,
/// that count depends only on ceil(2 level), clamped to 0..511, which indexes the table. Same
/// result as `code_nearest` for every finite level (tests/unit/pvrtc_search_test.cpp checks).
struct NearestCodeTable {
  std::uint8_t code[512];
};
constexpr NearestCodeTable make_nearest_code_table(int bits, bool alpha) {
  NearestCodeTable t{};
  const int maxc = (1 << bits) - 1;
  auto level = [&](int c) {
    if (alpha) return 34 * c;
    const int e = bits == 5 ? c : bits == 4 ? ((c << 1) | (c >> 3)) : ((c << 2) | (c >> 1));
    return (e << 3) | (e >> 2);
  };
  for (int i = 0; i < 512; ++i) {
    int n = 0;
    for (int c = 0; c < maxc; ++c) n += level(c) + level(c + 1) < i ? 1 : 0;
    t.code[i] = std::uint8_t(n);
  }
  return t;
}
inline constexpr NearestCodeTable kNearest5 = make_nearest_code_table(5, false);
inline constexpr NearestCodeTable kNearest4 = make_nearest_code_table(4, false);
inline constexpr NearestCodeTable kNearest3 = make_nearest_code_table(3, false);
inline constexpr NearestCodeTable kNearestAlpha3 = make_nearest_code_table(3, true);

/// Table index of a level: ceil(2 level) clamped to 0..511.
inline int nearest_code_index(float level) {
  const float t = std::clamp(2.0f * level, -1.0f, 511.0f);
  const int i = int(t);  // truncation: the ceiling for t <= 0
  return std::max(i + (float(i) < t ? 1 : 0), 0);
}

/// The code nearest to `level` from `table` (one of the kNearest* tables).
inline std::uint32_t code_nearest_fast(const NearestCodeTable& table, float level) {
  return table.code[nearest_code_index(level)];
}

/// Bilinear weights of texel coordinate `x` along one axis with blocks `bw` texels wide in a
/// padded extent of `extent` texels (a power of two): the left block index `b0`, the right
/// block index `b1` (wrapping) and the right weight `d` in [0, bw) (left weight bw - d).
struct AxisTap {
  std::int32_t b0, b1, d;
};
inline AxisTap axis_tap(std::int32_t x, std::int32_t bw, std::int32_t extent) {
  const std::int32_t xx = (x - bw / 2) & (extent - 1);
  const std::int32_t nb = extent / bw;
  AxisTap t;
  t.b0 = xx / bw;
  t.d = xx % bw;
  t.b1 = (t.b0 + 1) & (nb - 1);
  return t;
}

/// PVRTexTool-exact conversion of a bilinear sum `w32` (weights summing to 32, 5-bit colour)
/// to 8 bits, and of an alpha sum (weights summing to 32, 4-bit alpha).
inline std::int32_t w32_to_rgb8(std::int32_t w32) { return (w32 >> 7) + (w32 >> 2); }
inline std::int32_t w32_to_alpha8(std::int32_t w32) { return (w32 >> 5) + (w32 >> 1); }

/// Upscaled 8-bit colour of one texel from four expanded endpoints (p top-left, q top-right,
/// r bottom-left, s bottom-right) with horizontal weight `dx` of `bw` and vertical `dy` of 4.
inline void upscale_texel(const Rgba5& p, const Rgba5& q, const Rgba5& r, const Rgba5& s,
                          std::int32_t dx, std::int32_t dy, std::int32_t bw, std::uint8_t out[4]) {
  const std::int32_t wp = (bw - dx) * (4 - dy), wq = dx * (4 - dy), wr = (bw - dx) * dy,
                     ws = dx * dy;
  const std::int32_t scale = bw == 4 ? 2 : 1;  // weights sum to 16 (4 bpp) or 32 (2 bpp)
  const std::int32_t R = (p.r * wp + q.r * wq + r.r * wr + s.r * ws) * scale;
  const std::int32_t G = (p.g * wp + q.g * wq + r.g * wr + s.g * ws) * scale;
  const std::int32_t B = (p.b * wp + q.b * wq + r.b * wr + s.b * ws) * scale;
  const std::int32_t A = (p.a * wp + q.a * wq + r.a * wr + s.a * ws) * scale;
  out[0] = std::uint8_t(w32_to_rgb8(R));
  out[1] = std::uint8_t(w32_to_rgb8(G));
  out[2] = std::uint8_t(w32_to_rgb8(B));
  out[3] = std::uint8_t(w32_to_alpha8(A));
}

/// Modulation weights towards B in eighths: 4 bpp mode 0, 4 bpp mode 1 (index 2 is the
/// punch-through value), and the 2-bit values of 2 bpp.
inline constexpr std::int32_t kMod4Mode0[4] = {0, 3, 5, 8};
inline constexpr std::int32_t kMod4Mode1[4] = {0, 4, 4, 8};
/// Flag or-ed into an effective modulation weight when alpha is forced to 0.
inline constexpr std::uint8_t kPunchFlag = 0x10;

/// Final texel from upscaled A and B and an effective modulation weight (0..8, maybe with
/// kPunchFlag): (A (8 - m) + B m) / 8 with integer division; alpha 0 when punched.
inline void modulate(const std::uint8_t a[4], const std::uint8_t b[4], std::uint8_t m_eff,
                     std::uint8_t out[4]) {
  const std::int32_t m = m_eff & 0x0f;
  for (int c = 0; c < 4; ++c) out[c] = std::uint8_t((a[c] * (8 - m) + b[c] * m) / 8);
  if (m_eff & kPunchFlag) out[3] = 0;
}

/// Morton index (see pvrtc.h).
inline std::uint32_t morton(std::uint32_t bx, std::uint32_t by, std::uint32_t bw,
                            std::uint32_t bh) {
  TESSERA_DCHECK(bw > 0 && (bw & (bw - 1)) == 0 && bh > 0 && (bh & (bh - 1)) == 0);
  TESSERA_DCHECK(bx < bw && by < bh);
  const std::uint32_t mn = std::min(bw, bh);
  std::uint32_t idx = 0, shift = 0;
  for (std::uint32_t bit = 1; bit < mn; bit <<= 1) {
    if (by & bit) idx |= 1u << shift;
    if (bx & bit) idx |= 1u << (shift + 1);
    shift += 2;
  }
  std::uint32_t log_mn = 0;
  while ((1u << log_mn) < mn) ++log_mn;
  const std::uint32_t rest = bw > bh ? (bx >> log_mn) : (by >> log_mn);
  TESSERA_DCHECK((idx | (rest << shift)) < bw * bh);
  return idx | (rest << shift);
}

}  // namespace tessera::pvrtc::detail
