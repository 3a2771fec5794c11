// The preset table of the PVRTC encoder: one row per quality x format (see schedule.h for the
// fields). Why each value: "what and why" below; the numbers that chose them are in
// docs/benchmarks/pvrtc_history.md.
#include "pvrtc/encode/schedule.h"

namespace tessera::pvrtc::detail {

namespace {

// The thresholds' unit, a window SSE: the sum of squared 8-bit differences over the 7x7 texels
// a block influences (exact_search.cpp's window), of R, G, B and, in alpha mode, alpha (counted
// as many times as the pass's alpha weight). For RGB, RMS per channel = sqrt(SSE / (49 x 3)).
// Blocks at most this (RGB: ~4.5 RMS per channel; less with alpha) gain nothing from a reseed or
// an extra search round.
constexpr std::uint32_t kModerateWindowSse = 3000;
// RGB: ~6.4 RMS per channel: where one round of the exact search at normal pays for itself.
constexpr std::uint32_t kHighWindowSse = 6000;
// Round bound of a search run to convergence (it converges after 10-20 rounds).
constexpr int kUntilConverged = 64;
// high counts the squared alpha error twice where it compares encodings (reseed, crossover), as
// the exact searches do: alpha PSNR is over one channel, so its error costs more dB per unit.
constexpr int kHighAlphaWeight = 2;

struct Row {
  Quality quality;
  Format format;
  EncodeSchedule schedule;
};

constexpr Format k4bpp = Format::pvrtc1_4bpp, k2bpp = Format::pvrtc1_2bpp;
constexpr ExactSearchStep kSearchToConvergence{
    .rounds = kUntilConverged, .passes = 1, .min_error = 0, .neighbour_moves = true};

// Fields not named keep schedule.h's defaults (off / 0).
constexpr Row kPresets[] = {
    // fast: the paper's algorithm, intensity dilation then brute-force modulation.
    {Quality::fast, k4bpp, {.dilation_start = true}},
    {Quality::fast, k2bpp, {.dilation_start = true}},
    // normal, 4 bpp: principal-axis start (it separates equally bright colours that intensity
    // labelling merges), mode 1, one reseed pass for blocks whose footprint-wide start misses
    // their own texels (thin features, stripes), 3 refinement sweeps, then one round of the
    // exact search on the blocks that still err a lot.
    {Quality::normal,
     k4bpp,
     {.dilation_start = false,
      .try_mode1 = true,
      .reseed_passes = 1,
      .reseed_min_error = kModerateWindowSse,
      .refinement_sweeps = 3,
      .exact_search = {.rounds = 1, .passes = 1, .min_error = kHighWindowSse}}},
    // normal, 2 bpp: principal-axis start, the exact modulation descent after every modulation
    // choice (it sees the decoder's truncations the least-squares model ignores), 3 sweeps.
    {Quality::normal,
     k2bpp,
     {.dilation_start = false, .try_mode1 = true, .modulation_descent = 1, .refinement_sweeps = 3}},
    // high, 4 bpp: a second reseed pass next to changed blocks; few refinement sweeps, as the
    // exact search (every block, neighbour moves, to convergence) does most of the work; then
    // the crossover with a dilation-started encoding that goes straight to the same search (a
    // refinement first moved it towards the first encoding's minimum, leaving less to gain).
    {Quality::high,
     k4bpp,
     {.dilation_start = false,
      .try_mode1 = true,
      .reseed_passes = 2,
      .reseed_min_error = kModerateWindowSse,
      .reseed_alpha_weight = kHighAlphaWeight,
      .refinement_sweeps = 3,
      .exact_search = kSearchToConvergence,
      .crossover = true,
      .crossover_alpha_weight = kHighAlphaWeight,
      .crossover_search = kSearchToConvergence}},
    // high, 2 bpp: as normal, with 4 sweeps (the endpoint search refines again after it), two
    // more descent sweeps, the exact endpoint search, and the crossover with a second encoding
    // run through the same passes.
    {Quality::high,
     k2bpp,
     {.dilation_start = false,
      .try_mode1 = true,
      .modulation_descent = 1,
      .refinement_sweeps = 4,
      .descent_before_endpoint_search = 2,
      .endpoint_search_2bpp = true,
      .crossover = true,
      .crossover_alpha_weight = kHighAlphaWeight,
      .crossover_descent_2bpp = 3}},
};

}  // namespace

EncodeSchedule resolve_schedule(Quality quality, Format format, int iterations,
                                int exact_search_rounds) {
  EncodeSchedule s;
  for (const Row& row : kPresets) {
    if (row.quality == quality && row.format == format) s = row.schedule;
  }
  if (iterations >= 0) {
    s.refinement_sweeps = iterations;
    s.crossover = false;
  }
  if (exact_search_rounds > 0) {
    // Replaces the preset's search: at 2 bpp there is no 4 bpp search to run, and the endpoint
    // search is off.
    s.exact_search = {};
    if (format == Format::pvrtc1_4bpp) {
      s.exact_search = {exact_search_rounds, 4, kModerateWindowSse, false};
    }
    s.descent_before_endpoint_search = 0;
    s.endpoint_search_2bpp = false;
    s.crossover = false;
  }
  return s;
}

}  // namespace tessera::pvrtc::detail
