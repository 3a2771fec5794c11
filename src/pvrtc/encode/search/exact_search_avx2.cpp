// exact_search_avx2.cpp — the window evaluators of the 4 bpp exact search (exact_search_kernel.h)
// over the SIMD wrapper's 8-lane types (core/simd_wide.h): `local_error_avx2` four texels (16
// lanes) a vector and 8 a step instead of two and four, `planar_error_avx2` 16 texels a step
// instead of 8. The same operations lane for lane, so the same per-texel errors; only the bound
// is checked less often (every 8 / 16 texels), which changes nothing below the bound.
//
// Compiled with -mavx2 (src/CMakeLists.txt), which gives the wrapper its AVX2 backend, and
// called only after the run-time CPU check in exact_search.cpp. So that no AVX2 code can stand
// in for baseline code elsewhere, the wrapper's functions compiled here live in their own
// inline namespace (simd_int.h); otherwise this file includes no header with inline functions
// or templates of external linkage (not exact_search_kernel.h or pvrtc_kernel.h) and keeps its
// helpers in an anonymous namespace; it exports the three functions of exact_search_window.h
// only.
#include "pvrtc/encode/search/exact_search_window.h"

#if defined(TESSERA_HAVE_AVX2_KERNELS) && !defined(__AVX2__)
#error "exact_search_avx2.cpp must be compiled with -mavx2 where TESSERA_HAVE_AVX2_KERNELS is set"
#endif

#if defined(__AVX2__)

#include "core/simd.h"
#include "pvrtc/encode/search/exact_search_wide.h"

namespace tessera::pvrtc::detail {

namespace {

using namespace simd;

/// Squared errors of texels k .. k + 3's blends, lanes (texel RG, texel BA) x 4, as `pair_sq`
/// of local_error_simd_t: blends 0 (A), 8 (B), 3, 5, 4 and 4 with alpha punched through.
struct QuadSq {
  vint8 e0, e8, e3, e5, e4, e4p;
};

template <bool kAlpha>
inline void quad_sq(const LocalWindow& lw, int k, vu16x16 av, vu16x16 bv, vu16x16 aw,
                    QuadSq& o) {
  const vu16x16 own = load_u16x16(&lw.own16[k][0]);
  // Bilinear sums S (weights sum to 16); 8-bit colour (2S >> 7) + (2S >> 2), alpha
  // (2S >> 5) + (2S >> 1) (the alpha lanes: select_alpha).
  const vu16x16 sa = load_u16x16(&lw.rest16_a[k][0]) + mullo(own, av);
  const vu16x16 sb = load_u16x16(&lw.rest16_b[k][0]) + mullo(own, bv);
  vu16x16 ua = srl<6>(sa) + srl<1>(sa);
  vu16x16 ub = srl<6>(sb) + srl<1>(sb);
  if constexpr (kAlpha) {
    ua = select_alpha(ua, srl<4>(sa) + sa);
    ub = select_alpha(ub, srl<4>(sb) + sb);
  }
  const vu16x16 t = load_u16x16(&lw.t16[k][0]);
  auto err = [&](vu16x16 v) {
    const vu16x16 d = v - t;
    return kAlpha ? madd(d, mullo(d, aw)) : madd(d, d);
  };
  // Blends 4 (A + B) +- (A - B) >> 3 for m = 3, 5 (wrapping lanes, exact results) and
  // (A + B) >> 1 for m = 4, as the baseline.
  const vu16x16 sum = ua + ub, sum2 = sum + sum, sum4 = sum2 + sum2, diff = ua - ub;
  o.e0 = err(ua);
  o.e8 = err(ub);
  o.e3 = err(srl<3>(sum4 + diff));
  o.e5 = err(srl<3>(sum4 - diff));
  const vu16x16 v4 = srl<1>(sum);
  o.e4 = err(v4);
  if constexpr (kAlpha) o.e4p = err(select_alpha(v4, vu16x16()));
}

/// Texels 8s .. 8s + 7 of a LocalWindow bias array (texel k at element 2k), in the lane order
/// of pair_sums of two quads: texels (0 1 4 5 | 2 3 6 7).
inline vint8 bias8(const std::int32_t (*rows)[4], int s) {
  return even_lanes(load8(rows[4 * s]), load8(rows[4 * s + 2]));
}

// Eight texels a step: the per-texel sums of two quads' lanes (texels 0 1 4 5 | 2 3 6 7), then
// the minimum over the blends. The baseline takes it in float lanes (SSE2 has no 32-bit
// integer min; exact there, see exact_search_kernel.h); the exact integer minimum is the same
// number.
template <bool kAlpha, bool kStore>
std::uint32_t local_error_t(const LocalWindow& lw, const std::int32_t a[4],
                            const std::int32_t b[4], std::uint32_t bound,
                            std::uint32_t* texel_err) {
  const vu16x16 av = broadcast_endpoint(a), bv = broadcast_endpoint(b);
  const vu16x8 aw8 = load_u16x8(lw.weight16);
  const vu16x16 aw(aw8, aw8);
  vint8 acc;
  for (int s = 0; s < 7; ++s) {
    QuadSq x, y;
    quad_sq<kAlpha>(lw, 8 * s, av, bv, aw, x);
    quad_sq<kAlpha>(lw, 8 * s + 4, av, bv, aw, y);
    const vint8 b35 = bias8(lw.bias35, s);
    vint8 m4 = pair_sums(x.e4, y.e4) + bias8(lw.bias4, s);
    if constexpr (kAlpha) m4 = min(m4, pair_sums(x.e4p, y.e4p) + bias8(lw.bias4p, s));
    const vint8 m = min(min(min(pair_sums(x.e0, y.e0), pair_sums(x.e8, y.e8)),
                            min(pair_sums(x.e3, y.e3) + b35, pair_sums(x.e5, y.e5) + b35)),
                        m4);
    acc += m;
    if constexpr (kStore) {
      // Back to texel order; the last step stores texels 48-51 only.
      const vint8 ordered = permute64<0, 2, 1, 3>(m);
      std::int32_t* out = reinterpret_cast<std::int32_t*>(texel_err + 8 * s);
      if (s < 6) {
        store8(ordered, out);
      } else {
        store4(low(ordered), out);
      }
    } else {
      if (std::uint32_t(sum_lanes(acc)) >= bound) break;
    }
  }
  return std::uint32_t(sum_lanes(acc));
}

/// 16 texels (o .. o + 15; kTail: o .. o + 7) of channel c: the minimum over the slots of
/// (2^23 + d^2) + rest as planar_error, as two vectors of 8 float lanes (texels in order).
/// The 16-bit lanes are in the order (0-3 8-11 | 4-7 12-15) (loads permuted by 64-bit units),
/// so that each half's low / high four lanes widen to texels 0-7 / 8-15.
template <bool kTail>
inline vint8 planar_group(const PlanarWindow& pw, int c, int o, vu16x16 a16, vu16x16 b16) {
  auto load = [&](const std::uint16_t* p) {
    const vu16x16 v = kTail ? vu16x16(load_u16x8(p), vu16x8()) : load_u16x16(p);
    return permute64<0, 2, 1, 3>(v);
  };
  const vu16x16 own = load(&pw.own[o]);
  const vu16x16 sa = load(&pw.ra[c][o]) + mullo(own, a16);
  const vu16x16 sb = load(&pw.rb[c][o]) + mullo(own, b16);
  const vu16x16 ua = srl<6>(sa) + srl<1>(sa);
  const vu16x16 ub = srl<6>(sb) + srl<1>(sb);
  const vu16x16 sum = ua + ub, sum2 = sum + sum, sum4 = sum2 + sum2, diff = ua - ub;
  const vu16x16 bl[5] = {ua, ub, srl<3>(sum4 + diff), srl<3>(sum4 - diff), srl<1>(sum)};
  const vu16x16 t = load(&pw.t[c][o]);
  vf8 mlo, mhi;
  for (int sl = 0; sl < PlanarWindow::kSlots; ++sl) {
    const vu16x16 d = bl[sl] - t;
    const vu16x16 sq = mullo(d, d);
    // (2^23 + d^2) + (total - e - 2^23): exact integers below 2^24.
    const vf8 lo = f2p23_plus_lo(sq) + loadf8(&pw.rest[c][sl][o]);
    mlo = sl == 0 ? lo : min(mlo, lo);
    if constexpr (!kTail) {
      const vf8 hi = f2p23_plus_hi(sq) + loadf8(&pw.rest[c][sl][o + 8]);
      mhi = sl == 0 ? hi : min(mhi, hi);
    }
  }
  if constexpr (kTail) return to_int_trunc(mlo);
  return to_int_trunc(mlo) + to_int_trunc(mhi);
}

}  // namespace

std::uint32_t local_error_avx2(const LocalWindow& lw, const std::int32_t a[4],
                               const std::int32_t b[4], std::uint32_t bound) {
  return lw.nch == 4 ? local_error_t<true, false>(lw, a, b, bound, nullptr)
                     : local_error_t<false, false>(lw, a, b, bound, nullptr);
}

std::uint32_t local_error_store_avx2(const LocalWindow& lw, const std::int32_t a[4],
                                     const std::int32_t b[4], std::uint32_t* texel_err) {
  return lw.nch == 4 ? local_error_t<true, true>(lw, a, b, 0, texel_err)
                     : local_error_t<false, true>(lw, a, b, 0, texel_err);
}

std::uint32_t planar_error_avx2(const PlanarWindow& pw, int c, std::int32_t av, std::int32_t bv,
                                std::uint32_t bound) {
  const vu16x16 a16(static_cast<std::uint16_t>(av)), b16(static_cast<std::uint16_t>(bv));
  vint8 acc;
  for (int o = 0; o < 48; o += 16) {
    acc += planar_group<false>(pw, c, o, a16, b16);
    if (std::uint32_t(sum_lanes(acc)) >= bound) return std::uint32_t(sum_lanes(acc));
  }
  return std::uint32_t(sum_lanes(acc + planar_group<true>(pw, c, 48, a16, b16)));
}

}  // namespace tessera::pvrtc::detail

#else  // no AVX2 kernels in this build: polish_avx2_active() is false

namespace tessera::pvrtc::detail {

std::uint32_t local_error_avx2(const LocalWindow&, const std::int32_t*, const std::int32_t*,
                               std::uint32_t) {
  return 0;
}
std::uint32_t local_error_store_avx2(const LocalWindow&, const std::int32_t*,
                                     const std::int32_t*, std::uint32_t*) {
  return 0;
}
std::uint32_t planar_error_avx2(const PlanarWindow&, int, std::int32_t, std::int32_t,
                                std::uint32_t) {
  return 0;
}

}  // namespace tessera::pvrtc::detail

#endif
