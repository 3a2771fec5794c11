// encode_internal.h — state shared by the PVRTC encoder passes (dilation, modulation,
// refinement). One `EncoderState` is owned by one `encode` call.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "core/check.h"
#include "pvrtc/encode/progress.h"
#include "pvrtc/encode/schedule.h"
#include "pvrtc/format/pvrtc_internal.h"

namespace tessera::pvrtc::detail {

struct EncoderState {
  Grid g;
  bool alpha_mode = false;  ///< Translucent endpoints and alpha error are allowed/counted.
  bool punch = false;       ///< Punch-through (4 bpp mode 1 code 2) may be used.
  bool mode1 = false;       ///< 4 bpp: also try mode 1 (weights 0, 4, 8) on every block.
  int threads = 0;
  /// 2 bpp: coordinate-descent sweeps after every modulation choice of the refinement
  /// (`refine_modulation_2bpp`); 0: none.
  int modulation_descent = 0;
  /// Where the pass running now reports its progress (progress.h): callers set the range of
  /// the pass they call; inactive without a hook.
  Progress progress;
  /// Padded target texels (pw * ph RGBA; the source tiled; alpha 255 unless alpha_mode): the
  /// caller's pixels themselves when they already are exactly that, else `target_storage`.
  std::span<const std::uint8_t> target;
  /// Owns the target when it had to be built (shared: copies of the state share it).
  std::shared_ptr<const std::uint8_t[]> target_storage;
  /// Makes a new buffer of `bytes` the target, owned by the state, and returns it for the
  /// caller to fill (it is not zeroed first: the caller writes every byte).
  std::uint8_t* new_target(std::size_t bytes) {
    std::shared_ptr<std::uint8_t[]> p(new std::uint8_t[bytes]);
    std::uint8_t* d = p.get();
    target = std::span<const std::uint8_t>(d, bytes);
    target_storage = std::move(p);
    return d;
  }
  /// Makes `pixels` the target, owned by the state (no copy).
  void own_target(std::vector<std::uint8_t> pixels) {
    auto v = std::make_shared<const std::vector<std::uint8_t>>(std::move(pixels));
    target = std::span<const std::uint8_t>(*v);
    target_storage = std::shared_ptr<const std::uint8_t[]>(v, v->data());
  }
  /// Packed endpoint fields per block, linear order (A: bits 1-15 of its 16-bit field).
  std::vector<std::uint16_t> ca, cb;
  std::vector<std::uint8_t> mode;  ///< Modulation mode bit per block.
  std::vector<std::uint32_t> mod;  ///< Modulation bits per block.
  /// Effective modulation map (pw * ph) used by the refinement passes.
  std::vector<std::uint8_t> scratch_m;
  /// `EncodeOptions::alpha_weighted` (4 bpp, alpha mode only): per padded texel (pw * ph) the
  /// scale (3..16) of its colour differences (`colour_scale_of` of its target alpha); every score
  /// of the 4 bpp encoder then counts (`scale_diff(d, scale)`)^2 for a colour difference d.
  /// Empty: unweighted.
  std::vector<std::uint8_t> colour_scale;
  bool weighted() const { return !colour_scale.empty(); }

  std::uint64_t word(std::size_t i) const {
    TESSERA_DCHECK(i < ca.size() && i < cb.size() && i < mode.size() && i < mod.size());
    TESSERA_DCHECK(mode[i] <= 1 && (ca[i] & 1) == 0);  // the mode bit sits in bit 0 of A's field
    return std::uint64_t(mod[i]) | (std::uint64_t(ca[i] | mode[i]) << 32) |
           (std::uint64_t(cb[i]) << 48);
  }
  std::vector<std::uint64_t> words() const {
    std::vector<std::uint64_t> w(ca.size());
    for (std::size_t i = 0; i < w.size(); ++i) w[i] = word(i);
    return w;
  }
};

/// The smallest colour scale (`colour_scale_of`): invisible texels keep a weight of 9 / 256.
/// Weight 0 leaves every move that only they see a tie, so the greedy searches and the
/// least-squares fits stop wherever they start on them (mostly transparent blocks then hold
/// endpoints that suit neither their visible texels nor the blocks around them); a small weight
/// pulls them towards the texels' own (with --alpha-bleed: the nearest visible) colour.
/// Measured on the sprites of bench/pvrtc_assets.py (docs/benchmarks/pvrtc_assets.md).
constexpr std::uint16_t kMinColourScale = 3;

/// The colour scale of a texel of alpha `a` with `EncodeOptions::alpha_weighted`: 16 a / 255
/// rounded, at least kMinColourScale (3..16; exactly 16 for a = 255, so opaque texels weigh
/// what they weigh unweighted). The colour difference a renderer shows after blending is about
/// alpha times the stored one.
constexpr std::uint16_t colour_scale_of(std::uint8_t a) {
  const auto s = std::uint16_t((std::uint32_t(a) * 16 + 127) / 255);
  return s < kMinColourScale ? kMinColourScale : s;
}

/// A colour difference `d` (|d| <= 255) scaled by `scale` / 16 (scale 0..16), rounded half up:
/// floor((d scale + 8) / 16). Exactly d for scale 16, and |result| <= |d| for every scale
/// (|d scale / 16| <= |d|, and rounding to the nearest integer cannot pass the integer d), so
/// every bound that holds for the unweighted squared errors holds for the weighted ones. The
/// SIMD kernels compute the same value in wrapping u16 lanes: d scale + 4104 lies in
/// [24, 8184] (|d scale| <= 4080), so a logical shift by 4 and subtracting 256 floors exactly.
constexpr std::int32_t scale_diff(std::int32_t d, std::int32_t scale) {
  return (d * scale + 8) >> 4;
}

/// Calls fn(bx, by) for every block in the 2x2 colouring of the refinement and the searches:
/// the four classes (bx & 1, by & 1) one after the other, the blocks of one class in parallel
/// (two rows of a class apart by at least one row, so blocks of one class share no texel
/// window); deterministic for any thread count when fn touches only its block's window.
template <class Fn>
void for_each_block_2x2(const Grid& g, int threads, Fn&& fn) {
  for (int cls = 0; cls < 4; ++cls) {
    const int ox = cls & 1, oy = cls >> 1;
    parallel_for(0, g.nby / 2, 4,
                 [&](std::int64_t r0, std::int64_t r1) {
                   for (int r = int(r0); r < int(r1); ++r) {
                     TESSERA_DCHECK(2 * r + oy < g.nby);
                     for (int bx = ox; bx < g.nbx; bx += 2) fn(bx, 2 * r + oy);
                   }
                 },
                 {threads});
  }
}

/// Eight steps of power iteration for the principal axis of the `nch` x `nch` covariance `cov`,
/// from the start in `axis` (unit length on return). Stops early and returns false when the
/// next vector's squared length falls below `eps` (no dominant direction: `axis` keeps the last
/// good value); true otherwise. Float for the block-local searches, double for the footprint.
template <class T>
bool principal_axis(const T (&cov)[4][4], int nch, T (&axis)[4], T eps) {
  for (int it = 0; it < 8; ++it) {
    T n[4] = {0, 0, 0, 0}, len = 0;
    for (int a = 0; a < nch; ++a) {
      for (int b = 0; b < nch; ++b) n[a] += cov[a][b] * axis[b];
      len += n[a] * n[a];
    }
    if (len < eps) return false;
    len = std::sqrt(len);
    for (int a = 0; a < nch; ++a) axis[a] = n[a] / len;
  }
  return true;
}

/// Quantises a float RGBA endpoint (8-bit scale) to a packed endpoint field, choosing opaque or
/// translucent (when `allow_translucent`) by the smaller quantisation error.
std::uint16_t quantise_endpoint(const float c[4], bool is_b, bool allow_translucent);

/// Candidate endpoint pairs from a set of texels (block-local searches): the texels are split
/// by the sign of their projection on the principal axis of their `nch` colour channels.
struct SplitPairs {
  /// (A, B) fields: the half means (dark A, bright B) and the reverse, then the two extreme
  /// texels (darkest A, brightest B) and the reverse.
  std::uint16_t pairs[4][2];
  /// Single endpoints for pairing with a block's current A or B.
  std::uint16_t low_mean_a, high_mean_b, low_extreme_a, high_extreme_b;
};
/// Fills `out` from `n` texels `px` (RGBA floats, 8-bit scale); `translucent` allows the
/// translucent endpoint formats. False when the texels have no dominant axis or one side of the
/// split is empty (then `out` is not written).
bool split_pairs(const float (*px)[4], int n, int nch, bool translucent, SplitPairs& out);

/// The paper's initial endpoints: intensity labelling, 3x dilation of extrema, block averages.
/// Writes low (A) and high (B) float RGBA per block (4 floats each, linear block order). With
/// `flat`, also one byte per block: 1 where all the block's texels have the same intensity
/// (its brightest and darkest texel are the same one), which every uniform block is.
void dilation_endpoints(const EncoderState& s, std::vector<float>& low, std::vector<float>& high,
                        std::vector<std::uint8_t>* flat = nullptr);

/// Principal-axis endpoints over each block's bilinear footprint (see principal_axis.cpp); same
/// output layout as `dilation_endpoints`.
void principal_endpoints(const EncoderState& s, std::vector<float>& low, std::vector<float>& high);

/// Swaps the endpoints of blocks whose pair is about equally bright (luma difference under 0.3
/// of the colour distance) so that neighbouring blocks store their colours on the same side (see
/// principal_axis.cpp); `nch` channels (3, or 4 with alpha) count in the distances.
void orient_endpoints(const Grid& g, int nch, std::vector<float>& low, std::vector<float>& high);

/// Brute-force modulation for the current endpoints (exact decoder arithmetic); chooses the
/// per-block mode (punch-through for 4 bpp, direct vs interpolated for 2 bpp).
/// Returns the total error of the result (as `total_error`).
std::uint64_t choose_modulation(EncoderState& s);

/// Sum of squared errors of the exact decode against the target (RGB, + alpha in alpha mode;
/// colour differences scaled by `colour_scale` where the state has one).
std::uint64_t total_error(const EncoderState& s);

/// Least-squares refinement of endpoints with modulation fixed, alternating with
/// `choose_modulation`; keeps the best state. Runs at most `iterations` sweeps and stops early
/// when a sweep does not improve the error. `error` is the state's current total error (what
/// the `choose_modulation` that made its modulation returned), so no decode is spent on it.
void refine(EncoderState& s, int iterations, std::uint64_t error);

/// 4 bpp only: exact greedy search over +-1 perturbations of each block's endpoint codes,
/// keeping moves that lower the exact error of the block's texel window (see exact_search.cpp);
/// `passes` bounds the sweeps over the move list per block and round; blocks whose exact
/// window error (7x7 texels) is at most `min_error` are skipped. Re-chooses the modulation at
/// the end.
void search_endpoints_4bpp(EncoderState& s, int rounds, int passes, std::uint32_t min_error);

/// Extra choices of `search_endpoints_4bpp`.
struct EndpointSearchOptions {
  /// Also try each neighbour's A, B or both as the block's pair (high).
  bool neighbour_moves = false;
  /// One flag per block: the first round searches only flagged blocks; the others are searched
  /// once a neighbour changes. Null: every block.
  const std::vector<std::uint8_t>* seeds = nullptr;
};
void search_endpoints_4bpp(EncoderState& s, int rounds, int passes, std::uint32_t min_error,
                           const EndpointSearchOptions& options);

/// 4 bpp only: replaces the endpoints of blocks whose exact window error exceeds `min_error`
/// by pairs derived from the block's own texels where that lowers the exact window error
/// (see exact_search.cpp); modulation is left stale (call `choose_modulation`). `changed` (one flag
/// per block) is written with the blocks changed; when it already holds the previous pass's
/// flags, only blocks next to a changed one are visited. Returns the count changed.
int reseed(EncoderState& s, std::uint32_t min_error, std::vector<std::uint8_t>& changed);

/// The passes after the first modulation choice, as `schedule` says (see passes.cpp): reseed,
/// least-squares refinement, the exact search (4 bpp) or the modulation descent and exact
/// endpoint search (2 bpp). `error`: the state's current total error, as `choose_modulation`
/// returned it.
void optimise(EncoderState& s, const EncodeSchedule& schedule, std::uint64_t error);

/// Estimated costs of `optimise`, `optimise_alt` and `optimise_crossover` with `schedule` at
/// `format` (seconds per megapixel on one thread, for the progress reports; see passes.cpp).
double optimise_cost(const EncodeSchedule& schedule, Format format);
double alt_cost(const EncodeSchedule& schedule, Format format);
double crossover_cost(const EncodeSchedule& schedule, Format format);

/// 2 bpp only: with the endpoints fixed, re-chooses every stored modulation value by the exact
/// error of its texel and of the interpolated texels that read it, and the interpolation
/// variant of every interpolated block, in `sweeps` coordinate-descent sweeps (see
/// modulation_2bpp_descent.cpp). Returns the total error (as `total_error`).
std::uint64_t refine_modulation_2bpp(EncoderState& s, int sweeps);

/// 2 bpp only: exact greedy search over each block's endpoints (seeds from its texels,
/// neighbours' endpoints, +-1 code moves) scored over the 15x7 texels it influences, then the
/// modulation choice, its descent and the least-squares refinement again (see
/// exact_search_2bpp.cpp). The state changes only where the exact total error drops below `error`
/// (the state's current total error); returns the total error of the state left.
std::uint64_t search_endpoints_2bpp(EncoderState& s, std::uint64_t error);

/// `search_endpoints_2bpp` whose first round searches only the blocks flagged in `seeds` (one
/// flag per block; null: every block); the others are searched once a neighbour changes.
std::uint64_t search_endpoints_2bpp(EncoderState& s, std::uint64_t error,
                                    const std::vector<std::uint8_t>* seeds);

/// 2 bpp, for tests: the window score `search_endpoints_2bpp` gives block (bx, by) with the
/// endpoint fields (ca, cb) and every other block as in `s` (see exact_search_2bpp.cpp); stops once
/// it reaches `bound` (the result is then >= bound). `ordered`: texels summed in the search's order
/// (decreasing error under the block's current pair) instead of raster order.
std::uint32_t window_error_2bpp(const EncoderState& s, int bx, int by, std::uint16_t ca,
                                std::uint16_t cb, std::uint32_t bound, bool ordered);

/// Gives each block of `s` the endpoints of `other` (an encoding of the same target) where
/// those decode its own texels (4x4, or 8x4 at 2 bpp) with less error (alpha error counted
/// `alpha_weight` times); modulation is left stale. `seeds` gets one flag per block whose 3x3
/// neighbourhood mixes the two encodings (see crossover.cpp). Returns the count of blocks taken.
int crossover(EncoderState& s, const EncoderState& other, int alpha_weight,
              std::vector<std::uint8_t>& seeds);

/// high: runs the dilation-started encoding `alt` (endpoints and modulation set, total error
/// `alt_error`) through the passes of its format (4 bpp: `schedule.crossover_search`; 2 bpp:
/// `optimise` with `schedule`). It reads nothing of the first encoding, so the two may run at
/// the same time.
void optimise_alt(EncoderState& alt, std::uint64_t alt_error, const EncodeSchedule& schedule);

/// high: crosses the finished `alt` into `s` (see crossover.cpp) and resumes the exact search on
/// `s` where the two were mixed. 2 bpp: `s` changes only where its exact total error drops.
void optimise_crossover(EncoderState& s, const EncoderState& alt, const EncodeSchedule& schedule);

/// Normal maps (see modulation_angular.cpp): with the endpoints fixed, gives every texel the
/// modulation value whose decode makes the smallest angle with the target's vector (4 bpp; 2 bpp
/// blocks in direct mode; punch-through texels keep theirs). Deterministic for any thread count.
void choose_modulation_angular(EncoderState& s);

/// `reseed` with the squared alpha error counted `alpha_weight` times (the one above: 1).
int reseed(EncoderState& s, std::uint32_t min_error, std::vector<std::uint8_t>& changed,
           int alpha_weight);

}  // namespace tessera::pvrtc::detail
