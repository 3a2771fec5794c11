// Tests of the 4 bpp modulation kernels: the AVX2 block-row kernel (modulation_avx2.cpp)
// against the baseline pair kernel (modulation_kernel.h: SSE2, or scalar with TESSERA_NO_SIMD)
// on random and structured block rows, and whole encodes through either path. Skipped where
// the build or the CPU has no AVX2 kernel.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "pvrtc/modulation_avx2.h"
#include "pvrtc/modulation_kernel.h"
#include "tessera/procedural.h"
#include "tessera/pvrtc.h"

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
  std::vector<std::uint16_t> planes;            // [row][image * 4 + channel][vstride]
  std::vector<std::vector<std::uint8_t>> rows;  // 4 target rows, nbx * 16 bytes each
  const std::uint16_t* v[4] = {};
  const std::uint8_t* t[4] = {};
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
  return r;
}

template <bool kAlpha, bool kExtra>
void expect_row_identical(const Row& r, const char* what) {
  ModRow4 m;
  for (int j = 0; j < 4; ++j) {
    m.v[j] = r.v[j];
    m.t[j] = r.t[j];
  }
  m.vstride = r.vstride;
  std::vector<BlockModAvx2> got(std::size_t(r.nbx) + 1);
  got[std::size_t(r.nbx)].err0 = 0xdeadbeef;  // must stay untouched
  block_row_errors_avx2(r.v, r.t, r.vstride, r.nbx, kAlpha, kExtra, got.data());
  EXPECT_EQ(got[std::size_t(r.nbx)].err0, 0xdeadbeefu);
  for (int bx = 0; bx < r.nbx; bx += 2) {
    BlockMod want[2];
    block_pair_errors<kAlpha, kExtra>(m, bx, want);
    for (int h = 0; h < 2; ++h) {
      const BlockMod& w = want[h];
      const BlockModAvx2& g = got[std::size_t(bx + h)];
      SCOPED_TRACE(testing::Message() << what << " alpha " << kAlpha << " extra " << kExtra
                                      << " nbx " << r.nbx << " block " << bx + h);
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

}  // namespace

TEST(PvrtcModulationAvx2, RowMatchesBaselineKernel) {
  if (!modulation_avx2_supported()) GTEST_SKIP() << "no AVX2 kernel in this build or CPU";
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
  if (!modulation_avx2_supported()) GTEST_SKIP() << "no AVX2 kernel in this build or CPU";
  // Both images equal: every blend decodes the same, so every texel keeps code 0 (mode 0) and
  // rank 0 (mode 1).
  Row r = make_row(16, Fill::flat, 7);
  std::vector<BlockModAvx2> got(16);
  block_row_errors_avx2(r.v, r.t, r.vstride, 16, true, true, got.data());
  for (const BlockModAvx2& g : got) {
    EXPECT_EQ(g.bits0, 0u);
    EXPECT_EQ(g.bits1, 0u);
    EXPECT_EQ(g.any_clear, 0u);
  }
}

TEST(PvrtcModulationAvx2, EncodeMatchesBaseline) {
  if (!modulation_avx2_supported()) GTEST_SKIP() << "no AVX2 kernel in this build or CPU";
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
        SCOPED_TRACE(testing::Message()
                     << wh[0] << "x" << wh[1] << " alpha " << alpha << " quality " << int(q));
        EncodeOptions o;
        o.format = Format::pvrtc1_4bpp;
        o.quality = q;
        o.threads = 2;
        auto encode_with = [&](bool baseline_only) {
          BaselineOnly only(baseline_only);
          return encode(img, o);
        };
        const auto base = encode_with(true), fast = encode_with(false);
        ASSERT_TRUE(base.ok());
        ASSERT_TRUE(fast.ok());
        EXPECT_TRUE(*base == *fast);
      }
    }
  }
}
