// Tests of the PVRTC encoder's internal search passes (src/pvrtc/encode/encode_internal.h): the
// exact search's neighbour-copy moves and seeded rounds (4 bpp and 2 bpp), the crossover of two
// encodings (4 bpp and 2 bpp) and the orientation of the principal-axis start.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "pvrtc/encode/encode_internal.h"
#include "pvrtc/encode/search/exact_search_window.h"
#include "pvrtc/format/pvrtc_kernel.h"
#include "tessera/io.h"
#include "tessera/procedural.h"
#include "tessera/pvrtc.h"
#include "test_support.h"

using namespace tessera;
using namespace tessera::pvrtc;
using namespace tessera::pvrtc::detail;

namespace {

// An encoder state for `img` holding the blocks of `data` (an encoding of it in `format`).
// `mode1`: whether the 4 bpp modulation choice may use mode 1.
EncoderState state_from(const ImageRGBA8& img, const std::vector<std::uint8_t>& data, bool mode1,
                        Format format = Format::pvrtc1_4bpp) {
  EncoderState s;
  s.g = make_grid(format, img.width, img.height);
  s.alpha_mode = img.has_alpha;
  s.mode1 = mode1;
  s.threads = 1;
  std::vector<std::uint8_t> target = img.pixels;
  if (!img.has_alpha) {
    for (std::size_t i = 0; i < s.g.texels(); ++i) target[i * 4 + 3] = 255;
  }
  s.own_target(std::move(target));
  std::vector<std::uint64_t> w(s.g.blocks());
  load_words(s.g, data.data(), w.data());
  s.ca.resize(w.size());
  s.cb.resize(w.size());
  s.mode.resize(w.size());
  s.mod.resize(w.size());
  for (std::size_t i = 0; i < w.size(); ++i) {
    s.mod[i] = std::uint32_t(w[i]);
    const auto a = std::uint16_t(w[i] >> 32);
    s.mode[i] = a & 1;
    s.ca[i] = a & 0xfffe;
    s.cb[i] = std::uint16_t(w[i] >> 48);
  }
  return s;
}

std::vector<std::uint8_t> encode_or_die(const ImageRGBA8& img, Quality q,
                                        Format format = Format::pvrtc1_4bpp) {
  EncodeOptions o;
  o.format = format;
  o.quality = q;
  o.threads = 1;
  auto r = encode(img, o);
  EXPECT_TRUE(r.ok());
  return r.ok() ? *r : std::vector<std::uint8_t>{};
}

// Own-texel squared error (RGB) of every block of `s` as decoded with its current words.
std::vector<std::uint64_t> own_errors(const EncoderState& s, int alpha_weight = 0) {
  const std::vector<std::uint64_t> w = s.words();
  std::vector<std::uint8_t> dec(s.g.texels() * 4);
  decode_padded(s.g, w.data(), dec.data(), 1);
  std::vector<std::uint64_t> e(s.g.blocks(), 0);
  for (int y = 0; y < s.g.ph; ++y) {
    for (int x = 0; x < s.g.pw; ++x) {
      const std::size_t i = std::size_t(y) * std::size_t(s.g.pw) + std::size_t(x);
      for (int c = 0; c < 4; ++c) {
        const int d = int(dec[i * 4 + std::size_t(c)]) - int(s.target[i * 4 + std::size_t(c)]);
        e[std::size_t(y / 4) * std::size_t(s.g.nbx) + std::size_t(x / s.g.bw)] +=
            std::uint64_t(d * d) * std::uint64_t(c == 3 ? alpha_weight : 1);
      }
    }
  }
  return e;
}

}  // namespace

// The encoder hands the error `choose_modulation` returns to the refinement in place of a
// decode (passes.cpp, least_squares_refinement.cpp), so it must be exactly `total_error` of the
// result: 4 bpp with and without mode 1 (punch-through on RGBA), 2 bpp direct and interpolated
// blocks.
TEST(PvrtcSearch, ChooseModulationReturnsTheTotalError) {
  for (Procedural kind : all_procedurals()) {
    const ImageRGBA8 img = make_procedural(kind, 32, 32);
    for (Format format : {Format::pvrtc1_4bpp, Format::pvrtc1_2bpp}) {
      for (Quality q : {Quality::fast, Quality::normal}) {
        for (bool mode1 : {false, true}) {
          EncoderState s = state_from(img, encode_or_die(img, q, format), mode1, format);
          const std::uint64_t returned = choose_modulation(s);
          EXPECT_EQ(returned, total_error(s))
              << procedural_name(kind) << (format == Format::pvrtc1_2bpp ? " 2bpp" : " 4bpp")
              << (q == Quality::fast ? " fast" : " normal") << (mode1 ? " mode1" : "");
        }
      }
    }
  }
}

// After the exact search with neighbour moves has converged, no block can lower the exact
// error of the whole image by taking a neighbour's A, B or both. With mode 1 off every block
// stays in mode 0, so the search's window error is exactly the block's share of the total.
TEST(PvrtcSearch, NeighbourMovesReachALocalMinimum) {
  const ImageRGBA8 img = make_procedural(Procedural::bricks, 32, 32);
  EncoderState s = state_from(img, encode_or_die(img, Quality::fast), false);
  choose_modulation(s);
  const std::uint64_t before = total_error(s);
  EndpointSearchOptions po;
  po.neighbour_moves = true;
  search_endpoints_4bpp(s, 64, 1, 0, po);
  const std::uint64_t after = total_error(s);
  EXPECT_LT(after, before);
  const Grid& g = s.g;
  int tried = 0;
  for (int by = 0; by < g.nby; ++by) {
    for (int bx = 0; bx < g.nbx; ++bx) {
      const std::size_t j = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const std::size_t k = std::size_t((by + dy) & (g.nby - 1)) * std::size_t(g.nbx) +
                                std::size_t((bx + dx) & (g.nbx - 1));
          if (k == j) continue;
          const std::uint16_t cand[3][2] = {
              {s.ca[k], s.cb[j]}, {s.ca[j], s.cb[k]}, {s.ca[k], s.cb[k]}};
          for (const auto& c : cand) {
            EncoderState t = s;
            t.ca[j] = c[0];
            t.cb[j] = c[1];
            choose_modulation(t);
            EXPECT_GE(total_error(t), after) << "block " << bx << "," << by;
            ++tried;
          }
        }
      }
    }
  }
  EXPECT_EQ(tried, int(g.blocks()) * 24);
}

// A seeded search first visits only the seed blocks: with no seeds and nothing changed it
// leaves the state as it is; seeding every block is the unseeded search.
TEST(PvrtcSearch, SeededRoundsStartFromTheSeeds) {
  const ImageRGBA8 img = make_procedural(Procedural::noise, 32, 32);
  const EncoderState start = state_from(img, encode_or_die(img, Quality::fast), true);
  EndpointSearchOptions po;
  po.neighbour_moves = true;
  const std::vector<std::uint8_t> none(start.g.blocks(), 0), all(start.g.blocks(), 1);
  EncoderState a = start;
  po.seeds = &none;
  search_endpoints_4bpp(a, 64, 1, 0, po);
  EXPECT_EQ(a.ca, start.ca);
  EXPECT_EQ(a.cb, start.cb);
  EncoderState b = start, c = start;
  po.seeds = &all;
  search_endpoints_4bpp(b, 64, 1, 0, po);
  po.seeds = nullptr;
  search_endpoints_4bpp(c, 64, 1, 0, po);
  EXPECT_NE(b.ca, start.ca);
  EXPECT_EQ(b.words(), c.words());
}

// The crossover takes exactly the blocks whose own texels the other encoding decodes with
// less error (when the pair points the same way), and seeds the blocks next to a switch.
TEST(PvrtcSearch, CrossoverTakesTheBetterBlocks) {
  const ImageRGBA8 img = make_procedural(Procedural::bricks, 64, 64);
  const EncoderState fast = state_from(img, encode_or_die(img, Quality::fast), true);
  const EncoderState high = state_from(img, encode_or_die(img, Quality::high), true);
  std::vector<std::uint8_t> seeds;
  EncoderState self = high;
  EXPECT_EQ(crossover(self, high, 2, seeds), 0);
  EXPECT_EQ(seeds, std::vector<std::uint8_t>(high.g.blocks(), 0));

  EncoderState s = fast;
  const std::vector<std::uint64_t> mine = own_errors(fast), theirs = own_errors(high);
  const int taken = crossover(s, high, 2, seeds);
  EXPECT_GT(taken, 0);
  const Grid& g = s.g;
  std::vector<std::uint8_t> took(g.blocks(), 0);
  int count = 0;
  for (std::size_t j = 0; j < g.blocks(); ++j) {
    const bool from_high = s.ca[j] != fast.ca[j] || s.cb[j] != fast.cb[j];
    if (from_high) {
      EXPECT_EQ(s.ca[j], high.ca[j]);
      EXPECT_EQ(s.cb[j], high.cb[j]);
      EXPECT_LT(theirs[j], mine[j]) << "block " << j;
      took[j] = 1;
      ++count;
    } else if (high.ca[j] != fast.ca[j] || high.cb[j] != fast.cb[j]) {
      // Kept: not better, or pointing the other way.
      const Rgba5 a0 = expand_a(fast.ca[j]), b0 = expand_b(fast.cb[j]);
      const Rgba5 a1 = expand_a(high.ca[j]), b1 = expand_b(high.cb[j]);
      const int dot = (b0.r - a0.r) * (b1.r - a1.r) + (b0.g - a0.g) * (b1.g - a1.g) +
                      (b0.b - a0.b) * (b1.b - a1.b);
      EXPECT_TRUE(theirs[j] >= mine[j] || dot < 0) << "block " << j;
    }
  }
  EXPECT_EQ(count, taken);
  for (int by = 0; by < g.nby; ++by) {
    for (int bx = 0; bx < g.nbx; ++bx) {
      const std::size_t j = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
      bool mixed = false;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          mixed |= took[std::size_t((by + dy) & (g.nby - 1)) * std::size_t(g.nbx) +
                        std::size_t((bx + dx) & (g.nbx - 1))] != took[j];
        }
      }
      EXPECT_EQ(seeds[j] != 0, mixed) << "block " << bx << "," << by;
    }
  }
}

// 2 bpp: the crossover compares the blocks' own 8x4 texels (alpha counted twice on RGBA)
// and takes the other encoding's pair only where that errs less.
TEST(PvrtcSearch, Crossover2bppComparesWholeBlocks) {
  for (Procedural kind : {Procedural::bricks, Procedural::foliage}) {
    const ImageRGBA8 img = make_procedural(kind, 64, 32);
    const EncoderState fast = state_from(
        img, encode_or_die(img, Quality::fast, Format::pvrtc1_2bpp), false, Format::pvrtc1_2bpp);
    const EncoderState normal = state_from(
        img, encode_or_die(img, Quality::normal, Format::pvrtc1_2bpp), false, Format::pvrtc1_2bpp);
    const int aw = img.has_alpha ? 2 : 0;
    const std::vector<std::uint64_t> mine = own_errors(normal, aw), theirs = own_errors(fast, aw);
    EncoderState s = normal;
    std::vector<std::uint8_t> seeds;
    const int taken = crossover(s, fast, 2, seeds);
    EXPECT_GT(taken, 0) << procedural_name(kind);
    int count = 0;
    for (std::size_t j = 0; j < s.g.blocks(); ++j) {
      if (s.ca[j] != normal.ca[j] || s.cb[j] != normal.cb[j]) {
        EXPECT_EQ(s.ca[j], fast.ca[j]);
        EXPECT_EQ(s.cb[j], fast.cb[j]);
        EXPECT_LT(theirs[j], mine[j]) << procedural_name(kind) << " block " << j;
        ++count;
      }
    }
    EXPECT_EQ(count, taken);
    EXPECT_EQ(seeds.size(), s.g.blocks());
  }
}

// 2 bpp: seeding every block is the unseeded endpoint search; seeding none leaves the state.
TEST(PvrtcSearch, SeededEndpointSearch2bpp) {
  const ImageRGBA8 img = make_procedural(Procedural::noise, 64, 32);
  EncoderState start = state_from(img, encode_or_die(img, Quality::fast, Format::pvrtc1_2bpp),
                                  false, Format::pvrtc1_2bpp);
  start.modulation_descent = 1;
  const std::uint64_t e0 = choose_modulation(start);
  const std::vector<std::uint8_t> none(start.g.blocks(), 0), all(start.g.blocks(), 1);
  EncoderState a = start, b = start, c = start;
  EXPECT_EQ(search_endpoints_2bpp(a, e0, &none), e0);
  EXPECT_EQ(a.words(), start.words());
  const std::uint64_t eb = search_endpoints_2bpp(b, e0, &all);
  EXPECT_LT(eb, e0);
  EXPECT_EQ(search_endpoints_2bpp(c, e0), eb);
  EXPECT_EQ(b.words(), c.words());
}

// The crossover step of high (both formats) never leaves an error above the first encoding's
// and, at 2 bpp, lowers it on textures where the two starts end in different minima.
TEST(PvrtcSearch, OptimiseCrossoverNeverRaisesTheError) {
  for (Format format : {Format::pvrtc1_4bpp, Format::pvrtc1_2bpp}) {
    for (Procedural kind : {Procedural::bricks, Procedural::foliage, Procedural::noise}) {
      const ImageRGBA8 img = make_procedural(kind, 64, 32);
      EncoderState s = state_from(img, encode_or_die(img, Quality::normal, format), true, format);
      EncoderState alt = state_from(img, encode_or_die(img, Quality::fast, format), true, format);
      s.modulation_descent = alt.modulation_descent = format == Format::pvrtc1_2bpp ? 1 : 0;
      const std::uint64_t before = choose_modulation(s);
      const std::uint64_t alt_error = choose_modulation(alt);
      const EncodeSchedule high = resolve_schedule(Quality::high, format, -1, 0);
      optimise_alt(alt, alt_error, high);
      optimise_crossover(s, alt, high);
      const std::uint64_t after = total_error(s);
      EXPECT_LE(after, before) << procedural_name(kind) << " format " << int(format);
      if (format == Format::pvrtc1_2bpp) {
        EXPECT_LT(after, before) << procedural_name(kind);
      }
    }
  }
}

// Packing the unpacked stored values and mode gives back the same 32 modulation bits, for
// every mode and variant (the block's mode bit rides along in bit 32 of the word).
TEST(PvrtcSearch, Pack2bppInvertsUnpack) {
  std::uint64_t x = 0x9e3779b97f4a7c15ull;
  int seen[4] = {0, 0, 0, 0};
  for (int i = 0; i < 20000; ++i) {
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    const std::uint64_t word = (x & 0xffffffffull) | (std::uint64_t((x >> 40) & 1) << 32);
    std::uint8_t v[32];
    int mode = -1;
    unpack_2bpp_block(word, v, mode);
    ASSERT_GE(mode, 0);
    ASSERT_LE(mode, 3);
    ++seen[mode];
    EXPECT_EQ(pack_2bpp_block(v, mode), std::uint32_t(word)) << std::hex << word;
  }
  for (int m = 0; m < 4; ++m) EXPECT_GT(seen[m], 0) << "mode " << m;
}

// The descent never raises the exact error, lowers it on detailed content, and converges to a
// state where no single stored value (within what its texel may hold) or interpolation
// variant change lowers the whole image's exact error.
TEST(PvrtcSearch, ModulationDescent2bppReachesALocalMinimum) {
  for (Procedural kind : {Procedural::noise, Procedural::foliage}) {
    const ImageRGBA8 img = make_procedural(kind, 32, 16);
    EncoderState s = state_from(img, encode_or_die(img, Quality::fast, Format::pvrtc1_2bpp), false,
                                Format::pvrtc1_2bpp);
    const std::uint64_t before = total_error(s);
    const std::uint64_t after = refine_modulation_2bpp(s, 16);
    EXPECT_EQ(after, total_error(s));
    EXPECT_LE(after, before) << procedural_name(kind);
    if (kind == Procedural::noise) {
      EXPECT_LT(after, before);
    }
    const Grid& g = s.g;
    int tried = 0;
    for (std::size_t bi = 0; bi < g.blocks(); ++bi) {
      std::uint8_t v[32];
      int mode = 0;
      unpack_2bpp_block(s.word(bi), v, mode);
      auto try_block = [&](const std::uint8_t* nv, int nmode) {
        EncoderState t = s;
        t.mod[bi] = pack_2bpp_block(nv, nmode);
        t.mode[bi] = nmode != 0;
        EXPECT_GE(total_error(t), after) << procedural_name(kind) << " block " << bi;
        ++tried;
      };
      for (int i = 0; i < 32; ++i) {
        const int x = i % 8, y = i / 8;
        if (mode != 0 && ((x ^ y) & 1)) continue;  // interpolated texel
        const bool restricted = mode == 0 || i == 0 || (i == 20 && mode != 1);
        for (std::uint8_t c = 0; c < 4; ++c) {
          if (c == v[i] || (restricted && c != 0 && c != 3)) continue;
          std::uint8_t nv[32];
          std::copy(v, v + 32, nv);
          nv[i] = c;
          try_block(nv, mode);
        }
      }
      if (mode == 0) continue;
      for (int m = 1; m <= 3; ++m) {
        if (m == mode) continue;
        for (std::uint8_t c = 0; c < 4; ++c) {
          if (m != 1 && c != 0 && c != 3) continue;
          std::uint8_t nv[32];
          std::copy(v, v + 32, nv);
          nv[20] = c;
          try_block(nv, m);
        }
      }
    }
    EXPECT_GT(tried, 100);
  }
}

// The endpoint quantiser's table lookup gives code_nearest's code for every level: all
// multiples of 1/64 over and beyond 0..255 (block means are multiples of 1/32), the floats
// next to every midpoint between codes, and random levels.
TEST(PvrtcSearch, NearestCodeTableMatchesTheSearch) {
  struct Kind {
    const NearestCodeTable* table;
    int bits, channel;
  };
  const Kind kinds[] = {
      {&kNearest5, 5, 0}, {&kNearest4, 4, 0}, {&kNearest3, 3, 0}, {&kNearestAlpha3, 3, 3}};
  std::vector<float> levels;
  for (int k = -64 * 20; k <= 64 * 280; ++k) levels.push_back(float(k) / 64.0f);
  for (int h = -4; h <= 2 * 260; ++h) {
    const float m = float(h) / 2.0f;
    levels.push_back(std::nextafter(m, -1e9f));
    levels.push_back(std::nextafter(m, 1e9f));
  }
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> dist(-400.0f, 700.0f);
  for (int i = 0; i < 200000; ++i) levels.push_back(dist(rng));
  levels.push_back(1000.0f);
  levels.push_back(-1000.0f);
  for (const Kind& k : kinds) {
    int mismatches = 0;
    for (float level : levels) {
      if (code_nearest_fast(*k.table, level) != code_nearest(level, k.bits, k.channel) &&
          ++mismatches < 5) {
        ADD_FAILURE() << "bits " << k.bits << " channel " << k.channel << " level " << level;
      }
    }
    EXPECT_EQ(mismatches, 0);
    // Both ends are reached.
    EXPECT_EQ(code_nearest_fast(*k.table, 0.0f), 0u);
    EXPECT_EQ(code_nearest_fast(*k.table, 255.0f), (1u << k.bits) - 1);
  }
}

// orient_endpoints: a run of blocks that all store the same two equally bright colours, the
// upper half one way round and the lower half the other (a "domain wall", which the earlier
// block-by-block passes left in place: each block there agrees with three of its four
// neighbours), comes out oriented one way throughout. Pairs with a clear luma order keep it.
TEST(PvrtcSearch, OrientationRemovesDomainWalls) {
  const Grid g = make_grid(Format::pvrtc1_4bpp, 8, 64);  // 2 x 16 blocks
  ASSERT_EQ(g.nbx, 2);
  ASSERT_EQ(g.nby, 16);
  const float pink[4] = {255, 117, 144, 255};  // luma ~148
  const float cyan[4] = {0, 178, 238, 255};    // luma ~145
  std::vector<float> low(g.blocks() * 4), high(g.blocks() * 4);
  for (std::size_t i = 0; i < g.blocks(); ++i) {
    const bool upper = i / std::size_t(g.nbx) < 8;
    for (int c = 0; c < 4; ++c) {
      low[i * 4 + std::size_t(c)] = upper ? pink[c] : cyan[c];
      high[i * 4 + std::size_t(c)] = upper ? cyan[c] : pink[c];
    }
  }
  std::vector<float> low2 = low, high2 = high;
  orient_endpoints(g, 3, low, high);
  for (std::size_t i = 1; i < g.blocks(); ++i) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(low[i * 4 + std::size_t(c)], low[std::size_t(c)]) << "block " << i;
      EXPECT_EQ(high[i * 4 + std::size_t(c)], high[std::size_t(c)]) << "block " << i;
    }
  }
  // A block whose pair has a clear luma order is never swapped.
  for (int c = 0; c < 3; ++c) {
    low2[std::size_t(c)] = 40.0f;
    high2[std::size_t(c)] = 220.0f;
  }
  orient_endpoints(g, 3, low2, high2);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(low2[std::size_t(c)], 40.0f);
    EXPECT_EQ(high2[std::size_t(c)], 220.0f);
  }
}

// End to end on a photo that does not tile (../shared/data ldr-rgb-03: pink meets cyan, equally
// bright, at the wrap-around seam): the colours of the two edge columns are kept by normal at
// both bit rates. RMS per channel over columns 0 and 255: 4 bpp 6.6 (9.3 before the orientation
// regions), 2 bpp 10.2 (12.1 before).
TEST(PvrtcSearch, HueSeamAtTheWrapIsReproduced) {
  TESSERA_REQUIRE_SHARED_DATA(data);
  auto img = io::read_image((data / "images" / "ldr-rgb-03.png").string());
  ASSERT_TRUE(img.ok()) << img.status().message;
  ASSERT_EQ(img->width, 256);
  for (Format f : {Format::pvrtc1_4bpp, Format::pvrtc1_2bpp}) {
    const std::vector<std::uint8_t> data_bytes = encode_or_die(*img, Quality::normal, f);
    auto dec = decode(data_bytes, f, img->width, img->height, {1});
    ASSERT_TRUE(dec.ok());
    double e = 0;
    for (int y = 0; y < img->height; ++y) {
      for (int x : {0, img->width - 1}) {
        for (int c = 0; c < 3; ++c) {
          const double d = double(dec->at(x, y)[c]) - double(img->at(x, y)[c]);
          e += d * d;
        }
      }
    }
    const double rms = std::sqrt(e / (3.0 * 2.0 * img->height));
    EXPECT_LT(rms, f == Format::pvrtc1_4bpp ? 8.0 : 11.0)
        << (f == Format::pvrtc1_4bpp ? "4 bpp" : "2 bpp");
  }
}

// The 2 bpp endpoint search's window score (exact_search_2bpp.cpp) against a scalar reference built
// from the decoder's own upscaling: block (bx, by)'s candidate pair over the 15x7 texels it
// reaches, every texel at its best weight among those its block's mode allows ({0, 8} direct;
// interpolated blocks {0, 3, 5, 8} on stored texels, {0, 8} at (0, 0), {0, 3, 4, 5, 8} on the
// interpolated ones), alpha error counted twice. Mixed modes, RGB and RGBA, a 2x2-block level
// (the window's neighbours wrap onto the block itself) and a 4x4-block one; bounded and
// reordered evaluations give the same sum below the bound and at least the bound otherwise.
// Run with the baseline evaluator and with the AVX2 one (where the build and CPU have it).
static void check_window2_scores() {
  std::mt19937 rng(7);
  for (const auto& [w, h] : {std::pair{16, 8}, std::pair{32, 16}}) {
    for (Procedural kind : {Procedural::foliage, Procedural::noise}) {
      const ImageRGBA8 img = make_procedural(kind, w, h);
      EncoderState s = state_from(img, encode_or_die(img, Quality::normal, Format::pvrtc1_2bpp),
                                  false, Format::pvrtc1_2bpp);
      const Grid& g = s.g;
      for (std::size_t i = 0; i < g.blocks(); ++i) s.mode[i] = rng() & 1;
      const int aw = s.alpha_mode ? 2 : 0;
      int compared = 0;
      for (int by = 0; by < g.nby; ++by) {
        for (int bx = 0; bx < g.nbx; ++bx) {
          const std::size_t j = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
          for (int trial = 0; trial < 6; ++trial) {
            // The block's own pair, then random opaque / translucent fields.
            const std::uint16_t ca = trial == 0 ? s.ca[j] : std::uint16_t(rng() & 0xfffe);
            const std::uint16_t cb = trial == 0 ? s.cb[j] : std::uint16_t(rng() & 0xffff);
            std::vector<Rgba5> ea(g.blocks()), eb(g.blocks());
            for (std::size_t i = 0; i < g.blocks(); ++i) {
              ea[i] = expand_a(i == j ? ca : s.ca[i]);
              eb[i] = expand_b(i == j ? cb : s.cb[i]);
            }
            std::uint64_t expected = 0;
            for (int wy = 0; wy < 7; ++wy) {
              for (int wx = 0; wx < 15; ++wx) {
                const int x = (bx * 8 - 3 + wx) & (g.pw - 1), y = (by * 4 - 1 + wy) & (g.ph - 1);
                const AxisTap tx = axis_tap(x, 8, g.pw), ty = axis_tap(y, 4, g.ph);
                auto at = [&](const std::vector<Rgba5>& e, int cy, int cx) -> const Rgba5& {
                  return e[std::size_t(cy) * std::size_t(g.nbx) + std::size_t(cx)];
                };
                std::uint8_t ua[4], ub[4];
                upscale_texel(at(ea, ty.b0, tx.b0), at(ea, ty.b0, tx.b1), at(ea, ty.b1, tx.b0),
                              at(ea, ty.b1, tx.b1), tx.d, ty.d, 8, ua);
                upscale_texel(at(eb, ty.b0, tx.b0), at(eb, ty.b0, tx.b1), at(eb, ty.b1, tx.b0),
                              at(eb, ty.b1, tx.b1), tx.d, ty.d, 8, ub);
                const std::uint8_t* t =
                    &s.target[(std::size_t(y) * std::size_t(g.pw) + std::size_t(x)) * 4];
                const bool interp =
                    s.mode[std::size_t(y / 4) * std::size_t(g.nbx) + std::size_t(x / 8)] != 0;
                std::vector<int> weights = {0, 8};
                if (interp && ((x ^ y) & 1) != 0) {
                  weights = {0, 3, 4, 5, 8};
                } else if (interp && (x % 8 != 0 || y % 4 != 0)) {
                  weights = {0, 3, 5, 8};
                }
                std::uint64_t best = ~0ull;
                for (int m : weights) {
                  std::uint64_t e = 0;
                  for (int c = 0; c < 4; ++c) {
                    const int v = (int(ua[c]) * (8 - m) + int(ub[c]) * m) / 8 - int(t[c]);
                    e += std::uint64_t(v * v) * std::uint64_t(c == 3 ? aw : 1);
                  }
                  best = std::min(best, e);
                }
                expected += best;
              }
            }
            const std::uint32_t got = window_error_2bpp(s, bx, by, ca, cb, ~0u, false);
            ASSERT_EQ(got, expected) << procedural_name(kind) << " " << w << "x" << h << " block "
                                     << bx << "," << by << " trial " << trial;
            EXPECT_EQ(window_error_2bpp(s, bx, by, ca, cb, ~0u, true), expected);
            const auto bound = std::uint32_t(expected / 2 + 1);
            EXPECT_GE(window_error_2bpp(s, bx, by, ca, cb, bound, true), bound);
            EXPECT_EQ(window_error_2bpp(s, bx, by, ca, cb, std::uint32_t(expected + 1), true),
                      expected);
            ++compared;
          }
        }
      }
      EXPECT_EQ(compared, int(g.blocks()) * 6);
    }
  }
}

TEST(PvrtcSearch, Window2bppScoreMatchesTheDecoder) {
  for (bool baseline_only : {true, false}) {
    SCOPED_TRACE(baseline_only ? "baseline evaluator" : "evaluator in use (AVX2 where usable)");
    const bool previous = set_exact_search_baseline_only(baseline_only);
    check_window2_scores();
    set_exact_search_baseline_only(previous);
  }
}

// The 2 bpp endpoint search never raises the exact total error (it keeps the state it started
// from otherwise), returns the error of the state it leaves, and lowers it on textures whose
// least-squares start is not a local minimum of the exact error.
TEST(PvrtcSearch, EndpointSearch2bppLowersTheError) {
  for (Procedural kind : all_procedurals()) {
    const ImageRGBA8 img = make_procedural(kind, 64, 32);
    EncoderState s = state_from(img, encode_or_die(img, Quality::normal, Format::pvrtc1_2bpp),
                                false, Format::pvrtc1_2bpp);
    s.modulation_descent = 1;
    const std::uint64_t before = choose_modulation(s);
    const std::uint64_t after = search_endpoints_2bpp(s, before);
    EXPECT_EQ(after, total_error(s)) << procedural_name(kind);
    EXPECT_LE(after, before) << procedural_name(kind);
    if (kind == Procedural::bricks || kind == Procedural::noise || kind == Procedural::foliage) {
      EXPECT_LT(after, before) << procedural_name(kind);
    }
  }
}
