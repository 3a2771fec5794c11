// PNG fast path: chunk walk + libdeflate inflate + SSE2 unfiltering for the common 8-bit,
// non-interlaced files. Declines (std::nullopt) whenever it is not sure that libspng would
// give the same pixels; see png_fast.h for the exact subset.
#include "io/png_fast.h"

#include <libdeflate.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <utility>
#include <vector>

#include "core/simd.h"
#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace tessera::io::detail {

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

// Bytes readable after the inflated rows, so that 3-byte pixels can be read with 4-byte loads.
constexpr std::size_t kSlack = 4;

/// Asks Linux to back the whole 2 MiB pages inside [p, p + n) with transparent huge pages
/// where it only does so on request (/sys/kernel/mm/transparent_hugepage/enabled = madvise):
/// the first touch of a 4 MiB pixel buffer then takes 2 page faults instead of about 1000.
/// Only a hint: nothing changes where it is refused or unsupported.
void advise_huge_pages([[maybe_unused]] std::uint8_t* p, [[maybe_unused]] std::size_t n) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kHuge = std::uintptr_t(2) << 20;
  const std::uintptr_t begin = (std::uintptr_t(p) + kHuge - 1) & ~(kHuge - 1);
  const std::uintptr_t end = (std::uintptr_t(p) + n) & ~(kHuge - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#endif
}

// ---- unfiltering, fused with the expansion to RGBA8 ----------------------------------------
// Every scanline is unfiltered straight into its RGBA8 output row; the previous scanline's
// samples (Up, Average, Paeth) are read back from the previous output row, or from a row of
// zeros for the first. Sub, Average and Paeth are a serial dependency chain along a row, so
// rows are unfiltered in pairs: the second row's prediction only needs the first row's pixels
// x and x - 1, which the same loop iteration has just made, so the two chains run side by side
// (instruction-level parallelism) and the second row takes its "above" pixels from registers.
// `src`: the filtered samples of one scanline (no filter byte); `prev`, `out`: RGBA8 rows.

/// Where sample `j` of a kBpp-byte pixel goes in an RGBA8 pixel (grey+alpha: 0 and 3).
template <std::size_t kBpp>
constexpr std::size_t out_offset(std::size_t j) {
  return kBpp == 2 && j == 1 ? 3 : j;
}

std::uint8_t paeth(int a, int b, int c) {
  const int pa = std::abs(b - c), pb = std::abs(a - c), pc = std::abs(a + b - 2 * c);
  const int bc = pb <= pc ? b : c;  // written as selects: no branches in the serial chain
  return std::uint8_t(pa <= pb && pa <= pc ? a : bc);
}

/// One unfiltered sample: filtered byte x plus the prediction of `kFilter` from the sample to
/// the left (a), above (b) and above-left (c).
template <int kFilter>
int unfilter_sample(int x, int a, int b, int c) {
  if constexpr (kFilter == 0) {
    return x;
  } else if constexpr (kFilter == 1) {
    return (x + a) & 0xff;
  } else if constexpr (kFilter == 2) {
    return (x + b) & 0xff;
  } else if constexpr (kFilter == 3) {
    return (x + ((a + b) >> 1)) & 0xff;
  } else {
    return (x + paeth(a, b, c)) & 0xff;
  }
}

/// Writes one RGBA8 pixel from the kBpp unfiltered samples `v` (grey is replicated to RGB,
/// missing alpha is 255).
template <std::size_t kBpp>
void put_rgba(std::uint8_t* o, const int* v) {
  if constexpr (kBpp <= 2) {
    o[0] = o[1] = o[2] = std::uint8_t(v[0]);
    o[3] = kBpp == 2 ? std::uint8_t(v[1]) : 255;
  } else {
    o[0] = std::uint8_t(v[0]);
    o[1] = std::uint8_t(v[1]);
    o[2] = std::uint8_t(v[2]);
    o[3] = kBpp == 4 ? std::uint8_t(v[3]) : 255;
  }
}

/// Scalar unfiltering of one row (kTwo = false: `src1`, `out1` unused) or of two consecutive
/// rows with filters kF0 and kF1, `width` pixels of kBpp bytes each.
template <std::size_t kBpp, int kF0, int kF1, bool kTwo>
void unfilter_rows_scalar(const std::uint8_t* src0, const std::uint8_t* src1,
                          const std::uint8_t* prev, std::uint8_t* out0, std::uint8_t* out1,
                          std::size_t width) {
  int a0[kBpp] = {}, c0[kBpp] = {}, a1[kBpp] = {}, c1[kBpp] = {};
  for (std::size_t x = 0; x < width; ++x) {
    for (std::size_t j = 0; j < kBpp; ++j) {
      const int b0 = prev[4 * x + out_offset<kBpp>(j)];
      a0[j] = unfilter_sample<kF0>(src0[kBpp * x + j], a0[j], b0, c0[j]);
      c0[j] = b0;
      if constexpr (kTwo) {
        a1[j] = unfilter_sample<kF1>(src1[kBpp * x + j], a1[j], a0[j], c1[j]);
        c1[j] = a0[j];
      }
    }
    put_rgba<kBpp>(out0 + 4 * x, a0);
    if constexpr (kTwo) put_rgba<kBpp>(out1 + 4 * x, a1);
  }
}

#if defined(TESSERA_SIMD_SSE2)
#define TESSERA_PNG_SSE2 1
// RGB and RGBA: one pixel at a time in 16-bit lanes (the SIMD wrapper's vu16x8, lanes 0-3), the
// way libpng's SSE2 filters work. Loads always read 4 bytes (the inflated buffer has kSlack
// bytes after its last row); for 3-byte pixels the fourth lane holds the next pixel's first
// byte, which never reaches the other lanes, and is replaced by alpha 255 when stored.
using simd::vu16x8;
using simd::vu8x16;

/// Stores lanes 0-3 of `x` (each 0-255) as one RGBA8 pixel, OR-ing `alpha` (255 in lane 3 for
/// RGB rows, else zero) in.
void store_px(std::uint8_t* p, vu16x8 x, vu16x8 alpha) { simd::store_u8x4(x | alpha, p); }

/// unfilter_sample for the four 16-bit lanes of one pixel at once.
template <int kFilter>
vu16x8 unfilter_px(vu16x8 x, vu16x8 a, vu16x8 b, vu16x8 c) {
  const vu16x8 low(std::uint16_t{0xff});
  if constexpr (kFilter == 0) {
    return x;
  } else if constexpr (kFilter == 1) {
    return (x + a) & low;
  } else if constexpr (kFilter == 2) {
    return (x + b) & low;
  } else if constexpr (kFilter == 3) {
    return (x + simd::srl<1>(a + b)) & low;
  } else {
    // p - a = b - c, p - b = a - c, p - c = (b - c) + (a - c); a wins ties, then b.
    const vu16x8 zero;
    const vu16x8 pa0 = b - c, pb0 = a - c;
    const vu16x8 pc0 = pa0 + pb0;
    const vu16x8 pa = simd::max_s16(pa0, zero - pa0);
    const vu16x8 pb = simd::max_s16(pb0, zero - pb0);
    const vu16x8 pc = simd::max_s16(pc0, zero - pc0);
    const vu16x8 bc = simd::select(simd::cmpgt_s16(pb, pc), c, b);  // pb <= pc ? b : c
    const vu16x8 pred = simd::select(simd::cmpgt_s16(pa, simd::min_s16(pb, pc)), bc, a);
    return (x + pred) & low;
  }
}

/// unfilter_rows_scalar for 3- and 4-byte pixels with SSE2.
template <std::size_t kBpp, int kF0, int kF1, bool kTwo>
void unfilter_rows_simd(const std::uint8_t* src0, const std::uint8_t* src1,
                        const std::uint8_t* prev, std::uint8_t* out0, std::uint8_t* out1,
                        std::size_t width) {
  const std::uint8_t alpha_px[4] = {0, 0, 0, kBpp == 4 ? std::uint8_t{0} : std::uint8_t{255}};
  const vu16x8 alpha = simd::load_u8x4_lo(alpha_px);
  vu16x8 a0, c0, a1, c1;
  for (std::size_t x = 0; x < width; ++x) {
    const vu16x8 b0 = simd::load_u8x4_lo(prev + 4 * x);
    a0 = unfilter_px<kF0>(simd::load_u8x4_lo(src0 + kBpp * x), a0, b0, c0);
    c0 = b0;
    store_px(out0 + 4 * x, a0, alpha);
    if constexpr (kTwo) {
      a1 = unfilter_px<kF1>(simd::load_u8x4_lo(src1 + kBpp * x), a1, a0, c1);
      c1 = a0;
      store_px(out1 + 4 * x, a1, alpha);
    }
  }
}

/// The first bytes (grey samples) of 16 RGBA8 pixels.
vu8x16 load_grey16(const std::uint8_t* p) {
  const simd::vi32x4 low(0xff);
  return simd::narrow(simd::load_texels4(p) & low, simd::load_texels4(p + 16) & low,
                      simd::load_texels4(p + 32) & low, simd::load_texels4(p + 48) & low);
}

/// Stores 16 grey samples as 16 opaque grey RGBA8 pixels.
void store_grey16(std::uint8_t* p, vu8x16 g) {
  const simd::vi32x4 alpha(std::int32_t(0xff000000u));  // little-endian: byte 3 of each pixel
  const vu16x8 g16[2] = {simd::widen_lo(g), simd::widen_hi(g)};
  for (int k = 0; k < 4; ++k) {
    const simd::vi32x4 v = (k & 1) ? simd::widen32_hi(g16[k / 2]) : simd::widen32_lo(g16[k / 2]);
    const simd::vi32x4 px = v | simd::sll<8>(v) | simd::sll<16>(v) | alpha;
    simd::store4(px, reinterpret_cast<std::int32_t*>(p + 16 * k));
  }
}

/// unfilter_rows_scalar for grey rows filtered with None or Up only: no serial chain, so 16
/// pixels at a time, and the scalar kernel for the last width % 16.
template <int kF0, int kF1, bool kTwo>
void unfilter_grey_rows_simd(const std::uint8_t* src0, const std::uint8_t* src1,
                             const std::uint8_t* prev, std::uint8_t* out0, std::uint8_t* out1,
                             std::size_t width) {
  std::size_t x = 0;
  for (; x + 16 <= width; x += 16) {
    vu8x16 a0 = simd::load_u8x16(src0 + x);
    if constexpr (kF0 == 2) a0 = a0 + load_grey16(prev + 4 * x);
    store_grey16(out0 + 4 * x, a0);
    if constexpr (kTwo) {
      vu8x16 a1 = simd::load_u8x16(src1 + x);
      if constexpr (kF1 == 2) a1 = a1 + a0;
      store_grey16(out1 + 4 * x, a1);
    }
  }
  if (x < width) {
    unfilter_rows_scalar<1, kF0, kF1, kTwo>(src0 + x, kTwo ? src1 + x : nullptr, prev + 4 * x,
                                            out0 + 4 * x, kTwo ? out1 + 4 * x : nullptr, width - x);
  }
}
#endif

using UnfilterRowsFn = void (*)(const std::uint8_t*, const std::uint8_t*, const std::uint8_t*,
                                std::uint8_t*, std::uint8_t*, std::size_t);

#if defined(TESSERA_PNG_SSE2)
/// The grey row kernel for filters kF0 and kF1 (kF1 unused when !kTwo).
template <int kF0, int kF1, bool kTwo>
constexpr UnfilterRowsFn rows_kernel_grey() {
  if constexpr ((kF0 == 0 || kF0 == 2) && (!kTwo || kF1 == 0 || kF1 == 2)) {
    return &unfilter_grey_rows_simd<kF0, kF1, kTwo>;
  } else {
    return &unfilter_rows_scalar<1, kF0, kF1, kTwo>;
  }
}
#endif

/// The row kernel for kBpp-byte pixels and the filters (i / 5, i % 5), one row or two.
template <std::size_t kBpp, bool kTwo, std::size_t... I>
constexpr std::array<UnfilterRowsFn, sizeof...(I)> rows_kernels(std::index_sequence<I...>) {
#if defined(TESSERA_PNG_SSE2)
  if constexpr (kBpp >= 3) return {&unfilter_rows_simd<kBpp, int(I / 5), int(I % 5), kTwo>...};
  if constexpr (kBpp == 1) return {rows_kernel_grey<int(I / 5), int(I % 5), kTwo>()...};
#endif
  return {&unfilter_rows_scalar<kBpp, int(I / 5), int(I % 5), kTwo>...};
}

/// Unfilters `height` rows of the inflated stream `raw` (each a filter byte, then `width`
/// pixels of kBpp bytes) into the RGBA8 `out`. `zeros`: 4 * width zero bytes. False when a
/// filter byte is not 0-4.
template <std::size_t kBpp>
bool unfilter_image(const std::uint8_t* raw, std::size_t width, std::size_t height,
                    const std::uint8_t* zeros, std::uint8_t* out) {
  static constexpr auto kPairs = rows_kernels<kBpp, true>(std::make_index_sequence<25>());
  static constexpr auto kSingles = rows_kernels<kBpp, false>(std::make_index_sequence<25>());
  const std::size_t stride = 1 + kBpp * width, out_stride = 4 * width;
  const std::uint8_t* prev = zeros;
  std::size_t y = 0;
  for (; y + 1 < height; y += 2) {
    const std::uint8_t* line = raw + y * stride;
    std::uint8_t* dst = out + y * out_stride;
    if (line[0] > 4 || line[stride] > 4) return false;
    kPairs[line[0] * 5u + line[stride]](line + 1, line + stride + 1, prev, dst, dst + out_stride,
                                        width);
    prev = dst + out_stride;
  }
  if (y < height) {
    const std::uint8_t* line = raw + y * stride;
    if (line[0] > 4) return false;
    kSingles[line[0] * 5u](line + 1, nullptr, prev, out + y * out_stride, nullptr, width);
  }
  return true;
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
    if (!is_letter(type[0]) || !is_letter(type[1]) || !is_letter(type[2]) || !is_letter(type[3])) {
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
  // The rows are inflated into the end of the pixel buffer and unfiltered forward into its
  // start, so no second image-sized buffer (and its fresh pages) is needed. The rows start
  // late enough that unfiltering a pair of rows never overwrites inflated bytes not yet read:
  // pair (y, y + 1) writes below 4 * width * (y + 2) <= raw_at + y * stride, where its rows
  // start. The buffer is value-initialised, so the kSlack bytes after the rows are zeros.
  const std::size_t stride = 1 + row_bytes, out_row = 4 * std::size_t(width);
  const std::size_t out_bytes = out_row * height;
  const std::size_t raw_at = 2 * out_row + (height - 1) * (out_row > stride ? out_row - stride : 0);
  ImageRGBA8 img;
  img.width = int(width);
  img.height = int(height);
  img.has_alpha = color_type == 4 || color_type == 6;
  const std::size_t total = std::max(out_bytes, raw_at + std::size_t(raw_size) + kSlack);
  img.pixels.reserve(total);  // not touched yet: the hint can still take effect
  advise_huge_pages(img.pixels.data(), total);
  img.pixels.resize(total);
  std::uint8_t* const raw = img.pixels.data() + raw_at;
  std::size_t in_used = 0, out_made = 0;
  const libdeflate_result r =
      libdeflate_zlib_decompress_ex(inflater.get(), stream.data(), stream.size(), raw,
                                    std::size_t(raw_size), &in_used, &out_made);
  if (r != LIBDEFLATE_SUCCESS || in_used != stream.size() || out_made != raw_size) {
    return std::nullopt;
  }
  inflater.reset();
  joined = {};

  const std::vector<std::uint8_t> zeros(std::size_t(width) * 4, 0);
  bool ok = false;
  switch (channels) {
    case 1:
      ok = unfilter_image<1>(raw, width, height, zeros.data(), img.pixels.data());
      break;
    case 2:
      ok = unfilter_image<2>(raw, width, height, zeros.data(), img.pixels.data());
      break;
    case 3:
      ok = unfilter_image<3>(raw, width, height, zeros.data(), img.pixels.data());
      break;
    default:
      ok = unfilter_image<4>(raw, width, height, zeros.data(), img.pixels.data());
      break;
  }
  if (!ok) return std::nullopt;
  img.pixels.resize(out_bytes);  // drops the tail; keeps the allocation
  return img;
}

}  // namespace tessera::io::detail
