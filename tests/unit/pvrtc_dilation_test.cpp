// PVRTC intensity-dilation kernels (src/pvrtc/encode/start/dilation_kernels.h): the AVX2 row
// kernels against the baseline ones, lane for lane, on random and structured rows of widths 8 to
// 1024 (skipped where the CPU lacks AVX2), and whole fast encodes with the baseline kernels forced
// against the dispatched ones: the same bytes; the dilation's flat-block flags.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "pvrtc/encode/encode_internal.h"
#include "pvrtc/encode/start/dilation_kernels.h"
#include "tessera/procedural.h"
#include "tessera/pvrtc.h"
#include "test_require.h"

namespace tessera::pvrtc::detail {
namespace {

constexpr int kWidths[] = {8, 16, 32, 64, 1024};
constexpr int kPad = kDilationPad;

/// A padded row of T: `p()` points at element 0, kPad elements of slack on either side.
template <typename T>
struct Row {
  std::vector<T> buf;
  explicit Row(int w, T fill = T(0)) : buf(std::size_t(w) + 2 * kPad, fill) {}
  T* p() { return buf.data() + kPad; }
};

/// Skips the test where the AVX2 kernels are not built or the CPU cannot run them (fails where
/// the CPU has AVX2 and the run requires it: test_require.h).
#define REQUIRE_AVX2()                                       \
  const DilationKernels* avx2 = dilation_kernels_avx2();     \
  const DilationKernels* base = dilation_kernels_baseline(); \
  TESSERA_SKIP_WITHOUT_AVX2(avx2 != nullptr, "AVX2 dilation kernels not available")

std::vector<std::uint8_t> random_texels(std::mt19937& rng, int w, bool structured) {
  std::vector<std::uint8_t> t(std::size_t(w) * 4);
  for (std::size_t i = 0; i < t.size(); ++i) {
    // Structured: few distinct values (ties, flat runs); else any byte.
    t[i] = structured ? std::uint8_t((rng() % 3) * 127) : std::uint8_t(rng());
  }
  return t;
}

TEST(PvrtcDilationKernels, IntensityRowMatchesBaseline) {
  REQUIRE_AVX2();
  std::mt19937 rng(1);
  for (int w : kWidths) {
    for (int rep = 0; rep < 8; ++rep) {
      const auto src = random_texels(rng, w, rep & 1);
      for (bool alpha : {false, true}) {
        Row<float> a(w, -1.0f), b(w, -2.0f);
        base->intensity_row(src.data(), w, alpha, a.p());
        avx2->intensity_row(src.data(), w, alpha, b.p());
        for (int x = -1; x <= w; ++x) {
          ASSERT_EQ(a.p()[x], b.p()[x]) << "w " << w << " x " << x << " alpha " << alpha;
        }
      }
    }
  }
  // Extremes: white texels of every alpha (the largest products), black ones.
  for (int w : kWidths) {
    std::vector<std::uint8_t> src(std::size_t(w) * 4, 255);
    for (int x = 0; x < w; ++x) src[std::size_t(x) * 4 + 3] = std::uint8_t(x * 37);
    for (int x = 0; x < w; x += 5) src[std::size_t(x) * 4] = 0;
    Row<float> a(w), b(w);
    base->intensity_row(src.data(), w, true, a.p());
    avx2->intensity_row(src.data(), w, true, b.p());
    for (int x = -1; x <= w; ++x) ASSERT_EQ(a.p()[x], b.p()[x]) << "w " << w << " x " << x;
  }
}

/// Three wrap-padded rows of integer intensities below `levels` (as intensity_row makes them).
void random_intensity_rows(std::mt19937& rng, int w, std::uint32_t levels, Row<float> (&i)[3]) {
  for (auto& r : i) {
    for (int x = 0; x < w; ++x) r.p()[x] = float(rng() % levels);
    r.p()[-1] = r.p()[w - 1];
    r.p()[w] = r.p()[0];
  }
}

TEST(PvrtcDilationKernels, LabelRowMatchesBaseline) {
  REQUIRE_AVX2();
  std::mt19937 rng(2);
  for (int w : kWidths) {
    for (int rep = 0; rep < 12; ++rep) {
      // Integer intensities (as intensity_row makes), few levels half the time: many ties.
      const std::uint32_t levels = rep % 2 ? 3u : 1u << 24;
      Row<float> i[3] = {Row<float>(w), Row<float>(w), Row<float>(w)};
      random_intensity_rows(rng, w, levels, i);
      Row<float> mx(w), mn(w);
      Row<std::uint8_t> a(w, 7), b(w, 9);
      base->label_row(i[0].p(), i[1].p(), i[2].p(), w, mx.p(), mn.p(), a.p());
      avx2->label_row(i[0].p(), i[1].p(), i[2].p(), w, mx.p(), mn.p(), b.p());
      for (int x = 0; x < w; ++x) ASSERT_EQ(a.p()[x], b.p()[x]) << "w " << w << " x " << x;
    }
  }
}

// The labelling against its definition (paper §3, as its authors' FasTC code decides ties): a
// texel is a local maximum (minimum) when none of its 8 neighbours (wrapping) is brighter
// (darker) and not all of them are level with it; a texel of a uniform 3x3 area is neither.
// Both the baseline and (where it runs) the AVX2 kernel, on rows with many ties.
TEST(PvrtcDilationKernels, LabelRowFollowsTheDefinition) {
  std::vector<const DilationKernels*> kernels = {dilation_kernels_baseline()};
  if (dilation_kernels_avx2() != nullptr) kernels.push_back(dilation_kernels_avx2());
  std::mt19937 rng(3);
  int counts[4] = {};
  for (const DilationKernels* k : kernels) {
    for (int w : kWidths) {
      for (int rep = 0; rep < 8; ++rep) {
        const std::uint32_t levels = rep % 2 ? 2u : 5u;  // plateaus and uniform areas
        Row<float> i[3] = {Row<float>(w), Row<float>(w), Row<float>(w)};
        random_intensity_rows(rng, w, levels, i);
        Row<float> mx(w), mn(w);
        Row<std::uint8_t> out(w, 7);
        k->label_row(i[0].p(), i[1].p(), i[2].p(), w, mx.p(), mn.p(), out.p());
        for (int x = 0; x < w; ++x) {
          const float v = i[1].p()[x];
          int brighter = 0, darker = 0;
          for (int dy = 0; dy < 3; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
              const float n = i[dy].p()[(x + dx + w) % w];
              brighter += n > v;
              darker += n < v;
            }
          }
          const bool uniform = brighter == 0 && darker == 0;
          const int expect = uniform ? 0 : (brighter == 0 ? 1 : 0) | (darker == 0 ? 2 : 0);
          ASSERT_EQ(int(out.p()[x]), expect) << "w " << w << " x " << x;
          ++counts[expect];
        }
      }
    }
  }
  // Every case occurred: maxima, minima, neither (uniform areas among them); never both.
  EXPECT_GT(counts[0], 0);
  EXPECT_GT(counts[1], 0);
  EXPECT_GT(counts[2], 0);
  EXPECT_EQ(counts[3], 0);
}

/// np + 1 padded planes of one row.
struct Planes {
  std::vector<Row<std::uint8_t>> rows;
  std::uint8_t* ptr[5] = {};
  Planes(int np, int w, std::uint8_t fill = 0) {
    for (int c = 0; c <= np; ++c) rows.emplace_back(w, fill);
    for (int c = 0; c <= np; ++c) ptr[c] = rows[std::size_t(c)].p();
  }
};

TEST(PvrtcDilationKernels, InitRowsMatchBaseline) {
  REQUIRE_AVX2();
  std::mt19937 rng(3);
  for (int w : kWidths) {
    for (int np : {3, 4}) {
      for (int rep = 0; rep < 6; ++rep) {
        const auto src = random_texels(rng, w, rep & 1);
        Row<std::uint8_t> lab(w);
        for (int x = 0; x < w; ++x) lab.p()[x] = std::uint8_t(rep == 2 ? 3 : rng() % 4);
        Planes a0(np, w, 1), a1(np, w, 2), b0(np, w, 3), b1(np, w, 4);
        base->init_rows(np, lab.p(), src.data(), w, a0.ptr, a1.ptr);
        avx2->init_rows(np, lab.p(), src.data(), w, b0.ptr, b1.ptr);
        for (int c = 0; c <= np; ++c) {
          for (int x = 0; x < w; ++x) {
            ASSERT_EQ(a0.ptr[c][x], b0.ptr[c][x]) << "w " << w << " np " << np << " c " << c;
            ASSERT_EQ(a1.ptr[c][x], b1.ptr[c][x]) << "w " << w << " np " << np << " c " << c;
          }
        }
      }
    }
  }
}

TEST(PvrtcDilationKernels, DilateRowMatchesBaseline) {
  REQUIRE_AVX2();
  std::mt19937 rng(4);
  // Probability (in 1/100) that a texel is filled: none, sparse, half, dense, all.
  const int densities[] = {0, 3, 50, 90, 100};
  for (int w : kWidths) {
    for (int np : {3, 4}) {
      for (int density : densities) {
        for (int rep = 0; rep < 4; ++rep) {
          Planes in[3] = {Planes(np, w), Planes(np, w), Planes(np, w)};
          for (auto& p : in) {
            for (int x = 0; x < w; ++x) {
              const bool filled = int(rng() % 100) < density;
              p.ptr[np][x] = filled;
              for (int c = 0; c < np; ++c) {
                // Empty texels hold 0 in the pipeline; rep 3 also tries any byte there.
                p.ptr[c][x] = filled || rep == 3 ? std::uint8_t(rng()) : 0;
              }
            }
          }
          const std::uint8_t* const rows[3][5] = {
              {in[0].ptr[0], in[0].ptr[1], in[0].ptr[2], in[0].ptr[3], in[0].ptr[4]},
              {in[1].ptr[0], in[1].ptr[1], in[1].ptr[2], in[1].ptr[3], in[1].ptr[4]},
              {in[2].ptr[0], in[2].ptr[1], in[2].ptr[2], in[2].ptr[3], in[2].ptr[4]}};
          const std::size_t vstride = std::size_t(w) + 2 * kPad;
          Planes a(np, w, 5), b(np, w, 6);
          Row<std::uint8_t> vfa(w), vfb(w);
          std::vector<std::uint16_t> vsa(std::size_t(np) * vstride), vsb(vsa.size());
          base->dilate_row(np, w, rows, a.ptr, vfa.p(), vsa.data() + kPad, vstride);
          avx2->dilate_row(np, w, rows, b.ptr, vfb.p(), vsb.data() + kPad, vstride);
          for (int c = 0; c <= np; ++c) {
            for (int x = 0; x < w; ++x) {
              ASSERT_EQ(a.ptr[c][x], b.ptr[c][x]) << "w " << w << " np " << np << " density "
                                                  << density << " c " << c << " x " << x;
            }
          }
        }
      }
    }
  }
}

TEST(PvrtcDilationKernels, DilateRowAveragesEveryNeighbourCount) {
  REQUIRE_AVX2();
  // Every subset size n = 1..8 of the 8 neighbours of an empty texel, with extreme colours:
  // the rounded means (the reciprocal table) for every n, on both kernels.
  const int w = 64, np = 3;
  Planes in[3] = {Planes(np, w), Planes(np, w), Planes(np, w)};
  const int nb[8][2] = {{0, -1}, {0, 0}, {0, 1}, {1, -1}, {1, 1}, {2, -1}, {2, 0}, {2, 1}};
  for (int n = 1; n <= 8; ++n) {
    const int x0 = 4 * n;  // one texel per n, 4 apart so neighbourhoods do not overlap
    for (int k = 0; k < n; ++k) {
      Planes& p = in[nb[k][0]];
      const int x = x0 + nb[k][1];
      p.ptr[np][x] = 1;
      p.ptr[0][x] = 255;
      p.ptr[1][x] = std::uint8_t(k * 31);
      p.ptr[2][x] = std::uint8_t(k & 1 ? 255 : 0);
    }
  }
  const std::uint8_t* const rows[3][5] = {
      {in[0].ptr[0], in[0].ptr[1], in[0].ptr[2], in[0].ptr[3], nullptr},
      {in[1].ptr[0], in[1].ptr[1], in[1].ptr[2], in[1].ptr[3], nullptr},
      {in[2].ptr[0], in[2].ptr[1], in[2].ptr[2], in[2].ptr[3], nullptr}};
  const std::size_t vstride = std::size_t(w) + 2 * kPad;
  Planes a(np, w), b(np, w);
  Row<std::uint8_t> vf(w);
  std::vector<std::uint16_t> vs(std::size_t(np) * vstride);
  base->dilate_row(np, w, rows, a.ptr, vf.p(), vs.data() + kPad, vstride);
  avx2->dilate_row(np, w, rows, b.ptr, vf.p(), vs.data() + kPad, vstride);
  for (int n = 1; n <= 8; ++n) {
    const int x0 = 4 * n;
    unsigned s1 = 0, s2 = 0;
    for (int k = 0; k < n; ++k) {
      s1 += unsigned(k * 31);
      s2 += k & 1 ? 255u : 0u;
    }
    EXPECT_EQ(a.ptr[np][x0], 1) << n;
    EXPECT_EQ(a.ptr[0][x0], 255) << n;
    EXPECT_EQ(a.ptr[1][x0], (s1 + unsigned(n) / 2) / unsigned(n)) << n;
    EXPECT_EQ(a.ptr[2][x0], (s2 + unsigned(n) / 2) / unsigned(n)) << n;
    for (int c = 0; c <= np; ++c) EXPECT_EQ(a.ptr[c][x0], b.ptr[c][x0]) << n << " " << c;
  }
}

TEST(PvrtcDilationKernels, AccumulateRowMatchesBaseline) {
  REQUIRE_AVX2();
  std::mt19937 rng(5);
  for (int w : kWidths) {
    for (int planes : {4, 5}) {
      const std::size_t stride = std::size_t(w) + 2 * kPad, astride = std::size_t(w) + kPad;
      std::vector<std::uint8_t> rows(std::size_t(planes) * stride);
      std::vector<std::uint16_t> a(std::size_t(planes) * astride), b(a.size());
      for (int r = 0; r < 4; ++r) {
        for (auto& v : rows) v = std::uint8_t(rng());
        base->accumulate_row(planes, w, rows.data() + kPad, stride, a.data(), astride, r == 0);
        avx2->accumulate_row(planes, w, rows.data() + kPad, stride, b.data(), astride, r == 0);
      }
      for (int k = 0; k < planes; ++k) {
        for (int x = 0; x < w; ++x) {
          const std::size_t i = std::size_t(k) * astride + std::size_t(x);
          ASSERT_EQ(a[i], b[i]) << "w " << w << " plane " << k << " x " << x;
        }
      }
    }
  }
}

TEST(PvrtcDilationKernels, BlockExtremesMatchBaseline) {
  REQUIRE_AVX2();
  std::mt19937 rng(6);
  for (int w : kWidths) {
    for (int bw : {4, 8}) {
      if (w < 2 * bw) continue;
      const int nbx = w / bw;
      for (int rep = 0; rep < 12; ++rep) {
        // Integer intensities below 2^24: any, few levels (ties), or flat (all tied).
        const std::uint32_t levels = rep % 3 == 0 ? 1u << 24 : rep % 3 == 1 ? 3u : 1u;
        std::vector<float> rows(4 * std::size_t(w));
        for (auto& v : rows) v = float(levels == 1u ? 16711680u : rng() % levels);
        std::vector<DilationExtremes> a(static_cast<std::size_t>(nbx)), b(a.size());
        base->block_extremes(rows.data(), std::size_t(w), nbx, bw, 12, a.data());
        avx2->block_extremes(rows.data(), std::size_t(w), nbx, bw, 12, b.data());
        for (int bx = 0; bx < nbx; ++bx) {
          const auto &p = a[std::size_t(bx)], &q = b[std::size_t(bx)];
          ASSERT_EQ(p.xmax, q.xmax) << "w " << w << " bw " << bw << " block " << bx;
          ASSERT_EQ(p.ymax, q.ymax) << "w " << w << " bw " << bw << " block " << bx;
          ASSERT_EQ(p.xmin, q.xmin) << "w " << w << " bw " << bw << " block " << bx;
          ASSERT_EQ(p.ymin, q.ymin) << "w " << w << " bw " << bw << " block " << bx;
        }
        if (levels == 1u) {  // all tied: the block's first texel
          EXPECT_EQ(b[1].xmax, bw);
          EXPECT_EQ(b[1].ymax, 12);
        }
      }
    }
  }
}

TEST(PvrtcDilationKernels, BlockSumsMatchBaseline) {
  REQUIRE_AVX2();
  std::mt19937 rng(7);
  for (int w : kWidths) {
    for (int bw : {4, 8}) {
      for (int planes : {4, 5}) {
        const std::size_t astride = std::size_t(w) + kPad, ostride = std::size_t(w / bw) + 3;
        std::vector<std::uint16_t> acc(std::size_t(planes) * astride);
        for (auto& v : acc) v = std::uint16_t(rng() % 1021);  // 4 rows of bytes
        std::vector<std::uint32_t> a(std::size_t(planes) * ostride, 1), b(a.size(), 1);
        base->block_sums(acc.data(), astride, planes, w, bw, a.data(), ostride);
        avx2->block_sums(acc.data(), astride, planes, w, bw, b.data(), ostride);
        EXPECT_EQ(a, b) << "w " << w << " bw " << bw << " planes " << planes;
        EXPECT_EQ(b[ostride - 1], 1u);  // nothing written past w / bw
      }
    }
  }
}

/// Restores the run-time kernel choice when a test ends, whatever happens.
struct ForceBaseline {
  ForceBaseline() { dilation_force_baseline(true); }
  ~ForceBaseline() { dilation_force_baseline(false); }
};

TEST(PvrtcDilationEncode, ForcedBaselineGivesTheSameBytes) {
  if (dilation_kernels_avx2() == nullptr) {
    GTEST_LOG_(INFO) << "no AVX2 kernels: both runs use the baseline kernels";
  }
  const int sizes[][2] = {{8, 8}, {16, 64}, {256, 256}, {1024, 256}};
  for (const auto& sz : sizes) {
    for (Procedural kind : {Procedural::noise, Procedural::foliage, Procedural::text}) {
      if (sz[0] * sz[1] > 4096 && kind != Procedural::noise) continue;  // sanitizer build time
      const ImageRGBA8 img = make_procedural(kind, sz[0], sz[1], 7);
      for (Format format : {Format::pvrtc1_4bpp, Format::pvrtc1_2bpp}) {
        for (bool rgba : {false, true}) {
          for (int threads : {1, 0}) {
            EncodeOptions opt;
            opt.format = format;
            opt.quality = Quality::fast;
            opt.force_alpha = rgba;
            opt.threads = threads;
            auto dispatched = encode(img, opt);
            ASSERT_TRUE(dispatched.ok()) << dispatched.status().message;
            std::vector<std::uint8_t> baseline;
            {
              ForceBaseline force;
              auto r = encode(img, opt);
              ASSERT_TRUE(r.ok()) << r.status().message;
              baseline = std::move(*r);
            }
            EXPECT_EQ(*dispatched, baseline)
                << sz[0] << "x" << sz[1] << " " << procedural_name(kind) << " "
                << (format == Format::pvrtc1_4bpp ? "4bpp" : "2bpp") << (rgba ? " RGBA" : " RGB")
                << " threads " << threads;
          }
        }
      }
    }
  }
}

// The dilation's per-block flat flags (which gate the homogeneous-block shortcut) mark exactly
// the blocks whose texels all have one intensity: the uniform blocks, not the one with a single
// texel changed (nor any noise block).
/// Runs the dilation stage on `img` (one thread); returns the encoder state it ran on.
EncoderState dilate(const ImageRGBA8& img, Format format, bool rgba, std::vector<float>& low,
                    std::vector<float>& high, std::vector<std::uint8_t>& flat) {
  EncoderState s;
  s.g = make_grid(format, img.width, img.height);
  s.alpha_mode = rgba;
  s.threads = 1;
  s.own_target(img.pixels);
  dilation_endpoints(s, low, high, &flat);
  return s;
}

// A fully transparent image has one (premultiplied) intensity everywhere: no texel is an
// extremum, every texel stays empty, and each block's high / low colour is the colour of its
// brightest / darkest texel by the colours' own Rec.709 luma (first in raster order on ties),
// not one texel's colour for both.
TEST(PvrtcDilationEncode, OneIntensityBlockTakesItsBrightestAndDarkestColours) {
  for (Format format : {Format::pvrtc1_4bpp, Format::pvrtc1_2bpp}) {
    const int w = format == Format::pvrtc1_4bpp ? 32 : 64, h = 32;
    const int bw = format == Format::pvrtc1_4bpp ? 4 : 8;
    ImageRGBA8 img(w, h);
    img.has_alpha = true;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        std::uint8_t* p = &img.pixels[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * 4];
        p[0] = std::uint8_t((x * 7 + y * 3) & 255);
        p[1] = std::uint8_t((x * 5 + y * 11) & 255);
        p[2] = std::uint8_t((x * 13 + y) & 255);
        p[3] = 0;
      }
    }
    std::vector<float> low, high;
    std::vector<std::uint8_t> flat;
    const EncoderState s = dilate(img, format, true, low, high, flat);
    for (int by = 0; by < s.g.nby; ++by) {
      for (int bx = 0; bx < s.g.nbx; ++bx) {
        const std::size_t bi = std::size_t(by) * std::size_t(s.g.nbx) + std::size_t(bx);
        EXPECT_EQ(flat[bi], 1);
        const std::uint8_t *hi = nullptr, *lo = nullptr;
        int lmax = -1, lmin = 1 << 30;
        for (int y = by * 4; y < by * 4 + 4; ++y) {
          for (int x = bx * bw; x < bx * bw + bw; ++x) {
            const std::uint8_t* p =
                &img.pixels[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * 4];
            const int l = 2126 * p[0] + 7152 * p[1] + 722 * p[2];
            if (l > lmax) lmax = l, hi = p;
            if (l < lmin) lmin = l, lo = p;
          }
        }
        ASSERT_NE(hi, lo);
        for (int c = 0; c < 4; ++c) {
          EXPECT_EQ(high[bi * 4 + std::size_t(c)], float(hi[c])) << "block " << bx << "," << by;
          EXPECT_EQ(low[bi * 4 + std::size_t(c)], float(lo[c])) << "block " << bx << "," << by;
        }
      }
    }
  }
}

TEST(PvrtcDilationEncode, FlatFlagsMarkBlocksOfOneIntensity) {
  for (Format format : {Format::pvrtc1_4bpp, Format::pvrtc1_2bpp}) {
    ImageRGBA8 img = make_procedural(Procedural::noise, 64, 32, 3);
    const int bw = format == Format::pvrtc1_4bpp ? 4 : 8;
    auto fill_block = [&](int bx, int by, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
      for (int y = by * 4; y < by * 4 + 4; ++y) {
        for (int x = bx * bw; x < bx * bw + bw; ++x) {
          std::uint8_t* p = &img.pixels[(std::size_t(y) * 64 + std::size_t(x)) * 4];
          p[0] = r;
          p[1] = g;
          p[2] = b;
          p[3] = 255;
        }
      }
    };
    fill_block(0, 0, 10, 200, 30);
    fill_block(1, 0, 0, 0, 0);
    fill_block(2, 1, 255, 255, 255);
    fill_block(1, 2, 90, 90, 90);
    img.pixels[(std::size_t(9) * 64 + std::size_t(bw + 1)) * 4] =
        91;  // block (1, 2): one texel off
    for (bool rgba : {false, true}) {
      std::vector<float> low, high;
      std::vector<std::uint8_t> flat;
      const EncoderState s = dilate(img, format, rgba, low, high, flat);
      ASSERT_EQ(flat.size(), s.g.blocks());
      // Reference: the baseline intensity of every texel, compared within each block.
      std::vector<float> inten(64 + 2 * kPad);
      std::vector<float> all(64 * 32);
      for (int y = 0; y < 32; ++y) {
        dilation_kernels_baseline()->intensity_row(&img.pixels[std::size_t(y) * 64 * 4], 64, rgba,
                                                   inten.data() + kPad);
        std::memcpy(&all[std::size_t(y) * 64], inten.data() + kPad, 64 * sizeof(float));
      }
      int flagged = 0;
      for (int by = 0; by < s.g.nby; ++by) {
        for (int bx = 0; bx < s.g.nbx; ++bx) {
          bool same = true;
          const float first = all[std::size_t(by * 4) * 64 + std::size_t(bx * bw)];
          for (int y = by * 4; y < by * 4 + 4; ++y) {
            for (int x = bx * bw; x < bx * bw + bw; ++x) {
              same &= all[std::size_t(y) * 64 + std::size_t(x)] == first;
            }
          }
          const std::uint8_t f = flat[std::size_t(by) * std::size_t(s.g.nbx) + std::size_t(bx)];
          EXPECT_EQ(f != 0, same) << "block " << bx << "," << by << (rgba ? " RGBA" : " RGB");
          flagged += f;
        }
      }
      EXPECT_EQ(flagged, 3);  // the three uniform blocks; not the one with a texel off
    }
  }
}

}  // namespace
}  // namespace tessera::pvrtc::detail
