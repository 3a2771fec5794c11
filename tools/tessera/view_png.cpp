// tessera view: a fast PNG writer (view_png.h).
#include "view_png.h"

#include <libdeflate.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <memory>
#include <unordered_map>

namespace tessera::cli {

namespace {

using Bytes = std::vector<std::uint8_t>;

struct CompressorDeleter {
  void operator()(libdeflate_compressor* c) const { libdeflate_free_compressor(c); }
};
using Compressor = std::unique_ptr<libdeflate_compressor, CompressorDeleter>;

inline int paeth(int a, int b, int c) {
  const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
}

/// Writes row `y` of `px` (`stride` bytes a row, `bpp` bytes a texel) filtered with `filter`
/// (0 none, 1 sub, 2 up, 3 average, 4 Paeth) to `out` (its filter byte first).
void filter_row(const std::uint8_t* px, std::size_t stride, int bpp, int y, int filter,
                std::uint8_t* out) {
  const std::uint8_t* cur = px + std::size_t(y) * stride;
  const std::uint8_t* up = y > 0 ? cur - stride : nullptr;
  *out++ = std::uint8_t(filter);
  const std::size_t b = std::size_t(bpp);
  switch (filter) {
    case 0:
      std::copy(cur, cur + stride, out);
      break;
    case 1:
      for (std::size_t x = 0; x < stride; ++x)
        out[x] = std::uint8_t(cur[x] - (x >= b ? cur[x - b] : 0));
      break;
    case 2:
      for (std::size_t x = 0; x < stride; ++x) out[x] = std::uint8_t(cur[x] - (up ? up[x] : 0));
      break;
    case 3:
      for (std::size_t x = 0; x < stride; ++x) {
        const int a = x >= b ? cur[x - b] : 0, u = up ? up[x] : 0;
        out[x] = std::uint8_t(cur[x] - (a + u) / 2);
      }
      break;
    default:
      for (std::size_t x = 0; x < stride; ++x) {
        const int a = x >= b ? cur[x - b] : 0, u = up ? up[x] : 0;
        const int c = up && x >= b ? up[x - b] : 0;
        out[x] = std::uint8_t(cur[x] - paeth(a, u, c));
      }
  }
}

/// The filter whose output of a sample of rows (about 64, spread over the image) deflates
/// smallest at `level`: a cheap stand-in for trying every filter on every row.
int choose_filter(const std::uint8_t* px, std::size_t stride, int bpp, int height,
                  libdeflate_compressor* c) {
  const int step = std::max(1, height / 64);
  Bytes sample, out;
  int best = 0;
  std::size_t best_size = SIZE_MAX;
  for (int filter = 0; filter <= 4; ++filter) {
    sample.clear();
    for (int y = 0; y < height; y += step) {
      const std::size_t at = sample.size();
      sample.resize(at + stride + 1);
      filter_row(px, stride, bpp, y, filter, &sample[at]);
    }
    out.resize(libdeflate_zlib_compress_bound(c, sample.size()));
    const std::size_t n =
        libdeflate_zlib_compress(c, sample.data(), sample.size(), out.data(), out.size());
    if (n != 0 && n < best_size) {
      best_size = n;
      best = filter;
    }
  }
  return best;
}

void put_u32(Bytes& out, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(std::uint8_t(v >> s));
}

void put_chunk(Bytes& out, const char type[4], const std::uint8_t* body, std::size_t size) {
  put_u32(out, std::uint32_t(size));
  const std::size_t at = out.size();
  out.insert(out.end(), type, type + 4);
  if (size) out.insert(out.end(), body, body + size);
  put_u32(out, libdeflate_crc32(0, &out[at], size + 4));
}

/// The palette (RGB triples) and the index of every texel of an opaque image with at most 256
/// colours; false when it has more.
bool palette_of(const ImageRGBA8& image, Bytes& palette, Bytes& indices) {
  std::unordered_map<std::uint32_t, std::uint8_t> index;
  indices.resize(image.pixel_count());
  std::uint32_t last = 0xffffffffu;
  std::uint8_t last_index = 0;
  for (std::size_t i = 0; i < image.pixel_count(); ++i) {
    const std::uint8_t* p = &image.pixels[i * 4];
    const std::uint32_t rgb =
        std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16;
    if (rgb != last) {
      auto it = index.find(rgb);
      if (it == index.end()) {
        if (index.size() == 256) return false;
        it = index.emplace(rgb, std::uint8_t(index.size())).first;
        palette.insert(palette.end(), p, p + 3);
      }
      last = rgb;
      last_index = it->second;
    }
    indices[i] = last_index;
  }
  return true;
}

}  // namespace

std::vector<std::uint8_t> encode_view_png(const ImageRGBA8& image, int level, bool palette) {
  if (image.empty() || image.pixels.size() != image.pixel_count() * 4) return {};
  Compressor c(libdeflate_alloc_compressor(level));
  if (!c) return {};
  const bool opaque = all_opaque(ImageView8::of(image));
  Bytes plte, rgb;
  const bool indexed = palette && opaque && palette_of(image, plte, rgb);
  const int bpp = indexed ? 1 : opaque ? 3 : 4;
  const std::size_t stride = std::size_t(image.width) * std::size_t(bpp);
  const std::uint8_t* px = indexed ? rgb.data() : image.pixels.data();
  if (opaque && !indexed) {
    rgb.resize(image.pixel_count() * 3);
    parallel_for(0, image.height, 64, [&](std::int64_t y0, std::int64_t y1) {
      for (std::size_t i = std::size_t(y0) * image.width; i < std::size_t(y1) * image.width; ++i) {
        rgb[i * 3] = px[i * 4];
        rgb[i * 3 + 1] = px[i * 4 + 1];
        rgb[i * 3 + 2] = px[i * 4 + 2];
      }
    });
    px = rgb.data();
  }
  const int filter = choose_filter(px, stride, bpp, image.height, c.get());
  Bytes raw(std::size_t(image.height) * (stride + 1));
  parallel_for(0, image.height, 64, [&](std::int64_t y0, std::int64_t y1) {
    for (std::int64_t y = y0; y < y1; ++y) {
      filter_row(px, stride, bpp, int(y), filter, &raw[std::size_t(y) * (stride + 1)]);
    }
  });
  Bytes().swap(rgb);
  Bytes z(libdeflate_zlib_compress_bound(c.get(), raw.size()));
  const std::size_t zn =
      libdeflate_zlib_compress(c.get(), raw.data(), raw.size(), z.data(), z.size());
  if (zn == 0) return {};
  Bytes out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  out.reserve(zn + 64);
  std::array<std::uint8_t, 13> ihdr{};
  for (int i = 0; i < 4; ++i) {
    ihdr[std::size_t(i)] = std::uint8_t(std::uint32_t(image.width) >> (24 - 8 * i));
    ihdr[std::size_t(4 + i)] = std::uint8_t(std::uint32_t(image.height) >> (24 - 8 * i));
  }
  ihdr[8] = 8;                             // bit depth
  ihdr[9] = indexed ? 3 : opaque ? 2 : 6;  // palette, truecolour, with alpha when translucent
  put_chunk(out, "IHDR", ihdr.data(), ihdr.size());
  if (indexed) put_chunk(out, "PLTE", plte.data(), plte.size());
  for (std::size_t at = 0; at < zn; at += std::size_t{1} << 30) {
    put_chunk(out, "IDAT", z.data() + at, std::min(zn - at, std::size_t{1} << 30));
  }
  put_chunk(out, "IEND", nullptr, 0);
  return out;
}

}  // namespace tessera::cli
