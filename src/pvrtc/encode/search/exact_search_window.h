// exact_search_window.h — the window layouts of the PVRTC exact searches (4 bpp: exact_search.cpp,
// 2 bpp: exact_search_2bpp.cpp) and the AVX2 entry points of their window evaluators
// (exact_search_avx2.cpp and exact_search_2bpp_avx2.cpp, compiled with -mavx2): the baseline
// ones are in exact_search_kernel.h, which includes this header, and exact_search_2bpp.cpp (the
// evaluators themselves: exact_search_evaluators.h and exact_search_2bpp_evaluator.h).
//
// Included by the -mavx2 translation unit, so it holds plain declarations and trivial structs
// only: nothing here may be an inline function, a template or a member initialiser, nor may it
// include a standard header that defines inline functions (the linker could keep an AVX2 copy
// of one for the whole program).
#pragma once

#include <cstdint>

namespace tessera::pvrtc::detail {

// The 7x7 texels block j influences (its bilinear weight is 0 elsewhere), with the other three
// blocks' share of each texel's A and B sums precomputed, so a candidate pair for block j costs
// one multiply-add per channel and endpoint per texel. Exact: same arithmetic as the decoder.
struct LocalWindow {
  // Per texel, 16-bit, padded to 56 texels (texels 49-55 all zero: error 0) for the SIMD paths:
  // `rest16_a` / `rest16_b` the other blocks' share of the A / B bilinear sums (channels past
  // nch zero), `own16` block j's weight in the channel lanes, `t16` the target (alpha lane 0
  // if RGB), `bias35` / `bias4` / `bias4p` exclude the blends a texel's block mode lacks (4p:
  // weight 4 with alpha punched through, mode 1 with punch-through allowed only).
  alignas(16) std::uint16_t rest16_a[56][4], rest16_b[56][4], own16[56][4], t16[56][4];
  alignas(16) std::int32_t bias35[28][4], bias4[28][4], bias4p[28][4];
  int nch;
  bool punch;
  alignas(16) std::uint16_t weight16[8];  ///< Per-lane error weights (RGBA RGBA).
  /// Alpha-weighted colour error (`weighted`, which the AVX2 evaluators read too): per texel, the
  /// scale of its colour differences in the colour lanes (0..16) and 16 in the alpha lane
  /// (alpha differences as they are); pads 0. Not written otherwise.
  alignas(16) std::uint16_t scale16[56][4];
  bool weighted;
};

// A block's window in channel-planar form (texels in the LocalWindow's order, 8 per vector,
// 49-55 zero pads), with, for the block's current pair, each texel's error per blend slot
// (0: weight 0, 1: weight 8, 2: weight 3, 3: weight 5, 4: weight 4, or with alpha punched
// through where that is less) over all channels (`total`), and each colour channel's part of it
// (`e`). A candidate changing only colour channel c then scores, per texel, the minimum over
// the slots of total - e[c] (`rest[c]`, precomputed) plus the candidate's squared error in c.
struct PlanarWindow {
  static constexpr int kGroups = 7;
  static constexpr int kSlots = 5;
  // Excluded blends (not in the texel's block mode): 2^22 added to the slot's error keeps every
  // float below 2^24 (exact) and far above any real texel error (at most 5 * 255^2).
  static constexpr std::int32_t kExclude = 1 << 22;
  alignas(16) std::uint16_t ra[4][56], rb[4][56], t[4][56], own[56];
  alignas(16) std::int32_t excl35[56], excl4[56], excl4p[56];
  alignas(16) std::uint16_t e[3][kSlots][56];
  alignas(16) float total[kSlots][56];
  alignas(16) float rest[3][kSlots][56];  ///< total - e[c] - 2^23.
  int nch;
  std::int32_t alpha_weight;
  /// Alpha-weighted colour error (`weighted`): each texel's colour scale (LocalWindow::scale16).
  alignas(16) std::uint16_t scale[56];
  bool weighted;
};

// The AVX2 evaluators (exact_search_evaluators.h with the 8-lane types; alpha-weighted where
// lw.weighted / pw.weighted): the same integers as `local_error_simd` / `local_error_weighted` /
// `local_error_simd_t<.., true, ..>` / `planar_error_t` of exact_search_kernel.h (the endpoints
// as (r, g, b, a) 5-bit values), twice the texels a step; a bounded result below the bound is
// exact, else it is >= bound (the bound is checked every 8 / 16 texels instead of 4 / 8). Call
// only where `exact_search_avx2_active()`; in a build without the AVX2 kernels they return 0.

/// The window error of block j's endpoints (a, b); stops once it reaches `bound`.
std::uint32_t local_error_avx2(const LocalWindow& lw, const std::int32_t a[4],
                               const std::int32_t b[4], std::uint32_t bound);
/// The window error of (a, b), no bound, with each texel's error in texel_err[0 .. 52) (slots
/// in layout order; 49-51 are pads, error 0).
std::uint32_t local_error_store_avx2(const LocalWindow& lw, const std::int32_t a[4],
                                     const std::int32_t b[4], std::uint32_t* texel_err);
/// The window error with colour channel c (< 3) of A and B set to av, bv (after planar_refresh
/// and planar_rest(c)); stops once it reaches `bound`.
std::uint32_t planar_error_avx2(const PlanarWindow& pw, int c, std::int32_t av, std::int32_t bv,
                                std::uint32_t bound);

// 2 bpp: one block's window, the 15x7 texels its A and B reach (exact_search_2bpp.cpp). Per texel
// (slots 105-111 zero: error 0) the other blocks' share of the bilinear A and B sums in the
// channel lanes (weights summing to 32), the block's own bilinear weight, the target (alpha lane
// 0 for RGB input) and the blends its mode excludes.
struct Window2 {
  static constexpr int kWidth = 15, kHeight = 7;
  static constexpr int kTexels = kWidth * kHeight;  // 105
  static constexpr int kSlots = 112;                // padded to whole steps of eight texels
  // Added to the error of a blend the texel cannot take: far above any real error, and still
  // exact once converted to float.
  static constexpr std::int32_t kExclude = 1 << 24;
  alignas(32) std::uint16_t rest_a[kSlots][4], rest_b[kSlots][4], own[kSlots][4], t[kSlots][4];
  alignas(32) std::int32_t bias35[kSlots], bias4[kSlots];  ///< weights 3 / 5, and 4
  alignas(16) std::uint16_t weight16[8];                   ///< per-lane error weights
  int nch;
};

/// 2 bpp: the window error of the block's endpoints (a, b) as exact_search_2bpp.cpp's baseline,
/// eight texels a step instead of four; stops once it reaches `bound` (checked every 8 texels).
std::uint32_t window2_error_avx2(const Window2& w, const std::int32_t a[4], const std::int32_t b[4],
                                 std::uint32_t bound);
/// 2 bpp: the window error of (a, b), no bound, with each slot's error in texel_err[0 .. 112).
std::uint32_t window2_error_store_avx2(const Window2& w, const std::int32_t a[4],
                                       const std::int32_t b[4], std::uint32_t* texel_err);

/// True when search_endpoints_4bpp() (and the 2 bpp search) use the AVX2 evaluators: the build has
/// them, the CPU (and OS) can run them, it is not the scalar build (TESSERA_NO_SIMD) and the tests
/// have not switched them off.
bool exact_search_avx2_active();

/// Tests: true makes search_endpoints_4bpp() and reseed() use the baseline evaluators even where
/// the AVX2 ones run (the output is the same). Returns the previous setting. Not for use while
/// encoding.
bool set_exact_search_baseline_only(bool on);

}  // namespace tessera::pvrtc::detail
