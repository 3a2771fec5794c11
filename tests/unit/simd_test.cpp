// src/core/simd*.h, 4-lane wrapper: the float operations on special values (signed zeros, NaN,
// infinities, denormals, halves, out-of-range conversions) and the basic integer ones, checked
// lane by lane (bit for bit) against the scalar expression of their SSE2 semantics. Every
// integer and packed operation on generated lanes is in simd_int_test.cpp. Built twice:
// simd_test with the target's backend (SSE2 on x86-64, NEON on AArch64: the arm64 stage of
// scripts/test.sh cross-builds it and runs it under qemu-aarch64) and simd_scalar_test with
// TESSERA_NO_SIMD (the portable backend), so every backend is held to the same expressions.
#include "core/simd.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "simd_test_lanes.h"

namespace {

using namespace simd_test;  // NOLINT(google-build-using-namespace): the 4-lane types, lanes(), Rng

std::uint32_t bits(float x) { return std::bit_cast<std::uint32_t>(x); }

/// Same bits, or both NaN (which NaN an operation on two NaNs returns is not specified by C++).
void expect_same(float got, float want) {
  if (std::isnan(want)) {
    EXPECT_TRUE(std::isnan(got));
  } else {
    EXPECT_EQ(bits(got), bits(want)) << want;
  }
}

std::vector<float> special_values() {
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  return {0.0f,  -0.0f,  1.0f, -1.0f, 0.5f, -0.5f, 1.5f,   -2.5f,   3.75f, 8388608.0f,
          1e30f, -1e30f, inf,  -inf,  nan,  -nan,  1e-40f, -1e-40f, 0.1f,  255.5f};
}

/// Runs `check(x[k], y[k], lane)` for all pairs of special values, four pairs per vector.
template <class F>
void for_pairs(F check) {
  const std::vector<float> v = special_values();
  std::vector<float> xs, ys;
  for (float x : v) {
    for (float y : v) {
      xs.push_back(x);
      ys.push_back(y);
    }
  }
  while (xs.size() % 4) {
    xs.push_back(0.0f);
    ys.push_back(0.0f);
  }
  for (std::size_t k = 0; k < xs.size(); k += 4) check(&xs[k], &ys[k]);
}

TEST(Simd, FloatArithmeticIsOneIeeeOperationPerLane) {
  for_pairs([](const float* x, const float* y) {
    const vf32x4 a = simd::loadf4(x), b = simd::loadf4(y);
    const Lanes add = lanes(a + b), sub = lanes(a - b), mul = lanes(a * b), div = lanes(a / b);
    const Lanes mx = lanes(simd::max(a, b)), mn = lanes(simd::min(a, b));
    const Lanes sq = lanes(simd::sqrt(a));
    for (int i = 0; i < 4; ++i) {
      const float p = x[i], q = y[i];
      expect_same(add.f[i], p + q);
      expect_same(sub.f[i], p - q);
      expect_same(mul.f[i], p * q);
      expect_same(div.f[i], p / q);
      expect_same(sq.f[i], std::sqrt(p));
      // min / max pass their second operand through when the compare fails: exact bits.
      EXPECT_EQ(bits(mx.f[i]), bits(p > q ? p : q)) << p << " " << q;
      EXPECT_EQ(bits(mn.f[i]), bits(p < q ? p : q)) << p << " " << q;
    }
  });
}

TEST(Simd, FloatComparesSelectsAndMasks) {
  for_pairs([](const float* x, const float* y) {
    const vf32x4 a = simd::loadf4(x), b = simd::loadf4(y);
    const ILanes eq = lanes(simd::cmpeq(a, b)), lt = lanes(simd::cmplt(a, b));
    const ILanes le = lanes(simd::cmple(a, b)), gt = lanes(simd::cmpgt(a, b));
    const ILanes nge = lanes(simd::cmpnge(a, b)), ord = lanes(simd::cmpord(a, b));
    const vi32x4 m = simd::cmplt(a, b);
    const Lanes sel = lanes(simd::select(m, a, b));
    const Lanes keep = lanes(simd::keep_where(m, a)), zero = lanes(simd::zero_where(m, a));
    const int mm = simd::movemask(m);
    for (int i = 0; i < 4; ++i) {
      const float p = x[i], q = y[i];
      EXPECT_EQ(eq.i[i], p == q ? -1 : 0);
      EXPECT_EQ(lt.i[i], p < q ? -1 : 0);
      EXPECT_EQ(le.i[i], p <= q ? -1 : 0);
      EXPECT_EQ(gt.i[i], p > q ? -1 : 0);
      EXPECT_EQ(nge.i[i], !(p >= q) ? -1 : 0);
      EXPECT_EQ(ord.i[i], !std::isnan(p) && !std::isnan(q) ? -1 : 0);
      EXPECT_EQ(bits(sel.f[i]), bits(p < q ? p : q));
      EXPECT_EQ(bits(keep.f[i]), p < q ? bits(p) : 0u);
      EXPECT_EQ(bits(zero.f[i]), p < q ? 0u : bits(p));
      EXPECT_EQ(mm >> i & 1, p < q ? 1 : 0);
    }
  });
}

TEST(Simd, FloatConversionsAndShuffles) {
  const float in[8] = {-2.5f, -0.5f, 0.75f, 3.5f, -1e9f, 16777217.0f, 1e9f, -0.0f};
  for (int k = 0; k < 8; k += 4) {
    const ILanes t = lanes(simd::to_int_trunc(simd::loadf4(in + k)));
    for (int i = 0; i < 4; ++i) EXPECT_EQ(t.i[i], std::int32_t(in[k + i]));
  }
  const std::int32_t iv[4] = {-16777217, -3, 16777217, 2147483647};
  const Lanes f = lanes(simd::to_float(simd::load4(iv)));
  for (int i = 0; i < 4; ++i) EXPECT_EQ(bits(f.f[i]), bits(float(iv[i])));
  const std::int32_t sign = std::numeric_limits<std::int32_t>::min();
  const Lanes c = lanes(simd::as_float(vi32x4(0x3f800000, sign, 0x7fc00000, 1)));
  EXPECT_EQ(bits(c.f[0]), 0x3f800000u);
  EXPECT_EQ(bits(c.f[1]), 0x80000000u);
  EXPECT_EQ(bits(c.f[2]), 0x7fc00000u);
  EXPECT_EQ(bits(c.f[3]), 1u);
  EXPECT_EQ(lanes(simd::as_int(vf32x4(1.0f, -0.0f, 2.0f, 0.5f))).i[1], sign);

  const vf32x4 a(0.0f, 1.0f, 2.0f, 3.0f), b(4.0f, 5.0f, 6.0f, 7.0f);
  const Lanes ev = lanes(simd::even_lanes(a, b)), od = lanes(simd::odd_lanes(a, b));
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(ev.f[i], float(2 * i));
    EXPECT_EQ(od.f[i], float(2 * i + 1));
  }
  vf32x4 r0(0, 1, 2, 3), r1(4, 5, 6, 7), r2(8, 9, 10, 11), r3(12, 13, 14, 15);
  simd::transpose(r0, r1, r2, r3);
  const Lanes t[4] = {lanes(r0), lanes(r1), lanes(r2), lanes(r3)};
  vi32x4 i0(0, 1, 2, 3), i1(4, 5, 6, 7), i2(8, 9, 10, 11), i3(12, 13, 14, 15);
  simd::transpose(i0, i1, i2, i3);
  const ILanes ti[4] = {lanes(i0), lanes(i1), lanes(i2), lanes(i3)};
  for (int row = 0; row < 4; ++row) {
    for (int col = 0; col < 4; ++col) {
      EXPECT_EQ(t[row].f[col], float(4 * col + row));
      EXPECT_EQ(ti[row].i[col], 4 * col + row);
    }
  }
  alignas(16) float store[4];
  simd::storef4_aligned(simd::loadf4_aligned(in), store);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(store[i], in[i]);
}

TEST(Simd, Int32LanesCompareSelectAndMultiply) {
  const std::int32_t xs[8] = {-7, 0, 5, 2147483647, -2147483647 - 1, 46340, -3, 1 << 20};
  const std::int32_t ys[8] = {3, 0, -5, -1, 1, 46341, -3, 1 << 10};
  for (int k = 0; k < 8; k += 4) {
    const vi32x4 a = simd::load4(xs + k), b = simd::load4(ys + k);
    const ILanes eq = lanes(simd::cmpeq(a, b)), gt = lanes(simd::cmpgt(a, b));
    const ILanes lt = lanes(simd::cmplt(a, b)), an = lanes(simd::andnot(a, b));
    const ILanes sel = lanes(simd::select(simd::cmpgt(a, b), a, b));
    const ILanes mul = lanes(a * b), mn = lanes(simd::min(a, b));
    for (int i = 0; i < 4; ++i) {
      const std::int32_t p = xs[k + i], q = ys[k + i];
      EXPECT_EQ(eq.i[i], p == q ? -1 : 0);
      EXPECT_EQ(gt.i[i], p > q ? -1 : 0);
      EXPECT_EQ(lt.i[i], p < q ? -1 : 0);
      EXPECT_EQ(an.i[i], ~p & q);
      EXPECT_EQ(sel.i[i], p > q ? p : q);
      EXPECT_EQ(mn.i[i], p < q ? p : q);
      EXPECT_EQ(mul.i[i], std::int32_t(std::uint32_t(p) * std::uint32_t(q)));
    }
  }
  alignas(16) std::int32_t out[4] = {9, 9, 9, 9};
  simd::store4_aligned((simd::load4_aligned(out) & vi32x4(1)) | vi32x4(0, 2, 4, 6), out);
  EXPECT_EQ(out[0], 1);
  EXPECT_EQ(out[3], 7);
}

TEST(Simd, Int64LanesAddOrAndSigns) {
  const std::int64_t big = std::int64_t{1} << 40;
  const std::int64_t p[2] = {-big, big};
  const vi64x2 a = simd::load_i64x2(p);
  EXPECT_EQ(simd::movemask(a), 1);
  EXPECT_EQ(simd::movemask(vi64x2(big, -1)), 2);
  EXPECT_EQ(simd::movemask(a + vi64x2(big)), 0);
  EXPECT_EQ(simd::movemask(a + vi64x2(-big - 1, -2 * big)), 3);
  EXPECT_EQ(simd::movemask(vi64x2(1, 2) | vi64x2(-big, 0)), 1);
  EXPECT_EQ(simd::movemask(vi64x2(std::numeric_limits<std::int64_t>::max()) + vi64x2(1)), 3);
}

TEST(Simd, FloatToIntOutOfRangeAndHorizontalMinMax) {
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  // cvttps2dq: every lane it cannot represent (NaN, >= 2^31, < -2^31) gives INT32_MIN.
  const float in[12] = {2147483648.0f, 2147483520.0f, -2147483648.0f, -2147483904.0f, inf,
                        -inf,          nan,           -nan,           1e20f,          -1e20f,
                        -0.99f,        2147483000.0f};
  const std::int32_t want[12] = {INT32_MIN, 2147483520, INT32_MIN, INT32_MIN,
                                 INT32_MIN, INT32_MIN,  INT32_MIN, INT32_MIN,
                                 INT32_MIN, INT32_MIN,  0,         2147483008};
  for (int k = 0; k < 12; k += 4) {
    const ILanes t = lanes(simd::to_int_trunc(simd::loadf4(in + k)));
    for (int i = 0; i < 4; ++i) EXPECT_EQ(t.i[i], want[k + i]) << in[k + i];
  }
  // hmax / hmin: the pairwise order (lanes 1 0 3 2, then 2 3 0 1) with min / max's rules.
  const std::vector<float> v = special_values();
  for (std::size_t s = 0; s + 4 <= v.size(); ++s) {
    const float x[4] = {v[s], v[(s * 7 + 1) % v.size()], v[(s * 3 + 2) % v.size()], v[s + 3]};
    const auto mx = [](float p, float q) { return p > q ? p : q; };
    const auto mn = [](float p, float q) { return p < q ? p : q; };
    const float m[4] = {mx(x[0], x[1]), mx(x[1], x[0]), mx(x[2], x[3]), mx(x[3], x[2])};
    const float n[4] = {mn(x[0], x[1]), mn(x[1], x[0]), mn(x[2], x[3]), mn(x[3], x[2])};
    const Lanes hx = lanes(simd::hmax(simd::loadf4(x))), hn = lanes(simd::hmin(simd::loadf4(x)));
    for (int i = 0; i < 4; ++i) {
      EXPECT_EQ(bits(hx.f[i]), bits(mx(m[i], m[i ^ 2])));
      EXPECT_EQ(bits(hn.f[i]), bits(mn(n[i], n[i ^ 2])));
    }
  }
}

TEST(Simd, FloatSelectIsBitwiseAndMultiplyAddRoundsTwice) {
  Rng rng{4};
  for (int round = 0; round < 200; ++round) {
    std::int32_t m[4];
    float x[4], y[4], z[4];
    for (int i = 0; i < 4; ++i) {
      m[i] = std::int32_t(rng.next());
      x[i] = std::bit_cast<float>(rng.next() & 0xbfffffffu);  // no infinities or NaN
      y[i] = std::bit_cast<float>(rng.next() & 0xbfffffffu);
      z[i] = float(std::int32_t(rng.next())) * 1e-9f;
    }
    const vf32x4 a = simd::loadf4(x), b = simd::loadf4(y), c = simd::loadf4(z);
    const Lanes sel = lanes(simd::select(simd::load4(m), a, b));
    // vmulq + vaddq (or mulps + addps) must not become one fused multiply-add, which rounds
    // once: the build turns contraction off (-ffp-contract=off); this catches a build without.
    const Lanes fma = lanes(a * c + b);
    for (int i = 0; i < 4; ++i) {
      const std::uint32_t u =
          (std::uint32_t(m[i]) & bits(x[i])) | (~std::uint32_t(m[i]) & bits(y[i]));
      EXPECT_EQ(bits(sel.f[i]), u);
      volatile float product = x[i] * z[i];  // rounded to float before the addition
      expect_same(fma.f[i], product + y[i]);
    }
  }
}

TEST(Simd, BackendMacroMatchesTarget) {
#if defined(TESSERA_NO_SIMD)
  EXPECT_EQ(TESSERA_SIMD_VECTOR, 0);
#elif defined(__SSE2__)
  EXPECT_EQ(TESSERA_SIMD_VECTOR, 1);
#elif defined(__aarch64__) && !defined(__ARM_BIG_ENDIAN)
  EXPECT_EQ(TESSERA_SIMD_VECTOR, 1);
#if !defined(TESSERA_SIMD_NEON)
  ADD_FAILURE() << "AArch64 without the NEON backend";
#endif
#endif
}

}  // namespace
