// src/core/simd_avx2.h and simd_halves.h: every operation of the 8-lane types, checked lane by
// lane (bit for bit) against a scalar reference expression, on edge values and generated ones.
// Built three ways (tests/unit/CMakeLists.txt): simd_wide_test with the target's portable backend
// (two SSE2 halves on x86-64, two NEON halves on AArch64, where the arm64 stage runs it under
// qemu-aarch64), simd_wide_scalar_test with TESSERA_NO_SIMD (two scalar halves), and on x86-64
// simd_wide_avx2_test compiled with -mavx2 (the AVX2 backend; skipped on CPUs without AVX2).
// So every backend is held to the same expressions.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "core/simd.h"
#include "simd_test_rng.h"
#include "test_require.h"

namespace {

namespace simd = tessera::simd;
using simd::vf32x8;
using simd::vi32x8;
using simd::vu16x16;
using simd::vu8x32;

bool skip_here() {
#if defined(TESSERA_SIMD_AVX2)
  return __builtin_cpu_supports("avx2") == 0;
#else
  return false;
#endif
}

using simd_test::Rng;

struct I8 {
  std::int32_t l[8];
};
struct U16 {
  std::uint16_t l[16];
};
struct U8 {
  std::uint8_t l[32];
};
struct F8 {
  float l[8];
};
I8 lanes(vi32x8 a) {
  I8 r;
  simd::store8(a, r.l);
  return r;
}
U16 lanes(vu16x16 a) {
  U16 r;
  simd::store_u16x16(a, r.l);
  return r;
}
U8 lanes(vu8x32 a) {
  U8 r;
  simd::store_u8x32(a, r.l);
  return r;
}
F8 lanes(vf32x8 a) {
  F8 r;
  simd::storef8(a, r.l);
  return r;
}
std::int32_t wrap(std::int64_t x) { return std::int32_t(std::uint32_t(std::uint64_t(x))); }
std::uint8_t clamp_u8(std::int32_t x) { return std::uint8_t(x < 0 ? 0 : x > 255 ? 255 : x); }
std::uint16_t packs(std::int32_t x) {
  return std::uint16_t(std::int16_t(x < -32768 ? -32768 : x > 32767 ? 32767 : x));
}
std::uint32_t fbits(float x) {
  std::uint32_t b;
  std::memcpy(&b, &x, 4);
  return b;
}
void expect_same(float got, float want) {
  if (std::isnan(want)) {
    EXPECT_TRUE(std::isnan(got));
  } else {
    EXPECT_EQ(fbits(got), fbits(want)) << want;
  }
}

TEST(SimdWide, Int32Lanes) {
  TESSERA_SKIP_WITHOUT_AVX2(!skip_here(), "no AVX2 on this CPU");
  Rng rng{7};
  for (int round = 0; round < 400; ++round) {
    I8 x, y, m, n;
    for (int i = 0; i < 8; ++i) {
      x.l[i] = rng.i32();
      y.l[i] = rng.i32();
      m.l[i] = (rng.next() & 1) ? -1 : 0;
      n.l[i] = std::int32_t(rng.next() % 40);
    }
    const vi32x8 a = simd::load8(x.l), b = simd::load8(y.l);
    const I8 add = lanes(a + b), sub = lanes(a - b), mul = lanes(a * b), band = lanes(a & b),
             bor = lanes(a | b), bxor = lanes(a ^ b), anot = lanes(simd::andnot(a, b)),
             eq = lanes(simd::cmpeq(a, b)), gt = lanes(simd::cmpgt(a, b)),
             lt = lanes(simd::cmplt(a, b)), mn = lanes(simd::min(a, b)),
             mx = lanes(simd::max(a, b)), sel = lanes(simd::select(simd::load8(m.l), a, b)),
             sra = lanes(simd::sra<5>(a)), srl = lanes(simd::srl<7>(a)),
             sll = lanes(simd::sll<9>(a)), sllv = lanes(simd::sllv(a, simd::load8(n.l))),
             sb = lanes(simd::sll_bytes(a, round & 3)), div = lanes(simd::div255_u32(a)),
             slln = lanes(simd::sll(a, round % 40)), swp = lanes(simd::swap_pairs(a)),
             swp64 = lanes(simd::swap_pairs64(a)), swh = lanes(simd::swap_halves(a)),
             ps = lanes(simd::pair_sums(a, b)), ev = lanes(simd::even_lanes(a, b)),
             p64 = lanes(simd::permute64<0, 2, 1, 3>(a)),
             p64b = lanes(simd::permute64<3, 3, 0, 1>(a));
    std::int64_t sum = 0;
    for (int i = 0; i < 8; ++i) {
      const std::uint32_t u = std::uint32_t(x.l[i]), v = std::uint32_t(y.l[i]);
      const int h = i & 4, j = i & 3;
      EXPECT_EQ(add.l[i], wrap(std::int64_t(x.l[i]) + y.l[i]));
      EXPECT_EQ(sub.l[i], wrap(std::int64_t(x.l[i]) - y.l[i]));
      EXPECT_EQ(mul.l[i], std::int32_t(u * v));
      EXPECT_EQ(band.l[i], std::int32_t(u & v));
      EXPECT_EQ(bor.l[i], std::int32_t(u | v));
      EXPECT_EQ(bxor.l[i], std::int32_t(u ^ v));
      EXPECT_EQ(anot.l[i], std::int32_t(~u & v));
      EXPECT_EQ(eq.l[i], x.l[i] == y.l[i] ? -1 : 0);
      EXPECT_EQ(gt.l[i], x.l[i] > y.l[i] ? -1 : 0);
      EXPECT_EQ(lt.l[i], x.l[i] < y.l[i] ? -1 : 0);
      EXPECT_EQ(mn.l[i], std::min(x.l[i], y.l[i]));
      EXPECT_EQ(mx.l[i], std::max(x.l[i], y.l[i]));
      EXPECT_EQ(sel.l[i], m.l[i] ? x.l[i] : y.l[i]);
      EXPECT_EQ(sra.l[i], x.l[i] >> 5);
      EXPECT_EQ(srl.l[i], std::int32_t(u >> 7));
      EXPECT_EQ(sll.l[i], std::int32_t(u << 9));
      EXPECT_EQ(sllv.l[i], n.l[i] < 32 ? std::int32_t(u << n.l[i]) : 0);
      EXPECT_EQ(sb.l[i], std::int32_t((round & 3) ? u << (8 * (round & 3)) : u));
      EXPECT_EQ(slln.l[i], round % 40 < 32 ? std::int32_t(u << (round % 40)) : 0);
      EXPECT_EQ(div.l[i], std::int32_t(u / 255u));
      EXPECT_EQ(swp.l[i], x.l[i ^ 1]);
      EXPECT_EQ(swp64.l[i], x.l[i ^ 2]);
      EXPECT_EQ(swh.l[i], x.l[i ^ 4]);
      const std::int32_t* src = j < 2 ? x.l : y.l;
      EXPECT_EQ(ps.l[i], wrap(std::int64_t(src[h + 2 * (j & 1)]) + src[h + 2 * (j & 1) + 1]));
      EXPECT_EQ(ev.l[i], src[h + 2 * (j & 1)]);
      static constexpr int kP[4] = {0, 2, 1, 3}, kQ[4] = {3, 3, 0, 1};
      EXPECT_EQ(p64.l[i], x.l[2 * kP[i / 2] + (i & 1)]);
      EXPECT_EQ(p64b.l[i], x.l[2 * kQ[i / 2] + (i & 1)]);
      sum += x.l[i];
    }
    EXPECT_EQ(simd::sum_lanes(a), wrap(sum));
    std::uint8_t bytes[8];
    simd::store_u8x8(a, bytes);
    for (int i = 0; i < 8; ++i) EXPECT_EQ(bytes[i], clamp_u8(x.l[i]));
    // Halves and texel loads.
    const I8 lh = lanes(vi32x8(simd::high(a), simd::low(a)));
    for (int i = 0; i < 8; ++i) EXPECT_EQ(lh.l[i], x.l[i ^ 4]);
    std::uint8_t tex[32];
    std::memcpy(tex, x.l, 32);
    const I8 t = lanes(simd::load_texels8(tex));
    for (int i = 0; i < 8; ++i) {
      EXPECT_EQ(std::uint32_t(t.l[i]),
                std::uint32_t(tex[4 * i]) | std::uint32_t(tex[4 * i + 1]) << 8 |
                    std::uint32_t(tex[4 * i + 2]) << 16 | std::uint32_t(tex[4 * i + 3]) << 24);
    }
  }
}

TEST(SimdWide, FloatLanes) {
  TESSERA_SKIP_WITHOUT_AVX2(!skip_here(), "no AVX2 on this CPU");
  Rng rng{11};
  for (int round = 0; round < 400; ++round) {
    F8 x, y;
    I8 k;
    for (int i = 0; i < 8; ++i) {
      x.l[i] = rng.f32();
      y.l[i] = rng.f32();
      k.l[i] = rng.i32();
    }
    const vf32x8 a = simd::loadf8(x.l), b = simd::loadf8(y.l);
    const F8 add = lanes(a + b), sub = lanes(a - b), mul = lanes(a * b),
             mx = lanes(simd::max(a, b)), mn = lanes(simd::min(a, b)),
             cv = lanes(simd::to_float(simd::load8(k.l)));
    const I8 eq = lanes(simd::cmpeq(a, b)), lt = lanes(simd::cmplt(a, b)),
             tr = lanes(simd::to_int_trunc(a));
    for (int i = 0; i < 8; ++i) {
      const float u = x.l[i], v = y.l[i];
      expect_same(add.l[i], u + v);
      expect_same(sub.l[i], u - v);
      expect_same(mul.l[i], u * v);
      EXPECT_EQ(fbits(mx.l[i]), fbits(u > v ? u : v));
      EXPECT_EQ(fbits(mn.l[i]), fbits(u < v ? u : v));
      EXPECT_EQ(fbits(cv.l[i]), fbits(float(k.l[i])));
      EXPECT_EQ(eq.l[i], u == v ? -1 : 0);
      EXPECT_EQ(lt.l[i], u < v ? -1 : 0);
      EXPECT_EQ(tr.l[i], u >= -2147483648.0f && u < 2147483648.0f ? std::int32_t(u) : INT32_MIN);
    }
    const F8 lh = lanes(vf32x8(simd::high(a), simd::low(a)));
    for (int i = 0; i < 8; ++i) EXPECT_EQ(fbits(lh.l[i]), fbits(x.l[i ^ 4]));
  }
}

TEST(SimdWide, PackedLanes) {
  TESSERA_SKIP_WITHOUT_AVX2(!skip_here(), "no AVX2 on this CPU");
  Rng rng{13};
  for (int round = 0; round < 400; ++round) {
    U16 x, y, m, idx;
    I8 p, q;
    for (int i = 0; i < 16; ++i) {
      x.l[i] = rng.u16();
      y.l[i] = rng.u16();
      m.l[i] = (rng.next() & 1) ? 0xffff : 0;
      const std::uint32_t r = rng.next();
      idx.l[i] = std::uint16_t(((r & 0x8f) | (r >> 8 & 0x8f) << 8));
    }
    for (int i = 0; i < 8; ++i) {
      p.l[i] = rng.i32();
      q.l[i] = rng.i32();
    }
    const vu16x16 a = simd::load_u16x16(x.l), b = simd::load_u16x16(y.l),
                  mask = simd::load_u16x16(m.l);
    const U16 add = lanes(a + b), sub = lanes(a - b), band = lanes(a & b), bor = lanes(a | b),
              ml = lanes(simd::mullo(a, b)), mh = lanes(simd::mulhi(a, b)),
              sr = lanes(simd::srl<3>(a)), eq = lanes(simd::cmpeq(a, b)),
              gt = lanes(simd::cmpgt_s16(a, b)), sel = lanes(simd::select(mask, a, b)),
              sa = lanes(simd::select_alpha(a, b)), zl = lanes(simd::zip_lo(a, b)),
              zh = lanes(simd::zip_hi(a, b)),
              n16 = lanes(simd::narrow16(simd::load8(p.l), simd::load8(q.l))),
              sh = lanes(simd::shuffle_bytes(a, simd::load_u16x16(idx.l))),
              pm = lanes(simd::permute64<0, 2, 1, 3>(a));
    const I8 md = lanes(simd::madd(a, b));
    const F8 flo = lanes(simd::f2p23_plus_lo(a)), fhi = lanes(simd::f2p23_plus_hi(a));
    std::uint8_t xb[32], ib[32], shb[32];
    std::memcpy(xb, x.l, 32);
    std::memcpy(ib, idx.l, 32);
    std::memcpy(shb, sh.l, 32);
    for (int i = 0; i < 32; ++i) {
      EXPECT_EQ(shb[i], (ib[i] & 0x80) ? 0 : xb[(i & 16) | (ib[i] & 15)]);
    }
    for (int i = 0; i < 16; ++i) {
      const std::uint32_t u = x.l[i], v = y.l[i];
      const int h = i & 8, j = i & 7;
      EXPECT_EQ(add.l[i], std::uint16_t(u + v));
      EXPECT_EQ(sub.l[i], std::uint16_t(u - v));
      EXPECT_EQ(band.l[i], u & v);
      EXPECT_EQ(bor.l[i], u | v);
      EXPECT_EQ(ml.l[i], std::uint16_t(u * v));
      EXPECT_EQ(mh.l[i], std::uint16_t((u * v) >> 16));
      EXPECT_EQ(sr.l[i], u >> 3);
      EXPECT_EQ(eq.l[i], u == v ? 0xffff : 0);
      EXPECT_EQ(gt.l[i], std::int16_t(u) > std::int16_t(v) ? 0xffff : 0);
      EXPECT_EQ(sel.l[i], m.l[i] ? u : v);
      EXPECT_EQ(sa.l[i], (i & 3) == 3 ? v : u);
      EXPECT_EQ(zl.l[i], (j & 1 ? y.l : x.l)[h + j / 2]);
      EXPECT_EQ(zh.l[i], (j & 1 ? y.l : x.l)[h + 4 + j / 2]);
      EXPECT_EQ(n16.l[i], packs((j < 4 ? p.l : q.l)[h / 2 + (j & 3)]));
      static constexpr int kP[4] = {0, 2, 1, 3};
      EXPECT_EQ(pm.l[i], x.l[4 * kP[i / 4] + (i & 3)]);
    }
    for (int i = 0; i < 8; ++i) {
      const int k = 2 * i;
      EXPECT_EQ(md.l[i], wrap(std::int64_t(std::int16_t(x.l[k])) * std::int16_t(y.l[k]) +
                              std::int64_t(std::int16_t(x.l[k + 1])) * std::int16_t(y.l[k + 1])));
      const int h = (i & 4) * 2, j = i & 3;
      EXPECT_EQ(flo.l[i], 8388608.0f + float(x.l[h + j]));
      EXPECT_EQ(fhi.l[i], 8388608.0f + float(x.l[h + 4 + j]));
    }
    std::uint32_t mm = 0;
    for (int i = 0; i < 32; ++i) mm |= std::uint32_t(xb[i] >> 7) << i;
    EXPECT_EQ(simd::movemask_bytes(a), mm);
    // Narrowings and stores to bytes (int16 lanes clamped to 0..255), in lane order.
    const U8 nb = lanes(simd::narrow(a, b));
    std::uint8_t s16[16];
    simd::store_u8x16(a, s16);
    for (int i = 0; i < 16; ++i) {
      EXPECT_EQ(nb.l[i], clamp_u8(std::int16_t(x.l[i])));
      EXPECT_EQ(nb.l[16 + i], clamp_u8(std::int16_t(y.l[i])));
      EXPECT_EQ(s16[i], clamp_u8(std::int16_t(x.l[i])));
    }
    // Byte lanes, widening and byte loads.
    U8 c, d, bm;
    for (int i = 0; i < 32; ++i) {
      c.l[i] = std::uint8_t(rng.next());
      d.l[i] = (rng.next() & 3) ? c.l[i] : std::uint8_t(rng.next());
      bm.l[i] = (rng.next() & 1) ? 0xff : 0;
    }
    const vu8x32 e = simd::load_u8x32(c.l), f = simd::load_u8x32(d.l),
                 bmask = simd::load_u8x32(bm.l);
    const U8 badd = lanes(e + f), bnd = lanes(e & f), bo = lanes(e | f),
             ban = lanes(simd::andnot(e, f)), beq = lanes(simd::cmpeq(e, f)),
             bsel = lanes(simd::select(bmask, e, f));
    const U16 wl = lanes(simd::widen_lo(e)), wh = lanes(simd::widen_hi(e)),
              lw = lanes(simd::load_u8x16_u16(c.l + 3));
    bool any = false;
    for (int i = 0; i < 32; ++i) {
      EXPECT_EQ(badd.l[i], std::uint8_t(c.l[i] + d.l[i]));
      EXPECT_EQ(bnd.l[i], c.l[i] & d.l[i]);
      EXPECT_EQ(bo.l[i], c.l[i] | d.l[i]);
      EXPECT_EQ(ban.l[i], std::uint8_t(~c.l[i] & d.l[i]));
      EXPECT_EQ(beq.l[i], c.l[i] == d.l[i] ? 0xff : 0);
      EXPECT_EQ(bsel.l[i], bm.l[i] ? c.l[i] : d.l[i]);
      any = any || bm.l[i];
    }
    EXPECT_EQ(simd::any(bmask), any);
    EXPECT_FALSE(simd::any(vu8x32(std::uint8_t(0x7f))));
    for (int i = 0; i < 16; ++i) {
      EXPECT_EQ(wl.l[i], c.l[i]);
      EXPECT_EQ(wh.l[i], c.l[16 + i]);
      EXPECT_EQ(lw.l[i], c.l[3 + i]);
    }
    const std::uint64_t w64 = std::uint64_t(rng.next()) << 32 | rng.next();
    const U16 bc = lanes(simd::broadcast64(w64));
    for (int i = 0; i < 16; ++i) EXPECT_EQ(bc.l[i], std::uint16_t(w64 >> (16 * (i & 3))));
  }
}

TEST(SimdWide, TexelPlanes) {
  TESSERA_SKIP_WITHOUT_AVX2(!skip_here(), "no AVX2 on this CPU");
  Rng rng{17};
  std::uint8_t tex[128];
  for (auto& t : tex) t = std::uint8_t(rng.next());
  vu8x32 p8[4];
  vu16x16 p16[4];
  simd::load_planes(tex, p8);
  simd::load_planes(tex + 4, p16);
  for (int c = 0; c < 4; ++c) {
    const U8 b = lanes(p8[c]);
    const U16 w = lanes(p16[c]);
    for (int i = 0; i < 32; ++i) EXPECT_EQ(b.l[i], tex[4 * i + c]) << c << " " << i;
    for (int i = 0; i < 16; ++i) EXPECT_EQ(w.l[i], tex[4 + 4 * i + c]) << c << " " << i;
  }
}

TEST(SimdWide, WidthGenericNames) {
  TESSERA_SKIP_WITHOUT_AVX2(!skip_here(), "no AVX2 on this CPU");
  static_assert(simd::kLanes<simd::vf32x4> == 4 && simd::kLanes<vf32x8> == 8);
  static_assert(simd::kLanes<simd::vi32x4> == 4 && simd::kLanes<vi32x8> == 8);
  static_assert(simd::kLanes<simd::vu16x8> == 8 && simd::kLanes<vu16x16> == 16);
  static_assert(simd::kLanes<simd::vu8x16> == 16 && simd::kLanes<vu8x32> == 32);
  float f[8], g[8];
  std::uint16_t h[16], k[16];
  std::uint8_t b[32], c[32];
  for (int i = 0; i < 32; ++i) {
    if (i < 8) f[i] = float(i) - 2.5f;
    if (i < 16) h[i] = std::uint16_t(1000 * i + 7);
    b[i] = std::uint8_t(7 * i + 1);
  }
  simd::store(simd::load_as<vf32x8>(f), g);
  simd::store(simd::load_as<vu16x16>(h), k);
  simd::store(simd::load_as<vu8x32>(b), c);
  EXPECT_EQ(std::memcmp(f, g, sizeof f), 0);
  EXPECT_EQ(std::memcmp(h, k, sizeof h), 0);
  EXPECT_EQ(std::memcmp(b, c, sizeof b), 0);
  simd::store(simd::load_as<simd::vf32x4>(f + 4), g);
  EXPECT_EQ(std::memcmp(f + 4, g, 4 * sizeof(float)), 0);
  const std::int32_t v[8] = {-5, 0, 17, 255, 256, 1000, -1, 128};
  std::uint8_t o[8];
  simd::store_bytes(simd::load8(v), o);
  for (int i = 0; i < 8; ++i) EXPECT_EQ(o[i], clamp_u8(v[i]));
}

// The operations of simd_generic.h that kernels written once use on both widths, including the
// compositions the 4-lane backends spell out (simd_compose4.h: div255_u32, load_planes,
// lookup8).
TEST(SimdWide, KernelCompositionsOnBothWidths) {
  TESSERA_SKIP_WITHOUT_AVX2(!skip_here(), "no AVX2 on this CPU");
  Rng rng{23};
  for (int round = 0; round < 200; ++round) {
    std::int32_t x[8], r4[4], r8[8];
    for (auto& v : x) v = rng.i32();
    simd::store(simd::div255_u32(simd::load_as<simd::vi32x4>(x)), r4);
    simd::store(simd::div255_u32(simd::load_as<vi32x8>(x)), r8);
    for (int i = 0; i < 8; ++i) {
      const auto want = std::int32_t(std::uint32_t(x[i]) / 255u);
      if (i < 4) {
        EXPECT_EQ(r4[i], want) << x[i];
      }
      EXPECT_EQ(r8[i], want) << x[i];
    }
    std::uint8_t tex[64];
    for (auto& t : tex) t = std::uint8_t(rng.next());
    simd::store(simd::load_texels_as<simd::vi32x4>(tex), r4);
    simd::store(simd::load_texels_as<vi32x8>(tex), r8);
    EXPECT_EQ(std::memcmp(r4, tex, 16), 0);
    EXPECT_EQ(std::memcmp(r8, tex, 32), 0);
    std::uint16_t w8[8], w16[16];
    simd::store(simd::load_widen_as<simd::vu16x8>(tex + 3), w8);
    simd::store(simd::load_widen_as<vu16x16>(tex + 5), w16);
    for (int i = 0; i < 16; ++i) {
      if (i < 8) {
        EXPECT_EQ(w8[i], tex[3 + i]);
      }
      EXPECT_EQ(w16[i], tex[5 + i]);
    }
    simd::vu8x16 planes[4];
    simd::load_planes(tex, planes);
    for (int c = 0; c < 4; ++c) {
      std::uint8_t b[16];
      simd::store(planes[c], b);
      for (int i = 0; i < 16; ++i) EXPECT_EQ(b[i], tex[4 * i + c]) << c << " " << i;
    }
    // load_texel_planes: the 4-lane form fills the first nch planes, the 8-lane form all four.
    simd::vu16x8 p8[4];
    vu16x16 p16[4];
    simd::load_texel_planes<3>(tex, p8);
    simd::load_texel_planes<3>(tex, p16);
    for (int c = 0; c < 3; ++c) {
      std::uint16_t q8[8], q16[16];
      simd::store(p8[c], q8);
      simd::store(p16[c], q16);
      for (int i = 0; i < 16; ++i) {
        if (i < 8) {
          EXPECT_EQ(q8[i], tex[4 * i + c]);
        }
        EXPECT_EQ(q16[i], tex[4 * i + c]);
      }
    }
    // lookup8: indices -8..7 (as int16) in any lane.
    std::uint16_t table[8], idx[16], l8[8], l16[16];
    for (auto& t : table) t = rng.u16();
    for (auto& i : idx) i = std::uint16_t(int(rng.next() % 16) - 8);
    simd::store(simd::lookup8(table, simd::load_as<simd::vu16x8>(idx)), l8);
    simd::store(simd::lookup8(table, simd::load_as<vu16x16>(idx)), l16);
    for (int i = 0; i < 16; ++i) {
      const std::int16_t k = std::int16_t(idx[i]);
      const std::uint16_t want = k >= 0 ? table[k] : 0;
      if (i < 8) {
        EXPECT_EQ(l8[i], want) << k;
      }
      EXPECT_EQ(l16[i], want) << k;
    }
  }
}

TEST(SimdWide, BackendMatchesBuild) {
#if defined(__AVX2__) && !defined(TESSERA_NO_SIMD)
  EXPECT_EQ(TESSERA_SIMD_AVX2, 1);
#else
#if defined(TESSERA_SIMD_AVX2)
  ADD_FAILURE() << "AVX2 backend without -mavx2";
#endif
#endif
  SUCCEED();
}

}  // namespace
