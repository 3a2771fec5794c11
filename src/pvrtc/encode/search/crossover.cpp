// Crossover of two encodings of the same image (high quality, 4 bpp and 2 bpp).
//
// The greedy exact search (exact_search.cpp; exact_search_2bpp.cpp at 2 bpp) ends in a local
// minimum that depends on where it started. The principal-axis start (narrow pairs along each
// block's main colour axis) wins in smooth areas; the paper's intensity-dilation start (the local
// darkest and brightest colours) wins along sharp edges, where several blocks must hold the same
// dark / bright pair for the bilinear A and B images to stay apart across the edge. Each block
// takes the endpoints of the encoding whose exactly decoded texels (its own 4x4, or 8x4 at 2 bpp)
// err less there; the exact search then resumes on the blocks whose 3x3 neighbourhood mixes the two
// (elsewhere both encodings were already at their own minimum), with modulation re-chosen for
// the mixed result.
#include <cstdint>
#include <vector>

#include "pvrtc/encode/encode_internal.h"

namespace tessera::pvrtc::detail {

namespace {

/// Squared error of each block's own texels (RGB, + alpha counted `alpha_weight` times;
/// colour differences scaled by `colour_scale` where the state has one).
std::vector<std::uint64_t> block_errors(const EncoderState& s, int alpha_weight) {
  const Grid& g = s.g;
  const std::vector<std::uint64_t> w = s.words();
  std::vector<std::uint8_t> dec(g.texels() * 4);
  decode_padded(g, w.data(), dec.data(), s.threads);
  std::vector<std::uint64_t> err(g.blocks(), 0);
  const int bw = g.bw;
  const std::uint8_t* scale = s.weighted() ? s.colour_scale.data() : nullptr;
  parallel_for(0, g.nby, 16,
               [&](std::int64_t by0, std::int64_t by1) {
                 for (int by = int(by0); by < int(by1); ++by) {
                   for (int y = by * 4; y < by * 4 + 4; ++y) {
                     const std::size_t row = std::size_t(y) * std::size_t(g.pw);
                     for (int x = 0; x < g.pw; ++x) {
                       const std::size_t i = (row + std::size_t(x)) * 4;
                       std::uint64_t e = 0;
                       for (int c = 0; c < 4; ++c) {
                         std::int32_t d = std::int32_t(dec[i + std::size_t(c)]) -
                                          std::int32_t(s.target[i + std::size_t(c)]);
                         if (scale != nullptr && c < 3) d = scale_diff(d, scale[i / 4]);
                         e += std::uint64_t(d * d) * std::uint64_t(c == 3 ? alpha_weight : 1);
                       }
                       err[std::size_t(by) * std::size_t(g.nbx) + std::size_t(x / bw)] += e;
                     }
                   }
                 }
               },
               {s.threads});
  return err;
}

}  // namespace

int crossover(EncoderState& s, const EncoderState& other, int alpha_weight,
              std::vector<std::uint8_t>& seeds) {
  const Grid& g = s.g;
  const int aw = s.alpha_mode ? alpha_weight : 0;  // opaque: alpha is 255 on both sides
  const std::vector<std::uint64_t> mine = block_errors(s, aw), theirs = block_errors(other, aw);
  std::vector<std::uint8_t> taken(g.blocks(), 0);
  int count = 0;
  for (std::size_t j = 0; j < g.blocks(); ++j) {
    // A block whose pair is oriented the other way round (B - A pointing against ours) cannot
    // sit next to ours: the bilinear A and B images would blend dark into bright.
    const Rgba5 a0 = expand_a(s.ca[j]), b0 = expand_b(s.cb[j]);
    const Rgba5 a1 = expand_a(other.ca[j]), b1 = expand_b(other.cb[j]);
    const std::int32_t dot = (b0.r - a0.r) * (b1.r - a1.r) + (b0.g - a0.g) * (b1.g - a1.g) +
                             (b0.b - a0.b) * (b1.b - a1.b) + 4 * (b0.a - a0.a) * (b1.a - a1.a);
    if (dot >= 0 && theirs[j] < mine[j]) {
      s.ca[j] = other.ca[j];
      s.cb[j] = other.cb[j];
      taken[j] = 1;
      ++count;
    }
  }
  seeds.assign(g.blocks(), 0);
  for (int by = 0; by < g.nby; ++by) {
    for (int bx = 0; bx < g.nbx; ++bx) {
      const std::uint8_t own = taken[std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx)];
      std::uint8_t mixed = 0;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          mixed |= taken[std::size_t((by + dy) & (g.nby - 1)) * std::size_t(g.nbx) +
                         std::size_t((bx + dx) & (g.nbx - 1))] != own;
        }
      }
      seeds[std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx)] = mixed;
    }
  }
  return count;
}

}  // namespace tessera::pvrtc::detail
