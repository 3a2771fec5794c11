// tessera/io.h — reading and writing files and images.
//
// Readers never trust sizes found in a file: dimensions are checked against
// `kMaxImageDimension` / `kMaxImagePixels` before any allocation, a header announcing more
// pixels than the file's bytes can hold (uncompressed, or inflated at DEFLATE's or the
// format's largest ratio) is refused as truncated before the image is allocated, and every
// error message names the file and the problem in one line. Writers are atomic: data goes to a
// temporary file in the destination folder, which is renamed over the target only when
// everything was written, so a failure never leaves a partial or overwritten output.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "tessera/core.h"

namespace tessera {

/// Largest file `read_file` loads by default (2 GiB).
inline constexpr std::uint64_t kMaxFileBytes = std::uint64_t{1} << 31;

/// Reads a whole file. Fails with `io_error` when it cannot be opened or read and with
/// `too_large` when it is bigger than `max_bytes`.
Result<std::vector<std::uint8_t>> read_file(const std::string& path,
                                            std::uint64_t max_bytes = kMaxFileBytes);

/// Writes `data` to `path` atomically (temporary file in the same folder, then rename).
Status write_file_atomic(const std::string& path, std::span<const std::uint8_t> data);

/// Image file formats tessera recognises by their magic bytes.
enum class ImageFormat { unknown, png, jpeg, tga, bmp };

/// Guesses the format from the first bytes (PNG, JPEG and BMP by magic; TGA by a plausible
/// header, since TGA has no magic). Returns `unknown` when nothing matches.
ImageFormat detect_image_format(std::span<const std::uint8_t> bytes);

/// Decodes an image from memory to 8-bit RGBA. PNG (all bit depths and colour types,
/// including 16-bit, grey, grey+alpha, palette and tRNS) goes through libspng; JPEG, TGA and
/// BMP through stb_image. 16-bit samples are rounded to 8 bits. `name` is used in messages.
Result<ImageRGBA8> decode_image(std::span<const std::uint8_t> bytes, const std::string& name);

/// Decodes an image keeping 16-bit precision: values in [0, 1], colour space unchanged (no
/// sRGB conversion).
Result<ImageRGBAF> decode_image_float(std::span<const std::uint8_t> bytes,
                                      const std::string& name);

/// Reads and decodes an image file (`read_file` + `decode_image`).
Result<ImageRGBA8> read_image(const std::string& path);
/// Reads and decodes an image file keeping 16-bit precision (`decode_image_float`).
Result<ImageRGBAF> read_image_float(const std::string& path);

/// Encodes RGBA8 as PNG in memory. Writes RGB when `!image.has_alpha`, else RGBA.
Result<std::vector<std::uint8_t>> encode_png(const ImageRGBA8& image);

/// Encodes and writes a PNG atomically.
Status write_png(const std::string& path, const ImageRGBA8& image);

}  // namespace tessera
