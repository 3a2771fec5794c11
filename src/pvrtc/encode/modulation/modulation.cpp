// Modulation choice for fixed endpoints (exact decoder arithmetic) and the total error of a
// state: the 4 bpp brute force over the blends of both modes (planar SIMD, written once in
// modulation_blends.h: 8 texels at a time through modulation_kernel.h, or 16 with AVX2 where
// the CPU has it through modulation_avx2.cpp, alpha-weighted or not); the 2 bpp direct /
// interpolated choice is in modulation_2bpp.cpp.
#include <algorithm>
#include <atomic>
#include <limits>

#include "pvrtc/encode/encode_internal.h"
#include "pvrtc/encode/modulation/modulation_2bpp.h"
#include "pvrtc/encode/modulation/modulation_avx2.h"
#include "pvrtc/encode/modulation/modulation_kernel.h"
#include "pvrtc/encode/modulation/planar_endpoints.h"

namespace tessera::pvrtc::detail {

namespace {

std::atomic<bool> g_baseline_only{false};

/// The AVX2 block-row kernel runs here (checked once): built with it (src/CMakeLists.txt gives
/// *_avx2.cpp -mavx2 on x86-64) and the CPU has AVX2. Not with TESSERA_NO_SIMD (scalar build).
bool use_avx2() {
#if defined(TESSERA_NO_SIMD)
  return false;
#else
  return modulation_avx2_supported() && !g_baseline_only.load(std::memory_order_relaxed);
#endif
}

/// The mode, bits and error of a block from its scores (BlockMod or BlockModAvx2).
template <bool kExtra, class M>
std::uint32_t pick(EncoderState& s, const M& m, std::size_t bi) {
  std::uint8_t mode = 0;
  std::uint32_t bits = m.bits0, err = m.err0;
  if constexpr (kExtra) {
    if (s.mode1 && m.err1 < err) {
      mode = 1;
      bits = m.bits1;
      err = m.err1;
    }
    if (s.punch && m.any_clear && m.err1p < err) {
      mode = 1;
      bits = m.bits1p;
      err = m.err1p;
    }
  }
  s.mode[bi] = mode;
  s.mod[bi] = bits;
  return err;
}

template <bool kAlpha, bool kExtra, bool kWeighted = false>
std::uint64_t choose_modulation_4bpp_impl(EncoderState& s) {
  const Grid& g = s.g;
  const std::size_t nb = g.blocks();
  const std::vector<std::uint16_t> ep = planar_endpoints(s);
  std::vector<std::uint64_t> row_err(std::size_t(g.nby), 0);
  const std::size_t vstride = std::size_t(g.nbx) + 8;  // block_row_errors_avx2 reads 8 from bx
  const bool avx2 = use_avx2();
  parallel_for(0, g.nby, 4,
               [&](std::int64_t by0, std::int64_t by1) {
                 // Column sums of the 4 rows of a block row: [row][image * 4 + channel][block + 1].
                 std::vector<std::uint16_t> vp(4 * 8 * vstride, 0);
                 std::vector<BlockModAvx2> row_mods(avx2 ? std::size_t(g.nbx) : 0);
                 ModRow4 r;
                 for (int by = int(by0); by < int(by1); ++by) {
                   for (int j = 0; j < 4; ++j) {
                     const AxisTap ty = axis_tap(by * 4 + j, 4, g.ph);
                     const std::uint16_t wy0 = std::uint16_t(4 - ty.d), wy1 = std::uint16_t(ty.d);
                     for (int k = 0; k < 8; ++k) {
                       if ((k & 3) == 3 && !kAlpha) continue;
                       const std::uint16_t* e0 =
                           &ep[std::size_t(k) * nb + std::size_t(ty.b0) * std::size_t(g.nbx)];
                       const std::uint16_t* e1 =
                           &ep[std::size_t(k) * nb + std::size_t(ty.b1) * std::size_t(g.nbx)];
                       std::uint16_t* v = &vp[(std::size_t(j) * 8 + std::size_t(k)) * vstride];
                       for (int bx = 0; bx < g.nbx; ++bx) {
                         v[bx + 1] = std::uint16_t(e0[bx] * wy0 + e1[bx] * wy1);
                       }
                       v[0] = v[g.nbx];
                       v[g.nbx + 1] = v[1];
                     }
                     r.v[j] = &vp[std::size_t(j) * 8 * vstride];
                     r.t[j] = &s.target[std::size_t(by * 4 + j) * std::size_t(g.pw) * 4];
                     if constexpr (kWeighted) {
                       r.w[j] = &s.colour_scale[std::size_t(by * 4 + j) * std::size_t(g.pw)];
                     }
                   }
                   r.vstride = vstride;
                   std::uint64_t err_row = 0;
                   const std::size_t row0 = std::size_t(by) * std::size_t(g.nbx);
                   if (avx2) {
                     block_row_errors_avx2(r.v, r.t, kWeighted ? r.w : nullptr, vstride, g.nbx,
                                           kAlpha, kExtra, row_mods.data());
                     for (int bx = 0; bx < g.nbx; ++bx) {
                       err_row +=
                           pick<kExtra>(s, row_mods[std::size_t(bx)], row0 + std::size_t(bx));
                     }
                   } else {
                     for (int bx = 0; bx < g.nbx; bx += 2) {
                       BlockMod m[2];
                       block_pair_errors<kAlpha, kExtra, kWeighted>(r, bx, m);
                       for (int h = 0; h < 2; ++h) {
                         err_row += pick<kExtra>(s, m[h], row0 + std::size_t(bx + h));
                       }
                     }
                   }
                   row_err[std::size_t(by)] = err_row;
                 }
               },
               {s.threads});
  // The per-texel errors are those of the exact decode, so their sum is the total error.
  std::uint64_t total = 0;
  for (std::uint64_t e : row_err) total += e;
  return total;
}

std::uint64_t choose_modulation_4bpp(EncoderState& s) {
  const bool extra = s.mode1 || s.punch;
  if (s.alpha_mode && s.weighted()) {
    return extra ? choose_modulation_4bpp_impl<true, true, true>(s)
                 : choose_modulation_4bpp_impl<true, false, true>(s);
  }
  if (s.alpha_mode) {
    return extra ? choose_modulation_4bpp_impl<true, true>(s)
                 : choose_modulation_4bpp_impl<true, false>(s);
  }
  return extra ? choose_modulation_4bpp_impl<false, true>(s)
               : choose_modulation_4bpp_impl<false, false>(s);
}

}  // namespace

bool modulation_avx2_supported() { return avx2_kernels_usable(); }

bool set_modulation_baseline_only(bool on) { return g_baseline_only.exchange(on); }

std::uint64_t choose_modulation(EncoderState& s) {
  if (s.g.format == Format::pvrtc1_4bpp) return choose_modulation_4bpp(s);
  return choose_modulation_2bpp(s);  // returns the exact error of the decode too
}

std::uint64_t total_error(const EncoderState& s) {
  const Grid& g = s.g;
  const std::vector<std::uint64_t> w = s.words();
  std::vector<std::uint8_t> dec(g.texels() * 4);
  decode_padded(g, w.data(), dec.data(), s.threads);
  const int nch = s.alpha_mode ? 4 : 3;
  const std::uint8_t* scale = s.weighted() ? s.colour_scale.data() : nullptr;
  const double sum = parallel_sum(
      0, std::int64_t(g.texels()), 1 << 14,
      [&](std::int64_t i0, std::int64_t i1) {
        std::uint64_t e = 0;
        for (std::int64_t i = i0; i < i1; ++i) {
          for (int c = 0; c < nch; ++c) {
            const std::int32_t d = std::int32_t(dec[std::size_t(i) * 4 + std::size_t(c)]) -
                                   std::int32_t(s.target[std::size_t(i) * 4 + std::size_t(c)]);
            const std::int32_t dw =
                scale != nullptr && c < 3 ? scale_diff(d, scale[std::size_t(i)]) : d;
            e += std::uint64_t(dw * dw);
          }
        }
        return double(e);
      },
      {s.threads});
  return std::uint64_t(sum);
}

}  // namespace tessera::pvrtc::detail
