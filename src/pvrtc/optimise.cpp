// PVRTC encoder passes after the first modulation choice, per quality: reseed (polish.cpp),
// least-squares refinement (refine.cpp), the exact search (polish.cpp; polish_2bpp.cpp at
// 2 bpp) and, for high, the crossover with a second encoding (crossover.cpp). Gains
// quoted are means over the 21 power-of-two images of the benchmark set
// (docs/benchmarks/pvrtc.md), 4 bpp unless said otherwise.
#include "pvrtc/encode_internal.h"

namespace tessera::pvrtc::detail {

namespace {

// Blocks whose exact 8x8-window error is at most this (~4 per channel RMS) are not reseeded.
constexpr std::uint32_t kReseedMinError = 3000;
// Round bound of the exact search for high; it converges after 10-20 rounds on the set.
constexpr int kPolishUntilConverged = 64;
// high, RGBA: the reseed's exact window error counts alpha twice, as the exact search does
// (polish.cpp): +0.14 dB alpha.
constexpr int kHighAlphaWeight = 2;

int default_iterations(Quality q, Format f) {
  switch (q) {
    case Quality::fast:
      return 0;
    case Quality::normal:
      return 3;
    case Quality::high:
      // 4 bpp: the exact search below does most of the work; 16 sweeps instead of 3 bought
      // +0.01 dB RGB (alpha -0.01) for +15% time.
      // 2 bpp: the endpoint search (polish_2bpp.cpp) runs after these sweeps and refines again
      // after it; 4 sweeps instead of 16 before it: -0.0004 dB RGB for -15% time.
      return f == Format::pvrtc1_4bpp ? 3 : 4;
  }
  return 0;
}

}  // namespace

void optimise(EncoderState& s, Quality quality, int iterations, int exact_search_rounds,
              std::uint64_t error) {
  const Grid& g = s.g;
  // normal / high, 4 bpp: blocks whose footprint-wide start misses their own texels (thin
  // features, stripes) get endpoints from those texels where the exact error drops (photos:
  // normal +0.28 dB).
  if (quality != Quality::fast && g.format == Format::pvrtc1_4bpp) {
    std::vector<std::uint8_t> changed;
    // high: a second pass on the blocks next to changed ones (RGBA too since the exact search
    // runs on RGBA: +0.01 dB RGB there; a third pass bought nothing).
    const int passes = quality == Quality::high ? 2 : 1;
    for (int pass = 0; pass < passes; ++pass) {
      if (reseed(s, kReseedMinError, changed, quality == Quality::high ? kHighAlphaWeight : 1) == 0)
        break;
      error = choose_modulation(s);
    }
  }
  const int sweeps = iterations >= 0 ? iterations : default_iterations(quality, g.format);
  if (sweeps > 0) refine(s, sweeps, error);
  if (exact_search_rounds > 0) {
    polish(s, exact_search_rounds, 4, 3000);
  } else if (quality == Quality::high && g.format == Format::pvrtc1_4bpp) {
    // The exact search on every block (RGB and RGBA), one sweep of the moves per visit, rounds
    // until no block changes (blocks are revisited only after a neighbour changed, see
    // polish.cpp): +0.27 dB RGB, +0.22 dB alpha, SSIM +0.0021 over one round on blocks above
    // ~6.4 RMS (RGB only), for about 1.8x the encode time.
    // Copying a neighbour's A / B into a block (neighbour moves): +0.08 dB RGB on the 15
    // opaque images, +0.17 dB alpha on the 6 RGBA ones, for +25% time.
    PolishOptions po;
    po.neighbour_moves = true;
    polish(s, kPolishUntilConverged, 1, 0, po);
  } else if (quality == Quality::high && g.format == Format::pvrtc1_2bpp) {
    // Two more sweeps of the modulation descent (the refinement ran one after every
    // modulation choice): +0.01-0.02 dB for 5-15% more time.
    const std::uint64_t e = refine_modulation_2bpp(s, 2);
    // The exact endpoint search (polish_2bpp.cpp), then the modulation choice, its descent and
    // the refinement again: +0.15 dB RGB (29.85 -> 30.00; the 15 opaque images +0.19), +0.44 dB
    // alpha on the 6 RGBA images, SSIM +0.0020, for about 2x the encode time.
    search_endpoints_2bpp(s, e);
  } else if (quality == Quality::normal && g.format == Format::pvrtc1_4bpp) {
    // One round of the exact search on blocks above ~6.4 RMS per channel: +0.07 dB RGB,
    // +0.33 dB alpha for +27% time (two rounds above ~4.5 RMS: +0.16 / +0.51 for +58%).
    polish(s, 1, 1, 6000);
  }
}

// The crossover with a second encoding from the dilation start (crossover.cpp).
// 4 bpp: +0.16 dB RGB on the 15 opaque images (ldr-l-occlusion +0.8 dB), +0.05 dB RGB and
// +0.17 dB alpha on the 6 RGBA ones, for 2.7x the time of the single encoding.
// 2 bpp: +0.09 dB RGB (the 15 opaque images +0.10, ldr-rgb-02 and -06 +0.16-0.18), +0.17 dB
// alpha on the 6 RGBA ones, SSIM +0.0014, for about 2.8x the time of the single encoding.
void optimise_crossover(EncoderState& s, EncoderState& alt, std::uint64_t alt_error) {
  std::vector<std::uint8_t> seeds;
  if (s.g.format == Format::pvrtc1_2bpp) {
    // The dilation start runs the same passes as the first encoding (a cheaper second one, the
    // endpoint search straight from the dilation, lost most of the gain on the images tried).
    optimise(alt, Quality::high, -1, 0, alt_error);
    const std::uint64_t error = total_error(s);
    const std::vector<std::uint16_t> ca = s.ca, cb = s.cb;
    const std::vector<std::uint8_t> mode = s.mode;
    const std::vector<std::uint32_t> mod = s.mod;
    if (crossover(s, alt, kHighAlphaWeight, seeds) == 0) return;
    choose_modulation(s);
    const std::uint64_t e = search_endpoints_2bpp(s, refine_modulation_2bpp(s, 3), &seeds);
    if (e < error) return;
    s.ca = ca;  // the first encoding alone was better
    s.cb = cb;
    s.mode = mode;
    s.mod = mod;
    return;
  }
  PolishOptions po;
  po.neighbour_moves = true;
  // The dilation start goes straight to the exact search: three least-squares sweeps first
  // cost 0.03-0.13 dB RGB after the crossover on three of four images tried.
  polish(alt, kPolishUntilConverged, 1, 0, po);
  crossover(s, alt, kHighAlphaWeight, seeds);
  choose_modulation(s);
  po.seeds = &seeds;
  polish(s, kPolishUntilConverged, 1, 0, po);
}

}  // namespace tessera::pvrtc::detail
