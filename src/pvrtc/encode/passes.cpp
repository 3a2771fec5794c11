// PVRTC encoder passes after the first modulation choice, as the schedule (schedule.h) says:
// reseed (search/exact_search.cpp), least-squares refinement
// (search/least_squares_refinement.cpp), the exact search (search/exact_search.cpp; at 2 bpp
// modulation/modulation_2bpp_descent.cpp and search/exact_search_2bpp.cpp) and, for high, the
// crossover with a second encoding (search/crossover.cpp).
#include "pvrtc/encode/encode_internal.h"
#include "pvrtc/encode/schedule.h"

namespace tessera::pvrtc::detail {

namespace {

// Estimated costs of the passes, for the progress reports (progress.h): seconds per megapixel
// on one thread (1024x1024 procedural images, the mean of foliage and text); only their ratios
// matter.
constexpr double kReseedCost = 0.17;          // 4 bpp: one reseed pass and its modulation
constexpr double kSweepCost4 = 0.11;          // one refinement sweep (4 bpp; 2 bpp w/o descent)
constexpr double kSweepCost2 = 0.37;          // 2 bpp: one sweep with the modulation descent
constexpr double kSearchRoundCost = 0.25;     // 4 bpp: one round of the exact search (normal)
constexpr double kSearchConvergedCost = 3.5;  // 4 bpp: the exact search run to convergence
constexpr double kResumedSearchCost4 = 1.9;   // 4 bpp: the search resumed after the crossover
constexpr double kCrossoverCost = 0.12;       // the crossover and its modulation choice
constexpr double kDescentCost2 = 0.22;        // 2 bpp: one sweep of the modulation descent
constexpr double kEndpointSearchCost2 = 5.4;  // 2 bpp: `search_endpoints_2bpp`
constexpr double kResumedSearchCost2 = 3.3;   // 2 bpp: the same, seeded after the crossover

double search_cost(const ExactSearchStep& step) {
  if (step.rounds <= 0) return 0;
  return step.rounds >= 16 ? kSearchConvergedCost : step.rounds * kSearchRoundCost;
}

void run_exact_search(EncoderState& s, const ExactSearchStep& step,
                      const std::vector<std::uint8_t>* seeds = nullptr) {
  if (step.rounds <= 0) return;
  EndpointSearchOptions po;
  po.neighbour_moves = step.neighbour_moves;
  po.seeds = seeds;
  search_endpoints_4bpp(s, step.rounds, step.passes, step.min_error, po);
}

}  // namespace

double optimise_cost(const EncodeSchedule& schedule, Format format) {
  const bool four = format == Format::pvrtc1_4bpp;
  double c = schedule.refinement_sweeps *
             (four || schedule.modulation_descent == 0 ? kSweepCost4 : kSweepCost2);
  if (four) c += schedule.reseed_passes * kReseedCost + search_cost(schedule.exact_search);
  if (!four && schedule.endpoint_search_2bpp) {
    c += schedule.descent_before_endpoint_search * kDescentCost2 + kEndpointSearchCost2;
  }
  return c;
}

double alt_cost(const EncodeSchedule& schedule, Format format) {
  if (!schedule.crossover) return 0;
  return format == Format::pvrtc1_2bpp ? optimise_cost(schedule, format)
                                       : search_cost(schedule.crossover_search);
}

double crossover_cost(const EncodeSchedule& schedule, Format format) {
  if (!schedule.crossover) return 0;
  if (format == Format::pvrtc1_2bpp) {
    return kCrossoverCost + schedule.crossover_descent_2bpp * kDescentCost2 + kResumedSearchCost2;
  }
  return kCrossoverCost + kResumedSearchCost4;
}

void optimise(EncoderState& s, const EncodeSchedule& schedule, std::uint64_t error) {
  const bool four = s.g.format == Format::pvrtc1_4bpp;
  const Progress whole = s.progress;
  ProgressSteps steps(whole, optimise_cost(schedule, s.g.format));
  // Blocks whose footprint-wide start misses their own texels (thin features, stripes) get
  // endpoints from those texels where the exact error drops; a later pass visits only blocks
  // next to changed ones.
  if (four && schedule.reseed_passes > 0) {
    std::vector<std::uint8_t> changed;
    for (int pass = 0; pass < schedule.reseed_passes; ++pass) {
      s.progress = steps.next(kReseedCost);
      if (reseed(s, schedule.reseed_min_error, changed, schedule.reseed_alpha_weight) == 0) break;
      error = choose_modulation(s);
    }
  }
  s.progress = steps.next(schedule.refinement_sweeps *
                          (four || schedule.modulation_descent == 0 ? kSweepCost4 : kSweepCost2));
  if (schedule.refinement_sweeps > 0) refine(s, schedule.refinement_sweeps, error);
  // 4 bpp: the exact search over +-1 moves of each block's endpoint codes (blocks are revisited
  // only after a neighbour changed, see exact_search.cpp).
  if (four) {
    s.progress = steps.next(search_cost(schedule.exact_search));
    run_exact_search(s, schedule.exact_search);
  }
  if (!four && schedule.endpoint_search_2bpp) {
    // More sweeps of the modulation descent (the refinement ran one after every modulation
    // choice), then the exact endpoint search, which re-chooses the modulation, descends and
    // refines again after it.
    s.progress = steps.next(schedule.descent_before_endpoint_search * kDescentCost2);
    const std::uint64_t e = refine_modulation_2bpp(s, schedule.descent_before_endpoint_search);
    s.progress = steps.next(kEndpointSearchCost2);
    search_endpoints_2bpp(s, e);
  }
  s.progress = whole;
}

// The second encoding of the crossover: from the dilation start, 2 bpp through the same passes
// as the first encoding (a cheaper second one, the endpoint search straight from the dilation,
// lost most of the gain), 4 bpp straight to the exact search (see schedule.cpp).
void optimise_alt(EncoderState& alt, std::uint64_t alt_error, const EncodeSchedule& schedule) {
  if (alt.g.format == Format::pvrtc1_2bpp) {
    optimise(alt, schedule, alt_error);
  } else {
    run_exact_search(alt, schedule.crossover_search);
  }
}

// The crossover with the second encoding (crossover.cpp): the two starts stop in different
// local minima, the dilation one wins along sharp edges.
void optimise_crossover(EncoderState& s, const EncoderState& alt, const EncodeSchedule& schedule) {
  const Progress whole = s.progress;
  ProgressSteps steps(whole, crossover_cost(schedule, s.g.format));
  std::vector<std::uint8_t> seeds;
  if (s.g.format == Format::pvrtc1_2bpp) {
    s.progress = steps.next(kCrossoverCost);
    const std::uint64_t error = total_error(s);
    const std::vector<std::uint16_t> ca = s.ca, cb = s.cb;
    const std::vector<std::uint8_t> mode = s.mode;
    const std::vector<std::uint32_t> mod = s.mod;
    if (crossover(s, alt, schedule.crossover_alpha_weight, seeds) == 0) return;
    choose_modulation(s);
    s.progress = steps.next(schedule.crossover_descent_2bpp * kDescentCost2);
    const std::uint64_t descended = refine_modulation_2bpp(s, schedule.crossover_descent_2bpp);
    s.progress = steps.next(kResumedSearchCost2);
    const std::uint64_t e = search_endpoints_2bpp(s, descended, &seeds);
    s.progress = whole;
    if (e < error) return;
    s.ca = ca;  // the first encoding alone was better
    s.cb = cb;
    s.mode = mode;
    s.mod = mod;
    return;
  }
  s.progress = steps.next(kCrossoverCost);
  crossover(s, alt, schedule.crossover_alpha_weight, seeds);
  choose_modulation(s);
  s.progress = steps.next(kResumedSearchCost4);
  run_exact_search(s, schedule.crossover_search, &seeds);
  s.progress = whole;
}

}  // namespace tessera::pvrtc::detail
