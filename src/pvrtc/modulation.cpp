// Modulation choice for fixed endpoints (exact decoder arithmetic) and the total error of a
// state: the 4 bpp brute force over the blends of both modes (planar SIMD, 8 texels at a time;
// see modulation_kernel.h); the 2 bpp direct / interpolated choice is in modulation_2bpp.cpp.
#include <algorithm>
#include <limits>

#include "pvrtc/encode_internal.h"
#include "pvrtc/modulation_2bpp.h"
#include "pvrtc/modulation_kernel.h"

namespace tessera::pvrtc::detail {

namespace {

template <bool kAlpha, bool kExtra>
std::uint64_t choose_modulation_4bpp_impl(EncoderState& s) {
  const Grid& g = s.g;
  const std::size_t nb = g.blocks();
  // Expanded endpoints, planar: plane (image * 4 + channel), one u16 per block.
  std::vector<std::uint16_t> ep(8 * nb);
  for (std::size_t i = 0; i < nb; ++i) {
    const Rgba5 a = expand_a(s.ca[i]), b = expand_b(s.cb[i]);
    const std::int32_t v[8] = {a.r, a.g, a.b, a.a, b.r, b.g, b.b, b.a};
    for (int k = 0; k < 8; ++k) ep[std::size_t(k) * nb + i] = std::uint16_t(v[k]);
  }
  std::vector<std::uint64_t> row_err(std::size_t(g.nby), 0);
  const std::size_t vstride = std::size_t(g.nbx) + 8;
  parallel_for(
      0, g.nby, 4,
      [&](std::int64_t by0, std::int64_t by1) {
        // Column sums of the 4 rows of a block row: [row][image * 4 + channel][block + 1].
        std::vector<std::uint16_t> vp(4 * 8 * vstride, 0);
        ModRow4 r;
        for (int by = int(by0); by < int(by1); ++by) {
          for (int j = 0; j < 4; ++j) {
            const AxisTap ty = axis_tap(by * 4 + j, 4, g.ph);
            const std::uint16_t wy0 = std::uint16_t(4 - ty.d), wy1 = std::uint16_t(ty.d);
            for (int k = 0; k < 8; ++k) {
              if ((k & 3) == 3 && !kAlpha) continue;
              const std::uint16_t* e0 = &ep[std::size_t(k) * nb + std::size_t(ty.b0) * std::size_t(g.nbx)];
              const std::uint16_t* e1 = &ep[std::size_t(k) * nb + std::size_t(ty.b1) * std::size_t(g.nbx)];
              std::uint16_t* v = &vp[(std::size_t(j) * 8 + std::size_t(k)) * vstride];
              for (int bx = 0; bx < g.nbx; ++bx) {
                v[bx + 1] = std::uint16_t(e0[bx] * wy0 + e1[bx] * wy1);
              }
              v[0] = v[g.nbx];
              v[g.nbx + 1] = v[1];
            }
            r.v[j] = &vp[std::size_t(j) * 8 * vstride];
            r.t[j] = &s.target[std::size_t(by * 4 + j) * std::size_t(g.pw) * 4];
          }
          r.vstride = vstride;
          std::uint64_t err_row = 0;
          for (int bx = 0; bx < g.nbx; bx += 2) {
            BlockMod m[2];
            block_pair_errors<kAlpha, kExtra>(r, bx, m);
            for (int h = 0; h < 2; ++h) {
              const std::size_t bi = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx + h);
              std::uint8_t mode = 0;
              std::uint32_t bits = m[h].bits0, err = m[h].err0;
              if constexpr (kExtra) {
                if (s.mode1 && m[h].err1 < err) {
                  mode = 1;
                  bits = m[h].bits1;
                  err = m[h].err1;
                }
                if (s.punch && m[h].any_clear && m[h].err1p < err) {
                  mode = 1;
                  bits = m[h].bits1p;
                  err = m[h].err1p;
                }
              }
              s.mode[bi] = mode;
              s.mod[bi] = bits;
              err_row += err;
            }
          }
          row_err[std::size_t(by)] = err_row;
        }
      },
      s.threads);
  // The per-texel errors are those of the exact decode, so their sum is the total error.
  std::uint64_t total = 0;
  for (std::uint64_t e : row_err) total += e;
  return total;
}

std::uint64_t choose_modulation_4bpp(EncoderState& s) {
  const bool extra = s.mode1 || s.punch;
  if (s.alpha_mode) {
    return extra ? choose_modulation_4bpp_impl<true, true>(s)
                 : choose_modulation_4bpp_impl<true, false>(s);
  }
  return extra ? choose_modulation_4bpp_impl<false, true>(s)
               : choose_modulation_4bpp_impl<false, false>(s);
}

}  // namespace

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
  const double sum = parallel_sum(
      0, std::int64_t(g.texels()), 1 << 14,
      [&](std::int64_t i0, std::int64_t i1) {
        std::uint64_t e = 0;
        for (std::int64_t i = i0; i < i1; ++i) {
          for (int c = 0; c < nch; ++c) {
            const std::int32_t d = std::int32_t(dec[std::size_t(i) * 4 + std::size_t(c)]) -
                                   std::int32_t(s.target[std::size_t(i) * 4 + std::size_t(c)]);
            e += std::uint64_t(d * d);
          }
        }
        return double(e);
      },
      s.threads);
  return std::uint64_t(sum);
}

}  // namespace tessera::pvrtc::detail
