// simd_scalar.h — part of the SIMD wrapper (include "core/simd.h", which documents the whole
// set; simd_select.h includes this file where it chose this backend): the portable 4-lane types,
// four (eight, sixteen) plain lanes per type, for other CPUs and for builds with
// -DTESSERA_NO_SIMD. Each operation spells out SSE2's result, bit for bit.
//   vi32x4, vi64x2   the 32- and 64-bit integer lanes
//   vf32x4           the single-precision lanes
//   vu16x8, vu8x16   the packed small-integer lanes, with their conversions to and from vi32x4
//                    and vf32x4
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace tessera::simd {
inline namespace TESSERA_SIMD_ISA {

// ---- vi32x4, vi64x2 ----

struct vi32x4 {
  std::int32_t l[4] = {0, 0, 0, 0};
  vi32x4() = default;
  vi32x4(std::int32_t a, std::int32_t b, std::int32_t c, std::int32_t d) : l{a, b, c, d} {}
  explicit vi32x4(std::int32_t a) : l{a, a, a, a} {}
  std::int32_t lane(int i) const { return l[i]; }
};
inline vi32x4 load4(const std::int32_t* p) { return {p[0], p[1], p[2], p[3]}; }
inline vi32x4 load4_aligned(const std::int32_t* p) { return load4(p); }
inline void store4(vi32x4 a, std::int32_t* p) {
  for (int i = 0; i < 4; ++i) p[i] = a.l[i];
}
inline void store4_aligned(vi32x4 a, std::int32_t* p) { store4(a, p); }
inline vi32x4 load_texels4(const std::uint8_t* p) {
  vi32x4 r;
  for (int i = 0; i < 4; ++i) {
    std::uint32_t x;
    std::memcpy(&x, p + 4 * i, 4);
    r.l[i] = std::int32_t(x);
  }
  return r;
}
#define TESSERA_SIMD_I32_BINOP(op, expr)                                        \
  inline vi32x4 op(vi32x4 a, vi32x4 b) {                                        \
    vi32x4 r;                                                                   \
    for (int i = 0; i < 4; ++i) {                                               \
      const std::uint32_t x = std::uint32_t(a.l[i]), y = std::uint32_t(b.l[i]); \
      r.l[i] = std::int32_t(expr);                                              \
    }                                                                           \
    return r;                                                                   \
  }
TESSERA_SIMD_I32_BINOP(operator+, x + y)
TESSERA_SIMD_I32_BINOP(operator-, x - y)
TESSERA_SIMD_I32_BINOP(operator*, x* y)
TESSERA_SIMD_I32_BINOP(operator&, x& y)
TESSERA_SIMD_I32_BINOP(operator|, x | y)
TESSERA_SIMD_I32_BINOP(operator^, x ^ y)
TESSERA_SIMD_I32_BINOP(andnot, ~x& y)
TESSERA_SIMD_I32_BINOP(cmpeq, x == y ? ~0u : 0u)
TESSERA_SIMD_I32_BINOP(cmpgt, std::int32_t(x) > std::int32_t(y) ? ~0u : 0u)
TESSERA_SIMD_I32_BINOP(cmplt, std::int32_t(x) < std::int32_t(y) ? ~0u : 0u)
TESSERA_SIMD_I32_BINOP(min, std::int32_t(x) < std::int32_t(y) ? x : y)
TESSERA_SIMD_I32_BINOP(max, std::int32_t(x) > std::int32_t(y) ? x : y)
#undef TESSERA_SIMD_I32_BINOP
inline vi32x4& operator+=(vi32x4& a, vi32x4 b) { return a = a + b; }
// Shifts by 32 or more: SSE2's results (sra fills with the sign, srl and sll give zero).
template <int N>
inline vi32x4 sra(vi32x4 a) {
  static_assert(N >= 0);
  constexpr int n = N < 32 ? N : 31;
  return {a.l[0] >> n, a.l[1] >> n, a.l[2] >> n, a.l[3] >> n};
}
template <int N>
inline vi32x4 srl(vi32x4 a) {
  static_assert(N >= 0);
  vi32x4 r;
  if constexpr (N < 32) {
    for (int i = 0; i < 4; ++i) r.l[i] = std::int32_t(std::uint32_t(a.l[i]) >> N);
  }
  return r;
}
template <int N>
inline vi32x4 sll(vi32x4 a) {
  static_assert(N >= 0);
  vi32x4 r;
  if constexpr (N < 32) {
    for (int i = 0; i < 4; ++i) r.l[i] = std::int32_t(std::uint32_t(a.l[i]) << N);
  }
  return r;
}
inline vi32x4 select(vi32x4 mask, vi32x4 a, vi32x4 b) { return (mask & a) | andnot(mask, b); }
inline vi32x4 swap_pairs(vi32x4 a) { return {a.l[1], a.l[0], a.l[3], a.l[2]}; }
inline vi32x4 swap_pairs64(vi32x4 a) { return {a.l[2], a.l[3], a.l[0], a.l[1]}; }
inline vi32x4 select_alpha(vi32x4 rgb, vi32x4 a) { return {rgb.l[0], rgb.l[1], rgb.l[2], a.l[3]}; }
inline int movemask(vi32x4 mask) {
  int m = 0;
  for (int i = 0; i < 4; ++i) m |= (mask.l[i] < 0 ? 1 : 0) << i;
  return m;
}
inline vi32x4 pair_sums(vi32x4 a, vi32x4 b) {
  const auto add = [](std::int32_t x, std::int32_t y) {
    return std::int32_t(std::uint32_t(x) + std::uint32_t(y));
  };
  return {add(a.l[0], a.l[1]), add(a.l[2], a.l[3]), add(b.l[0], b.l[1]), add(b.l[2], b.l[3])};
}
inline vi32x4 even_lanes(vi32x4 a, vi32x4 b) { return {a.l[0], a.l[2], b.l[0], b.l[2]}; }
inline std::int32_t sum_lanes(vi32x4 a) {
  return std::int32_t(std::uint32_t(a.l[0]) + std::uint32_t(a.l[1]) + std::uint32_t(a.l[2]) +
                      std::uint32_t(a.l[3]));
}
inline std::int32_t sum_lanes02(vi32x4 a) {
  return std::int32_t(std::uint32_t(a.l[0]) + std::uint32_t(a.l[2]));
}
/// Clamped to 0..255, as SSE2's saturating packs.
inline void store_u8x4(vi32x4 a, std::uint8_t* out) {
  for (int i = 0; i < 4; ++i) out[i] = std::uint8_t(a.l[i] < 0 ? 0 : a.l[i] > 255 ? 255 : a.l[i]);
}

struct vi64x2 {
  std::int64_t l[2] = {0, 0};
  vi64x2() = default;
  explicit vi64x2(std::int64_t a) : l{a, a} {}
  vi64x2(std::int64_t lo, std::int64_t hi) : l{lo, hi} {}
};
inline vi64x2 load_i64x2(const std::int64_t* p) { return {p[0], p[1]}; }
inline vi64x2 operator+(vi64x2 a, vi64x2 b) {
  return {std::int64_t(std::uint64_t(a.l[0]) + std::uint64_t(b.l[0])),
          std::int64_t(std::uint64_t(a.l[1]) + std::uint64_t(b.l[1]))};
}
inline vi64x2 operator|(vi64x2 a, vi64x2 b) { return {a.l[0] | b.l[0], a.l[1] | b.l[1]}; }
inline int movemask(vi64x2 a) { return (a.l[0] < 0 ? 1 : 0) | (a.l[1] < 0 ? 2 : 0); }

// ---- vf32x4 ----

struct vf32x4 {
  float l[4] = {0, 0, 0, 0};
  vf32x4() = default;
  explicit vf32x4(float a) : l{a, a, a, a} {}
  vf32x4(float a, float b, float c, float d) : l{a, b, c, d} {}
};
inline vf32x4 loadf4(const float* p) { return {p[0], p[1], p[2], p[3]}; }
inline void storef4(vf32x4 a, float* p) {
  for (int i = 0; i < 4; ++i) p[i] = a.l[i];
}
inline vf32x4 loadf4_aligned(const float* p) { return loadf4(p); }
inline void storef4_aligned(vf32x4 a, float* p) { storef4(a, p); }
#define TESSERA_SIMD_F4_BINOP(op, expr)   \
  inline vf32x4 op(vf32x4 a, vf32x4 b) {  \
    vf32x4 r;                             \
    for (int i = 0; i < 4; ++i) {         \
      const float x = a.l[i], y = b.l[i]; \
      r.l[i] = (expr);                    \
    }                                     \
    return r;                             \
  }
TESSERA_SIMD_F4_BINOP(operator+, x + y)
TESSERA_SIMD_F4_BINOP(operator-, x - y)
TESSERA_SIMD_F4_BINOP(operator*, x* y)
TESSERA_SIMD_F4_BINOP(operator/, x / y)
TESSERA_SIMD_F4_BINOP(max, x > y ? x : y)
TESSERA_SIMD_F4_BINOP(min, x < y ? x : y)
#undef TESSERA_SIMD_F4_BINOP
inline vf32x4 sqrt(vf32x4 a) {
  return {std::sqrt(a.l[0]), std::sqrt(a.l[1]), std::sqrt(a.l[2]), std::sqrt(a.l[3])};
}
#define TESSERA_SIMD_F4_CMP(op, expr)     \
  inline vi32x4 op(vf32x4 a, vf32x4 b) {  \
    vi32x4 r;                             \
    for (int i = 0; i < 4; ++i) {         \
      const float x = a.l[i], y = b.l[i]; \
      r.l[i] = (expr) ? -1 : 0;           \
    }                                     \
    return r;                             \
  }
TESSERA_SIMD_F4_CMP(cmpeq, x == y)
TESSERA_SIMD_F4_CMP(cmplt, x < y)
TESSERA_SIMD_F4_CMP(cmple, x <= y)
TESSERA_SIMD_F4_CMP(cmpgt, x > y)
TESSERA_SIMD_F4_CMP(cmpnge, !(x >= y))
TESSERA_SIMD_F4_CMP(cmpord, x == x && y == y)
#undef TESSERA_SIMD_F4_CMP
inline vf32x4 as_float(vi32x4 a) {
  vf32x4 r;
  for (int i = 0; i < 4; ++i) r.l[i] = std::bit_cast<float>(a.l[i]);
  return r;
}
inline vi32x4 as_int(vf32x4 a) {
  vi32x4 r;
  for (int i = 0; i < 4; ++i) r.l[i] = std::bit_cast<std::int32_t>(a.l[i]);
  return r;
}
inline vf32x4 select(vi32x4 mask, vf32x4 a, vf32x4 b) {
  return as_float((mask & as_int(a)) | andnot(mask, as_int(b)));
}
inline vf32x4 keep_where(vi32x4 mask, vf32x4 a) { return as_float(mask & as_int(a)); }
inline vf32x4 zero_where(vi32x4 mask, vf32x4 a) { return as_float(andnot(mask, as_int(a))); }
inline vf32x4 to_float(vi32x4 a) {
  return {float(a.l[0]), float(a.l[1]), float(a.l[2]), float(a.l[3])};
}
/// Lanes outside int32 (and NaN) give INT32_MIN, as SSE2's cvttps2dq.
inline vi32x4 to_int_trunc(vf32x4 a) {
  vi32x4 r;
  for (int i = 0; i < 4; ++i) {
    const float x = a.l[i];
    r.l[i] = x >= -2147483648.0f && x < 2147483648.0f ? std::int32_t(x) : INT32_MIN;
  }
  return r;
}
inline vf32x4 even_lanes(vf32x4 a, vf32x4 b) { return {a.l[0], a.l[2], b.l[0], b.l[2]}; }
inline vf32x4 odd_lanes(vf32x4 a, vf32x4 b) { return {a.l[1], a.l[3], b.l[1], b.l[3]}; }
inline void transpose(vf32x4& a, vf32x4& b, vf32x4& c, vf32x4& d) {
  const vf32x4 r[4] = {a, b, c, d};
  a = {r[0].l[0], r[1].l[0], r[2].l[0], r[3].l[0]};
  b = {r[0].l[1], r[1].l[1], r[2].l[1], r[3].l[1]};
  c = {r[0].l[2], r[1].l[2], r[2].l[2], r[3].l[2]};
  d = {r[0].l[3], r[1].l[3], r[2].l[3], r[3].l[3]};
}
inline void transpose(vi32x4& a, vi32x4& b, vi32x4& c, vi32x4& d) {
  const vi32x4 r[4] = {a, b, c, d};
  a = {r[0].l[0], r[1].l[0], r[2].l[0], r[3].l[0]};
  b = {r[0].l[1], r[1].l[1], r[2].l[1], r[3].l[1]};
  c = {r[0].l[2], r[1].l[2], r[2].l[2], r[3].l[2]};
  d = {r[0].l[3], r[1].l[3], r[2].l[3], r[3].l[3]};
}
// hmax / hmin: the same pairwise order as the SSE2 shuffles, so NaN lanes give the same result.
inline vf32x4 hmax(vf32x4 a) {
  const vf32x4 m = max(a, vf32x4(a.l[1], a.l[0], a.l[3], a.l[2]));
  return max(m, vf32x4(m.l[2], m.l[3], m.l[0], m.l[1]));
}
inline vf32x4 hmin(vf32x4 a) {
  const vf32x4 m = min(a, vf32x4(a.l[1], a.l[0], a.l[3], a.l[2]));
  return min(m, vf32x4(m.l[2], m.l[3], m.l[0], m.l[1]));
}

// ---- vu16x8, vu8x16 ----

struct vu16x8 {
  std::uint16_t l[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  vu16x8() = default;
  explicit vu16x8(std::uint16_t a) {
    for (auto& x : l) x = a;
  }
  std::int32_t lane_sq(int i) const {
    return std::int32_t(std::int16_t(l[i])) * std::int16_t(l[i]);
  }
};
inline vu16x8 load_u8x8(const std::uint8_t* p) {
  vu16x8 r;
  for (int i = 0; i < 8; ++i) r.l[i] = p[i];
  return r;
}
inline vu16x8 load_u16x8(const std::uint16_t* p) {
  vu16x8 r;
  for (int i = 0; i < 8; ++i) r.l[i] = p[i];
  return r;
}
inline void store_u16x8(vu16x8 a, std::uint16_t* p) {
  for (int i = 0; i < 8; ++i) p[i] = a.l[i];
}
// SSE2's packus_epi16 (narrowings to bytes): the lane read as signed, clamped to 0..255.
namespace detail {
inline std::uint8_t packus16(std::uint16_t x) {
  const std::int16_t s = std::int16_t(x);
  return std::uint8_t(s < 0 ? 0 : s > 255 ? 255 : s);
}
}  // namespace detail
inline void store_u8x8(vu16x8 a, std::uint8_t* p) {
  for (int i = 0; i < 8; ++i) p[i] = detail::packus16(a.l[i]);
}
#define TESSERA_SIMD_U16_BINOP(op, expr)                      \
  inline vu16x8 op(vu16x8 a, vu16x8 b) {                      \
    vu16x8 r;                                                 \
    for (int i = 0; i < 8; ++i) r.l[i] = std::uint16_t(expr); \
    return r;                                                 \
  }
TESSERA_SIMD_U16_BINOP(operator+, a.l[i] + b.l[i])
TESSERA_SIMD_U16_BINOP(operator&, a.l[i] & b.l[i])
TESSERA_SIMD_U16_BINOP(operator-, a.l[i] - b.l[i])
TESSERA_SIMD_U16_BINOP(mullo, std::uint32_t(a.l[i]) * b.l[i])
TESSERA_SIMD_U16_BINOP(operator|, a.l[i] | b.l[i])
TESSERA_SIMD_U16_BINOP(mulhi, (std::uint32_t(a.l[i]) * b.l[i]) >> 16)
TESSERA_SIMD_U16_BINOP(cmpeq, a.l[i] == b.l[i] ? 0xffff : 0)
#undef TESSERA_SIMD_U16_BINOP
inline vi32x4 madd(vu16x8 a, vu16x8 b) {
  vi32x4 r;
  for (int i = 0; i < 4; ++i) {
    r.l[i] = std::int32_t(std::int16_t(a.l[2 * i])) * std::int16_t(b.l[2 * i]) +
             std::int32_t(std::int16_t(a.l[2 * i + 1])) * std::int16_t(b.l[2 * i + 1]);
  }
  return r;
}
inline vu16x8 load_u8x4x2(const std::uint8_t* p0, const std::uint8_t* p1) {
  vu16x8 r;
  for (int i = 0; i < 4; ++i) {
    r.l[i] = p0[i];
    r.l[4 + i] = p1[i];
  }
  return r;
}
template <int N>
inline vu16x8 srl(vu16x8 a) {
  static_assert(N >= 0);
  vu16x8 r;
  if constexpr (N < 16) {
    for (int i = 0; i < 8; ++i) r.l[i] = std::uint16_t(a.l[i] >> N);
  }
  return r;
}
inline vu16x8 select(vu16x8 mask, vu16x8 a, vu16x8 b) {
  vu16x8 r;
  for (int i = 0; i < 8; ++i) r.l[i] = std::uint16_t((mask.l[i] & a.l[i]) | (~mask.l[i] & b.l[i]));
  return r;
}

inline vu16x8 max_s16(vu16x8 a, vu16x8 b) {
  vu16x8 r;
  for (int i = 0; i < 8; ++i)
    r.l[i] = std::int16_t(a.l[i]) > std::int16_t(b.l[i]) ? a.l[i] : b.l[i];
  return r;
}
inline vu16x8 min_s16(vu16x8 a, vu16x8 b) {
  vu16x8 r;
  for (int i = 0; i < 8; ++i)
    r.l[i] = std::int16_t(a.l[i]) < std::int16_t(b.l[i]) ? a.l[i] : b.l[i];
  return r;
}
inline vu16x8 cmpgt_s16(vu16x8 a, vu16x8 b) {
  vu16x8 r;
  for (int i = 0; i < 8; ++i) r.l[i] = std::int16_t(a.l[i]) > std::int16_t(b.l[i]) ? 0xffff : 0;
  return r;
}
inline vu16x8 select_alpha(vu16x8 rgb, vu16x8 a) {
  rgb.l[3] = a.l[3];
  rgb.l[7] = a.l[7];
  return rgb;
}
inline vu16x8 load_u8x4_lo(const std::uint8_t* p) {
  vu16x8 r;
  for (int i = 0; i < 4; ++i) r.l[i] = p[i];
  return r;
}
inline void store_u8x4(vu16x8 a, std::uint8_t* p) {
  for (int i = 0; i < 4; ++i) p[i] = detail::packus16(a.l[i]);
}

struct vu8x16 {
  std::uint8_t l[16] = {};
  vu8x16() = default;
  explicit vu8x16(std::uint8_t a) {
    for (auto& x : l) x = a;
  }
};
inline vu8x16 load_u8x16(const std::uint8_t* p) {
  vu8x16 r;
  std::memcpy(r.l, p, 16);
  return r;
}
inline void store_u8x16(vu8x16 a, std::uint8_t* p) { std::memcpy(p, a.l, 16); }
#define TESSERA_SIMD_U8_BINOP(op, expr)                       \
  inline vu8x16 op(vu8x16 a, vu8x16 b) {                      \
    vu8x16 r;                                                 \
    for (int i = 0; i < 16; ++i) r.l[i] = std::uint8_t(expr); \
    return r;                                                 \
  }
TESSERA_SIMD_U8_BINOP(operator+, a.l[i] + b.l[i])
TESSERA_SIMD_U8_BINOP(operator&, a.l[i] & b.l[i])
TESSERA_SIMD_U8_BINOP(operator|, a.l[i] | b.l[i])
TESSERA_SIMD_U8_BINOP(cmpeq, a.l[i] == b.l[i] ? 0xff : 0)
TESSERA_SIMD_U8_BINOP(andnot, ~a.l[i] & b.l[i])
#undef TESSERA_SIMD_U8_BINOP
inline vu8x16 select(vu8x16 mask, vu8x16 a, vu8x16 b) {
  vu8x16 r;
  for (int i = 0; i < 16; ++i) r.l[i] = std::uint8_t((mask.l[i] & a.l[i]) | (~mask.l[i] & b.l[i]));
  return r;
}
inline bool any(vu8x16 mask) {
  for (std::uint8_t x : mask.l) {
    if (x & 0x80) return true;
  }
  return false;
}
inline vu16x8 widen_lo(vu8x16 a) {
  vu16x8 r;
  for (int i = 0; i < 8; ++i) r.l[i] = a.l[i];
  return r;
}
inline vu16x8 widen_hi(vu8x16 a) {
  vu16x8 r;
  for (int i = 0; i < 8; ++i) r.l[i] = a.l[8 + i];
  return r;
}
inline vu8x16 narrow(vu16x8 lo, vu16x8 hi) {
  vu8x16 r;
  for (int i = 0; i < 8; ++i) {
    r.l[i] = detail::packus16(lo.l[i]);
    r.l[8 + i] = detail::packus16(hi.l[i]);
  }
  return r;
}
inline vu8x16 narrow(vi32x4 a, vi32x4 b, vi32x4 c, vi32x4 d) {
  vu8x16 r;
  const vi32x4* v[4] = {&a, &b, &c, &d};
  for (int i = 0; i < 16; ++i) {
    const std::int32_t x = v[i / 4]->l[i % 4];
    r.l[i] = std::uint8_t(x < 0 ? 0 : x > 255 ? 255 : x);
  }
  return r;
}

// SSE2's packs_epi32: clamped to -32768..32767.
inline vu16x8 narrow16(vi32x4 a, vi32x4 b) {
  const auto packs = [](std::int32_t x) {
    return std::uint16_t(x < -32768 ? -32768 : x > 32767 ? 32767 : x);
  };
  vu16x8 r;
  for (int i = 0; i < 4; ++i) {
    r.l[i] = packs(a.l[i]);
    r.l[4 + i] = packs(b.l[i]);
  }
  return r;
}
inline vu16x8 zip_lo(vu16x8 a, vu16x8 b) {
  vu16x8 r;
  for (int i = 0; i < 4; ++i) {
    r.l[2 * i] = a.l[i];
    r.l[2 * i + 1] = b.l[i];
  }
  return r;
}
inline vu16x8 zip_hi(vu16x8 a, vu16x8 b) {
  vu16x8 r;
  for (int i = 0; i < 4; ++i) {
    r.l[2 * i] = a.l[4 + i];
    r.l[2 * i + 1] = b.l[4 + i];
  }
  return r;
}
inline void taps8(const std::uint16_t* p, vu16x8& left, vu16x8& right) {
  static constexpr int kL[8] = {0, 0, 1, 1, 1, 1, 2, 2};
  for (int i = 0; i < 8; ++i) {
    left.l[i] = p[kL[i]];
    right.l[i] = p[kL[i] + 1];
  }
}
inline vf32x4 f2p23_plus_lo(vu16x8 a) {
  vf32x4 r;
  for (int i = 0; i < 4; ++i) r.l[i] = 8388608.0f + float(a.l[i]);
  return r;
}
inline vf32x4 f2p23_plus_hi(vu16x8 a) {
  vf32x4 r;
  for (int i = 0; i < 4; ++i) r.l[i] = 8388608.0f + float(a.l[4 + i]);
  return r;
}
inline vi32x4 widen32_lo(vu16x8 a) { return {a.l[0], a.l[1], a.l[2], a.l[3]}; }
inline vi32x4 widen32_hi(vu16x8 a) { return {a.l[4], a.l[5], a.l[6], a.l[7]}; }
inline void transpose_8x4(const std::uint16_t* p, vu16x8 out[4]) {
  for (int c = 0; c < 4; ++c) {
    for (int i = 0; i < 8; ++i) out[c].l[i] = p[4 * i + c];
  }
}

}  // namespace TESSERA_SIMD_ISA
}  // namespace tessera::simd
