// Normal maps: the modulation of every texel chosen by the angle a renderer sees.
//
// A renderer renormalises the vector it samples from a normal map, so what matters is the
// angle between the decoded vector and the source's, not their squared RGB distance: of two
// decodes at the same RGB distance, the one along the source direction (too long or too short)
// costs nothing. With the endpoints fixed, a texel's modulation decides only its own colour
// (4 bpp, and 2 bpp blocks in direct mode), so choosing for every texel the value whose decode
// makes the smallest angle is exact and can only lower every texel's angle.
#include <cmath>
#include <vector>

#include "pvrtc/encode/encode_internal.h"

namespace tessera::pvrtc::detail {

namespace {

/// The vector of an 8-bit RGB texel (2 c / 255 - 1).
struct Vec3 {
  float x, y, z;
};
inline Vec3 vector_of(const std::uint8_t* c) {
  constexpr float k = 2.0f / 255.0f;
  return {float(c[0]) * k - 1.0f, float(c[1]) * k - 1.0f, float(c[2]) * k - 1.0f};
}

/// cos of the angle between `v` and the unit target `t` (-2 for a zero vector: never chosen
/// over a real one).
inline float cosine(const Vec3& v, const Vec3& t) {
  const float len = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  if (len < 1e-6f) return -2.0f;
  return (v.x * t.x + v.y * t.y + v.z * t.z) / len;
}

/// The decode of weight `m` (in eighths) between the upscaled endpoints `a` and `b`.
inline void blend(const std::uint8_t* a, const std::uint8_t* b, int m, std::uint8_t out[3]) {
  for (int c = 0; c < 3; ++c) out[c] = std::uint8_t((a[c] * (8 - m) + b[c] * m) / 8);
}

/// The best of the `n` weights `weights` for one texel, keeping `current` unless another is
/// strictly better (so an already optimal choice leaves the bytes as they were).
int best_code(const std::uint8_t* a, const std::uint8_t* b, const std::uint8_t* target,
              const int* weights, const int* codes, int n, int current) {
  Vec3 t = vector_of(target);
  const float tl = std::sqrt(t.x * t.x + t.y * t.y + t.z * t.z);
  if (tl < 1e-6f) {
    t = {0.0f, 0.0f, 1.0f};
  } else {
    t = {t.x / tl, t.y / tl, t.z / tl};
  }
  int best = current;
  float best_cos = -3.0f;
  for (int k = 0; k < n; ++k) {
    if (codes[k] != current) continue;
    std::uint8_t c[3];
    blend(a, b, weights[k], c);
    best_cos = cosine(vector_of(c), t);
  }
  for (int k = 0; k < n; ++k) {
    std::uint8_t c[3];
    blend(a, b, weights[k], c);
    const float cs = cosine(vector_of(c), t);
    if (cs > best_cos) {
      best_cos = cs;
      best = codes[k];
    }
  }
  return best;
}

}  // namespace

void choose_modulation_angular(EncoderState& s) {
  const Grid& g = s.g;
  const std::vector<std::uint64_t> words = s.words();
  std::vector<Rgba5> ea(g.blocks()), eb(g.blocks());
  expand_endpoints(g, words.data(), ea.data(), eb.data(), s.threads);
  const bool is4 = g.format == Format::pvrtc1_4bpp;
  const std::size_t row_bytes = std::size_t(g.pw) * 4;
  parallel_for(
      0, g.nby, 1,
      [&](std::int64_t r0, std::int64_t r1) {
        std::vector<std::uint8_t> ua(row_bytes * 4), ub(row_bytes * 4);
        for (int by = int(r0); by < int(r1); ++by) {
          upscale_rows(g, ea.data(), by * 4, by * 4 + 4, ua.data());
          upscale_rows(g, eb.data(), by * 4, by * 4 + 4, ub.data());
          for (int bx = 0; bx < g.nbx; ++bx) {
            const std::size_t i = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
            auto texel = [&](const std::vector<std::uint8_t>& u, int tx, int ty) {
              return u.data() + std::size_t(ty) * row_bytes + std::size_t(bx * g.bw + tx) * 4;
            };
            auto target = [&](int tx, int ty) {
              return s.target.data() +
                     (std::size_t(by * 4 + ty) * std::size_t(g.pw) + std::size_t(bx * g.bw + tx)) *
                         4;
            };
            if (is4) {
              // Mode 0: codes 0..3 are weights 0, 3, 5, 8. Mode 1: codes 0, 1, 3 are weights
              // 0, 4, 8; code 2 (punch-through) also sets alpha, so its texels keep it.
              static constexpr int kW0[4] = {0, 3, 5, 8}, kC0[4] = {0, 1, 2, 3};
              static constexpr int kW1[3] = {0, 4, 8}, kC1[3] = {0, 1, 3};
              const bool m1 = s.mode[i] != 0;
              std::uint32_t bits = s.mod[i];
              for (int ty = 0; ty < 4; ++ty) {
                for (int tx = 0; tx < 4; ++tx) {
                  const int shift = 2 * (4 * ty + tx);
                  const int cur = int(bits >> shift) & 3;
                  if (m1 && cur == 2) continue;
                  const int code = m1 ? best_code(texel(ua, tx, ty), texel(ub, tx, ty),
                                                  target(tx, ty), kW1, kC1, 3, cur)
                                      : best_code(texel(ua, tx, ty), texel(ub, tx, ty),
                                                  target(tx, ty), kW0, kC0, 4, cur);
                  bits = (bits & ~(3u << shift)) | (std::uint32_t(code) << shift);
                }
              }
              s.mod[i] = bits;
            } else if (s.mode[i] == 0) {
              // 2 bpp direct mode: each texel takes A or B (stored 0 or 3). Interpolated
              // blocks share values between texels and are left as they are.
              std::uint8_t values[32];
              int mode = 0;
              unpack_2bpp_block(s.word(i), values, mode);
              static constexpr int kW[2] = {0, 8}, kC[2] = {0, 3};
              for (int ty = 0; ty < 4; ++ty) {
                for (int tx = 0; tx < 8; ++tx) {
                  std::uint8_t& v = values[ty * 8 + tx];
                  v = std::uint8_t(best_code(texel(ua, tx, ty), texel(ub, tx, ty), target(tx, ty),
                                             kW, kC, 2, v));
                }
              }
              s.mod[i] = pack_2bpp_block(values, mode);
            }
          }
        }
      },
      {s.threads});
}

}  // namespace tessera::pvrtc::detail
