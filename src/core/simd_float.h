// simd_float.h — part of the SIMD wrapper (include "core/simd.h", which documents the whole set):
// single-precision lanes.
//   vf32x4 four float lanes: each operation is one IEEE single-precision operation per lane
//          (correctly rounded add, sub, mul, div, sqrt; no fused multiply-add; min / max /
//          compares with SSE's NaN rules, spelled out per function), so a lane gives the same
//          bits as the scalar expression written in the comment. Comparisons return vi32x4 masks.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "core/simd_int.h"

namespace tessera::simd {
inline namespace TESSERA_SIMD_ISA {

#if defined(TESSERA_SIMD_SSE2)

struct vf32x4 {
  __m128 v;
  vf32x4() : v(_mm_setzero_ps()) {}
  explicit vf32x4(__m128 x) : v(x) {}
  explicit vf32x4(float a) : v(_mm_set1_ps(a)) {}
  /// Lanes (a, b, c, d), lane 0 first.
  vf32x4(float a, float b, float c, float d) : v(_mm_setr_ps(a, b, c, d)) {}
};
inline vf32x4 loadf4(const float* p) { return vf32x4(_mm_loadu_ps(p)); }
inline void storef4(vf32x4 a, float* p) { _mm_storeu_ps(p, a.v); }
/// `p` 16-byte aligned.
inline vf32x4 loadf4_aligned(const float* p) { return vf32x4(_mm_load_ps(p)); }
inline void storef4_aligned(vf32x4 a, float* p) { _mm_store_ps(p, a.v); }
inline vf32x4 operator+(vf32x4 a, vf32x4 b) { return vf32x4(_mm_add_ps(a.v, b.v)); }
inline vf32x4 operator-(vf32x4 a, vf32x4 b) { return vf32x4(_mm_sub_ps(a.v, b.v)); }
inline vf32x4 operator*(vf32x4 a, vf32x4 b) { return vf32x4(_mm_mul_ps(a.v, b.v)); }
inline vf32x4 operator/(vf32x4 a, vf32x4 b) { return vf32x4(_mm_div_ps(a.v, b.v)); }
inline vf32x4 sqrt(vf32x4 a) { return vf32x4(_mm_sqrt_ps(a.v)); }
/// max: a > b ? a : b; min: a < b ? a : b (the second operand when the compare fails, NaN
/// included).
inline vf32x4 max(vf32x4 a, vf32x4 b) { return vf32x4(_mm_max_ps(a.v, b.v)); }
inline vf32x4 min(vf32x4 a, vf32x4 b) { return vf32x4(_mm_min_ps(a.v, b.v)); }
/// Compares as masks: all-ones lanes where `a op b`; false where either is NaN, except cmpnge
/// (!(a >= b)), which is true there; cmpord is true where neither is NaN.
inline vi32x4 cmpeq(vf32x4 a, vf32x4 b) { return vi32x4(_mm_castps_si128(_mm_cmpeq_ps(a.v, b.v))); }
inline vi32x4 cmplt(vf32x4 a, vf32x4 b) { return vi32x4(_mm_castps_si128(_mm_cmplt_ps(a.v, b.v))); }
inline vi32x4 cmple(vf32x4 a, vf32x4 b) { return vi32x4(_mm_castps_si128(_mm_cmple_ps(a.v, b.v))); }
inline vi32x4 cmpgt(vf32x4 a, vf32x4 b) { return vi32x4(_mm_castps_si128(_mm_cmpgt_ps(a.v, b.v))); }
inline vi32x4 cmpnge(vf32x4 a, vf32x4 b) {
  return vi32x4(_mm_castps_si128(_mm_cmpnge_ps(a.v, b.v)));
}
inline vi32x4 cmpord(vf32x4 a, vf32x4 b) {
  return vi32x4(_mm_castps_si128(_mm_cmpord_ps(a.v, b.v)));
}
/// Lanes of `a` where `mask` is all ones, else lanes of `b` (bitwise, NaN payloads kept).
inline vf32x4 select(vi32x4 mask, vf32x4 a, vf32x4 b) {
  const __m128 m = _mm_castsi128_ps(mask.v);
  return vf32x4(_mm_or_ps(_mm_and_ps(m, a.v), _mm_andnot_ps(m, b.v)));
}
/// mask & a: lanes of `a` where `mask` is all ones, +0.0f elsewhere.
inline vf32x4 keep_where(vi32x4 mask, vf32x4 a) {
  return vf32x4(_mm_and_ps(_mm_castsi128_ps(mask.v), a.v));
}
/// ~mask & a: +0.0f where `mask` is all ones, lanes of `a` elsewhere.
inline vf32x4 zero_where(vi32x4 mask, vf32x4 a) {
  return vf32x4(_mm_andnot_ps(_mm_castsi128_ps(mask.v), a.v));
}
/// The lanes' bits reinterpreted (no conversion).
inline vf32x4 as_float(vi32x4 a) { return vf32x4(_mm_castsi128_ps(a.v)); }
inline vi32x4 as_int(vf32x4 a) { return vi32x4(_mm_castps_si128(a.v)); }
/// int32 -> float, round to nearest even (exact below 2^24).
inline vf32x4 to_float(vi32x4 a) { return vf32x4(_mm_cvtepi32_ps(a.v)); }
/// float -> int32 truncating towards zero; lanes outside int32 and NaN give INT32_MIN (in
/// every backend).
inline vi32x4 to_int_trunc(vf32x4 a) { return vi32x4(_mm_cvttps_epi32(a.v)); }
/// Lanes (a0, a2, b0, b2) and (a1, a3, b1, b3): e.g. u and v of four interleaved (u, v) pairs.
inline vf32x4 even_lanes(vf32x4 a, vf32x4 b) {
  return vf32x4(_mm_shuffle_ps(a.v, b.v, _MM_SHUFFLE(2, 0, 2, 0)));
}
inline vf32x4 odd_lanes(vf32x4 a, vf32x4 b) {
  return vf32x4(_mm_shuffle_ps(a.v, b.v, _MM_SHUFFLE(3, 1, 3, 1)));
}
/// 4x4 transpose: row i of the result holds lane i of a, b, c, d.
inline void transpose(vf32x4& a, vf32x4& b, vf32x4& c, vf32x4& d) {
  _MM_TRANSPOSE4_PS(a.v, b.v, c.v, d.v);
}
inline void transpose(vi32x4& a, vi32x4& b, vi32x4& c, vi32x4& d) {
  vf32x4 fa = as_float(a), fb = as_float(b), fc = as_float(c), fd = as_float(d);
  transpose(fa, fb, fc, fd);
  a = as_int(fa);
  b = as_int(fb);
  c = as_int(fc);
  d = as_int(fd);
}
/// Every lane = the maximum (minimum) of the four lanes.
inline vf32x4 hmax(vf32x4 a) {
  const __m128 m = _mm_max_ps(a.v, _mm_shuffle_ps(a.v, a.v, _MM_SHUFFLE(2, 3, 0, 1)));
  return vf32x4(_mm_max_ps(m, _mm_shuffle_ps(m, m, _MM_SHUFFLE(1, 0, 3, 2))));
}
inline vf32x4 hmin(vf32x4 a) {
  const __m128 m = _mm_min_ps(a.v, _mm_shuffle_ps(a.v, a.v, _MM_SHUFFLE(2, 3, 0, 1)));
  return vf32x4(_mm_min_ps(m, _mm_shuffle_ps(m, m, _MM_SHUFFLE(1, 0, 3, 2))));
}

#elif defined(TESSERA_SIMD_NEON)

// NEON: add, sub, mul, sqrt and int -> float are single correctly rounded IEEE operations as
// on SSE (AArch64 Linux runs with round-to-nearest and without flush-to-zero, like SSE's
// default MXCSR; the build turns off GCC's contraction of a * b + c into a fused multiply-add:
// see CMakeLists.txt). min / max and float -> int differ in their instructions and are
// emulated; compares are the same predicates.
struct vf32x4 {
  float32x4_t v;
  vf32x4() : v(vdupq_n_f32(0.0f)) {}
  explicit vf32x4(float32x4_t x) : v(x) {}
  explicit vf32x4(float a) : v(vdupq_n_f32(a)) {}
  vf32x4(float a, float b, float c, float d) {
    const float t[4] = {a, b, c, d};
    v = vld1q_f32(t);
  }
};
inline vf32x4 loadf4(const float* p) { return vf32x4(vld1q_f32(p)); }
inline void storef4(vf32x4 a, float* p) { vst1q_f32(p, a.v); }
inline vf32x4 loadf4_aligned(const float* p) { return vf32x4(vld1q_f32(p)); }
inline void storef4_aligned(vf32x4 a, float* p) { vst1q_f32(p, a.v); }
inline vf32x4 operator+(vf32x4 a, vf32x4 b) { return vf32x4(vaddq_f32(a.v, b.v)); }
inline vf32x4 operator-(vf32x4 a, vf32x4 b) { return vf32x4(vsubq_f32(a.v, b.v)); }
inline vf32x4 operator*(vf32x4 a, vf32x4 b) { return vf32x4(vmulq_f32(a.v, b.v)); }
inline vf32x4 operator/(vf32x4 a, vf32x4 b) { return vf32x4(vdivq_f32(a.v, b.v)); }
inline vf32x4 sqrt(vf32x4 a) { return vf32x4(vsqrtq_f32(a.v)); }
/// Not vmaxq_f32 / vminq_f32 (NaN when either lane is NaN, and +0 > -0): a compare and a
/// bitwise select, which give SSE's maxps / minps exactly (`b` when the compare fails).
inline vf32x4 max(vf32x4 a, vf32x4 b) { return vf32x4(vbslq_f32(vcgtq_f32(a.v, b.v), a.v, b.v)); }
inline vf32x4 min(vf32x4 a, vf32x4 b) { return vf32x4(vbslq_f32(vcltq_f32(a.v, b.v), a.v, b.v)); }
inline vi32x4 cmpeq(vf32x4 a, vf32x4 b) {
  return vi32x4(vreinterpretq_s32_u32(vceqq_f32(a.v, b.v)));
}
inline vi32x4 cmplt(vf32x4 a, vf32x4 b) {
  return vi32x4(vreinterpretq_s32_u32(vcltq_f32(a.v, b.v)));
}
inline vi32x4 cmple(vf32x4 a, vf32x4 b) {
  return vi32x4(vreinterpretq_s32_u32(vcleq_f32(a.v, b.v)));
}
inline vi32x4 cmpgt(vf32x4 a, vf32x4 b) {
  return vi32x4(vreinterpretq_s32_u32(vcgtq_f32(a.v, b.v)));
}
inline vi32x4 cmpnge(vf32x4 a, vf32x4 b) {
  return vi32x4(vreinterpretq_s32_u32(vmvnq_u32(vcgeq_f32(a.v, b.v))));
}
inline vi32x4 cmpord(vf32x4 a, vf32x4 b) {
  return vi32x4(vreinterpretq_s32_u32(vandq_u32(vceqq_f32(a.v, a.v), vceqq_f32(b.v, b.v))));
}
inline vf32x4 select(vi32x4 mask, vf32x4 a, vf32x4 b) {
  return vf32x4(vbslq_f32(vreinterpretq_u32_s32(mask.v), a.v, b.v));
}
inline vf32x4 keep_where(vi32x4 mask, vf32x4 a) {
  return vf32x4(vreinterpretq_f32_s32(vandq_s32(mask.v, vreinterpretq_s32_f32(a.v))));
}
inline vf32x4 zero_where(vi32x4 mask, vf32x4 a) {
  return vf32x4(vreinterpretq_f32_s32(vbicq_s32(vreinterpretq_s32_f32(a.v), mask.v)));
}
inline vf32x4 as_float(vi32x4 a) { return vf32x4(vreinterpretq_f32_s32(a.v)); }
inline vi32x4 as_int(vf32x4 a) { return vi32x4(vreinterpretq_s32_f32(a.v)); }
inline vf32x4 to_float(vi32x4 a) { return vf32x4(vcvtq_f32_s32(a.v)); }
/// fcvtzs saturates (>= 2^31 -> INT32_MAX, NaN -> 0) where cvttps2dq gives INT32_MIN for
/// every lane it cannot represent: those lanes (NaN, >= 2^31; below -2^31 both give INT32_MIN)
/// are set to INT32_MIN.
inline vi32x4 to_int_trunc(vf32x4 a) {
  const uint32x4_t in_range = vcltq_f32(a.v, vdupq_n_f32(2147483648.0f));
  return vi32x4(vbslq_s32(in_range, vcvtq_s32_f32(a.v), vdupq_n_s32(INT32_MIN)));
}
inline vf32x4 even_lanes(vf32x4 a, vf32x4 b) { return vf32x4(vuzp1q_f32(a.v, b.v)); }
inline vf32x4 odd_lanes(vf32x4 a, vf32x4 b) { return vf32x4(vuzp2q_f32(a.v, b.v)); }
namespace detail {
/// 4x4 transpose of 32-bit lanes (bits moved, never converted): trn1 / trn2 of the 32-bit
/// lanes, then of the 64-bit halves.
inline void transpose_u32x4(uint32x4_t& a, uint32x4_t& b, uint32x4_t& c, uint32x4_t& d) {
  const uint64x2_t ab0 = vreinterpretq_u64_u32(vtrn1q_u32(a, b));  // a0 b0 a2 b2
  const uint64x2_t ab1 = vreinterpretq_u64_u32(vtrn2q_u32(a, b));  // a1 b1 a3 b3
  const uint64x2_t cd0 = vreinterpretq_u64_u32(vtrn1q_u32(c, d));  // c0 d0 c2 d2
  const uint64x2_t cd1 = vreinterpretq_u64_u32(vtrn2q_u32(c, d));  // c1 d1 c3 d3
  a = vreinterpretq_u32_u64(vtrn1q_u64(ab0, cd0));
  b = vreinterpretq_u32_u64(vtrn1q_u64(ab1, cd1));
  c = vreinterpretq_u32_u64(vtrn2q_u64(ab0, cd0));
  d = vreinterpretq_u32_u64(vtrn2q_u64(ab1, cd1));
}
}  // namespace detail
inline void transpose(vf32x4& a, vf32x4& b, vf32x4& c, vf32x4& d) {
  uint32x4_t w = vreinterpretq_u32_f32(a.v), x = vreinterpretq_u32_f32(b.v);
  uint32x4_t y = vreinterpretq_u32_f32(c.v), z = vreinterpretq_u32_f32(d.v);
  detail::transpose_u32x4(w, x, y, z);
  a = vf32x4(vreinterpretq_f32_u32(w));
  b = vf32x4(vreinterpretq_f32_u32(x));
  c = vf32x4(vreinterpretq_f32_u32(y));
  d = vf32x4(vreinterpretq_f32_u32(z));
}
inline void transpose(vi32x4& a, vi32x4& b, vi32x4& c, vi32x4& d) {
  uint32x4_t w = vreinterpretq_u32_s32(a.v), x = vreinterpretq_u32_s32(b.v);
  uint32x4_t y = vreinterpretq_u32_s32(c.v), z = vreinterpretq_u32_s32(d.v);
  detail::transpose_u32x4(w, x, y, z);
  a = vi32x4(vreinterpretq_s32_u32(w));
  b = vi32x4(vreinterpretq_s32_u32(x));
  c = vi32x4(vreinterpretq_s32_u32(y));
  d = vi32x4(vreinterpretq_s32_u32(z));
}
/// SSE2's pairwise order (lanes 1 0 3 2, then 2 3 0 1) with its max / min: the same NaN result.
inline vf32x4 hmax(vf32x4 a) {
  const vf32x4 m = max(a, vf32x4(vrev64q_f32(a.v)));
  return max(m, vf32x4(vextq_f32(m.v, m.v, 2)));
}
inline vf32x4 hmin(vf32x4 a) {
  const vf32x4 m = min(a, vf32x4(vrev64q_f32(a.v)));
  return min(m, vf32x4(vextq_f32(m.v, m.v, 2)));
}

#else  // scalar backend

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

#endif

}  // namespace TESSERA_SIMD_ISA
}  // namespace tessera::simd
