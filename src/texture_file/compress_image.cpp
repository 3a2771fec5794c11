// The image-to-texture pipeline shared by `tessera compress` (single file and batch), the
// Python module and tessera.batch: alpha detection, the power-of-two rule, the mip chain and
// the per-level encodes.
#include <algorithm>
#include <chrono>
#include <functional>
#include <span>

#include "tessera/mipmap.h"
#include "tessera/texture_file.h"

namespace tessera::texture_file {

namespace {

std::string size_text(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

/// Encodes every level of `chain` (level 0 first) into `tex.levels`, with the progress of
/// `options.encode.progress` over the whole chain: each level's fraction weighted by its pixels
/// (the encoders' costs are about linear in them); never backwards, and 1.0 once, at the end.
Status encode_chain(std::span<const ImageView8> chain, const CompressOptions& options,
                    const std::string& name, CompressedTexture& tex) {
  const std::function<void(double)>& hook = options.encode.progress;
  double total_pixels = 0, pixels_before = 0, last = -1;
  for (const ImageView8& level : chain) total_pixels += double(level.pixel_count());
  auto report = [&](double f) {
    f = std::min(f, 1.0);
    if (f <= last) return;
    last = f;
    hook(f);
  };
  pvrtc::EncodeOptions level_options = options.encode;
  for (const ImageView8& level : chain) {
    if (hook) {
      const double pixels = double(level.pixel_count());
      level_options.progress = [&, pixels](double f) {
        report((pixels_before + f * pixels) / total_pixels);
      };
    }
    Result<std::vector<std::uint8_t>> enc = pvrtc::encode(level, level_options);
    pixels_before += double(level.pixel_count());
    if (!enc) {
      Status s = enc.status();
      s.message = name + ": " + s.message;
      return s;
    }
    tex.levels.push_back(std::move(enc).value());
  }
  if (hook) report(1.0);
  return Status::success();
}

CompressedTexture texture_header(const CompressOptions& options, int width, int height,
                                 bool has_alpha) {
  CompressedTexture tex;
  tex.format = options.encode.format;
  tex.width = width;
  tex.height = height;
  tex.has_alpha = has_alpha;
  tex.srgb = options.srgb;
  return tex;
}

}  // namespace

Result<CompressedImage> compress_image(ImageRGBA8 image, const CompressOptions& options,
                                       const std::string& name) {
  if (image.pixels.size() != image.pixel_count() * 4) {
    return Status::error(ErrorCode::invalid_argument,
                         name + ": pixel buffer size does not match the image size");
  }
  CompressedImage out;
  // An alpha channel that is opaque everywhere (common in RGBA PNGs) gives an RGB texture.
  if (image.has_alpha) image.has_alpha = !all_opaque(ImageView8::of(image));

  image::MipmapOptions filter;
  filter.srgb = options.srgb;
  filter.threads = options.encode.threads;
  if (!pvrtc::check_dimensions(image.width, image.height, name).ok()) {
    const int pw = image::nearest_power_of_two(image.width),
              ph = image::nearest_power_of_two(image.height);
    if (!options.resize_pot) {
      return Status::error(ErrorCode::invalid_argument,
                           name + ": size " + size_text(image.width, image.height) +
                               " is not a power of two (PVRTC needs power-of-two sides); use "
                               "--resize-pot to resample to " + size_text(pw, ph));
    }
    Result<ImageRGBA8> resized = image::resize_image(image, pw, ph, filter);
    if (!resized) return resized.status();
    image = std::move(resized).value();
    out.resized = true;
  }
  if (Status s = pvrtc::check_dimensions(image.width, image.height, name); !s.ok()) return s;

  // Level 0 is `image` itself (no copy); the smaller levels come from generate_mipmaps.
  std::vector<ImageRGBA8> mips;
  std::vector<ImageView8> chain = {ImageView8::of(image)};
  if (options.mipmaps) {
    Result<std::vector<ImageRGBA8>> c = image::generate_mipmaps(image, filter);
    if (!c) return c.status();
    mips = std::move(c).value();
    chain.clear();
    for (const ImageRGBA8& m : mips) chain.push_back(ImageView8::of(m));
  }

  out.texture = texture_header(options, image.width, image.height, image.has_alpha);
  const auto t0 = std::chrono::steady_clock::now();
  if (Status s = encode_chain(chain, options, name, out.texture); !s.ok()) return s;
  out.encode_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (options.mipmaps) {
    out.sources.push_back(std::move(mips.front()));
  } else {
    out.sources.push_back(std::move(image));
  }
  return out;
}

Result<CompressedTexture> compress_view(const ImageView8& image, const CompressOptions& options,
                                        const std::string& name) {
  if (Status s = check_view(image, name); !s.ok()) return s;
  // A mip chain or a resample makes new pixels anyway: the owning pipeline, from one copy.
  if (options.mipmaps || !pvrtc::check_dimensions(image.width, image.height, name).ok()) {
    Result<CompressedImage> r = compress_image(to_image(image), options, name);
    if (!r) return r.status();
    return std::move(r->texture);
  }
  ImageView8 level = image;
  if (level.has_alpha) level.has_alpha = !all_opaque(level);
  CompressedTexture tex = texture_header(options, image.width, image.height, level.has_alpha);
  if (Status s = encode_chain(std::span<const ImageView8>(&level, 1), options, name, tex);
      !s.ok()) {
    return s;
  }
  return tex;
}

}  // namespace tessera::texture_file
