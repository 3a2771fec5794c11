// Least-squares refinement of PVRTC endpoints (the second stage of Fenney 2003, §1.2 of the
// paper): with modulation fixed, every texel is linear in the endpoint values of its four
// blocks, so each block's A and B colours have a closed-form 2x2 least-squares solution given
// its neighbours. Blocks are solved in a 2x2 colouring (blocks with the same (bx & 1, by & 1)
// share no texels), so each of the four passes is parallel and deterministic. Each solution is
// quantised by trying the floor/ceil code of every channel of A and B, then modulation is
// re-chosen and the whole sweep is kept only if the exact decoded error dropped.
#include <algorithm>
#include <cmath>

#include "pvrtc/encode_internal.h"
#include "pvrtc/simd.h"

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
// from 0 (normal: the scan was ~10% of solve_block).
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

void solve_block(EncoderState& s, std::vector<float>& lv, int bx, int by, bool continuous) {
  const Grid& g = s.g;
  const int bw = g.bw;
  const std::size_t j = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
  const std::vector<std::uint8_t>& m_eff = s.scratch_m;
  // Levels of the 3x3 block neighbourhood (wrapping); [1][1] is this block.
  const float* nb[3][3];
  for (int dy = 0; dy < 3; ++dy) {
    const int yb = (by - 1 + dy) & (g.nby - 1);
    for (int dx = 0; dx < 3; ++dx) {
      const int xb = (bx - 1 + dx) & (g.nbx - 1);
      nb[dy][dx] = &lv[(std::size_t(yb) * std::size_t(g.nbx) + std::size_t(xb)) * 8];
    }
  }
  // Texel (u, v) of the window lies between blocks (u >= bw) and (u >= bw) + 1 of the
  // neighbourhood horizontally (weight of the right one u % bw), likewise vertically.
  // The four channels go through the SIMD wrapper's float lanes side by side (lane c: the
  // same operations, in the same order, as a scalar loop over c: the same sums; normal
  // 1024^2: solve_block 2.x faster).
  float rgb_aa = 0, rgb_ab = 0, rgb_bb = 0;
  simd::vf4 ra_v, rb_v;
  Sums alpha;
  const float inv_total = 1.0f / float(4 * bw);
  for (int v = 1; v < 8; ++v) {
    const int y = (by * 4 - 2 + v) & (g.ph - 1);
    const int top = v >= 4 ? 1 : 0, dy = v & 3;
    const int own_y = top == 0 ? dy : 4 - dy;
    for (int u = 1; u < 2 * bw; ++u) {
      const int x = (bx * bw - bw / 2 + u) & (g.pw - 1);
      const int left = u >= bw ? 1 : 0, dx = u % bw;
      const int own_x = left == 0 ? dx : bw - dx;
      const std::size_t ti = std::size_t(y) * std::size_t(g.pw) + std::size_t(x);
      const std::uint8_t me = m_eff[ti];
      const float fb = float(me & 0x0f) * 0.125f, fa = 1.0f - fb;
      const float wts[2][2] = {{float((bw - dx) * (4 - dy)), float(dx * (4 - dy))},
                               {float((bw - dx) * dy), float(dx * dy)}};
      const simd::vf4 fa_v(fa), fb_v(fb);
      simd::vf4 other_v;
      for (int cy = 0; cy < 2; ++cy) {
        for (int cx = 0; cx < 2; ++cx) {
          if (top + cy == 1 && left + cx == 1) continue;  // this block
          const float* l = nb[top + cy][left + cx];
          const simd::vf4 wt(wts[cy][cx] * inv_total);
          other_v = other_v + wt * (fa_v * simd::loadf4(l) + fb_v * simd::loadf4(l + 4));
        }
      }
      const float wj = float(own_x * own_y) * inv_total;
      const std::uint8_t* t = &s.target[ti * 4];
      const float ca = wj * fa, cbv = wj * fb;
      // The decoder truncates twice (8-bit conversion, modulation): aim above the target by
      // the mean truncation loss so the linear model is unbiased.
      const float bias = float(kTruncBias) + ((me & 0x0f) % 8 != 0 ? float(kModBias) : 0.0f);
      rgb_aa += ca * ca;
      rgb_ab += ca * cbv;
      rgb_bb += cbv * cbv;
      // Lane 3 (alpha) of the residual is computed but not used.
      const simd::vf4 r_v = (simd::to_float(simd::vint4(t[0], t[1], t[2], t[3])) +
                             simd::vf4(bias)) - other_v;
      ra_v = ra_v + simd::vf4(ca) * r_v;
      rb_v = rb_v + simd::vf4(cbv) * r_v;
      if (s.alpha_mode && !(me & kPunchFlag)) {
        alignas(16) float other[4];
        simd::storef4(other_v, other);
        const double r = double(t[3]) - other[3];
        alpha.aa += ca * ca;
        alpha.ab += ca * cbv;
        alpha.bb += cbv * cbv;
        alpha.ra += ca * r;
        alpha.rb += cbv * r;
      }
    }
  }
  alignas(16) float ra[4], rb[4];
  simd::storef4(ra_v, ra);
  simd::storef4(rb_v, rb);
  Sums rgb[3];
  for (int c = 0; c < 3; ++c) {
    rgb[c].aa = rgb_aa;
    rgb[c].ab = rgb_ab;
    rgb[c].bb = rgb_bb;
    rgb[c].ra = ra[c];
    rgb[c].rb = rb[c];
  }
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
    if (small_gain) break;
  }
}

}  // namespace tessera::pvrtc::detail
