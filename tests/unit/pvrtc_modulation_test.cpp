// Tests of the 4 bpp modulation kernels: the AVX2 block-row kernel (modulation_avx2.cpp)
// against the baseline pair kernel (modulation_kernel.h: SSE2, or scalar with TESSERA_NO_SIMD)
// on random and structured block rows, alpha-weighted or not, and whole encodes through either
// path; and of the 2 bpp
// modulation choice: its AVX2 passes (modulation_2bpp_avx2.cpp) against the baseline ones on
// whole states and whole 2 bpp encodes. Skipped where the build or the CPU has no AVX2 kernel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "pvrtc/encode/encode_internal.h"
#include "pvrtc/encode/modulation/modulation_2bpp.h"
#include "pvrtc/encode/modulation/modulation_2bpp_avx2.h"
#include "pvrtc/encode/modulation/modulation_avx2.h"
#include "pvrtc/encode/modulation/modulation_kernel.h"
#include "tessera/procedural.h"
#include "tessera/pvrtc.h"
#include "test_require.h"

using namespace tessera;
using namespace tessera::pvrtc;
using namespace tessera::pvrtc::detail;

namespace {

enum class Fill {
  endpoints,  ///< column sums of 5-bit (alpha 4-bit) endpoints, as the encoder makes them
  wide,       ///< any column sum up to 4 * 255
  flat,       ///< both images equal and constant: every blend ties
  extremes,   ///< 0 or the largest sum, targets 0 or 255
};

// One block row's inputs in the layout of `ModRow4`, owning its storage.
struct Row {
  int nbx = 0;
  std::size_t vstride = 0;
  std::vector<std::uint16_t> planes;              // [row][image * 4 + channel][vstride]
  std::vector<std::vector<std::uint8_t>> rows;    // 4 target rows, nbx * 16 bytes each
  std::vector<std::vector<std::uint8_t>> scales;  // 4 colour-scale rows, nbx * 4 bytes each
  const std::uint16_t* v[4] = {};
  const std::uint8_t* t[4] = {};
  const std::uint8_t* w[4] = {};
};

Row make_row(int nbx, Fill fill, std::uint32_t seed) {
  std::mt19937 rng(seed);
  auto uni = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  Row r;
  r.nbx = nbx;
  r.vstride = std::size_t(nbx) + 8;
  r.planes.resize(4 * 8 * r.vstride);
  // Beyond the wrap elements: values no valid read may use.
  for (auto& x : r.planes) x = std::uint16_t(uni(0, 1020));
  const int flat_value = uni(0, 124);
  for (int j = 0; j < 4; ++j) {
    const int d = uni(0, 3);
    for (int k = 0; k < 8; ++k) {
      std::uint16_t* p = &r.planes[(std::size_t(j) * 8 + std::size_t(k)) * r.vstride];
      const int emax = (k & 3) == 3 ? 15 : 31;
      for (int bx = 0; bx < nbx; ++bx) {
        int s = 0;
        switch (fill) {
          case Fill::endpoints:
            s = uni(0, emax) * (4 - d) + uni(0, emax) * d;
            break;
          case Fill::wide:
            s = uni(0, 1020);
            break;
          case Fill::flat:
            s = (k & 3) == 3 ? flat_value / 2 : flat_value;
            break;
          case Fill::extremes:
            s = uni(0, 1) ? emax * 4 : 0;
            break;
        }
        p[bx + 1] = std::uint16_t(s);
      }
      p[0] = p[nbx];
      p[nbx + 1] = p[1];
    }
    r.v[j] = &r.planes[std::size_t(j) * 8 * r.vstride];
  }
  r.rows.resize(4);
  static constexpr int kAlphas[] = {0, 1, 127, 128, 200, 255};
  for (int j = 0; j < 4; ++j) {
    r.rows[std::size_t(j)].resize(std::size_t(nbx) * 16);
    std::uint8_t* q = r.rows[std::size_t(j)].data();
    for (int i = 0; i < nbx * 4; ++i) {
      for (int c = 0; c < 4; ++c) {
        int x = uni(0, 255);
        if (fill == Fill::extremes) x = uni(0, 1) ? 255 : 0;
        if (fill == Fill::flat) x = c == 3 ? 255 : 96;
        // Alpha: mostly opaque blocks, some with a few texels below 128 (punch-through).
        if (c == 3 && fill != Fill::flat) x = uni(0, 3) ? 255 : kAlphas[uni(0, 5)];
        q[i * 4 + c] = std::uint8_t(x);
      }
    }
    r.t[j] = q;
  }
  // Colour scales (alpha-weighted colour error): 0..16, the ends only for Fill::extremes.
  r.scales.resize(4);
  for (int j = 0; j < 4; ++j) {
    r.scales[std::size_t(j)].resize(std::size_t(nbx) * 4);
    for (auto& x : r.scales[std::size_t(j)]) {
      x = std::uint8_t(fill == Fill::extremes ? uni(0, 1) * 16 : uni(0, 16));
    }
    r.w[j] = r.scales[std::size_t(j)].data();
  }
  return r;
}

template <bool kAlpha, bool kExtra, bool kWeighted = false>
void expect_row_identical(const Row& r, const char* what) {
  ModRow4 m;
  for (int j = 0; j < 4; ++j) {
    m.v[j] = r.v[j];
    m.t[j] = r.t[j];
    m.w[j] = r.w[j];
  }
  m.vstride = r.vstride;
  std::vector<BlockModAvx2> got(std::size_t(r.nbx) + 1);
  got[std::size_t(r.nbx)].err0 = 0xdeadbeef;  // must stay untouched
  block_row_errors_avx2(r.v, r.t, kWeighted ? r.w : nullptr, r.vstride, r.nbx, kAlpha, kExtra,
                        got.data());
  EXPECT_EQ(got[std::size_t(r.nbx)].err0, 0xdeadbeefu);
  for (int bx = 0; bx < r.nbx; bx += 2) {
    BlockMod want[2];
    block_pair_errors<kAlpha, kExtra, kWeighted>(m, bx, want);
    for (int h = 0; h < 2; ++h) {
      const BlockMod& w = want[h];
      const BlockModAvx2& g = got[std::size_t(bx + h)];
      SCOPED_TRACE(testing::Message()
                   << what << " alpha " << kAlpha << " extra " << kExtra << " weighted "
                   << kWeighted << " nbx " << r.nbx << " block " << bx + h);
      EXPECT_EQ(g.bits0, w.bits0);
      EXPECT_EQ(g.err0, w.err0);
      EXPECT_EQ(g.bits1, w.bits1);
      EXPECT_EQ(g.err1, w.err1);
      EXPECT_EQ(g.bits1p, w.bits1p);
      EXPECT_EQ(g.err1p, w.err1p);
      EXPECT_EQ(g.any_clear != 0, w.any_clear);
    }
  }
}

void expect_all_variants(const Row& r, const char* what) {
  expect_row_identical<false, false>(r, what);
  expect_row_identical<false, true>(r, what);
  expect_row_identical<true, false>(r, what);
  expect_row_identical<true, true>(r, what);
  expect_row_identical<true, false, true>(r, what);
  expect_row_identical<true, true, true>(r, what);
}

// Sets `set_modulation_baseline_only` for a scope.
class BaselineOnly {
 public:
  explicit BaselineOnly(bool on) : previous_(set_modulation_baseline_only(on)) {}
  ~BaselineOnly() { set_modulation_baseline_only(previous_); }
  BaselineOnly(const BaselineOnly&) = delete;
  BaselineOnly& operator=(const BaselineOnly&) = delete;

 private:
  bool previous_;
};

/// Encodes `img` with the baseline kernels forced by `Guard` (BaselineOnly or
/// Baseline2bppOnly) and with the dispatched ones: the same bytes.
template <class Guard>
void expect_same_bytes_as_baseline(const ImageRGBA8& img, const EncodeOptions& o) {
  auto encode_with = [&](bool baseline_only) {
    Guard only(baseline_only);
    return encode(img, o);
  };
  const auto base = encode_with(true), fast = encode_with(false);
  ASSERT_TRUE(base.ok());
  ASSERT_TRUE(fast.ok());
  EXPECT_TRUE(*base == *fast);
}

}  // namespace

TEST(PvrtcModulationAvx2, RowMatchesBaselineKernel) {
  TESSERA_SKIP_WITHOUT_AVX2(modulation_avx2_supported(), "no AVX2 kernel in this build or CPU");
  // Widths 8 .. 256 texels; 24 (a step and a 2-block tail) is no PVRTC width but the kernel's.
  for (int width : {8, 16, 24, 32, 64, 256}) {
    for (std::uint32_t seed = 1; seed <= 12; ++seed) {
      expect_all_variants(make_row(width / 4, Fill::endpoints, seed), "endpoints");
      expect_all_variants(make_row(width / 4, Fill::wide, seed), "wide");
    }
    for (std::uint32_t seed = 1; seed <= 3; ++seed) {
      expect_all_variants(make_row(width / 4, Fill::flat, seed), "flat");
      expect_all_variants(make_row(width / 4, Fill::extremes, seed), "extremes");
    }
  }
}

TEST(PvrtcModulationAvx2, RowWithEqualImagesKeepsFirstCandidate) {
  TESSERA_SKIP_WITHOUT_AVX2(modulation_avx2_supported(), "no AVX2 kernel in this build or CPU");
  // Both images equal: every blend decodes the same, so every texel keeps code 0 (mode 0) and
  // rank 0 (mode 1).
  Row r = make_row(16, Fill::flat, 7);
  std::vector<BlockModAvx2> got(16);
  block_row_errors_avx2(r.v, r.t, nullptr, r.vstride, 16, true, true, got.data());
  for (const BlockModAvx2& g : got) {
    EXPECT_EQ(g.bits0, 0u);
    EXPECT_EQ(g.bits1, 0u);
    EXPECT_EQ(g.any_clear, 0u);
  }
}

TEST(PvrtcModulationAvx2, EncodeMatchesBaseline) {
  TESSERA_SKIP_WITHOUT_AVX2(modulation_avx2_supported(), "no AVX2 kernel in this build or CPU");
  const int sizes[][2] = {{8, 8}, {16, 64}, {128, 128}, {512, 128}};
  for (const auto& wh : sizes) {
    for (bool alpha : {false, true}) {
      ImageRGBA8 img = make_procedural(Procedural::noise, wh[0], wh[1], 3);
      if (alpha) {
        img.has_alpha = true;
        const ImageRGBA8 a = make_procedural(Procedural::bricks, wh[0], wh[1], 5);
        for (std::size_t i = 0; i < img.pixel_count(); ++i) {
          img.pixels[i * 4 + 3] = a.pixels[i * 4 + (i % 3)];  // some texels below 128
        }
      }
      for (Quality q : {Quality::fast, Quality::normal}) {
        for (bool weighted : {false, true}) {
          if (weighted && !alpha) continue;
          SCOPED_TRACE(testing::Message() << wh[0] << "x" << wh[1] << " alpha " << alpha
                                          << " quality " << int(q) << " weighted " << weighted);
          EncodeOptions o;
          o.format = Format::pvrtc1_4bpp;
          o.quality = q;
          o.threads = 2;
          o.alpha_weighted = weighted;
          expect_same_bytes_as_baseline<BaselineOnly>(img, o);
        }
      }
    }
  }
}

namespace {

// Sets `set_modulation_2bpp_baseline_only` for a scope.
class Baseline2bppOnly {
 public:
  explicit Baseline2bppOnly(bool on) : previous_(set_modulation_2bpp_baseline_only(on)) {}
  ~Baseline2bppOnly() { set_modulation_2bpp_baseline_only(previous_); }
  Baseline2bppOnly(const Baseline2bppOnly&) = delete;
  Baseline2bppOnly& operator=(const Baseline2bppOnly&) = delete;

 private:
  bool previous_;
};

enum class Content {
  random,      ///< random targets and endpoint fields
  flat,        ///< one target colour, A == B everywhere: every candidate ties
  extremes,    ///< targets 0 / 255, endpoints all-zero or all-ones fields
  structured,  ///< procedural targets (bricks / text), endpoints near the block's colours
};

// A 2 bpp state of w x h texels with endpoints and targets as `content` says.
EncoderState make_state_2bpp(int w, int h, bool alpha, Content content, std::uint32_t seed) {
  std::mt19937 rng(seed);
  auto uni = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  EncoderState s;
  s.g = make_grid(Format::pvrtc1_2bpp, w, h);
  s.alpha_mode = alpha;
  s.threads = 2;
  const std::size_t nb = s.g.blocks();
  std::vector<std::uint8_t> t(s.g.texels() * 4);
  ImageRGBA8 img;
  if (content == Content::structured) {
    img = make_procedural(seed % 2 ? Procedural::bricks : Procedural::text, s.g.pw, s.g.ph, seed);
  }
  const int flat_value = uni(0, 255);
  for (std::size_t i = 0; i < s.g.texels(); ++i) {
    for (int c = 0; c < 4; ++c) {
      int x = 0;
      switch (content) {
        case Content::random:
          x = uni(0, 255);
          break;
        case Content::flat:
          x = flat_value;
          break;
        case Content::extremes:
          x = uni(0, 1) ? 255 : 0;
          break;
        case Content::structured:
          x = img.pixels[i * 4 + std::size_t(c)];
          if (c == 3) x = int((i * 7) % 256);  // some texels below 128
          break;
      }
      if (c == 3 && !alpha) x = 255;
      t[i * 4 + std::size_t(c)] = std::uint8_t(x);
    }
  }
  s.own_target(std::move(t));
  s.ca.resize(nb);
  s.cb.resize(nb);
  for (std::size_t i = 0; i < nb; ++i) {
    int a = uni(0, 0xffff), b = uni(0, 0xffff);
    if (content == Content::flat) a = b = 0x7bde | (alpha ? 0 : 0x8000);
    if (content == Content::extremes) {
      a = uni(0, 1) ? 0xffff : 0;
      b = uni(0, 1) ? 0xffff : 0;
    }
    if (content == Content::structured) {
      // Opaque (bit 15) fields near the block's first texel, A darker than B.
      const std::size_t bx = i % std::size_t(s.g.nbx), by = i / std::size_t(s.g.nbx);
      const std::uint8_t* p = &s.target[(by * 4 * std::size_t(s.g.pw) + bx * 8) * 4];
      const int r5 = p[0] >> 3, g5 = p[1] >> 3, b4 = p[2] >> 4, b5 = p[2] >> 3;
      a = 0x8000 | (std::max(r5 - 3, 0) << 10) | (std::max(g5 - 3, 0) << 5) |
          (std::max(b4 - 2, 0) << 1);
      b = 0x8000 | (std::min(r5 + 3, 31) << 10) | (std::min(g5 + 3, 31) << 5) |
          std::min(b5 + 3, 31);
      if (alpha && uni(0, 3) == 0) a &= 0x7fff;
    }
    s.ca[i] = std::uint16_t(a & 0xfffe);  // bit 0 holds the mode
    s.cb[i] = std::uint16_t(b);
  }
  s.mode.assign(nb, 0xaa);
  s.mod.assign(nb, 0xdeadbeefu);
  return s;
}

}  // namespace

TEST(PvrtcModulation2bppAvx2, StateMatchesBaseline) {
  TESSERA_SKIP_WITHOUT_AVX2(modulation_avx2_supported(), "no AVX2 kernel in this build or CPU");
  const int sizes[][2] = {{8, 8},   {16, 8},  {8, 32},   {32, 8},  {128, 16},
                          {16, 64}, {64, 64}, {256, 32}, {512, 16}};
  int mode1_blocks = 0;
  for (const auto& wh : sizes) {
    for (bool alpha : {false, true}) {
      for (Content content :
           {Content::random, Content::flat, Content::extremes, Content::structured}) {
        for (std::uint32_t seed = 1; seed <= 3; ++seed) {
          SCOPED_TRACE(testing::Message() << wh[0] << "x" << wh[1] << " alpha " << alpha
                                          << " content " << int(content) << " seed " << seed);
          EncoderState base = make_state_2bpp(wh[0], wh[1], alpha, content, seed);
          EncoderState avx = base;
          std::uint64_t e_base = 0, e_avx = 0;
          {
            Baseline2bppOnly only(true);
            e_base = choose_modulation_2bpp(base);
          }
          {
            Baseline2bppOnly only(false);
            e_avx = choose_modulation_2bpp(avx);
          }
          EXPECT_EQ(e_avx, e_base);
          EXPECT_EQ(avx.mode, base.mode);
          EXPECT_EQ(avx.mod, base.mod);
          for (std::uint8_t m : base.mode) mode1_blocks += m;
        }
      }
    }
  }
  EXPECT_GT(mode1_blocks, 0);  // the interpolated modes were exercised
}

TEST(PvrtcModulation2bppAvx2, EncodeMatchesBaseline) {
  TESSERA_SKIP_WITHOUT_AVX2(modulation_avx2_supported(), "no AVX2 kernel in this build or CPU");
  const int sizes[][2] = {{8, 8}, {16, 8}, {8, 32}, {32, 8}, {128, 16}, {64, 64}, {256, 128}};
  for (const auto& wh : sizes) {
    for (bool alpha : {false, true}) {
      ImageRGBA8 img =
          make_procedural(alpha ? Procedural::foliage : Procedural::noise, wh[0], wh[1], 3);
      for (Quality q : {Quality::fast, Quality::normal, Quality::high}) {
        if (q == Quality::high && wh[0] * wh[1] > 64 * 64) continue;  // slow; normal covers it
        SCOPED_TRACE(testing::Message()
                     << wh[0] << "x" << wh[1] << " alpha " << alpha << " quality " << int(q));
        EncodeOptions o;
        o.format = Format::pvrtc1_2bpp;
        o.quality = q;
        o.threads = 2;
        expect_same_bytes_as_baseline<Baseline2bppOnly>(img, o);
      }
    }
  }
}
