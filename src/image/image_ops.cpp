// Per-texel preparations of an image: flips, premultiplied alpha, alpha bleeding (an exact
// Euclidean distance transform on the torus) and normal-map renormalisation.
#include "tessera/image_ops.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "image/normal_kernel.h"
#include "image/texel_loops.h"

namespace tessera::image {

namespace {

// ---------------------------------------------------------------------------------------------
// Exact 1-D lower envelope of parabolas (Felzenszwalb & Huttenlocher 2012), over the integers
// ---------------------------------------------------------------------------------------------

/// A site seen along one line: f(t) = (t - pos)^2 + height. Among sites equally near to t the
/// one with the smaller `key` wins, then the one with the smaller `pos` (copies of one site on
/// the tripled line share a key), so "nearest" is a strict total order at every t.
struct Parabola {
  std::int64_t pos = 0;
  std::int64_t height = 0;
  std::int64_t key = 0;
};

bool wins_tie(const Parabola& q, const Parabola& p) {
  return q.key < p.key || (q.key == p.key && q.pos < p.pos);
}

std::int64_t floor_div(std::int64_t num, std::int64_t den) {  // den > 0
  return num >= 0 ? num / den : -((-num + den - 1) / den);
}

/// The first integer t from which `q` beats `p` (p.pos < q.pos). q is lower than p exactly for
/// t > s = ((q.height + q.pos^2) - (p.height + p.pos^2)) / (2 (q.pos - p.pos)); at t == s (when
/// s is an integer) the tie order decides. Exact in 64-bit integers.
std::int64_t first_win(const Parabola& p, const Parabola& q) {
  const std::int64_t num = (q.height + q.pos * q.pos) - (p.height + p.pos * p.pos);
  const std::int64_t den = 2 * (q.pos - p.pos);
  return wins_tie(q, p) ? -floor_div(-num, den)  // ceil(s): q takes the tie
                        : floor_div(num, den) + 1;
}

/// Scratch space of `nearest_sites`, reused along the lines one worker handles.
struct Envelope {
  std::vector<int> v;           // parabolas on the envelope, by position
  std::vector<std::int64_t> z;  // z[k]: the first integer t where v[k] is the nearest
  std::vector<Parabola> sites;  // the current line's parabolas, by ascending position
};

/// For t = 0 .. n-1 writes to `out[t]` the index into `e.sites` (non-empty, ascending `pos`) of
/// the nearest site at t in the order of `Parabola`. Whether q beats p (p.pos < q.pos) is a
/// half-line of integers [first_win(p, q), inf), so each parabola of the envelope is the nearest
/// on one run of integers and the classic stack construction is exact here.
void nearest_sites(Envelope& e, int n, int* out) {
  const std::vector<Parabola>& s = e.sites;
  e.v.assign(1, 0);
  e.z.assign(1, std::numeric_limits<std::int64_t>::min());
  for (int q = 1; q < int(s.size()); ++q) {
    std::int64_t b = first_win(s[std::size_t(e.v.back())], s[std::size_t(q)]);
    // z[0] is -infinity: a parabola never beats one to its left everywhere.
    while (e.v.size() > 1 && b <= e.z.back()) {
      e.v.pop_back();
      e.z.pop_back();
      b = first_win(s[std::size_t(e.v.back())], s[std::size_t(q)]);
    }
    e.v.push_back(q);
    e.z.push_back(b);
  }
  std::size_t k = 0;
  for (int t = 0; t < n; ++t) {
    while (k + 1 < e.v.size() && e.z[k + 1] <= t) ++k;
    out[t] = e.v[k];
  }
}

/// Whether position p (of a site's copy shifted by -period, 0 or +period) can be nearest to
/// some t in [0, period): only copies within period / 2 of that range can, the others are left
/// out (the copy that is near has the same key, so the answers do not change).
bool within_reach(std::int64_t p, int period) {
  return p >= -(period / 2) - 1 && p <= period + period / 2;
}

std::int64_t torus_distance(int a, int b, int period) {
  const int d = a > b ? a - b : b - a;
  return std::min(d, period - d);
}

/// The sRGB premultiplication table: [a][c] = linear_to_srgb8(srgb8_to_linear(c) * a / 255).
const std::array<std::uint8_t, 256 * 256>& srgb_premultiply_table() {
  static const std::array<std::uint8_t, 256 * 256> table = [] {
    std::array<std::uint8_t, 256 * 256> t{};
    for (int a = 0; a < 256; ++a) {
      const float scale = float(a) / 255.0f;
      for (int c = 0; c < 256; ++c) {
        t[std::size_t(a) * 256 + std::size_t(c)] =
            linear_to_srgb8(srgb8_to_linear(std::uint8_t(c)) * scale);
      }
    }
    return t;
  }();
  return table;
}

}  // namespace

void flip_y(ImageRGBA8& image) {
  const std::size_t row = std::size_t(image.width) * 4;
  for (int y = 0; y < image.height / 2; ++y) {
    std::swap_ranges(image.at(0, y), image.at(0, y) + row, image.at(0, image.height - 1 - y));
  }
}

void premultiply_alpha(ImageRGBA8& image, bool srgb, const Parallel& parallel) {
  if (!image.has_alpha || image.empty()) return;
  const std::uint8_t* table = srgb ? srgb_premultiply_table().data() : nullptr;
  detail::for_each_texel(image, parallel, [&](std::uint8_t* p) {
    const unsigned a = p[3];
    for (int c = 0; c < 3; ++c) {
      // (c a + 127) / 255 is c a / 255 rounded to nearest: c a / 255 is never k + 1/2.
      p[c] = table ? table[a * 256 + p[c]] : std::uint8_t((p[c] * a + 127) / 255);
    }
  });
}

void bleed_alpha(ImageRGBA8& image, const Parallel& parallel) {
  if (!image.has_alpha || image.empty()) return;
  const int w = image.width, h = image.height;
  const std::size_t n = image.pixel_count();
  bool any_visible = false, any_clear = false;
  std::vector<std::uint8_t> row_has_clear(std::size_t(h), 0);
  for (std::size_t i = 0; i < n; ++i) {
    const bool visible = image.pixels[i * 4 + 3] != 0;
    any_visible |= visible;
    any_clear |= !visible;
    if (!visible) row_has_clear[i / std::size_t(w)] = 1;
  }
  if (!any_visible || !any_clear) return;

  // Pass 1, down each column: nearest_row[y * w + x] is the row of the visible texel of column
  // x nearest to row y on the wrapped column (of two equally near, the one in the smaller row),
  // or -1 when the column has none. The column's sites appear three times (shifted by -h, 0,
  // +h; `within_reach`) so that the plain 1-D transform over rows 0 .. h-1 sees the wrapped
  // distances.
  std::vector<std::int32_t> nearest_row(n, -1);
  constexpr int kColumnGrain = 32;
  parallel_for(
      0, w, kColumnGrain,
      [&](std::int64_t x0, std::int64_t x1) {
        const int cols = int(x1 - x0);
        std::vector<std::vector<int>> rows(std::size_t(cols), std::vector<int>{});
        for (int y = 0; y < h; ++y) {
          for (int i = 0; i < cols; ++i) {
            if (image.at(int(x0) + i, y)[3] != 0) rows[std::size_t(i)].push_back(y);
          }
        }
        Envelope e;
        std::vector<int> best(std::size_t(h), 0);
        for (int i = 0; i < cols; ++i) {
          const std::vector<int>& r = rows[std::size_t(i)];
          if (r.empty()) continue;
          e.sites.clear();
          for (int copy = -1; copy <= 1; ++copy) {
            for (const int y : r) {
              const std::int64_t p = y + std::int64_t(copy) * h;
              if (within_reach(p, h)) e.sites.push_back({p, 0, y});
            }
          }
          nearest_sites(e, h, best.data());
          for (int y = 0; y < h; ++y) {
            nearest_row[std::size_t(y) * std::size_t(w) + std::size_t(x0) + std::size_t(i)] =
                std::int32_t(e.sites[std::size_t(best[std::size_t(y)])].key);
          }
        }
      },
      parallel);

  // Pass 2, along each row with a transparent texel: column c offers its nearest visible texel
  // (c, r) as a parabola of height (vertical distance)^2 and key r * w + c, its row-major index,
  // so equally near texels resolve to the first in row-major order (within one column, pass 1
  // already kept the first). Columns again appear three times (-w, 0, +w). Only transparent
  // texels are written and only visible ones read, so rows run in parallel.
  parallel_for(
      0, h, 8,
      [&](std::int64_t y0, std::int64_t y1) {
        Envelope e;
        std::vector<int> best(std::size_t(w), 0);
        for (std::int64_t y = y0; y < y1; ++y) {
          if (!row_has_clear[std::size_t(y)]) continue;
          const std::int32_t* row = &nearest_row[std::size_t(y) * std::size_t(w)];
          e.sites.clear();
          for (int copy = -1; copy <= 1; ++copy) {
            for (int c = 0; c < w; ++c) {
              const std::int64_t p = c + std::int64_t(copy) * w;
              if (row[c] < 0 || !within_reach(p, w)) continue;
              const std::int64_t dy = torus_distance(int(y), row[c], h);
              e.sites.push_back({p, dy * dy, std::int64_t(row[c]) * w + c});
            }
          }
          nearest_sites(e, w, best.data());
          for (int x = 0; x < w; ++x) {
            std::uint8_t* p = image.at(x, int(y));
            if (p[3] != 0) continue;
            const std::int64_t key = e.sites[std::size_t(best[std::size_t(x)])].key;
            const std::uint8_t* from = image.at(int(key % w), int(key / w));
            p[0] = from[0];
            p[1] = from[1];
            p[2] = from[2];
          }
        }
      },
      parallel);
}

void normalise_normals(ImageRGBA8& image, const Parallel& parallel) {
  detail::for_each_texel(image, parallel, [](std::uint8_t* p) {
    double v[3] = {detail::decode_normal(p[0]), detail::decode_normal(p[1]),
                   detail::decode_normal(p[2])};
    detail::normalise_or_z(v);
    for (int c = 0; c < 3; ++c) p[c] = detail::encode_normal(v[c]);
  });
}

}  // namespace tessera::image
