// PVRTC1 decoder (bit-exact with PVRTexTool 4.17) and level geometry helpers.
#include <algorithm>
#include <bit>
#include <cstring>
#include <string>

#include "core/simd.h"
#include "pvrtc/format/pvrtc_internal.h"
#include "tessera/pvrtc.h"

namespace tessera::pvrtc {

using namespace detail;

int block_width(Format format) { return format == Format::pvrtc1_2bpp ? 8 : 4; }
int blocks_x(Format format, int width) { return std::max(width / block_width(format), 2); }
int blocks_y(Format /*format*/, int height) { return std::max(height / 4, 2); }
std::size_t block_count(Format format, int width, int height) {
  return std::size_t(blocks_x(format, width)) * std::size_t(blocks_y(format, height));
}
std::size_t level_size(Format format, int width, int height) {
  return block_count(format, width, height) * 8;
}

Status check_dimensions(int width, int height, const std::string& what) {
  if (width <= 0 || height <= 0 || width > kMaxImageDimension || height > kMaxImageDimension) {
    return Status::error(ErrorCode::invalid_argument,
                         what + ": PVRTC size " + std::to_string(width) + "x" +
                             std::to_string(height) + " is out of range (1.." +
                             std::to_string(kMaxImageDimension) + ")");
  }
  if (!std::has_single_bit(unsigned(width)) || !std::has_single_bit(unsigned(height))) {
    return Status::error(ErrorCode::invalid_argument,
                         what + ": PVRTC1 needs power-of-two dimensions, got " +
                             std::to_string(width) + "x" + std::to_string(height));
  }
  return check_image_size(width, height, what);
}

bool may_have_alpha(std::span<const std::uint8_t> data, Format format) {
  constexpr std::uint64_t kOpaqueBits = (std::uint64_t{1} << 47) | (std::uint64_t{1} << 63);
  for (std::size_t at = 0; at + 8 <= data.size(); at += 8) {
    std::uint64_t word = 0;
    for (int i = 0; i < 8; ++i) word |= std::uint64_t(data[at + std::size_t(i)]) << (8 * i);
    if ((word & kOpaqueBits) != kOpaqueBits) return true;  // a translucent endpoint
    if (format == Format::pvrtc1_4bpp && ((word >> 32) & 1) != 0) {
      // Punch-through block: a 2-bit value 2 (binary 10) has its high bit set, its low bit clear.
      const std::uint32_t mod = std::uint32_t(word);
      if ((mod & ~(mod << 1) & 0xAAAAAAAAu) != 0) return true;
    }
  }
  return false;
}

std::uint32_t morton_index(std::uint32_t bx, std::uint32_t by, std::uint32_t bw, std::uint32_t bh) {
  return morton(bx, by, bw, bh);
}

namespace detail {

Grid make_grid(Format format, int width, int height) {
  Grid g;
  g.format = format;
  g.bw = block_width(format);
  g.nbx = blocks_x(format, width);
  g.nby = blocks_y(format, height);
  g.pw = g.nbx * g.bw;
  g.ph = g.nby * 4;
  TESSERA_DCHECK(g.nbx >= 2 && (g.nbx & (g.nbx - 1)) == 0);
  TESSERA_DCHECK(g.nby >= 2 && (g.nby & (g.nby - 1)) == 0);
  return g;
}

namespace {

// The Morton index is the bitwise or of a part that depends on bx only and one on by only.
// Per m_eff byte: the blend weights of A and B for each channel and the output mask (alpha 0
// under punch-through), 4 bytes each, for `modulate_run`.
struct BlendTables {
  std::uint8_t wa[256][4], wb[256][4], mask[256][4];
};
constexpr BlendTables make_blend_tables() {
  BlendTables t{};
  for (int e = 0; e < 256; ++e) {
    const int m = e & 0x0f;
    for (int c = 0; c < 4; ++c) {
      t.wa[e][c] = std::uint8_t(m <= 8 ? 8 - m : 0);
      t.wb[e][c] = std::uint8_t(m);
      t.mask[e][c] = std::uint8_t(c == 3 && (e & kPunchFlag) ? 0 : 0xff);
    }
  }
  return t;
}
constexpr BlendTables kBlend = make_blend_tables();

// `modulate` over `n` consecutive texels, two a step through the SIMD wrapper (16-bit lanes:
// at most 255 * 8 before the shift): the same bytes as the per-texel kernel.
void modulate_run(const std::uint8_t* a, const std::uint8_t* b, const std::uint8_t* m_eff,
                  std::size_t n, std::uint8_t* out) {
  using simd::vu16x8;
  std::size_t i = 0;
  for (; i + 2 <= n; i += 2) {
    const std::uint8_t e0 = m_eff[i], e1 = m_eff[i + 1];
    const vu16x8 blend =
        simd::mullo(simd::load_u8x8(a + i * 4), simd::load_u8x4x2(kBlend.wa[e0], kBlend.wa[e1])) +
        simd::mullo(simd::load_u8x8(b + i * 4), simd::load_u8x4x2(kBlend.wb[e0], kBlend.wb[e1]));
    simd::store_u8x8(simd::srl<3>(blend) & simd::load_u8x4x2(kBlend.mask[e0], kBlend.mask[e1]),
                     out + i * 4);
  }
  for (; i < n; ++i) modulate(a + i * 4, b + i * 4, m_eff[i], out + i * 4);
}

/// Calls `f(m, i)` for every block of `g`: `m` its Morton-order index in the data, `i` its
/// row-major index.
template <class F>
void for_each_block(const Grid& g, F f) {
  std::vector<std::uint32_t> mx(std::size_t(g.nbx)), my(std::size_t(g.nby));
  for (int bx = 0; bx < g.nbx; ++bx) {
    mx[std::size_t(bx)] = morton(std::uint32_t(bx), 0, std::uint32_t(g.nbx), std::uint32_t(g.nby));
  }
  for (int by = 0; by < g.nby; ++by) {
    my[std::size_t(by)] = morton(0, std::uint32_t(by), std::uint32_t(g.nbx), std::uint32_t(g.nby));
  }
  for (int by = 0; by < g.nby; ++by) {
    for (int bx = 0; bx < g.nbx; ++bx) {
      const std::uint32_t m = mx[std::size_t(bx)] | my[std::size_t(by)];
      TESSERA_DCHECK(m < g.blocks());
      f(std::size_t(m), std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx));
    }
  }
}

}  // namespace

void load_words(const Grid& g, const std::uint8_t* data, std::uint64_t* words) {
  for_each_block(g, [&](std::size_t m, std::size_t i) {
    std::uint64_t w = 0;
    for (int k = 7; k >= 0; --k) w = (w << 8) | data[m * 8 + std::size_t(k)];
    words[i] = w;
  });
}

void store_words(const Grid& g, const std::uint64_t* words, std::uint8_t* data) {
  for_each_block(g, [&](std::size_t m, std::size_t i) {
    std::uint64_t w = words[i];
    for (int k = 0; k < 8; ++k) {
      data[m * 8 + std::size_t(k)] = std::uint8_t(w & 0xff);
      w >>= 8;
    }
  });
}

void expand_endpoints(const Grid& g, const std::uint64_t* words, Rgba5* ea, Rgba5* eb,
                      int threads) {
  parallel_for(0, std::int64_t(g.blocks()), 4096,
               [&](std::int64_t b0, std::int64_t b1) {
                 for (std::int64_t i = b0; i < b1; ++i) {
                   ea[i] = expand_a(std::uint32_t(words[i] >> 32) & 0xffffu);
                   eb[i] = expand_b(std::uint32_t(words[i] >> 48));
                 }
               },
               {threads});
}

void unpack_2bpp_block(std::uint64_t word, std::uint8_t values[32], int& mode) {
  std::uint32_t bits = std::uint32_t(word);
  mode = int((word >> 32) & 1);
  if (mode == 0) {
    for (int i = 0; i < 32; ++i) values[i] = (bits >> i) & 1 ? 3 : 0;
    return;
  }
  if (bits & 1) {
    mode = (bits & (1u << 20)) ? 3 : 2;
    if (bits & (1u << 21)) {
      bits |= 1u << 20;
    } else {
      bits &= ~(1u << 20);
    }
  }
  if (bits & 2) {
    bits |= 1;
  } else {
    bits &= ~1u;
  }
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 8; ++x) {
      if (((x ^ y) & 1) == 0) {
        values[y * 8 + x] = std::uint8_t(bits & 3);
        bits >>= 2;
      } else {
        values[y * 8 + x] = 0;
      }
    }
  }
}

std::uint32_t pack_2bpp_block(const std::uint8_t v[32], int mode) {
  TESSERA_DCHECK(mode >= 0 && mode <= 3);                  // direct, interpolated, H only, V only
  for (int i = 0; i < 32; ++i) TESSERA_DCHECK(v[i] <= 3);  // 2-bit stored modulation values
  if (mode == 0) {
    std::uint32_t bits = 0;
    for (int i = 0; i < 32; ++i) bits |= std::uint32_t(v[i] == 3) << i;
    return bits;
  }
  std::uint32_t bits = 0;
  int k = 0;
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 8; ++x) {
      if ((x ^ y) & 1) continue;
      bits |= std::uint32_t(v[y * 8 + x]) << (2 * k);
      ++k;
    }
  }
  // Texel (0, 0): bit 1 is its value (0 or 3), bit 0 flags H / V only.
  bits = (bits & ~3u) | (v[0] == 3 ? 2u : 0u) | (mode != 1 ? 1u : 0u);
  if (mode != 1) {  // texel (4, 2) is bits 20-21: bit 21 its value, bit 20 flags V only
    bits = (bits & ~(3u << 20)) | (v[2 * 8 + 4] == 3 ? 1u << 21 : 0u) | (mode == 3 ? 1u << 20 : 0u);
  }
  return bits;
}

void modulation_map(const Grid& g, const std::uint64_t* words, std::uint8_t* m_eff, int threads) {
  const int pw = g.pw;
  if (g.format == Format::pvrtc1_4bpp) {
    parallel_for(0, g.nby, 8,
                 [&](std::int64_t by0, std::int64_t by1) {
                   for (std::int64_t by = by0; by < by1; ++by) {
                     for (int bx = 0; bx < g.nbx; ++bx) {
                       const std::uint64_t w =
                           words[std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx)];
                       const bool mode1 = (w >> 32) & 1;
                       const std::uint32_t bits = std::uint32_t(w);
                       for (int y = 0; y < 4; ++y) {
                         std::uint8_t* row =
                             m_eff + (std::size_t(by) * 4 + std::size_t(y)) * std::size_t(pw) +
                             std::size_t(bx) * 4;
                         for (int x = 0; x < 4; ++x) {
                           const std::uint32_t v = (bits >> (2 * (4 * y + x))) & 3;
                           if (mode1) {
                             row[x] = std::uint8_t(kMod4Mode1[v] | (v == 2 ? kPunchFlag : 0));
                           } else {
                             row[x] = std::uint8_t(kMod4Mode0[v]);
                           }
                         }
                       }
                     }
                   }
                 },
                 {threads});
    return;
  }
  // 2 bpp: unpack stored values and modes, then resolve interpolated texels.
  std::vector<std::uint8_t> stored(g.texels());
  std::vector<std::uint8_t> modes(g.blocks());
  parallel_for(0, g.nby, 8,
               [&](std::int64_t by0, std::int64_t by1) {
                 std::uint8_t vals[32];
                 for (std::int64_t by = by0; by < by1; ++by) {
                   for (int bx = 0; bx < g.nbx; ++bx) {
                     const std::size_t bi = std::size_t(by) * std::size_t(g.nbx) + std::size_t(bx);
                     int mode = 0;
                     unpack_2bpp_block(words[bi], vals, mode);
                     modes[bi] = std::uint8_t(mode);
                     for (int y = 0; y < 4; ++y) {
                       std::memcpy(
                           &stored[(std::size_t(by) * 4 + std::size_t(y)) * std::size_t(pw) +
                                   std::size_t(bx) * 8],
                           &vals[y * 8], 8);
                     }
                   }
                 }
               },
               {threads});
  const int wmask = g.pw - 1, hmask = g.ph - 1;
  parallel_for(0, g.ph, 32,
               [&](std::int64_t y0, std::int64_t y1) {
                 for (std::int64_t yy = y0; yy < y1; ++yy) {
                   const int y = int(yy);
                   const std::uint8_t* row = &stored[std::size_t(y) * std::size_t(pw)];
                   const std::uint8_t* up = &stored[std::size_t((y - 1) & hmask) * std::size_t(pw)];
                   const std::uint8_t* dn = &stored[std::size_t((y + 1) & hmask) * std::size_t(pw)];
                   std::uint8_t* out = m_eff + std::size_t(y) * std::size_t(pw);
                   for (int x = 0; x < pw; ++x) {
                     const int mode =
                         modes[std::size_t(y >> 2) * std::size_t(g.nbx) + std::size_t(x >> 3)];
                     if (mode == 0 || ((x ^ y) & 1) == 0) {
                       out[x] = std::uint8_t(kMod4Mode0[row[x]]);
                       continue;
                     }
                     const std::int32_t l = kMod4Mode0[row[(x - 1) & wmask]];
                     const std::int32_t r = kMod4Mode0[row[(x + 1) & wmask]];
                     const std::int32_t u = kMod4Mode0[up[x]];
                     const std::int32_t d = kMod4Mode0[dn[x]];
                     std::int32_t m;
                     if (mode == 1) {
                       m = (u + d + l + r + 2) / 4;
                     } else if (mode == 2) {
                       m = (l + r + 1) / 2;
                     } else {
                       m = (u + d + 1) / 2;
                     }
                     out[x] = std::uint8_t(m);
                   }
                 }
               },
               {threads});
}

void upscale_rows(const Grid& g, const Rgba5* e, int y0, int y1, std::uint8_t* out) {
  using simd::vi32x4;
  static_assert(sizeof(Rgba5) == 4 * sizeof(std::int32_t));
  const int bw = g.bw, half = bw / 2, wmask = g.pw - 1;
  const vi32x4 step_scale(8 / bw);
  for (int y = y0; y < y1; ++y) {
    const AxisTap ty = axis_tap(y, 4, g.ph);
    const Rgba5* r0 = e + std::size_t(ty.b0) * std::size_t(g.nbx);
    const Rgba5* r1 = e + std::size_t(ty.b1) * std::size_t(g.nbx);
    const vi32x4 wy0(4 - ty.d), wy1(ty.d);
    std::uint8_t* o = out + std::size_t(y - y0) * std::size_t(g.pw) * 4;
    // Between the centres of blocks bx and bx + 1 the column sums are linear in x: the bilinear
    // sum (weights scaled to 32) starts at 8 L and grows by (R - L) * 8 / bw per texel.
    for (int bx = 0; bx < g.nbx; ++bx) {
      const int bx1 = (bx + 1) & (g.nbx - 1);
      const vi32x4 left = simd::load4(&r0[bx].r) * wy0 + simd::load4(&r1[bx].r) * wy1;
      const vi32x4 right = simd::load4(&r0[bx1].r) * wy0 + simd::load4(&r1[bx1].r) * wy1;
      vi32x4 w = left * vi32x4(8);
      const vi32x4 step = (right - left) * step_scale;
      const int x0 = bx * bw + half;
      for (int d = 0; d < bw; ++d) {
        const vi32x4 rgb = simd::sra<7>(w) + simd::sra<2>(w);
        const vi32x4 a = simd::sra<5>(w) + simd::sra<1>(w);
        simd::store_u8x4(simd::select_alpha(rgb, a), o + std::size_t((x0 + d) & wmask) * 4);
        w += step;
      }
    }
  }
}

void decode_padded(const Grid& g, const std::uint64_t* words, std::uint8_t* out, int threads) {
  std::vector<Rgba5> ea(g.blocks()), eb(g.blocks());
  expand_endpoints(g, words, ea.data(), eb.data(), threads);
  std::vector<std::uint8_t> m(g.texels());
  modulation_map(g, words, m.data(), threads);
  parallel_for(0, g.ph, 16,
               [&](std::int64_t y0, std::int64_t y1) {
                 std::vector<std::uint8_t> ua(std::size_t(g.pw) * 4 * std::size_t(y1 - y0));
                 std::vector<std::uint8_t> ub(ua.size());
                 upscale_rows(g, ea.data(), int(y0), int(y1), ua.data());
                 upscale_rows(g, eb.data(), int(y0), int(y1), ub.data());
                 const std::size_t first = std::size_t(y0) * std::size_t(g.pw);
                 modulate_run(ua.data(), ub.data(), &m[first],
                              std::size_t(y1 - y0) * std::size_t(g.pw), out + first * 4);
               },
               {threads});
}

}  // namespace detail

Result<ImageRGBA8> decode(std::span<const std::uint8_t> data, Format format, int width, int height,
                          const Parallel& parallel) {
  if (Status s = check_dimensions(width, height, "pvrtc::decode"); !s.ok()) return s;
  const std::size_t need = level_size(format, width, height);
  if (data.size() < need) {
    return Status::error(ErrorCode::corrupt_data, "pvrtc::decode: level needs " +
                                                      std::to_string(need) + " bytes, got " +
                                                      std::to_string(data.size()));
  }
  const Grid g = make_grid(format, width, height);
  std::vector<std::uint64_t> words(g.blocks());
  load_words(g, data.data(), words.data());
  std::vector<std::uint8_t> padded(g.texels() * 4);
  decode_padded(g, words.data(), padded.data(), parallel.threads);
  ImageRGBA8 img(width, height);
  bool alpha = false;
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* src = &padded[std::size_t(y) * std::size_t(g.pw) * 4];
    std::memcpy(img.at(0, y), src, std::size_t(width) * 4);
    for (int x = 0; x < width && !alpha; ++x) alpha = src[x * 4 + 3] != 255;
  }
  img.has_alpha = alpha;
  return img;
}

}  // namespace tessera::pvrtc
