// The image-to-texture pipeline shared by `tessera compress` (single file and batch), the
// Python module and tessera.batch: alpha detection, the power-of-two rule, the mip chain and
// the per-level encodes.
#include <algorithm>
#include <chrono>
#include <cstring>
#include <functional>

#include "tessera/mipmap.h"
#include "tessera/texture_file.h"

namespace tessera::texture_file {

namespace {

std::string size_text(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

/// True when some alpha byte differs from 255 (RGBA8, alpha in byte 3 of each texel).
bool any_translucent(const ImageRGBA8& image) {
  // Two texels a step: their alpha bytes are the top bytes of each little-endian half.
  constexpr std::uint64_t kAlpha2 = 0xff000000ff000000ull;
  const std::uint8_t* p = image.pixels.data();
  const std::size_t n = image.pixels.size();
  std::uint64_t all = kAlpha2;
  std::size_t i = 0;
  for (; i + 8 <= n && all == kAlpha2; i += 8) {
    std::uint64_t v;
    std::memcpy(&v, p + i, 8);
    all &= v | ~kAlpha2;
  }
  bool translucent = all != kAlpha2;
  for (i += 3; i < n && !translucent; i += 4) translucent = p[i] != 255;
  return translucent;
}

}  // namespace

Result<CompressedImage> compress_image(ImageRGBA8 image, const CompressOptions& options,
                                       const std::string& name) {
  CompressedImage out;
  // An alpha channel that is opaque everywhere (common in RGBA PNGs) gives an RGB texture.
  if (image.has_alpha) image.has_alpha = any_translucent(image);

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
  std::vector<const ImageRGBA8*> chain = {&image};
  if (options.mipmaps) {
    Result<std::vector<ImageRGBA8>> c = image::generate_mipmaps(image, filter);
    if (!c) return c.status();
    mips = std::move(c).value();
    chain.clear();
    for (const ImageRGBA8& m : mips) chain.push_back(&m);
  }

  CompressedTexture& tex = out.texture;
  tex.format = options.encode.format;
  tex.width = image.width;
  tex.height = image.height;
  tex.has_alpha = image.has_alpha;
  tex.srgb = options.srgb;
  const auto t0 = std::chrono::steady_clock::now();
  // Progress over the whole chain: each level's fraction weighted by its pixels (the encoders'
  // costs are about linear in them); never backwards, and 1.0 once, at the end.
  const std::function<void(double)>& hook = options.encode.progress;
  double total_pixels = 0, pixels_before = 0, last = -1;
  for (const ImageRGBA8* level : chain) total_pixels += double(level->pixel_count());
  auto report = [&](double f) {
    f = std::min(f, 1.0);
    if (f <= last) return;
    last = f;
    hook(f);
  };
  pvrtc::EncodeOptions level_options = options.encode;
  for (const ImageRGBA8* level : chain) {
    if (hook) {
      const double pixels = double(level->pixel_count());
      level_options.progress = [&, pixels](double f) {
        report((pixels_before + f * pixels) / total_pixels);
      };
    }
    Result<std::vector<std::uint8_t>> enc = pvrtc::encode(*level, level_options);
    pixels_before += double(level->pixel_count());
    if (!enc) {
      Status s = enc.status();
      s.message = name + ": " + s.message;
      return s;
    }
    tex.levels.push_back(std::move(enc).value());
  }
  if (hook) report(1.0);
  out.encode_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (options.mipmaps) {
    out.source = std::move(mips.front());
  } else {
    out.source = std::move(image);
  }
  return out;
}

}  // namespace tessera::texture_file
