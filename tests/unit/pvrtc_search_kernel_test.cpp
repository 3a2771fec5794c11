// Tests of the exact search's window evaluators (src/pvrtc/encode/search/exact_search_kernel.h):
// the channel-planar evaluator of one-colour-channel candidates against the general
// `local_error_simd` on random windows, including the bound (early exit) semantics of both; the
// AVX2 evaluators (exact_search_avx2.cpp) against the baseline ones, alpha-weighted or not, and
// whole encodes (4 bpp normal and high, 2 bpp high) with and without them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <vector>

#include "pvrtc/encode/encode_internal.h"
#include "pvrtc/encode/search/exact_search_kernel.h"
#include "pvrtc/format/pvrtc_internal.h"
#include "tessera/procedural.h"
#include "tessera/pvrtc.h"
#include "test_require.h"

using namespace tessera;
using namespace tessera::pvrtc;
using namespace tessera::pvrtc::detail;

namespace {

constexpr std::int32_t kExclude = 1 << 24;  // as build_local

// The early exit of an evaluator given `bound`: the exact error below the bound, else a value
// from the bound up to the exact error.
void expect_bounded(std::uint32_t got, std::uint32_t exact, std::uint32_t bound) {
  if (exact < bound) {
    EXPECT_EQ(got, exact) << "bound " << bound;
  } else {
    EXPECT_GE(got, bound) << "exact " << exact;
    EXPECT_LE(got, exact) << "bound " << bound;
  }
}

// A random window as build_local lays one out: per texel the other blocks' share of the A and B
// sums (bounded so that the whole sum stays within 16 times the channel maximum), block j's
// weight, the target and the blends its block mode lacks; texels 49-55 zero pads.
// `extremes`: the values at the ends of their ranges (targets 0 / 255, shares 0 / maximal, block
// j's weight 1 or 16, one block mode for the whole window or the other), where the 16-bit
// lanes come closest to wrapping and the blends to their limits.
void random_window(std::mt19937& rng, int nch, bool punch, int alpha_weight, LocalWindow& lw,
                   bool extremes = false) {
  auto uni0 = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  const int one_mode = extremes ? uni0(0, 2) : 2;  // 0 / 1: every texel in that mode
  auto uni = [&](int lo, int hi) { return extremes ? (uni0(0, 1) != 0 ? hi : lo) : uni0(lo, hi); };
  lw = LocalWindow{};
  lw.nch = nch;
  lw.punch = punch;
  for (int c = 0; c < 8; ++c) lw.weight16[c] = std::uint16_t((c & 3) == 3 ? alpha_weight : 1);
  for (int k = 0; k < 56; ++k) {
    const bool pad = k >= 49;
    const int own = pad ? 0 : uni(1, 16);
    for (int c = 0; c < 4; ++c) {
      const bool used = !pad && c < nch;
      const int top = c == 3 ? 15 : 31;
      lw.own16[k][c] = std::uint16_t(used ? own : 0);
      lw.rest16_a[k][c] = std::uint16_t(used ? uni(0, (16 - own) * top) : 0);
      lw.rest16_b[k][c] = std::uint16_t(used ? uni(0, (16 - own) * top) : 0);
      lw.t16[k][c] = std::uint16_t(used ? uni(0, 255) : 0);
    }
    const bool m1 = one_mode < 2 ? one_mode == 1 : uni0(0, 1) != 0;
    const std::int32_t b35 = pad ? 0 : m1 ? kExclude : 0;
    const std::int32_t b4 = pad ? 0 : m1 ? 0 : kExclude;
    const std::int32_t b4p = pad ? 0 : m1 && punch ? 0 : kExclude;
    for (int i = 0; i < 2; ++i) {
      lw.bias35[k / 2][(k & 1) * 2 + i] = b35;
      lw.bias4[k / 2][(k & 1) * 2 + i] = b4;
      lw.bias4p[k / 2][(k & 1) * 2 + i] = b4p;
    }
  }
}

Rgba5 random_pair_end(std::mt19937& rng, int nch) {
  auto uni = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  Rgba5 e;
  e.r = uni(0, 31);
  e.g = uni(0, 31);
  e.b = uni(0, 31);
  e.a = nch == 4 ? uni(0, 15) : 15;
  return e;
}

std::int32_t& channel(Rgba5& e, int c) { return c == 0 ? e.r : c == 1 ? e.g : e.b; }

void check_windows(int nch, bool punch, int alpha_weight, unsigned seed) {
  std::mt19937 rng(seed);
  for (int w = 0; w < 40; ++w) {
    LocalWindow lw;
    random_window(rng, nch, punch, alpha_weight, lw);
    PlanarWindow pw;
    build_planar(lw, pw);
    const Rgba5 a = random_pair_end(rng, nch), b = random_pair_end(rng, nch);
    planar_refresh(pw, a, b);
    for (int c = 0; c < 3; ++c) planar_rest(pw, c);
    for (int k = 0; k < 30; ++k) {
      const int c = int(rng() % 3);
      Rgba5 ca = a, cb = b;
      const int which = int(rng() % 3);  // A, B or both
      if (which != 1) channel(ca, c) = int(rng() % 32);
      if (which != 0) channel(cb, c) = int(rng() % 32);
      const std::uint32_t exact = local_error_simd(lw, ca, cb, ~0u);
      ASSERT_EQ(planar_error(pw, c, channel(ca, c), channel(cb, c), ~0u), exact)
          << "window " << w << " channel " << c;
      for (const std::uint32_t bound : {exact / 3, exact, exact + 1, exact + 1000}) {
        const std::uint32_t p = planar_error(pw, c, channel(ca, c), channel(cb, c), bound);
        expect_bounded(p, exact, bound);
        expect_bounded(local_error_simd(lw, ca, cb, bound), exact, bound);
      }
    }
    // The current pair itself (no channel changed) through the planar tables.
    const std::uint32_t cur = local_error_simd(lw, a, b, ~0u);
    Rgba5 ca = a;
    EXPECT_EQ(planar_error(pw, 1, channel(ca, 1), b.g, ~0u), cur);
    // The per-texel form sums to the same error.
    std::uint32_t texel[52];
    const std::uint32_t total = nch == 4 ? local_error_simd_t<true, true>(lw, a, b, 0, texel)
                                         : local_error_simd_t<false, true>(lw, a, b, 0, texel);
    EXPECT_EQ(total, cur);
    std::uint32_t sum = 0;
    for (int i = 0; i < 49; ++i) sum += texel[i];
    EXPECT_EQ(sum, cur);
  }
}

TEST(PvrtcSearchKernel, PlanarMatchesGeneralRgb) { check_windows(3, false, 1, 1); }
TEST(PvrtcSearchKernel, PlanarMatchesGeneralRgba) { check_windows(4, false, 2, 2); }
TEST(PvrtcSearchKernel, PlanarMatchesGeneralRgbaPunchThrough) { check_windows(4, true, 2, 3); }
TEST(PvrtcSearchKernel, PlanarMatchesGeneralRgbaWeight1) { check_windows(4, true, 1, 4); }

// Alpha-weighted colour error (EncodeOptions::alpha_weighted): the vector scaling is the
// scalar `scale_diff` for every difference and scale; scale 16 everywhere gives the unweighted
// errors, scale 0 everywhere the alpha error alone; and the planar evaluator agrees with the
// general one under random scales, bounded or not.
TEST(PvrtcSearchKernel, ScaleDiffMatchesScalar) {
  for (int sc = 0; sc <= 16; ++sc) {
    for (int d0 = -255; d0 <= 255; d0 += 8) {
      alignas(16) std::uint16_t d[8], out[8];
      for (int i = 0; i < 8; ++i) d[i] = std::uint16_t(std::min(d0 + i, 255));
      simd::store_u16x8(scale_diff16(simd::load_u16x8(d), simd::vu16x8(std::uint16_t(sc))), out);
      for (int i = 0; i < 8; ++i) {
        const int di = std::min(d0 + i, 255);
        const int want = scale_diff(di, sc);
        ASSERT_EQ(std::int16_t(out[i]), want) << "d " << di << " scale " << sc;
        ASSERT_LE(std::abs(want), std::abs(di));
        if (sc == 16) {
          ASSERT_EQ(want, di);
        }
      }
    }
  }
}

void set_scales(LocalWindow& lw, std::mt19937& rng, int fixed) {
  lw.weighted = true;
  for (int k = 0; k < 56; ++k) {
    const auto sc = std::uint16_t(k >= 49 ? 0 : fixed >= 0 ? fixed : int(rng() % 17));
    for (int c = 0; c < 3; ++c) lw.scale16[k][c] = sc;
    lw.scale16[k][3] = 16;
  }
}

TEST(PvrtcSearchKernel, WeightedScalesSixteenAreUnweighted) {
  std::mt19937 rng(21);
  for (int w = 0; w < 30; ++w) {
    LocalWindow lw;
    random_window(rng, 4, w % 2 == 0, 2, lw, w % 3 == 0);
    LocalWindow weighted = lw;
    set_scales(weighted, rng, 16);
    const Rgba5 a = random_pair_end(rng, 4), b = random_pair_end(rng, 4);
    EXPECT_EQ(local_error_weighted(weighted, a, b, ~0u), local_error_simd(lw, a, b, ~0u));
    PlanarWindow p0, p1;
    build_planar(lw, p0);
    build_planar(weighted, p1);
    planar_refresh(p0, a, b);
    planar_refresh_t<true>(p1, a, b);
    for (int c = 0; c < 3; ++c) {
      planar_rest(p0, c);
      planar_rest(p1, c);
      const int v = int(rng() % 32);
      EXPECT_EQ(planar_error_t<true>(p1, c, v, v, ~0u), planar_error(p0, c, v, v, ~0u));
    }
  }
}

TEST(PvrtcSearchKernel, WeightedScaleZeroIsAlphaAlone) {
  std::mt19937 rng(22);
  for (int w = 0; w < 30; ++w) {
    LocalWindow lw;
    random_window(rng, 4, true, 2, lw);
    LocalWindow weighted = lw;
    set_scales(weighted, rng, 0);
    LocalWindow alpha_only = lw;  // colour lanes zero: every colour difference 0
    for (int k = 0; k < 56; ++k) {
      for (int c = 0; c < 3; ++c) {
        alpha_only.rest16_a[k][c] = alpha_only.rest16_b[k][c] = alpha_only.t16[k][c] = 0;
      }
    }
    const Rgba5 a = random_pair_end(rng, 4), b = random_pair_end(rng, 4);
    EXPECT_EQ(local_error_weighted(weighted, a, b, ~0u),
              local_error_simd(alpha_only, Rgba5{0, 0, 0, a.a}, Rgba5{0, 0, 0, b.a}, ~0u));
  }
}

TEST(PvrtcSearchKernel, WeightedPlanarMatchesGeneral) {
  std::mt19937 rng(23);
  for (int w = 0; w < 40; ++w) {
    SCOPED_TRACE(testing::Message() << "window " << w);
    LocalWindow lw;
    random_window(rng, 4, w % 2 == 0, 2, lw, w % 4 == 0);
    set_scales(lw, rng, -1);
    PlanarWindow pw;
    build_planar(lw, pw);
    const Rgba5 a = random_pair_end(rng, 4), b = random_pair_end(rng, 4);
    planar_refresh_t<true>(pw, a, b);
    for (int c = 0; c < 3; ++c) planar_rest(pw, c);
    for (int k = 0; k < 30; ++k) {
      const int c = int(rng() % 3);
      Rgba5 ca = a, cb = b;
      if (k > 0) {
        channel(ca, c) = int(rng() % 32);
        channel(cb, c) = int(rng() % 32);
      }
      const std::uint32_t exact = local_error_weighted(lw, ca, cb, ~0u);
      ASSERT_EQ(planar_error_t<true>(pw, c, channel(ca, c), channel(cb, c), ~0u), exact);
      for (const std::uint32_t bound : {exact / 3, exact, exact + 1}) {
        const std::uint32_t p = planar_error_t<true>(pw, c, channel(ca, c), channel(cb, c), bound);
        expect_bounded(p, exact, bound);
        expect_bounded(local_error_weighted(lw, ca, cb, bound), exact, bound);
      }
    }
    std::uint32_t texel[52];
    const std::uint32_t total = local_error_simd_t<true, true, true>(lw, a, b, 0, texel);
    std::uint32_t sum = 0;
    for (int i = 0; i < 49; ++i) sum += texel[i];
    EXPECT_EQ(sum, total);
    EXPECT_EQ(total, local_error_weighted(lw, a, b, ~0u));
  }
}

TEST(PvrtcSearchKernel, SingleColourChannel) {
  const Rgba5 a{10, 11, 12, 13}, b{20, 21, 22, 14};
  Rgba5 x = a, y = b;
  EXPECT_EQ(single_colour_channel(x, y, a, b, 4), -1);  // nothing changed
  x.g = 3;
  EXPECT_EQ(single_colour_channel(x, y, a, b, 4), 1);
  y.g = 4;
  EXPECT_EQ(single_colour_channel(x, y, a, b, 4), 1);
  y.a = 1;
  EXPECT_EQ(single_colour_channel(x, y, a, b, 4), -1);  // alpha counts with nch 4
  EXPECT_EQ(single_colour_channel(x, y, a, b, 3), 1);   // but not with nch 3
  x.r = 0;
  EXPECT_EQ(single_colour_channel(x, y, a, b, 3), -1);
}

// The AVX2 evaluators against the baseline ones: the same error below the bound, >= the bound
// (and no more than the error) otherwise (expect_bounded); the same per-texel errors.
std::vector<std::uint32_t> bounds_for(std::uint32_t exact) {
  return {0u,    1u,        exact / 3,    exact / 2, exact > 0 ? exact - 1 : 0u,
          exact, exact + 1, exact + 1000, ~0u};
}

// weighted (nch 4): random colour scales, against the baseline's kWeighted evaluators.
void check_avx2_windows(int nch, bool punch, int alpha_weight, unsigned seed, bool extremes,
                        bool weighted = false) {
  std::mt19937 rng(seed);
  for (int w = 0; w < 60; ++w) {
    SCOPED_TRACE(testing::Message() << "window " << w);
    LocalWindow lw;
    random_window(rng, nch, punch, alpha_weight, lw, extremes);
    if (weighted) set_scales(lw, rng, -1);
    const Rgba5 a = random_pair_end(rng, nch), b = random_pair_end(rng, nch);
    const std::int32_t va[4] = {a.r, a.g, a.b, a.a}, vb[4] = {b.r, b.g, b.b, b.a};
    auto base_local = [&](const Rgba5& ca, const Rgba5& cb, std::uint32_t bound) {
      return weighted ? local_error_weighted(lw, ca, cb, bound)
                      : local_error_simd(lw, ca, cb, bound);
    };
    // Per-texel errors (what order_local sorts by).
    std::uint32_t base[52], avx2[52];
    for (int i = 0; i < 52; ++i) base[i] = avx2[i] = 0xdeadbeefu;
    const std::uint32_t total = weighted   ? local_error_simd_t<true, true, true>(lw, a, b, 0, base)
                                : nch == 4 ? local_error_simd_t<true, true>(lw, a, b, 0, base)
                                           : local_error_simd_t<false, true>(lw, a, b, 0, base);
    EXPECT_EQ(local_error_store_avx2(lw, va, vb, avx2), total);
    for (int i = 0; i < 52; ++i) EXPECT_EQ(avx2[i], base[i]) << "texel " << i;
    // General candidates (any channels), bounded.
    for (int k = 0; k < 40; ++k) {
      Rgba5 ca = random_pair_end(rng, nch), cb = random_pair_end(rng, nch);
      if (k == 0) ca = a, cb = b;
      const std::int32_t ka[4] = {ca.r, ca.g, ca.b, ca.a}, kb[4] = {cb.r, cb.g, cb.b, cb.a};
      const std::uint32_t exact = base_local(ca, cb, ~0u);
      ASSERT_EQ(local_error_avx2(lw, ka, kb, ~0u), exact) << "candidate " << k;
      for (const std::uint32_t bound : bounds_for(exact)) {
        expect_bounded(base_local(ca, cb, bound), exact, bound);
        expect_bounded(local_error_avx2(lw, ka, kb, bound), exact, bound);
      }
    }
    // One-colour-channel candidates through the planar tables of (a, b).
    PlanarWindow pw;
    build_planar(lw, pw);
    weighted ? planar_refresh_t<true>(pw, a, b) : planar_refresh(pw, a, b);
    for (int c = 0; c < 3; ++c) planar_rest(pw, c);
    auto base_planar = [&](int c, std::int32_t pa, std::int32_t pb, std::uint32_t bound) {
      return weighted ? planar_error_t<true>(pw, c, pa, pb, bound)
                      : planar_error(pw, c, pa, pb, bound);
    };
    for (int k = 0; k < 40; ++k) {
      const int c = int(rng() % 3);
      const std::int32_t pa = k == 0 ? va[c] : int(rng() % 32);
      const std::int32_t pb = k == 0 ? vb[c] : int(rng() % 32);
      const std::uint32_t exact = base_planar(c, pa, pb, ~0u);
      ASSERT_EQ(planar_error_avx2(pw, c, pa, pb, ~0u), exact) << "candidate " << k;
      for (const std::uint32_t bound : bounds_for(exact)) {
        expect_bounded(base_planar(c, pa, pb, bound), exact, bound);
        expect_bounded(planar_error_avx2(pw, c, pa, pb, bound), exact, bound);
      }
    }
  }
}

#define SKIP_WITHOUT_AVX2() \
  TESSERA_SKIP_WITHOUT_AVX2(avx2_kernels_usable(), "no AVX2 kernels in this build or CPU")

TEST(PvrtcSearchAvx2, MatchesBaselineRgb) {
  SKIP_WITHOUT_AVX2();
  check_avx2_windows(3, false, 1, 11, false);
  check_avx2_windows(3, false, 1, 12, true);
}
TEST(PvrtcSearchAvx2, MatchesBaselineRgba) {
  SKIP_WITHOUT_AVX2();
  check_avx2_windows(4, false, 2, 13, false);
  check_avx2_windows(4, false, 2, 14, true);
}
TEST(PvrtcSearchAvx2, MatchesBaselineRgbaPunchThrough) {
  SKIP_WITHOUT_AVX2();
  check_avx2_windows(4, true, 2, 15, false);
  check_avx2_windows(4, true, 2, 16, true);
  check_avx2_windows(4, true, 1, 17, false);
  check_avx2_windows(4, true, 1, 18, true);
}
TEST(PvrtcSearchAvx2, MatchesBaselineWeighted) {
  SKIP_WITHOUT_AVX2();
  check_avx2_windows(4, false, 2, 19, false, true);
  check_avx2_windows(4, true, 2, 20, false, true);
  check_avx2_windows(4, true, 2, 21, true, true);
}

// Sets `set_exact_search_baseline_only` for a scope.
class BaselineOnlyScope {
 public:
  explicit BaselineOnlyScope(bool on) : previous_(set_exact_search_baseline_only(on)) {}
  ~BaselineOnlyScope() { set_exact_search_baseline_only(previous_); }
  BaselineOnlyScope(const BaselineOnlyScope&) = delete;
  BaselineOnlyScope& operator=(const BaselineOnlyScope&) = delete;

 private:
  bool previous_;
};

TEST(PvrtcSearchAvx2, EncodeMatchesBaseline) {
  SKIP_WITHOUT_AVX2();
  {
    BaselineOnlyScope only(true);
    EXPECT_FALSE(exact_search_avx2_active());
  }
#if !defined(TESSERA_NO_SIMD)
  EXPECT_TRUE(exact_search_avx2_active());
#endif
  const int sizes[][2] = {{64, 16}, {16, 64}, {8, 8}, {128, 64}};
  for (const auto& wh : sizes) {
    for (int variant = 0; variant < 4; ++variant) {  // RGB, RGBA, RGBA no punch-through, foliage
      ImageRGBA8 img = make_procedural(variant == 3   ? Procedural::foliage
                                       : variant == 0 ? Procedural::text
                                                      : Procedural::noise,
                                       wh[0], wh[1], 3);
      if (variant == 1 || variant == 2) {
        img.has_alpha = true;
        const ImageRGBA8 al = make_procedural(Procedural::bricks, wh[0], wh[1], 5);
        for (std::size_t i = 0; i < img.pixel_count(); ++i) {
          img.pixels[i * 4 + 3] = al.pixels[i * 4 + (i % 3)];  // some texels below 128
        }
      }
      for (int fq = 0; fq < 3; ++fq) {  // 4 bpp normal, high; 2 bpp high (its endpoint search)
        const Quality q = fq == 0 ? Quality::normal : Quality::high;
        const Format f = fq == 2 ? Format::pvrtc1_2bpp : Format::pvrtc1_4bpp;
        for (bool weighted : {false, true}) {  // alpha-weighted: 4 bpp RGBA only
          if (weighted && (variant != 1 || f != Format::pvrtc1_4bpp)) continue;
          SCOPED_TRACE(testing::Message()
                       << wh[0] << "x" << wh[1] << " variant " << variant << " quality " << int(q)
                       << " format " << int(f) << " weighted " << weighted);
          EncodeOptions o;
          o.format = f;
          o.quality = q;
          o.threads = 2;
          o.punch_through = variant != 2;
          o.alpha_weighted = weighted;
          auto encode_with = [&](bool baseline_only) {
            BaselineOnlyScope only(baseline_only);
            return encode(img, o);
          };
          const auto base = encode_with(true), fast = encode_with(false);
          ASSERT_TRUE(base.ok() && fast.ok());
          EXPECT_EQ(*base, *fast);
        }
      }
    }
  }
}

}  // namespace
