// Texture storage (all levels of all layers in one float buffer), float mip chains for any size
// (exact area box downsampling, optionally alpha-weighted; GL level sizes max(1, floor(s / 2))),
// and construction with its checks. The sampling driver that resolves the kernel's taps to
// texels: texture_sampling.cpp.
#include "tessera/texture.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace tessera::texture {

// ---------------------------------------------------------------------------------------------
// Mip chains
// ---------------------------------------------------------------------------------------------

namespace {

/// For one axis, the source texels each destination texel covers and their weights: destination
/// texel d covers the source interval [d * s, (d + 1) * s) with s = src / dst, and source texel
/// i weighs the overlap of [i, i + 1) with that interval / s. Weights of one destination texel sum
/// to 1, and every source texel's weights sum to 1 / s over all destinations, so means are
/// preserved.
struct AxisFilter {
  std::vector<int> first;             ///< First source texel of destination d.
  std::vector<int> count;             ///< Number of source texels of destination d.
  std::vector<double> weight;         ///< kMaxSpan weights per destination.
  static constexpr int kMaxSpan = 4;  // s <= 3 (3 -> 1), so at most 4 texels are touched.

  AxisFilter(int src, int dst) : first(dst), count(dst), weight(std::size_t(dst) * kMaxSpan) {
    const double s = double(src) / double(dst);
    for (int d = 0; d < dst; ++d) {
      // d * src is an exact integer, so interval ends that fall on texel edges stay exact.
      const double lo = double(d) * src / dst;
      const double hi = double(d + 1) * src / dst;
      int i0 = int(std::floor(lo));
      int i1 = int(std::ceil(hi)) - 1;
      if (i1 > src - 1) i1 = src - 1;
      // Drop slivers that come only from rounding (overlap below 1e-12 texels).
      while (i0 < i1 && double(i0 + 1) - lo < 1e-12) ++i0;
      while (i1 > i0 && hi - double(i1) < 1e-12) --i1;
      first[d] = i0;
      count[d] = i1 - i0 + 1;
      for (int k = 0; k < count[d]; ++k) {
        const double a = std::max(lo, double(i0 + k));
        const double b = std::min(hi, double(i0 + k + 1));
        weight[std::size_t(d) * kMaxSpan + k] = (b - a) / s;
      }
    }
  }
};

}  // namespace

ImageRGBAF downsample_box(const ImageRGBAF& image, const TextureOptions& options) {
  if (image.empty()) return {};
  const bool alpha_weighted = options.alpha_weighted;
  const int dw = mip_dimension(image.width, 1);
  const int dh = mip_dimension(image.height, 1);
  const AxisFilter fx(image.width, dw);
  const AxisFilter fy(image.height, dh);
  ImageRGBAF out(dw, dh);
  parallel_for(0, dh, 8,
               [&](std::int64_t y_begin, std::int64_t y_end) {
                 for (std::int64_t yy = y_begin; yy < y_end; ++yy) {
                   const int y = int(yy);
                   for (int x = 0; x < dw; ++x) {
                     double plain[3] = {0, 0, 0};  // sum w * c
                     double pre[3] = {0, 0, 0};    // sum w * a * c
                     double alpha = 0;             // sum w * a
                     for (int j = 0; j < fy.count[y]; ++j) {
                       const double wy = fy.weight[std::size_t(y) * AxisFilter::kMaxSpan + j];
                       const int sy = fy.first[y] + j;
                       for (int i = 0; i < fx.count[x]; ++i) {
                         const double w = wy * fx.weight[std::size_t(x) * AxisFilter::kMaxSpan + i];
                         const float* s = image.at(fx.first[x] + i, sy);
                         for (int c = 0; c < 3; ++c) {
                           plain[c] += w * s[c];
                           pre[c] += w * s[3] * s[c];
                         }
                         alpha += w * s[3];
                       }
                     }
                     float* d = out.at(x, y);
                     const bool use_pre = alpha_weighted && alpha > 0.0;
                     for (int c = 0; c < 3; ++c) d[c] = float(use_pre ? pre[c] / alpha : plain[c]);
                     d[3] = float(alpha);
                   }
                 }
               },
               {options.threads});
  return out;
}

std::vector<ImageRGBAF> build_mip_chain(const ImageRGBAF& image, const TextureOptions& options) {
  std::vector<ImageRGBAF> chain;
  if (image.empty()) return chain;
  int levels = mip_level_count(image.width, image.height);
  if (options.max_levels > 0 && options.max_levels < levels) levels = options.max_levels;
  chain.reserve(std::size_t(levels));
  chain.push_back(image);
  for (int l = 1; l < levels; ++l) {
    chain.push_back(downsample_box(chain.back(), options));
  }
  return chain;
}

// ---------------------------------------------------------------------------------------------
// Storage
// ---------------------------------------------------------------------------------------------

/// Assembles per-layer chains into a Texture's flat storage (friend of Texture).
struct TextureBuilder {
  static Texture assemble(const std::vector<std::vector<ImageRGBAF>>& chains) {
    Texture tex;
    const ImageRGBAF& base = chains.front().front();
    tex.shape_ =
        TextureShape{base.width, base.height, int(chains.front().size()), int(chains.size())};
    std::size_t total = 0;
    for (const auto& chain : chains)
      for (const ImageRGBAF& level : chain) total += level.pixels.size();
    tex.texels_.reserve(total);
    tex.offsets_.reserve(chains.size() * chains.front().size());
    for (const auto& chain : chains) {
      for (const ImageRGBAF& level : chain) {
        tex.offsets_.push_back(tex.texels_.size());
        tex.texels_.insert(tex.texels_.end(), level.pixels.begin(), level.pixels.end());
      }
    }
    return tex;
  }
};

namespace {

Status check_layers(int width, int height, std::size_t layers, const char* what) {
  if (layers == 0) {
    return Status::error(ErrorCode::invalid_argument, std::string(what) + ": no layers");
  }
  if (width <= 0 || height <= 0) {
    return Status::error(ErrorCode::invalid_argument, std::string(what) + ": empty image");
  }
  Status s = check_image_size(width, height, what);
  if (!s.ok()) return s;
  if (std::uint64_t(width) * std::uint64_t(height) * layers > kMaxImagePixels) {
    return Status::error(ErrorCode::too_large, std::string(what) + ": " + std::to_string(layers) +
                                                   " layers of " + std::to_string(width) + "x" +
                                                   std::to_string(height) +
                                                   " exceed the texel limit");
  }
  return Status::success();
}

Status check_options(const TextureOptions& options, const char* what) {
  if (options.max_levels < 0) {
    return Status::error(ErrorCode::invalid_argument,
                         std::string(what) + ": max_levels must be >= 0");
  }
  return Status::success();
}

ImageRGBAF decode_rgba8(const ImageRGBA8& image, bool srgb, int threads) {
  if (srgb) return to_linear(image, {threads});
  ImageRGBAF out(image.width, image.height);
  const std::size_t n = image.pixels.size();
  for (std::size_t i = 0; i < n; ++i) out.pixels[i] = float(image.pixels[i]) / 255.0f;
  return out;
}

template <class Image, class Decode>
Result<Texture> build_array(const std::vector<Image>& layers, const TextureOptions& options,
                            const char* what, Decode decode) {
  if (layers.empty())
    return Status::error(ErrorCode::invalid_argument, std::string(what) + ": no layers");
  const int w = layers.front().width;
  const int h = layers.front().height;
  if (Status s = check_layers(w, h, layers.size(), what); !s.ok()) return s;
  if (Status s = check_options(options, what); !s.ok()) return s;
  for (std::size_t i = 1; i < layers.size(); ++i) {
    if (layers[i].width != w || layers[i].height != h) {
      return Status::error(ErrorCode::size_mismatch,
                           std::string(what) + ": layer " + std::to_string(i) + " is " +
                               std::to_string(layers[i].width) + "x" +
                               std::to_string(layers[i].height) + ", layer 0 is " +
                               std::to_string(w) + "x" + std::to_string(h));
    }
  }
  std::vector<std::vector<ImageRGBAF>> chains;
  chains.reserve(layers.size());
  for (const Image& layer : layers) {
    chains.push_back(build_mip_chain(decode(layer), options));
  }
  return TextureBuilder::assemble(chains);
}

}  // namespace

Result<Texture> Texture::from_rgba8(const ImageRGBA8& image, const TextureOptions& options) {
  return array_from_rgba8(std::vector<ImageRGBA8>{image}, options);
}

Result<Texture> Texture::from_float(const ImageRGBAF& image, const TextureOptions& options) {
  return array_from_float(std::vector<ImageRGBAF>{image}, options);
}

Result<Texture> Texture::array_from_rgba8(const std::vector<ImageRGBA8>& layers,
                                          const TextureOptions& options) {
  for (const ImageRGBA8& layer : layers) {
    if (layer.pixels.size() != layer.pixel_count() * 4) {
      return Status::error(ErrorCode::invalid_argument, "texture: pixel buffer size mismatch");
    }
  }
  return build_array(layers, options, "texture", [&options](const ImageRGBA8& img) {
    return decode_rgba8(img, options.srgb, options.threads);
  });
}

Result<Texture> Texture::array_from_float(const std::vector<ImageRGBAF>& layers,
                                          const TextureOptions& options) {
  for (const ImageRGBAF& layer : layers) {
    if (layer.pixels.size() != layer.pixel_count() * 4) {
      return Status::error(ErrorCode::invalid_argument, "texture: pixel buffer size mismatch");
    }
  }
  return build_array(layers, options, "texture",
                     [](const ImageRGBAF& img) -> const ImageRGBAF& { return img; });
}

Result<Texture> Texture::from_float_levels(std::vector<ImageRGBAF> levels) {
  if (levels.empty()) return Status::error(ErrorCode::invalid_argument, "texture: no levels");
  const int w = levels.front().width;
  const int h = levels.front().height;
  if (Status s = check_layers(w, h, 1, "texture"); !s.ok()) return s;
  const int full = mip_level_count(w, h);
  if (int(levels.size()) > full) {
    return Status::error(ErrorCode::invalid_argument, "texture: " + std::to_string(levels.size()) +
                                                          " levels given, a " + std::to_string(w) +
                                                          "x" + std::to_string(h) + " chain has " +
                                                          std::to_string(full));
  }
  for (std::size_t l = 0; l < levels.size(); ++l) {
    const int ew = mip_dimension(w, int(l));
    const int eh = mip_dimension(h, int(l));
    if (levels[l].width != ew || levels[l].height != eh ||
        levels[l].pixels.size() != levels[l].pixel_count() * 4) {
      return Status::error(ErrorCode::size_mismatch, "texture: level " + std::to_string(l) +
                                                         " is " + std::to_string(levels[l].width) +
                                                         "x" + std::to_string(levels[l].height) +
                                                         ", expected " + std::to_string(ew) + "x" +
                                                         std::to_string(eh));
    }
  }
  std::vector<std::vector<ImageRGBAF>> chains;
  chains.push_back(std::move(levels));
  return TextureBuilder::assemble(chains);
}

TextureLevelView Texture::level(int layer, int level) const {
  const std::size_t index = std::size_t(layer) * std::size_t(shape_.levels) + std::size_t(level);
  return {shape_.level_width(level), shape_.level_height(level), texels_.data() + offsets_[index]};
}

ImageRGBAF Texture::level_image(int layer, int level) const {
  const TextureLevelView view = this->level(layer, level);
  ImageRGBAF out(view.width, view.height);
  std::copy(view.texels, view.texels + out.pixels.size(), out.pixels.begin());
  return out;
}

}  // namespace tessera::texture
