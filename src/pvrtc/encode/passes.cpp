// PVRTC encoder passes after the first modulation choice, as the schedule (schedule.h) says:
// reseed (search/exact_search.cpp), least-squares refinement
// (search/least_squares_refinement.cpp), the exact search (search/exact_search.cpp; at 2 bpp
// modulation/modulation_2bpp_descent.cpp and search/exact_search_2bpp.cpp) and, for high, the
// crossover with a second encoding (search/crossover.cpp).
#include "pvrtc/encode/encode_internal.h"
#include "pvrtc/encode/schedule.h"

namespace tessera::pvrtc::detail {

namespace {

void run_exact_search(EncoderState& s, const ExactSearchStep& step,
                      const std::vector<std::uint8_t>* seeds = nullptr) {
  if (step.rounds <= 0) return;
  PolishOptions po;
  po.neighbour_moves = step.neighbour_moves;
  po.seeds = seeds;
  polish(s, step.rounds, step.passes, step.min_error, po);
}

}  // namespace

void optimise(EncoderState& s, const EncodeSchedule& schedule, std::uint64_t error) {
  // Blocks whose footprint-wide start misses their own texels (thin features, stripes) get
  // endpoints from those texels where the exact error drops; a later pass visits only blocks
  // next to changed ones.
  if (s.g.format == Format::pvrtc1_4bpp && schedule.reseed_passes > 0) {
    std::vector<std::uint8_t> changed;
    for (int pass = 0; pass < schedule.reseed_passes; ++pass) {
      if (reseed(s, schedule.reseed_min_error, changed, schedule.reseed_alpha_weight) == 0) break;
      error = choose_modulation(s);
    }
  }
  if (schedule.refinement_sweeps > 0) refine(s, schedule.refinement_sweeps, error);
  // 4 bpp: the exact search over +-1 moves of each block's endpoint codes (blocks are revisited
  // only after a neighbour changed, see exact_search.cpp).
  run_exact_search(s, schedule.exact_search);
  if (s.g.format == Format::pvrtc1_2bpp && schedule.endpoint_search_2bpp) {
    // More sweeps of the modulation descent (the refinement ran one after every modulation
    // choice), then the exact endpoint search, which re-chooses the modulation, descends and
    // refines again after it.
    const std::uint64_t e = refine_modulation_2bpp(s, schedule.descent_before_endpoint_search);
    search_endpoints_2bpp(s, e);
  }
}

// The crossover with a second encoding from the dilation start (crossover.cpp): the two starts
// stop in different local minima, the dilation one wins along sharp edges.
void optimise_crossover(EncoderState& s, EncoderState& alt, std::uint64_t alt_error,
                        const EncodeSchedule& schedule) {
  std::vector<std::uint8_t> seeds;
  if (s.g.format == Format::pvrtc1_2bpp) {
    // The dilation start runs the same passes as the first encoding (a cheaper second one, the
    // endpoint search straight from the dilation, lost most of the gain).
    optimise(alt, schedule, alt_error);
    const std::uint64_t error = total_error(s);
    const std::vector<std::uint16_t> ca = s.ca, cb = s.cb;
    const std::vector<std::uint8_t> mode = s.mode;
    const std::vector<std::uint32_t> mod = s.mod;
    if (crossover(s, alt, schedule.crossover_alpha_weight, seeds) == 0) return;
    choose_modulation(s);
    const std::uint64_t descended = refine_modulation_2bpp(s, schedule.crossover_descent_2bpp);
    const std::uint64_t e = search_endpoints_2bpp(s, descended, &seeds);
    if (e < error) return;
    s.ca = ca;  // the first encoding alone was better
    s.cb = cb;
    s.mode = mode;
    s.mod = mod;
    return;
  }
  // The dilation start goes straight to the exact search (see schedule.cpp).
  run_exact_search(alt, schedule.crossover_search);
  crossover(s, alt, schedule.crossover_alpha_weight, seeds);
  choose_modulation(s);
  run_exact_search(s, schedule.crossover_search, &seeds);
}

}  // namespace tessera::pvrtc::detail
