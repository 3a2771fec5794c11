// tessera/io.h — reading and writing files and images.
//
// Readers never trust sizes found in a file: dimensions are checked against
// `kMaxImageDimension` / `kMaxImagePixels` before any allocation, a header announcing more
// pixels than the file's bytes can hold (uncompressed, or inflated at DEFLATE's or the
// format's largest ratio) is refused as truncated before the image is allocated, and every
// error message names the file and the problem in one line. Writers never leave a partial
// output and never replace what is not the user's file (see `write_file_atomic`). "-" means
// standard input or output wherever a path is taken.
// Tests: tests/unit/io_test.cpp, io_png_fast_test.cpp, file_write_test.cpp;
// tests/cli/cli_io_test.py.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "tessera/core.h"

namespace tessera::io {

/// Largest file `read_file` loads by default (2 GiB).
inline constexpr std::uint64_t kMaxFileBytes = std::uint64_t{1} << 31;

/// How `path` is named in messages: "<stdin>" (or "<stdout>" when `output`) for "-", else
/// `path` itself.
std::string io_name(const std::string& path, bool output = false);

/// Reads a whole file. "-" reads standard input; pipes, FIFOs, character devices and
/// `/dev/stdin` are read to their end in chunks (no seeking), regular files in one go. Fails
/// with `io_error` (message: the name, what failed and the OS reason) when it cannot be opened
/// or read or is a directory, and with `too_large` as soon as more than `max_bytes` arrive.
Result<std::vector<std::uint8_t>> read_file(const std::string& path,
                                            std::uint64_t max_bytes = kMaxFileBytes);

/// Writes `data` to `path` without ever replacing what is not the user's file:
///   * "-" writes to standard output;
///   * an existing device, FIFO or socket, or a path through /proc (`/dev/stdout`,
///     `/dev/fd/N`), is opened and written in place: no temporary, no rename;
///   * otherwise the symbolic links are followed to the final target, the data goes to a
///     temporary file beside the target and is renamed over it when all was written: a link
///     stays a link (a dangling one gets its target created), an existing file keeps its
///     permission bits, and a failed write leaves the old file and no temporary behind.
/// A directory is an error that names it. Safe to call from several threads on different paths.
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
Result<ImageRGBAF> decode_image_float(std::span<const std::uint8_t> bytes, const std::string& name);

/// Reads and decodes an image file (`read_file` + `decode_image`).
Result<ImageRGBA8> read_image(const std::string& path);
/// Reads and decodes an image file keeping 16-bit precision (`decode_image_float`).
Result<ImageRGBAF> read_image_float(const std::string& path);

/// Encodes RGBA8 as PNG in memory. Writes RGB when `!image.has_alpha`, else RGBA.
Result<std::vector<std::uint8_t>> encode_png(const ImageRGBA8& image);

/// Encodes and writes a PNG (`write_file_atomic`), whatever the name's extension.
Status write_png(const std::string& path, const ImageRGBA8& image);

/// The format an image written to `path` takes from its extension (case-insensitive): .png,
/// .bmp, .tga, .jpg/.jpeg; PNG for "-" and for a name without extension. Any other extension
/// is an `invalid_argument` error naming the path and the formats there are, so PNG bytes never
/// land under a .gif or .webp name.
Result<ImageFormat> image_format_for_output(const std::string& path);

/// Encodes RGBA8 in `format`: PNG through libspng (RGB when `!image.has_alpha`), BMP and TGA
/// (RGB or RGBA) and JPEG (quality 95, RGB: alpha dropped) through stb_image_write.
Result<std::vector<std::uint8_t>> encode_image(const ImageRGBA8& image, ImageFormat format);

/// Writes an image in the format its name asks for (`image_format_for_output`), through
/// `write_file_atomic`.
Status write_image(const std::string& path, const ImageRGBA8& image);

}  // namespace tessera::io
