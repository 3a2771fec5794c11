// src/core/simd*.h: the integer and packed operations of the 4-lane wrapper (vi32x4, vi64x2,
// vu16x8, vu8x16), each against the scalar expression of its SSE2 semantics on generated lanes.
// The float operations and the special-value checks are in simd_test.cpp. Built twice like it:
// simd_int_test with the target's backend (SSE2 on x86-64, NEON on AArch64, also run under
// qemu-aarch64 by tests/arch/pvrtc_arch_bytes.sh) and simd_int_scalar_test with TESSERA_NO_SIMD
// (the portable backend), so every backend is held to the same expressions.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "core/simd.h"
#include "simd_test_lanes.h"

namespace {

using namespace simd_test;  // NOLINT(google-build-using-namespace): the 4-lane types, lanes(), Rng
using simd_test::lanes;     // overloaded below for vu16x8 and vu8x16

// ---- Every integer and packed operation against its SSE2 semantics, on generated lanes -------
// Lanes mix edge values (zero, +-1, the 8- / 16- / 32-bit limits, 255 / 256, 0x7fff / 0x8000)
// with pseudo-random ones; each backend must give the bits the reference expression does.

std::int32_t wrap(std::int64_t x) { return std::int32_t(std::uint32_t(std::uint64_t(x))); }
std::uint8_t clamp_u8(std::int32_t x) { return std::uint8_t(x < 0 ? 0 : x > 255 ? 255 : x); }
std::int16_t clamp_s16(std::int32_t x) {
  return std::int16_t(x < -32768 ? -32768 : x > 32767 ? 32767 : x);
}

struct U16Lanes {
  std::uint16_t u[8];
};
U16Lanes lanes(vu16x8 a) {
  U16Lanes r;
  simd::store_u16x8(a, r.u);
  return r;
}
struct U8Lanes {
  std::uint8_t u[16];
};
U8Lanes lanes(vu8x16 a) {
  U8Lanes r;
  simd::store_u8x16(a, r.u);
  return r;
}

template <int N>
void check_shifts(vi32x4 a, const std::int32_t* x) {
  const ILanes ra = lanes(simd::sra<N>(a)), rl = lanes(simd::srl<N>(a)),
               ll = lanes(simd::sll<N>(a));
  for (int i = 0; i < 4; ++i) {
    const std::uint32_t u = std::uint32_t(x[i]);
    EXPECT_EQ(ra.i[i], x[i] >> (N < 32 ? N : 31)) << N;
    EXPECT_EQ(rl.i[i], N < 32 ? std::int32_t(u >> (N % 32)) : 0) << N;
    EXPECT_EQ(ll.i[i], N < 32 ? std::int32_t(u << (N % 32)) : 0) << N;
  }
}
template <int N>
void check_shifts16(vu16x8 a, const std::uint16_t* x) {
  const U16Lanes r = lanes(simd::srl<N>(a));
  for (int i = 0; i < 8; ++i) EXPECT_EQ(r.u[i], N < 16 ? x[i] >> (N % 16) : 0) << N;
}

TEST(Simd, Int32LanesEveryOperation) {
  Rng rng{1};
  for (int round = 0; round < 500; ++round) {
    std::int32_t x[4], y[4], m[4];
    for (int i = 0; i < 4; ++i) {
      x[i] = rng.i32();
      y[i] = rng.i32();
      m[i] = std::int32_t(rng.next());  // any bits: select is bitwise
    }
    const vi32x4 a = simd::load4(x), b = simd::load4(y), mask = simd::load4(m);
    const ILanes add = lanes(a + b), sub = lanes(a - b), mul = lanes(a * b);
    const ILanes an = lanes(a & b), orr = lanes(a | b), xr = lanes(a ^ b);
    const ILanes sel = lanes(simd::select(mask, a, b)), mn = lanes(simd::min(a, b));
    const ILanes sw = lanes(simd::swap_pairs(a)), sa = lanes(simd::select_alpha(a, b));
    const ILanes ps = lanes(simd::pair_sums(a, b)), ev = lanes(simd::even_lanes(a, b));
    const ILanes mx = lanes(simd::max(a, b)), sw64 = lanes(simd::swap_pairs64(a));
    vi32x4 acc = a;
    acc += b;
    for (int i = 0; i < 4; ++i) {
      const std::int64_t p = x[i], q = y[i];
      EXPECT_EQ(add.i[i], wrap(p + q));
      EXPECT_EQ(lanes(acc).i[i], wrap(p + q));
      EXPECT_EQ(sub.i[i], wrap(p - q));
      EXPECT_EQ(mul.i[i], wrap(p * q));
      EXPECT_EQ(an.i[i], x[i] & y[i]);
      EXPECT_EQ(orr.i[i], x[i] | y[i]);
      EXPECT_EQ(xr.i[i], x[i] ^ y[i]);
      EXPECT_EQ(sel.i[i], (m[i] & x[i]) | (~m[i] & y[i]));
      EXPECT_EQ(mn.i[i], std::min(x[i], y[i]));
      EXPECT_EQ(sw.i[i], x[i ^ 1]);
      EXPECT_EQ(mx.i[i], std::max(x[i], y[i]));
      EXPECT_EQ(sw64.i[i], x[i ^ 2]);
      EXPECT_EQ(sa.i[i], i == 3 ? y[3] : x[i]);
      EXPECT_EQ(a.lane(i), x[i]);
    }
    for (int i = 0; i < 2; ++i) {
      EXPECT_EQ(ps.i[i], wrap(std::int64_t(x[2 * i]) + x[2 * i + 1]));
      EXPECT_EQ(ps.i[2 + i], wrap(std::int64_t(y[2 * i]) + y[2 * i + 1]));
      EXPECT_EQ(ev.i[i], x[2 * i]);
      EXPECT_EQ(ev.i[2 + i], y[2 * i]);
    }
    EXPECT_EQ(simd::sum_lanes(a), wrap(std::int64_t(x[0]) + x[1] + x[2] + x[3]));
    EXPECT_EQ(simd::sum_lanes02(a), wrap(std::int64_t(x[0]) + x[2]));
    EXPECT_EQ(simd::movemask(a), (x[0] < 0) | (x[1] < 0) << 1 | (x[2] < 0) << 2 | (x[3] < 0) << 3);
    std::uint8_t bytes[4];
    simd::store_u8x4(a, bytes);
    for (int i = 0; i < 4; ++i) EXPECT_EQ(bytes[i], clamp_u8(x[i])) << x[i];
    check_shifts<0>(a, x);
    check_shifts<1>(a, x);
    check_shifts<8>(a, x);
    check_shifts<31>(a, x);
    check_shifts<32>(a, x);
    check_shifts<33>(a, x);
    for (int k = 0; k < 4; ++k) {
      const ILanes s = lanes(simd::sll_bytes(a, k));
      for (int i = 0; i < 4; ++i) EXPECT_EQ(s.i[i], std::int32_t(std::uint32_t(x[i]) << 8 * k));
    }
    // Texels: bytes little-endian in each 32-bit lane.
    std::uint8_t tex[16];
    for (int i = 0; i < 16; ++i) tex[i] = std::uint8_t(rng.next());
    const ILanes t = lanes(simd::load_texels4(tex));
    for (int i = 0; i < 4; ++i) {
      EXPECT_EQ(std::uint32_t(t.i[i]), tex[4 * i] | tex[4 * i + 1] << 8 | tex[4 * i + 2] << 16 |
                                           std::uint32_t(tex[4 * i + 3]) << 24);
    }
  }
  const ILanes c = lanes(vi32x4(1, -2, 3, INT32_MIN)), s = lanes(vi32x4(-7));
  EXPECT_EQ(c.i[1], -2);
  EXPECT_EQ(c.i[3], INT32_MIN);
  EXPECT_EQ(s.i[2], -7);
  EXPECT_EQ(lanes(vi32x4()).i[3], 0);
}

TEST(Simd, Int64LanesEveryOperation) {
  Rng rng{2};
  for (int round = 0; round < 200; ++round) {
    const std::int64_t x[2] = {std::int64_t(std::uint64_t(rng.next()) << 32 | rng.next()),
                               round % 7 == 0 ? INT64_MIN : std::int64_t(rng.next()) - (1 << 30)};
    const std::int64_t y[2] = {round % 5 == 0 ? INT64_MAX : std::int64_t(rng.i32()),
                               std::int64_t(std::uint64_t(rng.next()) << 33)};
    const vi64x2 a = simd::load_i64x2(x), b(y[0], y[1]);
    const auto sign = [](std::int64_t v0, std::int64_t v1) { return (v0 < 0) | (v1 < 0) << 1; };
    const auto add = [](std::int64_t p, std::int64_t q) {
      return std::int64_t(std::uint64_t(p) + std::uint64_t(q));
    };
    EXPECT_EQ(simd::movemask(a), sign(x[0], x[1]));
    EXPECT_EQ(simd::movemask(a + b), sign(add(x[0], y[0]), add(x[1], y[1])));
    EXPECT_EQ(simd::movemask(a | b), sign(x[0] | y[0], x[1] | y[1]));
    EXPECT_EQ(simd::movemask(vi64x2(x[1])), sign(x[1], x[1]));
  }
  EXPECT_EQ(simd::movemask(vi64x2()), 0);
}

// The 16-bit lanes (vu16x8): arithmetic, compares, selects, zips, widening, narrowing,
// shifts, stores, on eight generated lanes.
void check_u16_lanes(Rng& rng) {
  std::uint16_t x[8], y[8], m[8];
  for (int i = 0; i < 8; ++i) {
    x[i] = rng.u16();
    y[i] = rng.u16();
    m[i] = std::uint16_t(rng.next());
  }
  const vu16x8 a = simd::load_u16x8(x), b = simd::load_u16x8(y), mask = simd::load_u16x8(m);
  const U16Lanes add = lanes(a + b), sub = lanes(a - b), lo = lanes(simd::mullo(a, b));
  const U16Lanes hi = lanes(simd::mulhi(a, b)), an = lanes(a & b), orr = lanes(a | b);
  const U16Lanes eq = lanes(simd::cmpeq(a, b)), eqs = lanes(simd::cmpeq(a, a));
  const U16Lanes sel = lanes(simd::select(mask, a, b));
  const U16Lanes zl = lanes(simd::zip_lo(a, b)), zh = lanes(simd::zip_hi(a, b));
  const ILanes md = lanes(simd::madd(a, b));
  const ILanes w0 = lanes(simd::widen32_lo(a)), w1 = lanes(simd::widen32_hi(a));
  const Lanes f0 = lanes(simd::f2p23_plus_lo(a)), f1 = lanes(simd::f2p23_plus_hi(a));
  std::uint8_t b8[8];
  simd::store_u8x8(a, b8);
  for (int i = 0; i < 8; ++i) {
    const std::uint32_t p = x[i], q = y[i];
    EXPECT_EQ(add.u[i], std::uint16_t(p + q));
    EXPECT_EQ(sub.u[i], std::uint16_t(p - q));
    EXPECT_EQ(lo.u[i], std::uint16_t(p * q));
    EXPECT_EQ(hi.u[i], std::uint16_t(p * q >> 16));
    EXPECT_EQ(an.u[i], p & q);
    EXPECT_EQ(orr.u[i], p | q);
    EXPECT_EQ(eq.u[i], p == q ? 0xffff : 0);
    EXPECT_EQ(eqs.u[i], 0xffff);
    EXPECT_EQ(sel.u[i], (m[i] & p) | (~m[i] & q & 0xffff));
    EXPECT_EQ(zl.u[i], i % 2 ? y[i / 2] : x[i / 2]);
    EXPECT_EQ(zh.u[i], i % 2 ? y[4 + i / 2] : x[4 + i / 2]);
    EXPECT_EQ(b8[i], clamp_u8(std::int16_t(x[i]))) << x[i];  // packus: signed 16-bit lanes
    EXPECT_EQ(a.lane_sq(i), std::int32_t(std::int16_t(x[i])) * std::int16_t(x[i]));
  }
  const U16Lanes mxs = lanes(simd::max_s16(a, b)), mns = lanes(simd::min_s16(a, b));
  const U16Lanes gts = lanes(simd::cmpgt_s16(a, b)), sal = lanes(simd::select_alpha(a, b));
  std::uint8_t four[4], b4[6] = {0, 0, 0, 0, 0xee, 0xee};
  std::memcpy(four, x, 4);
  const U16Lanes l4 = lanes(simd::load_u8x4_lo(four));
  simd::store_u8x4(a, b4);
  for (int i = 0; i < 8; ++i) {
    const std::int16_t p = std::int16_t(x[i]), q = std::int16_t(y[i]);
    EXPECT_EQ(mxs.u[i], std::uint16_t(std::max(p, q)));
    EXPECT_EQ(mns.u[i], std::uint16_t(std::min(p, q)));
    EXPECT_EQ(gts.u[i], p > q ? 0xffff : 0);
    EXPECT_EQ(sal.u[i], (i & 3) == 3 ? y[i] : x[i]);
    EXPECT_EQ(l4.u[i], i < 4 ? four[i] : 0);
    if (i < 4) {
      EXPECT_EQ(b4[i], clamp_u8(p));
    }
  }
  EXPECT_EQ(b4[4], 0xee);  // four bytes written, no more
  for (int i = 0; i < 4; ++i) {
    const std::int64_t s = std::int64_t(std::int16_t(x[2 * i])) * std::int16_t(y[2 * i]) +
                           std::int64_t(std::int16_t(x[2 * i + 1])) * std::int16_t(y[2 * i + 1]);
    EXPECT_EQ(md.i[i], wrap(s));
    EXPECT_EQ(w0.i[i], x[i]);
    EXPECT_EQ(w1.i[i], x[4 + i]);
    EXPECT_EQ(f0.f[i], 8388608.0f + float(x[i]));
    EXPECT_EQ(f1.f[i], 8388608.0f + float(x[4 + i]));
  }
  check_shifts16<0>(a, x);
  check_shifts16<1>(a, x);
  check_shifts16<15>(a, x);
  check_shifts16<16>(a, x);
  check_shifts16<17>(a, x);
  const U8Lanes nw = lanes(simd::narrow(a, b));
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(nw.u[i], clamp_u8(std::int16_t(x[i])));
    EXPECT_EQ(nw.u[8 + i], clamp_u8(std::int16_t(y[i])));
  }
}

// 32-bit lanes narrowed (saturating) to 16 and 8 bits.
void check_narrow_i32(Rng& rng) {
  std::int32_t v[16];
  for (int i = 0; i < 16; ++i) v[i] = rng.i32();
  const vi32x4 q0 = simd::load4(v), q1 = simd::load4(v + 4);
  const vi32x4 q2 = simd::load4(v + 8), q3 = simd::load4(v + 12);
  const U16Lanes n16 = lanes(simd::narrow16(q0, q1));
  const U8Lanes n8 = lanes(simd::narrow(q0, q1, q2, q3));
  for (int i = 0; i < 8; ++i) EXPECT_EQ(std::int16_t(n16.u[i]), clamp_s16(v[i])) << v[i];
  for (int i = 0; i < 16; ++i) EXPECT_EQ(n8.u[i], clamp_u8(v[i])) << v[i];
}

// The bytes (vu8x16), and byte loads widened to 16 bits.
void check_u8_lanes(Rng& rng) {
  std::uint8_t c[16], d[16], k[16];
  for (int i = 0; i < 16; ++i) {
    c[i] = std::uint8_t(rng.next() % 7 == 0 ? 0x80 : rng.next());
    d[i] = std::uint8_t(i % 3 == 0 ? c[i] : rng.next());
    k[i] = std::uint8_t(rng.next());
  }
  const vu8x16 e = simd::load_u8x16(c), f = simd::load_u8x16(d), km = simd::load_u8x16(k);
  const U8Lanes s8 = lanes(e + f), a8 = lanes(e & f), o8 = lanes(e | f);
  const U8Lanes q8 = lanes(simd::cmpeq(e, f)), an8 = lanes(simd::andnot(e, f));
  const U8Lanes sel8 = lanes(simd::select(km, e, f));
  const U16Lanes wl = lanes(simd::widen_lo(e)), wh = lanes(simd::widen_hi(e));
  for (int i = 0; i < 16; ++i) {
    EXPECT_EQ(s8.u[i], std::uint8_t(c[i] + d[i]));
    EXPECT_EQ(a8.u[i], c[i] & d[i]);
    EXPECT_EQ(o8.u[i], c[i] | d[i]);
    EXPECT_EQ(q8.u[i], c[i] == d[i] ? 0xff : 0);
    EXPECT_EQ(an8.u[i], ~c[i] & d[i] & 0xff);
    EXPECT_EQ(sel8.u[i], (k[i] & c[i]) | (~k[i] & d[i] & 0xff));
  }
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(wl.u[i], c[i]);
    EXPECT_EQ(wh.u[i], c[8 + i]);
  }
  bool top = false;
  for (int i = 0; i < 16; ++i) top = top || (k[i] & 0x80) != 0;
  EXPECT_EQ(simd::any(km), top);
  for (int i = 0; i < 16; ++i) {
    std::uint8_t one[16] = {};
    one[i] = std::uint8_t(0x80 | (k[i] & 0x7f));
    EXPECT_TRUE(simd::any(simd::load_u8x16(one)));
    one[i] = std::uint8_t(k[i] & 0x7f);
    EXPECT_FALSE(simd::any(simd::load_u8x16(one)));
  }

  // Byte loads widened to 16 bits.
  const U16Lanes l8 = lanes(simd::load_u8x8(c)), l44 = lanes(simd::load_u8x4x2(c + 8, d + 4));
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(l8.u[i], c[i]);
    EXPECT_EQ(l44.u[i], i < 4 ? c[8 + i] : d[i]);
  }
}

// Shuffles of 16-bit texel planes.
void check_texel_shuffles(Rng& rng) {
  std::uint16_t p[32];
  for (int i = 0; i < 32; ++i) p[i] = rng.u16();
  vu16x8 left, right;
  simd::taps8(p, left, right);
  static constexpr int kL[8] = {0, 0, 1, 1, 1, 1, 2, 2};
  const U16Lanes tl = lanes(left), tr = lanes(right);
  vu16x8 planes[4];
  simd::transpose_8x4(p, planes);
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(tl.u[i], p[kL[i]]);
    EXPECT_EQ(tr.u[i], p[kL[i] + 1]);
    for (int ch = 0; ch < 4; ++ch) EXPECT_EQ(lanes(planes[ch]).u[i], p[4 * i + ch]);
  }
}

// channel16: channel c of eight RGBA8 texels.
void check_channel16(Rng& rng) {
  std::uint8_t texels[32];
  for (int i = 0; i < 32; ++i) texels[i] = std::uint8_t(rng.next());
  const vi32x4 t0 = simd::load_texels4(texels), t1 = simd::load_texels4(texels + 16);
  for (int ch = 0; ch < 4; ++ch) {
    const U16Lanes cl = lanes(simd::channel16(t0, t1, ch));
    for (int i = 0; i < 8; ++i) EXPECT_EQ(cl.u[i], texels[4 * i + ch]);
  }
}

TEST(Simd, PackedLanesEveryOperation) {
  Rng rng{3};
  for (int round = 0; round < 500; ++round) {
    // In this order: each step draws its lanes from the one generator.
    check_u16_lanes(rng);
    check_narrow_i32(rng);
    check_u8_lanes(rng);
    check_texel_shuffles(rng);
    check_channel16(rng);
  }
  EXPECT_EQ(lanes(vu16x8(std::uint16_t(0x8001))).u[5], 0x8001);
  EXPECT_EQ(lanes(vu8x16(std::uint8_t(0xfe))).u[15], 0xfe);
  EXPECT_EQ(lanes(vu16x8()).u[0], 0);
  EXPECT_EQ(lanes(vu8x16()).u[0], 0);
}

}  // namespace
