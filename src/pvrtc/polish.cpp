// Exact local search on 4 bpp endpoints: "reseed" (before the refinement) and "polish" (after).
//
// Reseed: the principal-axis start sees each block's whole bilinear footprint, so where the
// block's own texels span only part of it (stripes, thin dark creases next to bright areas)
// one endpoint lands far from every texel, no texel selects it and the least-squares
// refinement cannot move it again. Each block whose exact window error is high tries endpoint
// pairs from its own 4x4 texels (principal split means and extreme texels, both orientations)
// and keeps the best if it lowers the exact error of its window.
//
// The least-squares model is linear and ignores the decoder's truncations, so it stalls where
// quantisation matters most (edges, saturated colours). Here each block's endpoint codes are
// perturbed (one channel +-1, or all colour channels of A, of B or of both together) and a move
// is kept only when the exact decoded error over the 8x8 texels the block influences drops,
// with every texel's modulation re-chosen within its block's mode. Blocks are visited in the
// same 2x2 colouring as the refinement, so the passes are parallel and deterministic.
#include <algorithm>
#include <cmath>
#include <limits>

#include "pvrtc/encode_internal.h"

namespace tessera::pvrtc::detail {

namespace {

struct Window {
  const EncoderState* s;
  const std::vector<Rgba5>* ea;
  const std::vector<Rgba5>* eb;
  const std::vector<std::uint8_t>* modes;
  int nch;
};

// Error of the 8x8 window of block (bx, by) with endpoints (a, b) substituted for the block's
// own; writes the best code of each window texel to `codes` (64 entries) when not null.
std::uint32_t window_error(const Window& w, int bx, int by, const Rgba5& a, const Rgba5& b,
                           std::uint8_t* codes) {
  const EncoderState& s = *w.s;
  const Grid& g = s.g;
  const std::size_t j = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
  std::uint32_t total = 0;
  int k = 0;
  for (int yy = by * 4 - 2; yy < by * 4 + 6; ++yy) {
    const AxisTap ty = axis_tap(yy, 4, g.ph);
    const int y = yy & (g.ph - 1);
    for (int xx = bx * 4 - 2; xx < bx * 4 + 6; ++xx, ++k) {
      const AxisTap tx = axis_tap(xx, 4, g.pw);
      const int x = xx & (g.pw - 1);
      const std::size_t blk[4] = {std::size_t(ty.b0) * std::size_t(g.nbx) + std::size_t(tx.b0),
                                  std::size_t(ty.b0) * std::size_t(g.nbx) + std::size_t(tx.b1),
                                  std::size_t(ty.b1) * std::size_t(g.nbx) + std::size_t(tx.b0),
                                  std::size_t(ty.b1) * std::size_t(g.nbx) + std::size_t(tx.b1)};
      const Rgba5* pa[4];
      const Rgba5* pb[4];
      for (int i = 0; i < 4; ++i) {
        pa[i] = blk[i] == j ? &a : &(*w.ea)[blk[i]];
        pb[i] = blk[i] == j ? &b : &(*w.eb)[blk[i]];
      }
      std::uint8_t ua[4], ub[4];
      upscale_texel(*pa[0], *pa[1], *pa[2], *pa[3], tx.d, ty.d, 4, ua);
      upscale_texel(*pb[0], *pb[1], *pb[2], *pb[3], tx.d, ty.d, 4, ub);
      const std::uint8_t* t = &s.target[(std::size_t(y) * std::size_t(g.pw) + std::size_t(x)) * 4];
      const bool mode1 = (*w.modes)[std::size_t(y >> 2) * std::size_t(g.nbx) + std::size_t(x >> 2)];
      const std::int32_t* tab = mode1 ? kMod4Mode1 : kMod4Mode0;
      std::uint32_t best = std::numeric_limits<std::uint32_t>::max();
      std::uint8_t bc = 0;
      for (int c = 0; c < 4; ++c) {
        const bool punch = mode1 && c == 2;
        if (punch && !s.punch) continue;
        const std::int32_t m = tab[c];
        std::uint32_t e = 0;
        for (int ch = 0; ch < w.nch; ++ch) {
          std::int32_t v = (ua[ch] * (8 - m) + ub[ch] * m) >> 3;
          if (ch == 3 && punch) v = 0;
          const std::int32_t d = v - t[ch];
          e += std::uint32_t(d * d);
        }
        if (e < best) {
          best = e;
          bc = std::uint8_t(c);
        }
      }
      total += best;
      if (codes) codes[k] = bc;
    }
  }
  return total;
}

// Candidate moves on the codes of one endpoint pair. Returns false when the move is invalid.
bool apply_move(int move, EndpointCodes& a, EndpointCodes& b) {
  int ba[4], bb[4];
  channel_bits(false, a.opaque, ba);
  channel_bits(true, b.opaque, bb);
  std::uint32_t* ca[4] = {&a.r, &a.g, &a.b, &a.a};
  std::uint32_t* cb[4] = {&b.r, &b.g, &b.b, &b.a};
  auto step = [](std::uint32_t* c, int bits, int d) {
    if (bits == 0) return false;
    const int v = int(*c) + d;
    if (v < 0 || v >= (1 << bits)) return false;
    *c = std::uint32_t(v);
    return true;
  };
  if (move < 16) {  // single channel: endpoint (move / 8), channel ((move / 2) % 4), sign
    const bool on_b = move >= 8;
    const int ch = (move / 2) % 4;
    const int d = (move & 1) ? 1 : -1;
    return on_b ? step(cb[ch], bb[ch], d) : step(ca[ch], ba[ch], d);
  }
  // Joint colour moves: 16/17 A, 18/19 B, 20/21 both, 22 spread, 23 contract.
  const int m = move - 16;
  bool ok = true;
  for (int ch = 0; ch < 3 && ok; ++ch) {
    if (m < 2) {
      ok = step(ca[ch], ba[ch], m ? 1 : -1);
    } else if (m < 4) {
      ok = step(cb[ch], bb[ch], m == 3 ? 1 : -1);
    } else if (m < 6) {
      ok = step(ca[ch], ba[ch], m == 5 ? 1 : -1) && step(cb[ch], bb[ch], m == 5 ? 1 : -1);
    } else {
      ok = step(ca[ch], ba[ch], m == 6 ? -1 : 1) && step(cb[ch], bb[ch], m == 6 ? 1 : -1);
    }
  }
  return ok;
}

constexpr int kMoves = 24;
// Windows whose error is already this small (64 texels; ~5 per channel RMS) are skipped.
constexpr std::uint32_t kSkipBelow = 3000;

// Candidate endpoint pairs for block (bx, by) from its own 4x4 texels: their principal axis
// splits them into two halves; the half means and the two extreme texels each give a pair, in
// both orientations. Writes up to 4 (A, B) field pairs; returns the count.
int reseed_candidates(const EncoderState& s, int bx, int by, std::uint16_t out[4][2]) {
  const Grid& g = s.g;
  const int nch = s.alpha_mode ? 4 : 3;
  float px[16][4];
  float mean[4] = {0, 0, 0, 0};
  for (int i = 0; i < 16; ++i) {
    const std::uint8_t* t =
        &s.target[(std::size_t(by * 4 + i / 4) * std::size_t(g.pw) + std::size_t(bx * 4 + i % 4)) *
                  4];
    for (int c = 0; c < 4; ++c) {
      px[i][c] = float(t[c]);
      mean[c] += float(t[c]) / 16.0f;
    }
  }
  float cov[4][4] = {};
  for (int i = 0; i < 16; ++i) {
    for (int a = 0; a < nch; ++a) {
      for (int b = 0; b < nch; ++b) cov[a][b] += (px[i][a] - mean[a]) * (px[i][b] - mean[b]);
    }
  }
  float axis[4] = {0.2126f, 0.7152f, 0.0722f, 0.5f};
  for (int it = 0; it < 8; ++it) {
    float n[4] = {0, 0, 0, 0}, len = 0;
    for (int a = 0; a < nch; ++a) {
      for (int b = 0; b < nch; ++b) n[a] += cov[a][b] * axis[b];
      len += n[a] * n[a];
    }
    if (len < 1e-6f) return 0;
    len = std::sqrt(len);
    for (int a = 0; a < nch; ++a) axis[a] = n[a] / len;
  }
  float lo[4] = {0, 0, 0, 0}, hi[4] = {0, 0, 0, 0}, nlo = 0, nhi = 0;
  float pmin = 1e30f, pmax = -1e30f;
  int imin = 0, imax = 0;
  for (int i = 0; i < 16; ++i) {
    float p = 0;
    for (int a = 0; a < nch; ++a) p += (px[i][a] - mean[a]) * axis[a];
    float* acc = p < 0 ? lo : hi;
    (p < 0 ? nlo : nhi) += 1;
    for (int c = 0; c < 4; ++c) acc[c] += px[i][c];
    if (p < pmin) {
      pmin = p;
      imin = i;
    }
    if (p > pmax) {
      pmax = p;
      imax = i;
    }
  }
  if (nlo == 0 || nhi == 0) return 0;
  for (int c = 0; c < 4; ++c) {
    lo[c] /= nlo;
    hi[c] /= nhi;
  }
  const bool ta = s.alpha_mode;
  out[0][0] = quantise_endpoint(lo, false, ta);
  out[0][1] = quantise_endpoint(hi, true, ta);
  out[1][0] = quantise_endpoint(hi, false, ta);
  out[1][1] = quantise_endpoint(lo, true, ta);
  out[2][0] = quantise_endpoint(px[imin], false, ta);
  out[2][1] = quantise_endpoint(px[imax], true, ta);
  out[3][0] = quantise_endpoint(px[imax], false, ta);
  out[3][1] = quantise_endpoint(px[imin], true, ta);
  return 4;
}

}  // namespace

int reseed(EncoderState& s, std::uint32_t min_error) {
  const Grid& g = s.g;
  if (g.format != Format::pvrtc1_4bpp) return 0;
  std::vector<Rgba5> ea(g.blocks()), eb(g.blocks());
  for (std::size_t i = 0; i < g.blocks(); ++i) {
    ea[i] = expand_a(s.ca[i]);
    eb[i] = expand_b(s.cb[i]);
  }
  const Window w{&s, &ea, &eb, &s.mode, s.alpha_mode ? 4 : 3};
  std::vector<std::uint8_t> changed(g.blocks(), 0);
  for (int cls = 0; cls < 4; ++cls) {
    const int ox = cls & 1, oy = cls >> 1;
    parallel_for(
        0, g.nby / 2, 4,
        [&](std::int64_t r0, std::int64_t r1) {
          for (int r = int(r0); r < int(r1); ++r) {
            const int by = 2 * r + oy;
            for (int bx = ox; bx < g.nbx; bx += 2) {
              const std::size_t j = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
              std::uint32_t best = window_error(w, bx, by, ea[j], eb[j], nullptr);
              if (best <= min_error) continue;
              std::uint16_t cand[4][2];
              const int n = reseed_candidates(s, bx, by, cand);
              int pick = -1;
              for (int k = 0; k < n; ++k) {
                const std::uint32_t e =
                    window_error(w, bx, by, expand_a(cand[k][0]), expand_b(cand[k][1]), nullptr);
                if (e < best) {
                  best = e;
                  pick = k;
                }
              }
              if (pick < 0) continue;
              s.ca[j] = cand[pick][0];
              s.cb[j] = cand[pick][1];
              ea[j] = expand_a(s.ca[j]);
              eb[j] = expand_b(s.cb[j]);
              changed[j] = 1;
            }
          }
        },
        s.threads);
  }
  int count = 0;
  for (std::uint8_t c : changed) count += c;
  return count;
}

void polish(EncoderState& s, int rounds) {
  const Grid& g = s.g;
  if (g.format != Format::pvrtc1_4bpp || rounds <= 0) return;
  std::vector<Rgba5> ea(g.blocks()), eb(g.blocks());
  for (std::size_t i = 0; i < g.blocks(); ++i) {
    ea[i] = expand_a(s.ca[i]);
    eb[i] = expand_b(s.cb[i]);
  }
  // Per-texel codes, written back to the block words at the end.
  std::vector<std::uint8_t> codes(g.texels());
  for (int by = 0; by < g.nby; ++by) {
    for (int bx = 0; bx < g.nbx; ++bx) {
      const std::uint32_t bits = s.mod[std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx)];
      for (int i = 0; i < 16; ++i) {
        codes[std::size_t(by * 4 + i / 4) * std::size_t(g.pw) + std::size_t(bx * 4 + i % 4)] =
            std::uint8_t((bits >> (2 * i)) & 3);
      }
    }
  }
  const Window w{&s, &ea, &eb, &s.mode, s.alpha_mode ? 4 : 3};
  for (int round = 0; round < rounds; ++round) {
    for (int cls = 0; cls < 4; ++cls) {
      const int ox = cls & 1, oy = cls >> 1;
      parallel_for(
          0, g.nby / 2, 4,
          [&](std::int64_t r0, std::int64_t r1) {
            std::uint8_t best_codes[64];
            for (int r = int(r0); r < int(r1); ++r) {
              const int by = 2 * r + oy;
              for (int bx = ox; bx < g.nbx; bx += 2) {
                const std::size_t j = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
                std::uint16_t cur_a = s.ca[j], cur_b = s.cb[j];
                std::uint32_t best = window_error(w, bx, by, ea[j], eb[j], best_codes);
                if (best <= kSkipBelow) continue;
                bool improved = true;
                for (int pass = 0; pass < 4 && improved; ++pass) {
                  improved = false;
                  for (int mv = 0; mv < kMoves; ++mv) {
                    EndpointCodes a = unpack_endpoint(false, cur_a),
                                  b = unpack_endpoint(true, cur_b);
                    if (!apply_move(mv, a, b)) continue;
                    const std::uint16_t na = std::uint16_t(pack_endpoint(false, a));
                    const std::uint16_t nb = std::uint16_t(pack_endpoint(true, b));
                    std::uint8_t trial[64];
                    const std::uint32_t e =
                        window_error(w, bx, by, expand_a(na), expand_b(nb), trial);
                    if (e < best) {
                      best = e;
                      cur_a = na;
                      cur_b = nb;
                      std::copy(trial, trial + 64, best_codes);
                      improved = true;
                    }
                  }
                }
                if (cur_a == s.ca[j] && cur_b == s.cb[j]) continue;
                s.ca[j] = cur_a;
                s.cb[j] = cur_b;
                ea[j] = expand_a(cur_a);
                eb[j] = expand_b(cur_b);
                int k = 0;
                for (int yy = by * 4 - 2; yy < by * 4 + 6; ++yy) {
                  for (int xx = bx * 4 - 2; xx < bx * 4 + 6; ++xx, ++k) {
                    codes[std::size_t(yy & (g.ph - 1)) * std::size_t(g.pw) +
                          std::size_t(xx & (g.pw - 1))] = best_codes[k];
                  }
                }
              }
            }
          },
          s.threads);
    }
  }
  for (int by = 0; by < g.nby; ++by) {
    for (int bx = 0; bx < g.nbx; ++bx) {
      std::uint32_t bits = 0;
      for (int i = 0; i < 16; ++i) {
        bits |= std::uint32_t(codes[std::size_t(by * 4 + i / 4) * std::size_t(g.pw) +
                                    std::size_t(bx * 4 + i % 4)])
                << (2 * i);
      }
      s.mod[std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx)] = bits;
    }
  }
}

}  // namespace tessera::pvrtc::detail
