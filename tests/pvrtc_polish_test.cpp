// Tests of the exact search's window evaluators (src/pvrtc/polish_kernel.h): the channel-planar
// evaluator of one-colour-channel candidates against the general `local_error_simd` on random
// windows, including the bound (early exit) semantics of both.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>

#include "pvrtc/polish_kernel.h"

using namespace tessera::pvrtc::detail;

namespace {

constexpr std::int32_t kExclude = 1 << 24;  // as build_local

// A random window as build_local lays one out: per texel the other blocks' share of the A and B
// sums (bounded so that the whole sum stays within 16 times the channel maximum), block j's
// weight, the target and the blends its block mode lacks; texels 49-55 zero pads.
void random_window(std::mt19937& rng, int nch, bool punch, int alpha_weight, LocalWindow& lw) {
  auto uni = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
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
    const bool m1 = uni(0, 1) != 0;
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
        const std::uint32_t g = local_error_simd(lw, ca, cb, bound);
        if (exact < bound) {
          EXPECT_EQ(p, exact);
          EXPECT_EQ(g, exact);
        } else {
          EXPECT_GE(p, bound);
          EXPECT_GE(g, bound);
          EXPECT_LE(p, exact);
          EXPECT_LE(g, exact);
        }
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

TEST(PvrtcPolishKernel, PlanarMatchesGeneralRgb) { check_windows(3, false, 1, 1); }
TEST(PvrtcPolishKernel, PlanarMatchesGeneralRgba) { check_windows(4, false, 2, 2); }
TEST(PvrtcPolishKernel, PlanarMatchesGeneralRgbaPunchThrough) { check_windows(4, true, 2, 3); }
TEST(PvrtcPolishKernel, PlanarMatchesGeneralRgbaWeight1) { check_windows(4, true, 1, 4); }

TEST(PvrtcPolishKernel, SingleColourChannel) {
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

}  // namespace
