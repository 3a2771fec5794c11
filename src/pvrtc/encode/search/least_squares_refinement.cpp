// Least-squares refinement of PVRTC endpoints (the second stage of Fenney 2003, §1.2 of the
// paper): with modulation fixed, every texel is linear in the endpoint values of its four
// blocks, so each block's A and B colours have a closed-form 2x2 least-squares solution given
// its neighbours. Blocks are solved in a 2x2 colouring (blocks with the same (bx & 1, by & 1)
// share no texels), so each of the four passes is parallel and deterministic. Each solution is
// quantised by trying the floor/ceil code of every channel of A and B, then modulation is
// re-chosen and the whole sweep is kept only if the exact decoded error dropped.
#include <algorithm>
#include <cmath>

#include "core/simd.h"
#include "pvrtc/encode/encode_internal.h"

namespace tessera::pvrtc::detail {

namespace {

// Level (8-bit scale, linear in the expanded value) of an expanded channel value.
constexpr float kRgbScale = 8.25f;    // (e << 3) | (e >> 2) ~ 8.25 e for 5-bit e
constexpr float kAlphaScale = 17.0f;  // 4-bit alpha a -> 17 a
// Mean loss of the decoder's truncations: the 8-bit conversion floors twice (about 0.5
// measured) and the modulation blend (A (8 - m) + B m) / 8 floors unless m is 0 or 8
// (7/16 on average).
constexpr double kTruncBias = 0.5;
constexpr double kModBias = 0.4375;
constexpr double kSpread = 0.0;
constexpr int kContinuousSweeps = 0;
constexpr double kMinGain = 0.0025;

// Per-block endpoint levels: A rgba then B rgba.
void endpoint_levels(std::uint16_t ca, std::uint16_t cb, float* out) {
  const Rgba5 a = expand_a(ca), b = expand_b(cb);
  out[0] = float(a.r) * kRgbScale;
  out[1] = float(a.g) * kRgbScale;
  out[2] = float(a.b) * kRgbScale;
  out[3] = float(a.a) * kAlphaScale;
  out[4] = float(b.r) * kRgbScale;
  out[5] = float(b.g) * kRgbScale;
  out[6] = float(b.b) * kRgbScale;
  out[7] = float(b.a) * kAlphaScale;
}

// Expanded-value level of a code of `bits` bits for channel `ch` (alpha codes are 3-bit).
float code_value(std::uint32_t code, int bits, int ch) {
  if (ch == 3) return float(code * 2) * kAlphaScale;
  const std::int32_t e = bits == 5   ? std::int32_t(code)
                         : bits == 4 ? expand4to5(code)
                                     : expand3to5(code);
  return float(e) * kRgbScale;
}

// Two candidate codes bracketing `level`: the largest code whose value is at most `level` (0
// when there is none, or for NaN) and the next. Values rise with the code, so a proportional
// estimate corrected by the same comparisons finds it in a step or two instead of a scan up
// from 0 (the scan showed in profiles of solve_block at normal quality).
void bracket(float level, int bits, int ch, std::uint32_t out[2]) {
  const std::uint32_t maxc = (1u << bits) - 1;
  std::uint32_t c = 0;
  if (level > 0.0f) {  // false for NaN
    const float top = code_value(maxc, bits, ch);
    c = std::uint32_t(std::min(level, top) / top * float(maxc));
    while (c > 0 && code_value(c, bits, ch) > level) --c;
    while (c < maxc && code_value(c + 1, bits, ch) <= level) ++c;
  }
  out[0] = c;
  out[1] = std::min(c + 1, maxc);
}

struct Sums {
  double aa = 0, ab = 0, bb = 0;
  double ra = 0, rb = 0;
};

// Per effective-modulation byte (weight 0..8 | kPunchFlag): the blend weight of B, the bias of
// the decoder's truncations (see kTruncBias, kModBias) and 1 where the texel's alpha counts
// (not punched through).
struct ModulationTables {
  float fb[256], bias[256], alpha[256];
};
constexpr ModulationTables make_modulation_tables() {
  ModulationTables t{};
  for (int me = 0; me < 256; ++me) {
    t.fb[me] = float(me & 0x0f) * 0.125f;
    t.bias[me] = float(kTruncBias) + ((me & 0x0f) % 8 != 0 ? float(kModBias) : 0.0f);
    t.alpha[me] = (me & kPunchFlag) ? 0.0f : 1.0f;
  }
  return t;
}
constexpr ModulationTables kModTables = make_modulation_tables();

// Weight of a block in texel (u, v) of its window (the 2bw x 8 texels around it, u and v
// from the window's top-left), over the bilinear total 4 bw: [bw == 8][v][u].
struct OwnWeights {
  float w[2][8][16];
};
constexpr OwnWeights make_own_weights() {
  OwnWeights t{};
  for (int wide = 0; wide < 2; ++wide) {
    const int bw = wide ? 8 : 4;
    for (int v = 0; v < 8; ++v) {
      const int dy = v & 3, own_y = v < 4 ? dy : 4 - dy;
      for (int u = 0; u < 2 * bw; ++u) {
        const int dx = u % bw, own_x = u < bw ? dx : bw - dx;
        t.w[wide][v][u] = float(own_x * own_y) / float(4 * bw);
      }
    }
  }
  return t;
}
constexpr OwnWeights kOwnWeights = make_own_weights();

// The sums of one block's least-squares system over its window, with the other three blocks
// of every texel fixed: the residual of texel t is target + bias - (fa OA + fb OB), where OA
// and OB are the other blocks' bilinear share of A and B, and the unknowns' coefficients are
// ca = w fa, cb = w fb (w: the block's own bilinear weight). Four texels of a window row go
// through the SIMD wrapper's float lanes side by side (lane i: the same operations in the same
// order on every backend), the lanes summed in a fixed order at the end.
struct WindowSums {
  float aa = 0, ab = 0, bb = 0;  // RGB texels (all)
  float ra[4] = {}, rb[4] = {};  // [3]: alpha, over the texels not punched through
  float alpha_aa = 0, alpha_ab = 0, alpha_bb = 0;
};

float lane_sum(simd::vf32x4 a) {
  alignas(16) float l[4];
  simd::storef4(a, l);
  return (l[0] + l[1]) + (l[2] + l[3]);
}

// kWeighted (alpha-weighted colour error): each texel's colour rows of the system are scaled by
// its colour scale / 16 (a weighted least-squares fit, weight (scale / 16)^2 per texel; 1.0 for
// opaque texels, where the products are the unweighted ones exactly); alpha is unweighted.
template <bool kWeighted>
void window_sums(const EncoderState& s, const std::vector<float>& lv, int bx, int by,
                 WindowSums& out) {
  using simd::vf32x4;
  const Grid& g = s.g;
  const int bw = g.bw, width = 2 * bw, groups = width / 4;
  const int channels = s.alpha_mode ? 4 : 3;
  // Levels of the 3x3 block neighbourhood (wrapping); [1][1] is this block.
  const float* nb[3][3];
  for (int dy = 0; dy < 3; ++dy) {
    const int yb = (by - 1 + dy) & (g.nby - 1);
    for (int dx = 0; dx < 3; ++dx) {
      const int xb = (bx - 1 + dx) & (g.nbx - 1);
      nb[dy][dx] = &lv[(std::size_t(yb) * std::size_t(g.nbx) + std::size_t(xb)) * 8];
    }
  }
  // Texel (u, v) of the window lies between neighbourhood columns (u >= bw) and (u >= bw) + 1
  // (weights bw - u % bw and u % bw) and rows (v >= 4) and (v >= 4) + 1 (4 - v % 4, v % 4).
  // h[r][k][u]: the horizontal interpolation in neighbourhood row r of level k (A rgba, B rgba)
  // at column u, leaving out this block.
  alignas(16) float h[3][8][16];
  for (int q = 0; q < groups; ++q) {
    const int left = 4 * q >= bw ? 1 : 0;
    alignas(16) float wl[4], wr[4];
    for (int i = 0; i < 4; ++i) {
      const int dx = (4 * q + i) % bw;
      wl[i] = float(bw - dx);
      wr[i] = float(dx);
    }
    const vf32x4 wl_v = simd::loadf4(wl), wr_v = simd::loadf4(wr);
    for (int r = 0; r < 3; ++r) {
      const float* lo = r == 1 && left == 1 ? nullptr : nb[r][left];
      const float* hi = r == 1 && left == 0 ? nullptr : nb[r][left + 1];
      for (int k = 0; k < 8; ++k) {
        vf32x4 acc;
        if (lo != nullptr && hi != nullptr) {
          acc = wl_v * vf32x4(lo[k]) + wr_v * vf32x4(hi[k]);
        } else if (lo != nullptr) {
          acc = wl_v * vf32x4(lo[k]);
        } else {
          acc = wr_v * vf32x4(hi[k]);
        }
        simd::storef4(acc, &h[r][k][4 * q]);
      }
    }
  }
  const std::vector<std::uint8_t>& m_eff = s.scratch_m;
  const float inv_total = 1.0f / float(4 * bw);
  const auto& own = kOwnWeights.w[bw == 8 ? 1 : 0];
  vf32x4 aa, ab, bb, ra[4], rb[4], alpha_aa, alpha_ab, alpha_bb;
  alignas(16) std::uint8_t tex_wrap[16 * 4];
  std::uint8_t me_wrap[16], sc_wrap[16];
  const int x0 = bx * bw - bw / 2;
  const bool wraps = x0 < 0 || x0 + width > g.pw;
  // Row v = 0 is left out: the block's own weight is 0 there (likewise column 0, whose lanes
  // add exact zeros).
  for (int v = 1; v < 8; ++v) {
    const int y = (by * 4 - 2 + v) & (g.ph - 1);
    const int top = v >= 4 ? 1 : 0, dy = v & 3;
    const vf32x4 wy0(float(4 - dy) * inv_total), wy1(float(dy) * inv_total);
    const std::size_t row = std::size_t(y) * std::size_t(g.pw);
    const std::uint8_t* tex = &s.target[(row + std::size_t(x0 < 0 ? 0 : x0)) * 4];
    const std::uint8_t* me = &m_eff[row + std::size_t(x0 < 0 ? 0 : x0)];
    const std::uint8_t* sc =
        kWeighted ? &s.colour_scale[row + std::size_t(x0 < 0 ? 0 : x0)] : nullptr;
    if (wraps) {
      for (int u = 0; u < width; ++u) {
        const std::size_t x = std::size_t((x0 + u) & (g.pw - 1));
        for (int c = 0; c < 4; ++c) tex_wrap[u * 4 + c] = s.target[(row + x) * 4 + std::size_t(c)];
        me_wrap[u] = m_eff[row + x];
        if constexpr (kWeighted) sc_wrap[u] = s.colour_scale[row + x];
      }
      tex = tex_wrap;
      me = me_wrap;
      if constexpr (kWeighted) sc = sc_wrap;
    }
    for (int q = 0; q < groups; ++q) {
      alignas(16) float fb_l[4], bias_l[4], alpha_l[4];
      for (int i = 0; i < 4; ++i) {
        const std::uint8_t m = me[4 * q + i];
        fb_l[i] = kModTables.fb[m];
        bias_l[i] = kModTables.bias[m];
        alpha_l[i] = kModTables.alpha[m];
      }
      const vf32x4 fb = simd::loadf4(fb_l), fa = vf32x4(1.0f) - fb;
      const vf32x4 wj = simd::loadf4(&own[v][4 * q]);
      const vf32x4 ca = wj * fa, cb = wj * fb;
      vf32x4 sw, caw = ca, cbw = cb;  // colour rows: scaled by the texels' colour scales
      if constexpr (kWeighted) {
        alignas(16) float sw_l[4];
        for (int i = 0; i < 4; ++i) sw_l[i] = float(sc[4 * q + i]) * 0.0625f;
        sw = simd::loadf4(sw_l);
        caw = ca * sw;
        cbw = cb * sw;
      }
      aa = aa + caw * caw;
      ab = ab + caw * cbw;
      bb = bb + cbw * cbw;
      const simd::vi32x4 t = simd::load_texels4(tex + 16 * q);
      const vf32x4 bias = simd::loadf4(bias_l);
      for (int c = 0; c < channels; ++c) {
        const simd::vi32x4 tc_i = c == 0   ? t & simd::vi32x4(0xff)
                                  : c == 1 ? simd::srl<8>(t) & simd::vi32x4(0xff)
                                  : c == 2 ? simd::srl<16>(t) & simd::vi32x4(0xff)
                                           : simd::srl<24>(t);
        const vf32x4 oa =
            wy0 * simd::loadf4(&h[top][c][4 * q]) + wy1 * simd::loadf4(&h[top + 1][c][4 * q]);
        const vf32x4 ob = wy0 * simd::loadf4(&h[top][4 + c][4 * q]) +
                          wy1 * simd::loadf4(&h[top + 1][4 + c][4 * q]);
        const vf32x4 other = fa * oa + fb * ob;
        if (c < 3) {
          // The decoder truncates twice (8-bit conversion, modulation): aim above the target
          // by the mean truncation loss so the linear model is unbiased.
          vf32x4 res = (simd::to_float(tc_i) + bias) - other;
          if constexpr (kWeighted) res = res * sw;
          ra[c] = ra[c] + caw * res;
          rb[c] = rb[c] + cbw * res;
        } else {
          const vf32x4 am = simd::loadf4(alpha_l);
          const vf32x4 ca_a = ca * am, cb_a = cb * am;
          const vf32x4 res = simd::to_float(tc_i) - other;
          alpha_aa = alpha_aa + ca_a * ca_a;
          alpha_ab = alpha_ab + ca_a * cb_a;
          alpha_bb = alpha_bb + cb_a * cb_a;
          ra[3] = ra[3] + ca_a * res;
          rb[3] = rb[3] + cb_a * res;
        }
      }
    }
  }
  out.aa = lane_sum(aa);
  out.ab = lane_sum(ab);
  out.bb = lane_sum(bb);
  for (int c = 0; c < 4; ++c) {
    out.ra[c] = lane_sum(ra[c]);
    out.rb[c] = lane_sum(rb[c]);
  }
  out.alpha_aa = lane_sum(alpha_aa);
  out.alpha_ab = lane_sum(alpha_ab);
  out.alpha_bb = lane_sum(alpha_bb);
}

void solve_block(EncoderState& s, std::vector<float>& lv, int bx, int by, bool continuous) {
  const Grid& g = s.g;
  const std::size_t j = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
  WindowSums ws;
  if (s.weighted()) {
    window_sums<true>(s, lv, bx, by, ws);
  } else {
    window_sums<false>(s, lv, bx, by, ws);
  }
  Sums rgb[3], alpha;
  for (int c = 0; c < 3; ++c) {
    rgb[c].aa = ws.aa;
    rgb[c].ab = ws.ab;
    rgb[c].bb = ws.bb;
    rgb[c].ra = ws.ra[c];
    rgb[c].rb = ws.rb[c];
  }
  alpha.aa = ws.alpha_aa;
  alpha.ab = ws.alpha_ab;
  alpha.bb = ws.alpha_bb;
  alpha.ra = ws.ra[3];
  alpha.rb = ws.rb[3];
  float* cur = &lv[j * 8];
  EndpointCodes ea = unpack_endpoint(false, s.ca[j]);
  EndpointCodes eb = unpack_endpoint(true, s.cb[j]);
  int bits_a[4], bits_b[4];
  channel_bits(false, ea.opaque, bits_a);
  channel_bits(true, eb.opaque, bits_b);
  std::uint32_t* code_a[4] = {&ea.r, &ea.g, &ea.b, &ea.a};
  std::uint32_t* code_b[4] = {&eb.r, &eb.g, &eb.b, &eb.a};
  for (int c = 0; c < 4; ++c) {
    Sums sm = c < 3 ? rgb[c] : alpha;
    if (c == 3 && (!s.alpha_mode || (ea.opaque && eb.opaque))) break;
    const bool var_a = c < 3 || !ea.opaque, var_b = c < 3 || !eb.opaque;
    // Regularise towards the current values so degenerate systems stay put.
    const double lambda = 1e-3 * (sm.aa + sm.bb) + 1e-9;
    double A = cur[c], B = cur[4 + c];
    if (var_a && var_b) {
      const double mu = kSpread * (sm.aa + sm.bb);
      const double m00 = sm.aa + lambda + mu, m01 = sm.ab - mu, m11 = sm.bb + lambda + mu;
      const double r0 = sm.ra + lambda * cur[c], r1 = sm.rb + lambda * cur[4 + c];
      const double det = m00 * m11 - m01 * m01;
      if (det > 0) {
        A = (r0 * m11 - r1 * m01) / det;
        B = (m00 * r1 - m01 * r0) / det;
      }
    } else if (var_a) {
      A = (sm.ra - sm.ab * B + lambda * cur[c]) / (sm.aa + lambda);
    } else {
      B = (sm.rb - sm.ab * A + lambda * cur[4 + c]) / (sm.bb + lambda);
    }
    if (continuous) {
      const double hi = c == 3 ? 255.0 : 255.75;
      if (var_a) cur[c] = float(std::clamp(A, 0.0, hi));
      if (var_b) cur[4 + c] = float(std::clamp(B, 0.0, hi));
      continue;
    }
    std::uint32_t cand_a[2] = {*code_a[c], *code_a[c]}, cand_b[2] = {*code_b[c], *code_b[c]};
    const int ba = c < 3 ? bits_a[c] : 3, bb = c < 3 ? bits_b[c] : 3;
    if (var_a) bracket(float(A), ba, c, cand_a);
    if (var_b) bracket(float(B), bb, c, cand_b);
    double best = 1e300;
    for (std::uint32_t qa : cand_a) {
      const double la = var_a ? code_value(qa, ba, c) : double(cur[c]);
      for (std::uint32_t qb : cand_b) {
        const double lb = var_b ? code_value(qb, bb, c) : double(cur[4 + c]);
        const double e = sm.aa * la * la + 2 * sm.ab * la * lb + sm.bb * lb * lb - 2 * sm.ra * la -
                         2 * sm.rb * lb;
        if (e < best) {
          best = e;
          if (var_a) *code_a[c] = qa;
          if (var_b) *code_b[c] = qb;
        }
      }
    }
  }
  if (continuous) return;
  s.ca[j] = std::uint16_t(pack_endpoint(false, ea));
  s.cb[j] = std::uint16_t(pack_endpoint(true, eb));
  endpoint_levels(s.ca[j], s.cb[j], cur);
}

}  // namespace

void refine(EncoderState& s, int iterations, std::uint64_t error) {
  const Grid& g = s.g;
  std::uint64_t best_err = error;
  std::vector<float> lv(g.blocks() * 8);
  for (int it = 0; it < iterations; ++it) {
    const std::vector<std::uint16_t> save_a = s.ca, save_b = s.cb;
    const std::vector<std::uint8_t> save_mode = s.mode;
    const std::vector<std::uint32_t> save_mod = s.mod;
    for (std::size_t i = 0; i < g.blocks(); ++i) endpoint_levels(s.ca[i], s.cb[i], &lv[i * 8]);
    s.scratch_m.resize(g.texels());
    {
      const std::vector<std::uint64_t> w = s.words();
      modulation_map(g, w.data(), s.scratch_m.data(), s.threads);
    }
    for (int sweep = 0; sweep <= kContinuousSweeps; ++sweep) {
      const bool continuous = sweep < kContinuousSweeps;
      for_each_block_2x2(g, s.threads,
                         [&](int bx, int by) { solve_block(s, lv, bx, by, continuous); });
    }
    std::uint64_t err = choose_modulation(s);
    if (s.modulation_descent > 0) err = refine_modulation_2bpp(s, s.modulation_descent);
    if (err >= best_err) {
      s.ca = save_a;
      s.cb = save_b;
      s.mode = save_mode;
      s.mod = save_mod;
      break;
    }
    // Converged: the sweep gained less than kMinGain of the error (~0.01 dB).
    const bool small_gain = double(best_err - err) < kMinGain * double(best_err);
    best_err = err;
    s.progress.at(double(it + 1) / iterations);
    if (small_gain) break;
  }
}

}  // namespace tessera::pvrtc::detail
