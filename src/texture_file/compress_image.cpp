// The image-to-texture pipeline shared by `tessera compress` (single file and batch), the
// Python module and tessera.batch: the preparation steps of `CompressOptions` (flip, alpha
// detection, the power-of-two rule, premultiplication, the mip chain, alpha bleeding), then
// every image's and level's encode, for 2D textures, cube maps and arrays; and the error of
// what was made (`measure_level0`).
#include <algorithm>
#include <chrono>
#include <functional>
#include <span>

#include "tessera/image_mipmap.h"
#include "tessera/image_ops.h"
#include "tessera/metrics.h"
#include "tessera/texture_file.h"

namespace tessera::texture_file {

namespace {

Status bad(const std::string& message) {
  return Status::error(ErrorCode::invalid_argument, message);
}

/// The option combinations that make no sense, named by the library's field names.
Status check_options(const CompressOptions& options) {
  if (options.normal_map && options.srgb) {
    return bad("normal_map and srgb: a normal map holds vectors, never sRGB colour");
  }
  if (options.premultiply && options.alpha_bleed) {
    return bad(
        "alpha_bleed applies to straight alpha: with premultiply, transparent texels are "
        "black already");
  }
  if (options.premultiply && options.encode.alpha_weighted) {
    return bad(
        "alpha_weighted applies to straight alpha: with premultiply, colour carries alpha "
        "already");
  }
  if (options.encode.alpha_weighted && options.encode.format != pvrtc::Format::pvrtc1_4bpp) {
    return bad(
        "alpha_weighted and the 2 bpp format: alpha-weighted colour error is for 4 bpp only");
  }
  if (options.mip_levels < 0) {
    return bad("mip_levels " + std::to_string(options.mip_levels) + " is negative");
  }
  return Status::success();
}

/// One image ready to encode: its mip chain (level 0 first; one level without mipmaps).
struct Prepared {
  std::vector<ImageRGBA8> chain;
  bool resized = false;
};

/// The steps of `CompressOptions`, in its documented order, on one image.
Result<Prepared> prepare(ImageRGBA8 image, const CompressOptions& options,
                         const std::string& name) {
  if (image.pixels.size() != image.pixel_count() * 4) {
    return bad(name + ": pixel buffer size does not match the image size");
  }
  Prepared out;
  const Parallel parallel{options.encode.threads};
  if (options.flip_y) image::flip_y(image);
  // An alpha channel that is opaque everywhere (common in RGBA PNGs) gives an RGB texture.
  if (image.has_alpha) image.has_alpha = !all_opaque(ImageView8::of(image));

  image::MipmapOptions filter;
  filter.srgb = options.srgb;
  filter.normal_map = options.normal_map;
  filter.threads = options.encode.threads;
  if (!pvrtc::check_dimensions(image.width, image.height, name).ok()) {
    const int pw = image::nearest_power_of_two(image.width),
              ph = image::nearest_power_of_two(image.height);
    if (!options.resize_pot) {
      return bad(name + ": size " + size_text(image.width, image.height) +
                 " is not a power of two (PVRTC needs power-of-two sides); resample to " +
                 size_text(pw, ph) + " with resize_pot");
    }
    Result<ImageRGBA8> resized = image::resize_image(image, pw, ph, filter);
    if (!resized) return resized.status();
    image = std::move(resized).value();
    out.resized = true;
  }
  if (Status s = pvrtc::check_dimensions(image.width, image.height, name); !s.ok()) return s;
  if (options.premultiply && image.has_alpha) {
    image::premultiply_alpha(image, options.srgb, parallel);
    filter.premultiply = false;  // colour already carries alpha: average it as it is
  }
  if (options.mipmaps) {
    filter.max_levels = options.mip_levels;
    filter.filter = options.mip_filter;
    Result<std::vector<ImageRGBA8>> c = image::generate_mipmaps(image, filter);
    if (!c) return c.status();
    out.chain = std::move(c).value();
  } else {
    out.chain.push_back(std::move(image));
  }
  if (options.alpha_bleed) {
    for (ImageRGBA8& level : out.chain) image::bleed_alpha(level, parallel);
  }
  return out;
}

/// Encodes every image's chain (image-major) into `tex.levels` (level-major: each level holds
/// the images in order), with the progress of `options.encode.progress` over the whole
/// texture: each image level's fraction weighted by its pixels (the encoders' costs are about
/// linear in them); never backwards, and 1.0 once, at the end.
Status encode_images(std::span<const std::vector<ImageView8>> images,
                     const CompressOptions& options, std::span<const std::string> names,
                     CompressedTexture& tex) {
  const std::function<void(double)>& hook = options.encode.progress;
  double total_pixels = 0, pixels_before = 0, last = -1;
  for (const std::vector<ImageView8>& chain : images) {
    for (const ImageView8& level : chain) total_pixels += double(level.pixel_count());
  }
  auto report = [&](double f) {
    f = std::min(f, 1.0);
    if (f <= last) return;
    last = f;
    hook(f);
  };
  tex.levels.assign(images.front().size(), {});
  pvrtc::EncodeOptions level_options = options.encode;
  level_options.normal_map = level_options.normal_map || options.normal_map;
  for (std::size_t i = 0; i < images.size(); ++i) {
    for (std::size_t l = 0; l < images[i].size(); ++l) {
      const ImageView8& level = images[i][l];
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
        s.message = names[i] + ": " + s.message;
        return s;
      }
      if (tex.levels[l].empty()) {
        tex.levels[l] = std::move(enc).value();
      } else {
        tex.levels[l].insert(tex.levels[l].end(), enc->begin(), enc->end());
      }
    }
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
  tex.premultiplied = options.premultiply && has_alpha;
  return tex;
}

/// Checks the count and sizes of the images of a texture of `shape` before any work.
Status check_shape(std::span<const ImageRGBA8> images, const TextureShape& shape,
                   std::span<const std::string> names) {
  if (names.size() != images.size()) {
    return bad("compress_images: " + std::to_string(images.size()) + " images but " +
               std::to_string(names.size()) + " names");
  }
  if (shape.faces != 1 && shape.faces != 6) {
    return bad(std::to_string(shape.faces) + " faces (1, or 6 for a cube map)");
  }
  const std::size_t n = images.size();
  const bool cube = shape.faces == 6;
  if (n == 0) return bad("no images to compress");
  if (!shape.array && n != std::size_t(shape.faces)) {
    return bad(cube ? "a cube map takes exactly 6 faces (+X, -X, +Y, -Y, +Z, -Z), not " +
                          std::to_string(n) + " (with array: 6 per layer)"
                    : std::to_string(n) + " images for one 2D texture (use array)");
  }
  if (n % std::size_t(shape.faces) != 0) {
    return bad("a cube map array takes 6 faces per layer: " + std::to_string(n) +
               " images is not a multiple of 6");
  }
  if (n > std::size_t(kMaxTextureImages)) {
    return bad(std::to_string(n) + " images: at most " + std::to_string(kMaxTextureImages) +
               " per texture");
  }
  for (std::size_t i = 0; i < n; ++i) {
    const ImageRGBA8& im = images[i];
    if (cube && im.width != im.height) {
      return bad(names[i] + ": " + size_text(im.width, im.height) +
                 " is not square (cube map faces must be)");
    }
    if (i > 0 && (im.width != images[0].width || im.height != images[0].height)) {
      return bad(names[i] + ": " + size_text(im.width, im.height) + ", but " + names[0] + " is " +
                 size_text(images[0].width, images[0].height) +
                 " (every face and layer needs one size)");
    }
  }
  return Status::success();
}

}  // namespace

Result<CompressedImage> compress_images(std::vector<ImageRGBA8> images, const TextureShape& shape,
                                        const CompressOptions& options,
                                        std::span<const std::string> names) {
  if (Status s = check_options(options); !s.ok()) return s;
  if (Status s = check_shape(images, shape, names); !s.ok()) return s;
  std::vector<Prepared> prepared;
  prepared.reserve(images.size());
  bool has_alpha = false;
  for (std::size_t i = 0; i < images.size(); ++i) {
    Result<Prepared> p = prepare(std::move(images[i]), options, names[i]);
    if (!p) return p.status();
    has_alpha = has_alpha || p->chain.front().has_alpha;
    prepared.push_back(std::move(p).value());
  }
  const ImageRGBA8& first = prepared.front().chain.front();
  CompressedImage out;
  out.texture = texture_header(options, first.width, first.height, has_alpha);
  out.texture.faces = shape.faces;
  out.texture.array = shape.array;
  out.texture.layers = int(prepared.size()) / shape.faces;
  out.resized = prepared.front().resized;

  // Each image is encoded as it would be alone (its own alpha detection): an opaque face of a
  // texture with alpha keeps opaque endpoints, which every PVRTC1 decoder reads the same way.
  std::vector<std::vector<ImageView8>> views(prepared.size());
  for (std::size_t i = 0; i < prepared.size(); ++i) {
    for (const ImageRGBA8& level : prepared[i].chain) views[i].push_back(ImageView8::of(level));
  }
  const auto t0 = std::chrono::steady_clock::now();
  if (Status s = encode_images(views, options, names, out.texture); !s.ok()) return s;
  out.encode_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  for (Prepared& p : prepared) out.sources.push_back(std::move(p.chain.front()));
  return out;
}

Result<CompressedImage> compress_image(ImageRGBA8 image, const CompressOptions& options,
                                       const std::string& name) {
  std::vector<ImageRGBA8> images;
  images.push_back(std::move(image));
  return compress_images(std::move(images), TextureShape{}, options,
                         std::span<const std::string>(&name, 1));
}

Result<CompressedTexture> compress_view(const ImageView8& image, const CompressOptions& options,
                                        const std::string& name) {
  if (Status s = check_view(image, name); !s.ok()) return s;
  if (Status s = check_options(options); !s.ok()) return s;
  // A mip chain, a resample or a preparation step makes new pixels anyway: the owning
  // pipeline, from one copy.
  const bool prepares =
      options.flip_y || options.premultiply || options.alpha_bleed || options.normal_map;
  if (options.mipmaps || prepares ||
      !pvrtc::check_dimensions(image.width, image.height, name).ok()) {
    Result<CompressedImage> r = compress_image(to_image(image), options, name);
    if (!r) return r.status();
    return std::move(r->texture);
  }
  ImageView8 level = image;
  if (level.has_alpha) level.has_alpha = !all_opaque(level);
  CompressedTexture tex = texture_header(options, image.width, image.height, level.has_alpha);
  const std::vector<ImageView8> chain = {level};
  if (Status s = encode_images(std::span<const std::vector<ImageView8>>(&chain, 1), options,
                               std::span<const std::string>(&name, 1), tex);
      !s.ok()) {
    return s;
  }
  return tex;
}

Result<metrics::ImageComparison> measure_level0(const CompressedTexture& texture,
                                                std::span<const ImageRGBA8> sources, int threads) {
  if (sources.size() != std::size_t(texture.image_count())) {
    return bad("measure_level0: " + std::to_string(sources.size()) + " source image(s) for a " +
               "texture of " + std::to_string(texture.image_count()) +
               " (every face of every layer)");
  }
  metrics::ImageComparison total;
  metrics::CompareOptions co;
  co.threads = threads;
  int n = 0;
  for (int layer = 0; layer < texture.layers; ++layer) {
    for (int face = 0; face < texture.faces; ++face, ++n) {
      Result<ImageRGBA8> decoded = decode_texture_image(texture, 0, layer, face, {threads});
      if (!decoded) return decoded.status();
      Result<metrics::ImageComparison> c =
          metrics::compare_images(sources[std::size_t(n)], *decoded, co);
      if (!c) return c.status();
      total.mse_rgb += c->mse_rgb;
      total.mse_alpha += c->mse_alpha;
      total.has_alpha = total.has_alpha || c->has_alpha;
      total.ssim_gray = n == 0 ? c->ssim_gray : total.ssim_gray + c->ssim_gray;
      total.max_abs = std::max(total.max_abs, c->max_abs);
    }
  }
  total.mse_rgb /= n;
  total.mse_alpha /= n;
  total.ssim_gray /= n;
  total.psnr_rgb = metrics::psnr_from_mse(total.mse_rgb);
  total.psnr_alpha = metrics::psnr_from_mse(total.mse_alpha);
  return total;
}

}  // namespace tessera::texture_file
