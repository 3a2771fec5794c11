// Modulation choice for fixed endpoints (exact decoder arithmetic) and the total error of a
// state: the 4 bpp brute force over the blends of both modes (planar SIMD, 8 texels at a time;
// see modulation_kernel.h) and the 2 bpp direct / interpolated choice.
#include <algorithm>
#include <limits>

#include "pvrtc/encode_internal.h"
#include "pvrtc/modulation_kernel.h"

namespace tessera::pvrtc::detail {

namespace {

inline std::uint32_t texel_error(const std::uint8_t* t, const std::uint8_t* a,
                                 const std::uint8_t* b, std::int32_t m, bool punch, int nch) {
  std::uint32_t e = 0;
  for (int c = 0; c < nch; ++c) {
    std::int32_t v = (a[c] * (8 - m) + b[c] * m) / 8;
    if (c == 3 && punch) v = 0;
    const std::int32_t d = v - t[c];
    e += std::uint32_t(d * d);
  }
  return e;
}


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

// 2 bpp: per block, direct 1-bit modulation (mode 0) or 2-bit checkerboard with interpolated
// texels (mode 1: H+V, H only or V only), whichever has the smaller estimated error. The
// estimate for interpolated texels assumes neighbouring blocks store their greedy 2-bit values.
void choose_modulation_2bpp(EncoderState& s) {
  const Grid& g = s.g;
  std::vector<Rgba5> ea(g.blocks()), eb(g.blocks());
  for (std::size_t i = 0; i < g.blocks(); ++i) {
    ea[i] = expand_a(s.ca[i]);
    eb[i] = expand_b(s.cb[i]);
  }
  const int nch = s.alpha_mode ? 4 : 3;
  const std::size_t n = g.texels();
  std::vector<std::uint8_t> ua(n * 4), ub(n * 4), greedy(n);
  parallel_for(
      0, g.ph, 16,
      [&](std::int64_t y0, std::int64_t y1) {
        upscale_rows(g, ea.data(), int(y0), int(y1), &ua[std::size_t(y0) * std::size_t(g.pw) * 4]);
        upscale_rows(g, eb.data(), int(y0), int(y1), &ub[std::size_t(y0) * std::size_t(g.pw) * 4]);
        for (std::size_t i = std::size_t(y0) * std::size_t(g.pw);
             i < std::size_t(y1) * std::size_t(g.pw); ++i) {
          std::uint32_t best = std::numeric_limits<std::uint32_t>::max(), bc = 0;
          for (std::uint32_t c = 0; c < 4; ++c) {
            const std::uint32_t e =
                texel_error(&s.target[i * 4], &ua[i * 4], &ub[i * 4], kMod4Mode0[c], false, nch);
            if (e < best) {
              best = e;
              bc = c;
            }
          }
          greedy[i] = std::uint8_t(bc);
        }
      },
      s.threads);
  const int wm = g.pw - 1, hm = g.ph - 1;
  parallel_for(
      0, g.nby, 4,
      [&](std::int64_t by0, std::int64_t by1) {
        for (int by = int(by0); by < int(by1); ++by) {
          for (int bx = 0; bx < g.nbx; ++bx) {
            const std::size_t bi = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
            auto at = [&](int x, int y) {
              return std::size_t(y & hm) * std::size_t(g.pw) + std::size_t(x & wm);
            };
            auto err_m = [&](std::size_t i, std::int32_t m) {
              return texel_error(&s.target[i * 4], &ua[i * 4], &ub[i * 4], m, false, nch);
            };
            // Mode 0.
            std::uint32_t bits0 = 0, err0 = 0;
            for (int y = 0; y < 4; ++y) {
              for (int x = 0; x < 8; ++x) {
                const std::size_t i = at(bx * 8 + x, by * 4 + y);
                const std::uint32_t e0 = err_m(i, 0), e1 = err_m(i, 8);
                if (e1 < e0) bits0 |= 1u << (y * 8 + x);
                err0 += std::min(e0, e1);
              }
            }
            // Mode 1 variants: 0 = H+V, 1 = H only, 2 = V only.
            std::uint32_t best_err = err0, best_bits = bits0;
            std::uint8_t best_mode = 0;
            // Stored values of this block, with texel (0,0) restricted to 0/3, and (4,2) too for
            // the H/V-only variants.
            for (int variant = 0; variant < 3; ++variant) {
              std::uint8_t code[4][8];
              std::uint32_t err = 0;
              auto restricted = [&](std::size_t i) -> std::uint8_t {
                return err_m(i, 8) < err_m(i, 0) ? 3 : 0;
              };
              for (int y = 0; y < 4; ++y) {
                for (int x = 0; x < 8; ++x) {
                  if ((x ^ y) & 1) continue;
                  const std::size_t i = at(bx * 8 + x, by * 4 + y);
                  std::uint8_t c = greedy[i];
                  if ((x == 0 && y == 0) || (variant > 0 && x == 4 && y == 2)) c = restricted(i);
                  code[y][x] = c;
                  err += err_m(i, kMod4Mode0[c]);
                }
              }
              auto stored = [&](int x, int y) -> std::int32_t {
                if (x >= 0 && x < 8 && y >= 0 && y < 4) return kMod4Mode0[code[y][x]];
                return kMod4Mode0[greedy[at(bx * 8 + x, by * 4 + y)]];
              };
              for (int y = 0; y < 4 && err < best_err; ++y) {
                for (int x = 0; x < 8; ++x) {
                  if (((x ^ y) & 1) == 0) continue;
                  std::int32_t m;
                  if (variant == 0) {
                    m = (stored(x, y - 1) + stored(x, y + 1) + stored(x - 1, y) + stored(x + 1, y) +
                         2) /
                        4;
                  } else if (variant == 1) {
                    m = (stored(x - 1, y) + stored(x + 1, y) + 1) / 2;
                  } else {
                    m = (stored(x, y - 1) + stored(x, y + 1) + 1) / 2;
                  }
                  err += err_m(at(bx * 8 + x, by * 4 + y), m);
                }
              }
              if (err < best_err) {
                std::uint32_t bits = 0;
                int k = 0;
                for (int y = 0; y < 4; ++y) {
                  for (int x = 0; x < 8; ++x) {
                    if ((x ^ y) & 1) continue;
                    bits |= std::uint32_t(code[y][x]) << (2 * k);
                    ++k;
                  }
                }
                // Texel (0,0): only its high bit is stored; bit 0 flags the H/V-only variants,
                // and bit 20 (the low bit of texel (4,2)) tells V-only from H-only.
                bits &= ~1u;
                bits &= ~(1u << 20);
                if (variant > 0) {
                  bits |= 1u;
                  if (variant == 2) bits |= 1u << 20;
                }
                best_err = err;
                best_bits = bits;
                best_mode = 1;
              }
            }
            s.mode[bi] = best_mode;
            s.mod[bi] = best_bits;
          }
        }
      },
      s.threads);
}

}  // namespace

std::uint64_t choose_modulation(EncoderState& s) {
  if (s.g.format == Format::pvrtc1_4bpp) return choose_modulation_4bpp(s);
  choose_modulation_2bpp(s);  // its block choice uses estimates: measure the real decode
  return total_error(s);
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
