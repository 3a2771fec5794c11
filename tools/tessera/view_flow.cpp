// tessera view: what the page's workflow needs beyond one result: thumbnails for the overview of
// every input, files opened from the page, the decoded image as a download.
#include <algorithm>

#include "tessera/io.h"
#include "view.h"

namespace tessera::cli {

namespace {

/// `image` box-reduced to at most `size` texels a side (each output texel the mean of the
/// input texels its box covers; an image already that small is kept).
ImageRGBA8 box_reduce(const ImageRGBA8& image, int size) {
  const int longest = std::max(image.width, image.height);
  if (longest <= size) return image;
  const int w = std::max(1, int(std::int64_t(image.width) * size / longest));
  const int h = std::max(1, int(std::int64_t(image.height) * size / longest));
  ImageRGBA8 out(w, h);
  out.has_alpha = image.has_alpha;
  for (int y = 0; y < h; ++y) {
    const int y0 = int(std::int64_t(y) * image.height / h);
    const int y1 = std::max(y0 + 1, int(std::int64_t(y + 1) * image.height / h));
    for (int x = 0; x < w; ++x) {
      const int x0 = int(std::int64_t(x) * image.width / w);
      const int x1 = std::max(x0 + 1, int(std::int64_t(x + 1) * image.width / w));
      std::uint64_t sum[4] = {};
      for (int sy = y0; sy < y1; ++sy) {
        for (int sx = x0; sx < x1; ++sx) {
          const std::uint8_t* p = image.at(sx, sy);
          for (int c = 0; c < 4; ++c) sum[c] += p[c];
        }
      }
      const std::uint64_t n = std::uint64_t(x1 - x0) * std::uint64_t(y1 - y0);
      for (int c = 0; c < 4; ++c) out.at(x, y)[c] = std::uint8_t((sum[c] + n / 2) / n);
    }
  }
  return out;
}

}  // namespace

std::string put_thumbnail(const ViewInput& input, int size, int threads, BlobStore& blobs) {
  if (!input.error.empty()) return "";
  ImageRGBA8 decoded;
  const ImageRGBA8* image = &input.image;
  if (input.is_texture) {
    Result<ImageRGBA8> d = texture_file::decode_texture_image(input.texture, 0, 0, 0, {threads});
    if (!d) return "";
    decoded = std::move(d).value();
    image = &decoded;
  }
  Result<std::vector<std::uint8_t>> png = io::encode_png(box_reduce(*image, size));
  return png ? blobs.put("image/png", std::move(png).value()) : std::string();
}

Result<std::vector<std::uint8_t>> decoded_png(const std::vector<std::uint8_t>& file, int threads) {
  Result<texture_file::CompressedTexture> tex = texture_file::parse_texture(file, "result");
  if (!tex) return tex.status();
  Result<ImageRGBA8> image = texture_file::decode_texture_image(*tex, 0, 0, 0, {threads});
  if (!image) return image.status();
  return io::encode_png(*image);
}

Result<std::vector<std::uint8_t>> convert_texture(const std::vector<std::uint8_t>& file,
                                                  const std::string& container) {
  const texture_file::ContainerFormat to =
      container == "pvr"    ? texture_file::ContainerFormat::pvr3
      : container == "ktx"  ? texture_file::ContainerFormat::ktx1
      : container == "ktx2" ? texture_file::ContainerFormat::ktx2
                            : texture_file::ContainerFormat::unknown;
  if (to == texture_file::ContainerFormat::unknown) {
    return Status::error(ErrorCode::invalid_argument, "no container '" + container + "'");
  }
  if (texture_file::detect_container(file) == to) return file;
  Result<texture_file::CompressedTexture> tex = texture_file::parse_texture(file, "result");
  if (!tex) return tex.status();
  return texture_file::serialise_texture(*tex, to);
}

std::string opened_file_name(const std::string& name) {
  std::string n = name.substr(std::min(name.size(), name.find_last_of("/\\") + 1));
  if (n.size() > 255) n.resize(255);
  if (n.empty() || n == "." || n == "..") n = "opened";
  return n;
}

}  // namespace tessera::cli
