// Image output in the format the file name asks for: PNG (libspng), BMP, TGA, JPEG
// (stb_image_write).
#include <algorithm>
#include <cctype>
#include <cstring>

#include "io/stb_encoder.h"
#include "tessera/io.h"

namespace tessera::io {

Result<ImageFormat> image_format_for_output(const std::string& path) {
  if (path == "-") return ImageFormat::png;
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash) ||
      dot + 1 == path.size() || dot == (slash == std::string::npos ? 0 : slash + 1)) {
    return ImageFormat::png;  // no extension: PNG
  }
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == "png") return ImageFormat::png;
  if (ext == "bmp") return ImageFormat::bmp;
  if (ext == "tga") return ImageFormat::tga;
  if (ext == "jpg" || ext == "jpeg") return ImageFormat::jpeg;
  return Status::error(ErrorCode::invalid_argument, path + ": cannot write '." + ext +
                                                        "' images (use .png, .bmp, .tga or .jpg)");
}

Result<std::vector<std::uint8_t>> encode_image(const ImageRGBA8& image, ImageFormat format) {
  if (format == ImageFormat::png) return encode_png(image);
  if (Status s = check_image_size(image.width, image.height, "image encoder"); !s.ok()) return s;
  if (image.pixels.size() != image.pixel_count() * 4) {
    return Status::error(ErrorCode::invalid_argument, "image encoder: pixel buffer size mismatch");
  }
  detail::StbFormat f = detail::StbFormat::bmp;
  switch (format) {
    case ImageFormat::bmp:
      f = detail::StbFormat::bmp;
      break;
    case ImageFormat::tga:
      f = detail::StbFormat::tga;
      break;
    case ImageFormat::jpeg:
      f = detail::StbFormat::jpeg;
      break;
    case ImageFormat::png:
    case ImageFormat::unknown:
      return Status::error(ErrorCode::invalid_argument, "image encoder: unknown format");
  }
  const bool alpha = image.has_alpha && format != ImageFormat::jpeg;
  std::vector<std::uint8_t> rgb;
  const std::uint8_t* data = image.pixels.data();
  if (!alpha) {
    rgb.resize(image.pixel_count() * 3);
    for (std::size_t i = 0; i < image.pixel_count(); ++i) {
      std::memcpy(&rgb[i * 3], &image.pixels[i * 4], 3);
    }
    data = rgb.data();
  }
  std::vector<std::uint8_t> out;
  if (!detail::stb_encode(f, image.width, image.height, alpha ? 4 : 3, data, out)) {
    return Status::error(ErrorCode::io_error, "image encoder: stb_image_write failed");
  }
  return out;
}

Status write_image(const std::string& path, const ImageRGBA8& image) {
  Result<ImageFormat> format = image_format_for_output(path);
  if (!format) return format.status();
  Result<std::vector<std::uint8_t>> bytes = encode_image(image, *format);
  if (!bytes) {
    return Status::error(bytes.status().code, io_name(path, true) + ": " + bytes.status().message);
  }
  return write_file_atomic(path, *bytes);
}

}  // namespace tessera::io
