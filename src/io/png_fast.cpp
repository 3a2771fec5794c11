// PNG fast path: chunk walk + libdeflate inflate + SSE2 unfiltering for the common 8-bit,
// non-interlaced files. Declines (std::nullopt) whenever it is not sure that libspng would
// give the same pixels; see png_fast.h for the exact subset.
#include "io/png_fast.h"

#include <libdeflate.h>

#include <algorithm>
#include <bit>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace tessera::detail {

namespace {

std::uint32_t be32(const std::uint8_t* p) {
  return (std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) | (std::uint32_t(p[2]) << 8) |
         std::uint32_t(p[3]);
}

bool is_type(const std::uint8_t* t, const char (&name)[5]) { return std::memcmp(t, name, 4) == 0; }

bool is_letter(std::uint8_t c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }

struct DecompressorDeleter {
  void operator()(libdeflate_decompressor* d) const { libdeflate_free_decompressor(d); }
};

// iCCP and text chunks are the only accepted ancillary chunks that libspng inflates and keeps;
// kept this small, they can never reach its chunk-count, chunk-size or cache limits
// (64 MiB / 256 MiB / 1000 chunks, at most 1032:1 expansion), which would be fatal errors.
constexpr std::uint64_t kMaxCachedChunkBytes = 32u << 10;
constexpr int kMaxCachedChunks = 16;
// DEFLATE cannot expand data by more than 1032:1 (258 bytes from a 2-bit length/distance pair).
constexpr std::uint64_t kMaxDeflateRatio = 1032;

// Bytes readable after the inflated rows and the zero row, so that 3-byte pixels can be read
// with 4-byte loads.
constexpr std::size_t kSlack = 4;

// ---- unfiltering -------------------------------------------------------------------------
// `row` holds the filtered bytes of one scanline (no filter byte), `prev` the unfiltered
// previous scanline (zeros for the first). bpp: bytes per pixel (1 to 4).

std::uint8_t paeth(int a, int b, int c) {
  const int pa = std::abs(b - c), pb = std::abs(a - c), pc = std::abs(a + b - 2 * c);
  const int bc = pb <= pc ? b : c;  // written as selects: no branches in the serial chain
  return std::uint8_t(pa <= pb && pa <= pc ? a : bc);
}

void unfilter_scalar(int filter, std::uint8_t* row, const std::uint8_t* prev, std::size_t n,
                     std::size_t bpp) {
  switch (filter) {
    case 1:
      for (std::size_t i = bpp; i < n; ++i) row[i] = std::uint8_t(row[i] + row[i - bpp]);
      break;
    case 3:
      for (std::size_t i = 0; i < std::min(bpp, n); ++i) {
        row[i] = std::uint8_t(row[i] + prev[i] / 2);
      }
      for (std::size_t i = bpp; i < n; ++i) {
        row[i] = std::uint8_t(row[i] + ((unsigned(row[i - bpp]) + prev[i]) >> 1));
      }
      break;
    case 4:
      for (std::size_t i = 0; i < std::min(bpp, n); ++i) row[i] = std::uint8_t(row[i] + prev[i]);
      for (std::size_t i = bpp; i < n; ++i) {
        row[i] = std::uint8_t(row[i] + paeth(row[i - bpp], prev[i], prev[i - bpp]));
      }
      break;
    default:
      break;
  }
}

#if defined(__SSE2__)
// One pixel (3 or 4 bytes) at a time in 16-bit lanes, the way libpng's SSE2 filters work.
// Loads always read 4 bytes (the buffers have kSlack bytes after their last row); for 3-byte
// pixels the fourth lane is ignored and never stored.
__m128i load_px(const std::uint8_t* p) {
  std::uint32_t v;
  std::memcpy(&v, p, 4);
  return _mm_unpacklo_epi8(_mm_cvtsi32_si128(int(v)), _mm_setzero_si128());
}
template <std::size_t kBpp>
void store_px(std::uint8_t* p, __m128i x) {
  const std::uint32_t v = std::uint32_t(_mm_cvtsi128_si32(_mm_packus_epi16(x, x)));
  if constexpr (kBpp == 4) {
    std::memcpy(p, &v, 4);
  } else {
    const std::uint16_t lo = std::uint16_t(v);
    std::memcpy(p, &lo, 2);
    p[2] = std::uint8_t(v >> 16);
  }
}

template <std::size_t kBpp>
void unfilter_simd(int filter, std::uint8_t* row, const std::uint8_t* prev, std::size_t n) {
  const __m128i low = _mm_set1_epi16(0xff);
  const __m128i zero = _mm_setzero_si128();
  __m128i a = zero, c = zero;
  if (filter == 1) {
    for (std::size_t i = 0; i + kBpp <= n; i += kBpp) {
      a = _mm_and_si128(_mm_add_epi16(load_px(row + i), a), low);
      store_px<kBpp>(row + i, a);
    }
  } else if (filter == 3) {
    for (std::size_t i = 0; i + kBpp <= n; i += kBpp) {
      const __m128i b = load_px(prev + i);
      const __m128i avg = _mm_srli_epi16(_mm_add_epi16(a, b), 1);
      a = _mm_and_si128(_mm_add_epi16(load_px(row + i), avg), low);
      store_px<kBpp>(row + i, a);
    }
  } else if (filter == 4) {
    for (std::size_t i = 0; i + kBpp <= n; i += kBpp) {
      const __m128i b = load_px(prev + i);
      // p - a = b - c, p - b = a - c, p - c = (b - c) + (a - c).
      const __m128i pa0 = _mm_sub_epi16(b, c), pb0 = _mm_sub_epi16(a, c);
      const __m128i pc0 = _mm_add_epi16(pa0, pb0);
      const __m128i pa = _mm_max_epi16(pa0, _mm_sub_epi16(zero, pa0));
      const __m128i pb = _mm_max_epi16(pb0, _mm_sub_epi16(zero, pb0));
      const __m128i pc = _mm_max_epi16(pc0, _mm_sub_epi16(zero, pc0));
      const __m128i smallest = _mm_min_epi16(pc, _mm_min_epi16(pa, pb));
      const __m128i use_a = _mm_cmpeq_epi16(smallest, pa);
      const __m128i use_b = _mm_andnot_si128(use_a, _mm_cmpeq_epi16(smallest, pb));
      const __m128i use_c = _mm_andnot_si128(_mm_or_si128(use_a, use_b), _mm_set1_epi16(-1));
      const __m128i pred = _mm_or_si128(
          _mm_or_si128(_mm_and_si128(use_a, a), _mm_and_si128(use_b, b)), _mm_and_si128(use_c, c));
      a = _mm_and_si128(_mm_add_epi16(load_px(row + i), pred), low);
      store_px<kBpp>(row + i, a);
      c = b;
    }
  }
}
#endif

void unfilter_row(int filter, std::uint8_t* row, const std::uint8_t* prev, std::size_t n,
                  std::size_t bpp) {
  if (filter == 0) return;
  if (filter == 2) {
    for (std::size_t i = 0; i < n; ++i) row[i] = std::uint8_t(row[i] + prev[i]);
    return;
  }
#if defined(__SSE2__)
  if (bpp == 4) return unfilter_simd<4>(filter, row, prev, n);
  if (bpp == 3) return unfilter_simd<3>(filter, row, prev, n);
#endif
  unfilter_scalar(filter, row, prev, n, bpp);
}

// ---- expansion to RGBA8 -------------------------------------------------------------------

void expand_row(const std::uint8_t* src, std::uint8_t* dst, std::size_t width, int color_type) {
  switch (color_type) {
    case 6:
      std::memcpy(dst, src, width * 4);
      break;
    case 2:  // reads one byte past the row's last pixel (kSlack)
      for (std::size_t x = 0; x < width; ++x) {
        std::uint32_t v;
        std::memcpy(&v, src + 3 * x, 4);
        v |= std::endian::native == std::endian::little ? 0xff000000u : 0xffu;  // alpha
        std::memcpy(dst + 4 * x, &v, 4);
      }
      break;
    case 4:
      for (std::size_t x = 0; x < width; ++x) {
        dst[4 * x] = dst[4 * x + 1] = dst[4 * x + 2] = src[2 * x];
        dst[4 * x + 3] = src[2 * x + 1];
      }
      break;
    default:  // 0
      for (std::size_t x = 0; x < width; ++x) {
        dst[4 * x] = dst[4 * x + 1] = dst[4 * x + 2] = src[x];
        dst[4 * x + 3] = 255;
      }
      break;
  }
}

}  // namespace

std::optional<ImageRGBA8> decode_png_fast(std::span<const std::uint8_t> bytes) {
  static constexpr std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  const std::uint8_t* const data = bytes.data();
  const std::size_t size = bytes.size();
  if (size < 8 || std::memcmp(data, kSignature, 8) != 0) return std::nullopt;

  std::uint32_t width = 0, height = 0;
  int color_type = -1;
  std::vector<std::span<const std::uint8_t>> idats;
  std::uint64_t idat_bytes = 0, cached_bytes = 0;
  int cached_chunks = 0;
  enum { kHeader, kBeforeIdat, kInIdat, kAfterIdat } state = kHeader;
  bool saw_iend = false;
  for (std::size_t pos = 8; !saw_iend;) {
    if (size - pos < 12) return std::nullopt;  // truncated (or no IEND)
    const std::uint32_t length = be32(data + pos);
    if (length > 0x7fffffffu || size - pos - 12 < length) return std::nullopt;
    const std::uint8_t* type = data + pos + 4;
    const std::uint8_t* body = data + pos + 8;
    if (libdeflate_crc32(0, type, std::size_t(length) + 4) != be32(body + length)) {
      return std::nullopt;
    }
    pos += std::size_t(length) + 12;
    if (!is_letter(type[0]) || !is_letter(type[1]) || !is_letter(type[2]) ||
        !is_letter(type[3])) {
      return std::nullopt;
    }
    if (state == kHeader) {
      if (!is_type(type, "IHDR") || length != 13) return std::nullopt;
      width = be32(body);
      height = be32(body + 4);
      const std::uint8_t depth = body[8], ctype = body[9];
      if (width == 0 || height == 0 || width > std::uint32_t(kMaxImageDimension) ||
          height > std::uint32_t(kMaxImageDimension) || depth != 8 ||
          (ctype != 0 && ctype != 2 && ctype != 4 && ctype != 6) || body[10] != 0 ||
          body[11] != 0 || body[12] != 0) {
        return std::nullopt;
      }
      if (!check_image_size(width, height, "").ok()) return std::nullopt;
      color_type = ctype;
      state = kBeforeIdat;
      continue;
    }
    if (is_type(type, "IDAT")) {
      if (state == kAfterIdat) return std::nullopt;
      state = kInIdat;
      if (length > 0) idats.emplace_back(body, length);
      idat_bytes += length;
      continue;
    }
    if (state == kInIdat) state = kAfterIdat;
    if (is_type(type, "IEND")) {
      if (state != kAfterIdat || length != 0) return std::nullopt;
      saw_iend = true;  // libspng stops reading here too: trailing bytes are ignored
      continue;
    }
    if (!(type[0] & 0x20)) return std::nullopt;  // PLTE, a misplaced IHDR, unknown critical
    if (is_type(type, "tRNS") || is_type(type, "eXIf") || is_type(type, "sPLT")) {
      return std::nullopt;
    }
    if (is_type(type, "iCCP") || is_type(type, "tEXt") || is_type(type, "zTXt") ||
        is_type(type, "iTXt")) {
      cached_bytes += length;
      if (cached_bytes > kMaxCachedChunkBytes || ++cached_chunks > kMaxCachedChunks) {
        return std::nullopt;
      }
    }
    // Every other ancillary chunk is either stored without any effect on the pixels or, when
    // malformed or misplaced, discarded by libspng (which is not in strict mode).
  }

  const std::size_t channels = color_type == 6 ? 4 : color_type == 2 ? 3 : color_type == 4 ? 2 : 1;
  const std::size_t row_bytes = std::size_t(width) * channels;
  const std::uint64_t raw_size = std::uint64_t(height) * (1 + row_bytes);
  // A header promising more data than the compressed bytes can hold is corrupt: decline
  // before allocating anything of its size.
  if (idat_bytes < 8 || raw_size > idat_bytes * kMaxDeflateRatio) return std::nullopt;

  std::vector<std::uint8_t> joined;
  std::span<const std::uint8_t> stream = idats.front();
  if (idats.size() > 1) {
    joined.resize(std::size_t(idat_bytes));
    std::size_t at = 0;
    for (std::span<const std::uint8_t> s : idats) {
      std::memcpy(joined.data() + at, s.data(), s.size());
      at += s.size();
    }
    stream = joined;
  }

  std::unique_ptr<libdeflate_decompressor, DecompressorDeleter> inflater(
      libdeflate_alloc_decompressor());
  if (!inflater) return std::nullopt;
  // Not value-initialised: every byte is written by the decompressor or the size check fails.
  std::unique_ptr<std::uint8_t[]> raw(new std::uint8_t[std::size_t(raw_size) + kSlack]);
  std::memset(raw.get() + raw_size, 0, kSlack);
  std::size_t in_used = 0, out_made = 0;
  const libdeflate_result r =
      libdeflate_zlib_decompress_ex(inflater.get(), stream.data(), stream.size(), raw.get(),
                                    std::size_t(raw_size), &in_used, &out_made);
  if (r != LIBDEFLATE_SUCCESS || in_used != stream.size() || out_made != raw_size) {
    return std::nullopt;
  }
  inflater.reset();
  joined = {};

  ImageRGBA8 img;  // no zero fill: every row is written below
  img.width = int(width);
  img.height = int(height);
  img.has_alpha = color_type == 4 || color_type == 6;
  img.pixels.resize(img.pixel_count() * 4);
  const std::vector<std::uint8_t> zeros(row_bytes + kSlack, 0);
  const std::uint8_t* prev = zeros.data();
  for (std::size_t y = 0; y < height; ++y) {
    std::uint8_t* line = raw.get() + y * (1 + row_bytes);
    const int filter = line[0];
    if (filter > 4) return std::nullopt;
    unfilter_row(filter, line + 1, prev, row_bytes, channels);
    expand_row(line + 1, img.pixels.data() + y * std::size_t(width) * 4, width, color_type);
    prev = line + 1;
  }
  return img;
}

}  // namespace tessera::detail
