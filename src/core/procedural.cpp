// Deterministic procedural images for demos and tests.
#include "tessera/procedural.h"

#include <algorithm>
#include <cmath>

namespace tessera {

namespace {

std::uint32_t hash3(std::int32_t x, std::int32_t y, std::uint32_t seed) {
  std::uint32_t h = seed * 0x9E3779B1u;
  h ^= std::uint32_t(x) * 0x85EBCA77u;
  h = (h << 13) | (h >> 19);
  h ^= std::uint32_t(y) * 0xC2B2AE3Du;
  h ^= h >> 16;
  h *= 0x7FEB352Du;
  h ^= h >> 15;
  h *= 0x846CA68Bu;
  h ^= h >> 16;
  return h;
}

double unit_hash(std::int32_t x, std::int32_t y, std::uint32_t seed) {
  return double(hash3(x, y, seed) & 0xFFFFFF) / double(0xFFFFFF);
}

/// Smooth value noise in [0, 1] at (x, y) with integer lattice cells.
double value_noise(double x, double y, std::uint32_t seed) {
  const double fx = std::floor(x), fy = std::floor(y);
  const std::int32_t ix = std::int32_t(fx), iy = std::int32_t(fy);
  double tx = x - fx, ty = y - fy;
  tx = tx * tx * (3.0 - 2.0 * tx);
  ty = ty * ty * (3.0 - 2.0 * ty);
  const double a = unit_hash(ix, iy, seed), b = unit_hash(ix + 1, iy, seed);
  const double c = unit_hash(ix, iy + 1, seed), d = unit_hash(ix + 1, iy + 1, seed);
  return (a + (b - a) * tx) + ((c + (d - c) * tx) - (a + (b - a) * tx)) * ty;
}

double fbm(double x, double y, int octaves, std::uint32_t seed) {
  double sum = 0.0, amp = 0.5, norm = 0.0;
  for (int o = 0; o < octaves; ++o) {
    sum += amp * value_noise(x, y, seed + std::uint32_t(o) * 101u);
    norm += amp;
    x *= 2.0;
    y *= 2.0;
    amp *= 0.5;
  }
  return sum / norm;
}

std::uint8_t to8(double v) { return std::uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); }

void put(ImageRGBA8& img, int x, int y, double r, double g, double b, double a = 1.0) {
  std::uint8_t* p = img.at(x, y);
  p[0] = to8(r);
  p[1] = to8(g);
  p[2] = to8(b);
  p[3] = to8(a);
}

}  // namespace

const std::vector<Procedural>& all_procedurals() {
  static const std::vector<Procedural> kinds = {Procedural::gradient, Procedural::bricks,
                                                Procedural::noise, Procedural::foliage,
                                                Procedural::text};
  return kinds;
}

const char* procedural_name(Procedural kind) {
  switch (kind) {
    case Procedural::gradient:
      return "gradient";
    case Procedural::bricks:
      return "bricks";
    case Procedural::noise:
      return "noise";
    case Procedural::foliage:
      return "foliage";
    case Procedural::text:
      return "text";
  }
  return "unknown";
}

ImageRGBA8 make_procedural(Procedural kind, int width, int height, std::uint32_t seed) {
  ImageRGBA8 img(width, height);
  img.has_alpha = kind == Procedural::foliage;
  const double s = 256.0 / double(std::max(width, height));  // content scale: 256-px design
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double u = (x + 0.5) * s, v = (y + 0.5) * s;  // design pixels
      switch (kind) {
        case Procedural::gradient: {
          const double dx = u - 128.0, dy = v - 110.0;
          const double r = std::sqrt(dx * dx + dy * dy);
          const double ring = 0.5 + 0.5 * std::cos(r / 9.0);
          put(img, x, y, 0.15 + 0.7 * u / 256.0, 0.2 + 0.5 * ring * (1.0 - v / 256.0),
              0.25 + 0.6 * v / 256.0);
          break;
        }
        case Procedural::bricks: {
          const double bh = 16.0, bw = 36.0;
          const int row = int(std::floor(v / bh));
          const double off = (row & 1) ? bw * 0.5 : 0.0;
          const int col = int(std::floor((u + off) / bw));
          const double lu = std::fmod(u + off, bw), lv = std::fmod(v, bh);
          const bool mortar = lu < 2.5 || lv < 2.5;
          const double n = fbm(u / 6.0, v / 6.0, 3, seed + 7);
          if (mortar) {
            put(img, x, y, 0.78 * n + 0.1, 0.76 * n + 0.1, 0.7 * n + 0.1);
          } else {
            const double tint = unit_hash(col, row, seed);
            put(img, x, y, 0.45 + 0.35 * tint + 0.15 * n, 0.18 + 0.15 * tint + 0.1 * n,
                0.12 + 0.08 * n);
          }
          break;
        }
        case Procedural::noise: {
          const double n = fbm(u / 24.0, v / 24.0, 6, seed);
          const double m = fbm(u / 40.0 + 17.0, v / 40.0, 4, seed + 3);
          put(img, x, y, 0.2 + 0.7 * n, 0.15 + 0.6 * n * m + 0.2 * m, 0.1 + 0.5 * (1.0 - m) * n);
          break;
        }
        case Procedural::foliage: {
          // Leaves: noise-shaped blobs, cut out where the density falls below a threshold,
          // with a 2-pixel soft edge.
          const double d = fbm(u / 18.0, v / 18.0, 4, seed + 11);
          const double vein = std::abs(std::sin((u + 1.7 * v) / 5.0));
          const double a = std::clamp((d - 0.48) / 0.06, 0.0, 1.0);
          put(img, x, y, 0.1 + 0.25 * d, 0.3 + 0.5 * d * (0.7 + 0.3 * vein), 0.08 + 0.1 * vein, a);
          break;
        }
        case Procedural::text: {
          // Glyph-like strokes: a grid of cells, each with hashed horizontal/vertical/diagonal
          // bars one to two pixels wide.
          const int cx = int(u / 12.0), cy = int(v / 16.0);
          const double lu = std::fmod(u, 12.0), lv = std::fmod(v, 16.0);
          const std::uint32_t h = hash3(cx, cy, seed);
          bool ink = false;
          if ((h & 1) && std::abs(lu - 3.0) < 0.9 && lv > 3 && lv < 13) ink = true;
          if ((h & 2) && std::abs(lu - 8.0) < 0.9 && lv > 3 && lv < 13) ink = true;
          if ((h & 4) && std::abs(lv - 4.0) < 0.9 && lu > 2 && lu < 9) ink = true;
          if ((h & 8) && std::abs(lv - 8.0) < 0.9 && lu > 2 && lu < 9) ink = true;
          if ((h & 16) && std::abs(lv - 12.0) < 0.9 && lu > 2 && lu < 9) ink = true;
          if ((h & 32) && std::abs((lu - 2.0) * 10.0 / 7.0 - (lv - 3.0)) < 1.0 && lv > 3 && lv < 13)
            ink = true;
          const double paper = 0.93 - 0.05 * (v / 256.0);
          if (ink) {
            put(img, x, y, 0.08, 0.08, 0.2);
          } else {
            put(img, x, y, paper, paper - 0.02, paper - 0.08);
          }
          break;
        }
      }
    }
  }
  return img;
}

}  // namespace tessera
