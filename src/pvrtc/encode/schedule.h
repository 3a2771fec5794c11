// schedule.h — what each quality level runs, resolved once per encode.
//
// `resolve_schedule` turns (quality, format, the `iterations` and `exact_search_rounds`
// overrides of EncodeOptions) into one `EncodeSchedule`, as astcenc resolves its presets into a
// config: encode.cpp and passes.cpp read only the schedule, never the quality. The table of
// presets (one row per quality x format) is in schedule.cpp; the measurements behind each
// choice are in docs/benchmarks/pvrtc_history.md.
#pragma once

#include <cstdint>

#include "tessera/pvrtc.h"

namespace tessera::pvrtc::detail {

/// One run of the 4 bpp exact search (exact_search.cpp, `search_endpoints_4bpp`); `rounds` 0: not
/// run.
struct ExactSearchStep {
  int rounds = 0;  ///< Round bound; rounds stop early once no block changed.
  int passes = 1;  ///< Sweeps of the move list per block visit.
  /// Blocks whose exact 7x7-window error is at most this are skipped.
  std::uint32_t min_error = 0;
  bool neighbour_moves = false;  ///< Also try copying a neighbour's A, B or both.
};

/// The passes of one encode, in the order they run (encode.cpp, then passes.cpp).
struct EncodeSchedule {
  // --- start (encode/start/) and modulation (encode/modulation/)
  /// Initial endpoints: the paper's intensity dilation (dilation.cpp) when true, else the
  /// principal-axis split of each block's bilinear footprint (principal_axis.cpp).
  bool dilation_start = true;
  /// 4 bpp: also try modulation mode 1 (weights 0, 4, 8) on every block.
  bool try_mode1 = false;
  /// 2 bpp: sweeps of the exact modulation descent after every modulation choice of the
  /// refinement (modulation_2bpp_descent.cpp); 0: none.
  int modulation_descent = 0;

  // --- reseed (4 bpp, exact_search.cpp `reseed`), before the refinement
  int reseed_passes = 0;  ///< 0: none; pass k > 0 visits only blocks next to changed ones.
  std::uint32_t reseed_min_error = 0;  ///< Blocks at most this (exact 7x7-window error) are kept.
  int reseed_alpha_weight = 1;         ///< The squared alpha error counts this many times.

  // --- least-squares refinement (least_squares_refinement.cpp)
  int refinement_sweeps = 0;  ///< At most this many sweeps; stops early when one gains too little.

  // --- exact search
  ExactSearchStep exact_search = {};  ///< 4 bpp, after the refinement.
  /// 2 bpp: sweeps of the modulation descent before the exact endpoint search; 0: none.
  int descent_before_endpoint_search = 0;
  /// 2 bpp: the exact endpoint search (exact_search_2bpp.cpp, `search_endpoints_2bpp`).
  bool endpoint_search_2bpp = false;

  // --- crossover (crossover.cpp) with a second encoding from the dilation start
  bool crossover = false;
  int crossover_alpha_weight = 1;  ///< Alpha weight of the per-block comparison.
  /// 4 bpp: the second encoding goes straight from its start to this search; the first then
  /// resumes it on the blocks where the two were mixed. 2 bpp: the second encoding runs the
  /// same passes as the first (the whole schedule above).
  ExactSearchStep crossover_search = {};
  /// 2 bpp: descent sweeps on the crossed result before its endpoint search resumes.
  int crossover_descent_2bpp = 0;
};

/// The schedule of `quality` at `format`, with the overrides of `EncodeOptions`:
/// `iterations` >= 0 replaces the refinement sweeps, `exact_search_rounds` > 0 replaces the
/// preset's exact search (4 bpp: that many rounds, 4 passes, blocks above 3000; 2 bpp: no
/// endpoint search); either override turns the crossover off.
EncodeSchedule resolve_schedule(Quality quality, Format format, int iterations,
                                int exact_search_rounds);

}  // namespace tessera::pvrtc::detail
