// Image decoding (libspng for PNG, stb_image for JPEG/TGA/BMP) and PNG encoding.
#include <spng.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <limits>
#include <memory>
#include <string>

#include "io/png_fast.h"
#include "io/stb_decoder.h"
#include "tessera/io.h"

namespace tessera::io {

namespace {

struct SpngDeleter {
  void operator()(spng_ctx* ctx) const { spng_ctx_free(ctx); }
};
using SpngPtr = std::unique_ptr<spng_ctx, SpngDeleter>;

Status spng_status(const std::string& name, const char* what, int err) {
  // Truncation shows up as SPNG_EOF or as a failed read of a chunk.
  const ErrorCode code = ErrorCode::corrupt_data;
  return Status::error(code, name + ": " + what + ": " + spng_strerror(err));
}

/// Raw decoded PNG: either 8-bit (`samples8`) or 16-bit (`samples16`) RGBA.
struct PngRaw {
  int width = 0, height = 0;
  bool has_alpha = false;
  bool sixteen = false;
  std::vector<std::uint8_t> samples8;
  std::vector<std::uint16_t> samples16;
};

Result<PngRaw> decode_png_raw(std::span<const std::uint8_t> bytes, const std::string& name,
                              bool want16) {
  SpngPtr ctx(spng_ctx_new(0));
  if (!ctx) return Status::error(ErrorCode::io_error, name + ": out of memory");
  spng_set_crc_action(ctx.get(), SPNG_CRC_ERROR, SPNG_CRC_ERROR);
  spng_set_image_limits(ctx.get(), kMaxImageDimension, kMaxImageDimension);
  spng_set_chunk_limits(ctx.get(), 64u << 20, 256u << 20);
  if (int e = spng_set_png_buffer(ctx.get(), bytes.data(), bytes.size())) {
    return spng_status(name, "cannot read PNG", e);
  }
  spng_ihdr ihdr{};
  if (int e = spng_get_ihdr(ctx.get(), &ihdr)) return spng_status(name, "bad PNG header", e);
  if (Status s = check_image_size(ihdr.width, ihdr.height, name); !s.ok()) return s;
  // The image data is at least width * height * channels * depth bits once inflated, and
  // DEFLATE expands at most 1032:1, so a header announcing more than the file's bytes can
  // hold is a truncated or corrupt file: refuse it before allocating the image (a 30-byte file
  // claiming 4101 x 64218 16-bit grey made the decode below allocate 2 GiB).
  const std::uint64_t channels = ihdr.color_type == SPNG_COLOR_TYPE_TRUECOLOR_ALPHA   ? 4
                                 : ihdr.color_type == SPNG_COLOR_TYPE_TRUECOLOR       ? 3
                                 : ihdr.color_type == SPNG_COLOR_TYPE_GRAYSCALE_ALPHA ? 2
                                                                                      : 1;
  const std::uint64_t min_inflated =
      std::uint64_t(ihdr.width) * ihdr.height * channels * ihdr.bit_depth / 8;
  if (min_inflated > std::uint64_t(bytes.size()) * detail::kMaxDeflateRatio + 4096) {
    return Status::error(ErrorCode::corrupt_data,
                         name + ": truncated PNG: " + std::to_string(bytes.size()) +
                             " bytes cannot hold the " + std::to_string(ihdr.width) + "x" +
                             std::to_string(ihdr.height) + " image its header announces");
  }

  PngRaw raw;
  raw.width = int(ihdr.width);
  raw.height = int(ihdr.height);
  spng_trns trns{};
  raw.has_alpha = ihdr.color_type == SPNG_COLOR_TYPE_TRUECOLOR_ALPHA ||
                  ihdr.color_type == SPNG_COLOR_TYPE_GRAYSCALE_ALPHA ||
                  spng_get_trns(ctx.get(), &trns) == 0;
  raw.sixteen = want16 || ihdr.bit_depth == 16;
  const int fmt = raw.sixteen ? SPNG_FMT_RGBA16 : SPNG_FMT_RGBA8;
  std::size_t out_size = 0;
  if (int e = spng_decoded_image_size(ctx.get(), fmt, &out_size)) {
    return spng_status(name, "cannot decode PNG", e);
  }
  void* out = nullptr;
  if (raw.sixteen) {
    raw.samples16.resize(out_size / 2);
    out = raw.samples16.data();
  } else {
    raw.samples8.resize(out_size);
    out = raw.samples8.data();
  }
  if (int e = spng_decode_image(ctx.get(), out, out_size, fmt, SPNG_DECODE_TRNS)) {
    return spng_status(name, "corrupt or truncated PNG data", e);
  }
  // Read the chunks after the image data up to IEND, so a file cut short after its last IDAT
  // is reported as truncated rather than silently accepted.
  if (int e = spng_decode_chunks(ctx.get())) {
    return spng_status(name, "truncated PNG (no IEND)", e);
  }
  // libspng does not insist on IEND's CRC; the chunk is fixed, so look for all 12 bytes.
  static constexpr std::uint8_t kIend[12] = {0,   0,   0,    0,    'I',  'E',
                                             'N', 'D', 0xAE, 0x42, 0x60, 0x82};
  if (std::search(bytes.begin(), bytes.end(), std::begin(kIend), std::end(kIend)) == bytes.end()) {
    return Status::error(ErrorCode::corrupt_data, name + ": truncated PNG (incomplete IEND chunk)");
  }
  return raw;
}

bool has_prefix(std::span<const std::uint8_t> b, std::initializer_list<std::uint8_t> magic) {
  if (b.size() < magic.size()) return false;
  return std::equal(magic.begin(), magic.end(), b.begin());
}

std::uint32_t le16(std::span<const std::uint8_t> b, std::size_t o) {
  return std::uint32_t(b[o]) | (std::uint32_t(b[o + 1]) << 8);
}
std::uint32_t le32(std::span<const std::uint8_t> b, std::size_t o) {
  return le16(b, o) | (le16(b, o + 2) << 16);
}

/// stb_image allocates the whole image before it finds out that the data is missing, so a
/// tiny file with a lying header costs a gigabyte. Refuse files too short to hold the pixels
/// their header announces: exact for uncompressed TGA/BMP, a lower bound for RLE (at most 128
/// or 255 pixels per packet) and JPEG (at least 2 bits per 8x8 block, halved for slack).
Status check_payload(std::span<const std::uint8_t> b, ImageFormat format, std::uint64_t w,
                     std::uint64_t h, const std::string& name) {
  const std::uint64_t px = w * h;
  std::uint64_t need = 0, have = b.size();
  if (format == ImageFormat::tga && b.size() >= 18) {
    const std::uint64_t bytes_pp = (std::uint64_t(b[16]) + 7) / 8;
    const std::uint64_t cmap = std::uint64_t(le16(b, 5)) * ((std::uint64_t(b[7]) + 7) / 8);
    const std::uint64_t offset = 18 + std::uint64_t(b[0]) + (b[1] ? cmap : 0);
    have = b.size() > offset ? b.size() - offset : 0;
    need = b[2] >= 9 ? (px + 127) / 128 * (1 + bytes_pp) : px * bytes_pp;
  } else if (format == ImageFormat::bmp && b.size() >= 34) {
    const std::uint64_t offset = le32(b, 10), bpp = le16(b, 28), compression = le32(b, 30);
    have = b.size() > offset ? b.size() - offset : 0;
    if (compression == 0 || compression == 3) {
      need = (w * bpp + 31) / 32 * 4 * h;
    } else if (compression == 1 || compression == 2) {
      need = (px + 254) / 255 * 2;
    }
  } else if (format == ImageFormat::jpeg) {
    need = px / 512;
  }
  if (have < need) {
    return Status::error(ErrorCode::corrupt_data, name + ": truncated image: header says " +
                                                      std::to_string(w) + "x" + std::to_string(h) +
                                                      " but only " + std::to_string(have) +
                                                      " bytes of pixel data follow (at least " +
                                                      std::to_string(need) + " needed)");
  }
  return Status::success();
}

Result<ImageRGBA8> decode_stb(std::span<const std::uint8_t> bytes, const std::string& name,
                              ImageFormat format) {
  if (bytes.size() > std::size_t(std::numeric_limits<int>::max())) {
    return Status::error(ErrorCode::too_large, name + ": file too large");
  }
  int w = 0, h = 0, comp = 0;
  if (!detail::stb_info(bytes.data(), int(bytes.size()), &w, &h, &comp)) {
    return Status::error(ErrorCode::corrupt_data,
                         name + ": cannot read image header: " + detail::stb_failure_reason());
  }
  if (Status s = check_image_size(w, h, name); !s.ok()) return s;
  if (Status s = check_payload(bytes, format, std::uint64_t(w), std::uint64_t(h), name); !s.ok()) {
    return s;
  }
  std::unique_ptr<unsigned char, decltype(&detail::stb_free)> data(
      detail::stb_load_rgba(bytes.data(), int(bytes.size()), &w, &h, &comp), &detail::stb_free);
  if (!data) {
    return Status::error(ErrorCode::corrupt_data,
                         name + ": corrupt or truncated image: " + detail::stb_failure_reason());
  }
  ImageRGBA8 img(w, h);
  std::memcpy(img.pixels.data(), data.get(), img.pixels.size());
  img.has_alpha = (comp == 2 || comp == 4) && format != ImageFormat::jpeg;
  return img;
}

}  // namespace

ImageFormat detect_image_format(std::span<const std::uint8_t> b) {
  if (has_prefix(b, {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A})) return ImageFormat::png;
  if (has_prefix(b, {0xFF, 0xD8, 0xFF})) return ImageFormat::jpeg;
  if (has_prefix(b, {'B', 'M'})) return ImageFormat::bmp;
  // TGA has no magic: accept a plausible header (colour-map type 0/1, a known image type and
  // pixel depth).
  if (b.size() >= 18) {
    const std::uint8_t cmap = b[1], type = b[2], depth = b[16];
    const bool type_ok =
        type == 1 || type == 2 || type == 3 || type == 9 || type == 10 || type == 11;
    const bool depth_ok = depth == 8 || depth == 15 || depth == 16 || depth == 24 || depth == 32;
    if (cmap <= 1 && type_ok && depth_ok) return ImageFormat::tga;
  }
  return ImageFormat::unknown;
}

Result<ImageRGBA8> decode_image(std::span<const std::uint8_t> bytes, const std::string& name) {
  const ImageFormat format = detect_image_format(bytes);
  if (format == ImageFormat::unknown) {
    if (bytes.empty()) return Status::error(ErrorCode::corrupt_data, name + ": empty file");
    return Status::error(ErrorCode::corrupt_data,
                         name + ": not a PNG, JPEG, TGA or BMP image (unrecognised magic)");
  }
  if (format != ImageFormat::png) return decode_stb(bytes, name, format);
  // libdeflate fast path for the common files; anything it declines (corrupt files included)
  // goes through libspng, which gives the same pixels and writes the error messages.
  if (std::optional<ImageRGBA8> fast = detail::decode_png_fast(bytes)) return std::move(*fast);
  return detail::decode_png_spng(bytes, name);
}

namespace detail {

Result<ImageRGBA8> decode_png_spng(std::span<const std::uint8_t> bytes, const std::string& name) {
  Result<PngRaw> raw = decode_png_raw(bytes, name, false);
  if (!raw) return raw.status();
  ImageRGBA8 img;  // no zero-filled buffer: the decoded samples become the pixels
  img.width = raw->width;
  img.height = raw->height;
  img.has_alpha = raw->has_alpha;
  if (raw->sixteen) {
    img.pixels.resize(img.pixel_count() * 4);
    for (std::size_t i = 0; i < img.pixels.size(); ++i) {
      img.pixels[i] = std::uint8_t((std::uint32_t(raw->samples16[i]) * 255u + 32767u) / 65535u);
    }
  } else {
    img.pixels = std::move(raw->samples8);
  }
  return img;
}

}  // namespace detail

Result<ImageRGBAF> decode_image_float(std::span<const std::uint8_t> bytes,
                                      const std::string& name) {
  if (detect_image_format(bytes) == ImageFormat::png) {
    Result<PngRaw> raw = decode_png_raw(bytes, name, true);
    if (!raw) return raw.status();
    ImageRGBAF img(raw->width, raw->height);
    for (std::size_t i = 0; i < img.pixels.size(); ++i) {
      img.pixels[i] = float(raw->samples16[i]) / 65535.0f;
    }
    return img;
  }
  Result<ImageRGBA8> img8 = decode_image(bytes, name);
  if (!img8) return img8.status();
  ImageRGBAF img(img8->width, img8->height);
  for (std::size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = img8->pixels[i] / 255.0f;
  return img;
}

Result<ImageRGBA8> read_image(const std::string& path) {
  Result<std::vector<std::uint8_t>> bytes = read_file(path);
  if (!bytes) return bytes.status();
  return decode_image(*bytes, io_name(path));
}

Result<ImageRGBAF> read_image_float(const std::string& path) {
  Result<std::vector<std::uint8_t>> bytes = read_file(path);
  if (!bytes) return bytes.status();
  return decode_image_float(*bytes, io_name(path));
}

Result<std::vector<std::uint8_t>> encode_png(const ImageRGBA8& image) {
  if (Status s = check_image_size(image.width, image.height, "PNG encoder"); !s.ok()) return s;
  if (image.pixels.size() != image.pixel_count() * 4) {
    return Status::error(ErrorCode::invalid_argument, "PNG encoder: pixel buffer size mismatch");
  }
  SpngPtr ctx(spng_ctx_new(SPNG_CTX_ENCODER));
  if (!ctx) return Status::error(ErrorCode::io_error, "PNG encoder: out of memory");
  spng_set_option(ctx.get(), SPNG_ENCODE_TO_BUFFER, 1);
  spng_ihdr ihdr{};
  ihdr.width = std::uint32_t(image.width);
  ihdr.height = std::uint32_t(image.height);
  ihdr.bit_depth = 8;
  ihdr.color_type = image.has_alpha ? SPNG_COLOR_TYPE_TRUECOLOR_ALPHA : SPNG_COLOR_TYPE_TRUECOLOR;
  if (int e = spng_set_ihdr(ctx.get(), &ihdr)) return spng_status("PNG encoder", "header", e);

  std::vector<std::uint8_t> rgb;
  const void* data = image.pixels.data();
  std::size_t size = image.pixels.size();
  if (!image.has_alpha) {
    rgb.resize(image.pixel_count() * 3);
    for (std::size_t i = 0; i < image.pixel_count(); ++i) {
      std::memcpy(&rgb[i * 3], &image.pixels[i * 4], 3);
    }
    data = rgb.data();
    size = rgb.size();
  }
  if (int e = spng_encode_image(ctx.get(), data, size, SPNG_FMT_PNG, SPNG_ENCODE_FINALIZE)) {
    return spng_status("PNG encoder", "encode", e);
  }
  std::size_t png_size = 0;
  int err = 0;
  void* png = spng_get_png_buffer(ctx.get(), &png_size, &err);
  if (!png) return spng_status("PNG encoder", "buffer", err);
  std::vector<std::uint8_t> out(static_cast<std::uint8_t*>(png),
                                static_cast<std::uint8_t*>(png) + png_size);
  std::free(png);
  return out;
}

Status write_png(const std::string& path, const ImageRGBA8& image) {
  Result<std::vector<std::uint8_t>> png = encode_png(image);
  if (!png) {
    return Status::error(png.status().code, io_name(path, true) + ": " + png.status().message);
  }
  return write_file_atomic(path, *png);
}

}  // namespace tessera::io
