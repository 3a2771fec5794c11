// Texture storage (all levels of all layers in one float buffer), float mip chains for any size
// (exact area box downsampling, optionally alpha-weighted; GL level sizes max(1, floor(s / 2))),
// and the sampling driver that resolves the kernel's taps to texels.
#include "tessera/texture.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "texture/sampler_kernel.h"
#include "texture/sampler_quad_kernel.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace tessera {

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

ImageRGBAF downsample_box(const ImageRGBAF& image, bool alpha_weighted, int threads) {
  if (image.empty()) return {};
  const int dw = mip_dimension(image.width, 1);
  const int dh = mip_dimension(image.height, 1);
  const AxisFilter fx(image.width, dw);
  const AxisFilter fy(image.height, dh);
  ImageRGBAF out(dw, dh);
  parallel_for(
      0, dh, 8,
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
      threads);
  return out;
}

std::vector<ImageRGBAF> build_mip_chain(const ImageRGBAF& image, bool alpha_weighted,
                                        int max_levels, int threads) {
  std::vector<ImageRGBAF> chain;
  if (image.empty()) return chain;
  int levels = mip_level_count(image.width, image.height);
  if (max_levels > 0 && max_levels < levels) levels = max_levels;
  chain.reserve(std::size_t(levels));
  chain.push_back(image);
  for (int l = 1; l < levels; ++l) {
    chain.push_back(downsample_box(chain.back(), alpha_weighted, threads));
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
  if (srgb) return to_linear(image, threads);
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
    chains.push_back(build_mip_chain(decode(layer), options.alpha_weighted, options.max_levels,
                                     options.threads));
  }
  return TextureBuilder::assemble(chains);
}

/// Accumulates tap values as the kernel produces them, in the same order and arithmetic as
/// `Texture::resolve` (acc += weight * value per tap, weight = wx * wy), so both paths agree
/// bit for bit. Quads read their 2x2 texels through two row pointers.
struct AccumulateSink {
  const float* texels;
  const std::size_t* level_offsets;  // offsets of the lookup's layer, indexed by level
  const TextureShape* shape;
  const float* border;
  texture_detail::Accum4 acc;

  void add(float w, const float* p) { acc.add(w, p); }

  void point(const TexelTap& tap) {
    const float* p = border;
    if (!tap.is_border()) {
      const std::size_t stride = std::size_t(shape->level_width(tap.level)) * 4;
      p = texels + level_offsets[tap.level] + std::size_t(tap.resolved_y) * stride +
          std::size_t(tap.resolved_x) * 4;
    }
    add(tap.weight, p);
  }

  void quad(const texture_detail::QuadTaps& q) {
    const float* base = texels + level_offsets[q.level];
    const std::size_t stride = std::size_t(shape->level_width(q.level)) * 4;
    const std::ptrdiff_t c0 = std::ptrdiff_t(q.rx[0]) * 4;
    const std::ptrdiff_t c1 = std::ptrdiff_t(q.rx[1]) * 4;
    if ((q.rx[0] | q.rx[1] | q.ry[0] | q.ry[1]) >= 0) {  // no border reads (the common case)
      const float* r0 = base + std::size_t(q.ry[0]) * stride;
      const float* r1 = base + std::size_t(q.ry[1]) * stride;
      add(q.wx[0] * q.wy[0], r0 + c0);
      add(q.wx[1] * q.wy[0], r0 + c1);
      add(q.wx[0] * q.wy[1], r1 + c0);
      add(q.wx[1] * q.wy[1], r1 + c1);
      return;
    }
    for (int j = 0; j < 2; ++j) {
      const float* row = base + std::size_t(q.ry[j] < 0 ? 0 : q.ry[j]) * stride;
      for (int k = 0; k < 2; ++k) {
        const bool is_border = q.ry[j] < 0 || q.rx[k] < 0;
        add(q.wx[k] * q.wy[j], is_border ? border : row + (k ? c1 : c0));
      }
    }
  }
};

/// Resolves the adjacent pair (x0, x0 + 1) like `resolve_pair`, with a mask instead of a
/// modulo for the common wrap of a power-of-two size (two's complement `x & (size - 1)` is the
/// mathematical x mod size, negative x included).
inline void resolve_pair_fast(int x0, int size, AddressMode mode, int out[2]) {
  if (mode == AddressMode::wrap && (size & (size - 1)) == 0) {
    out[0] = x0 & (size - 1);
    out[1] = (x0 + 1) & (size - 1);
    return;
  }
  texture_detail::resolve_pair(x0, size, mode, out);
}

/// Adds the four taps of one bilinear block with weights `w` = (w00, w10, w01, w11), tap (k, j)
/// at column rx[k], row ry[j], rows then columns, as `AccumulateSink::quad` does. Border taps
/// (rx or ry < 0) read `border`.
inline void add_bilinear_weights(texture_detail::Accum4& acc, const float* base, std::size_t stride,
                                 const int rx[2], const int ry[2], const float w[4],
                                 const float* border) {
  const std::ptrdiff_t c0 = std::ptrdiff_t(rx[0]) * 4;
  const std::ptrdiff_t c1 = std::ptrdiff_t(rx[1]) * 4;
  if ((rx[0] | rx[1] | ry[0] | ry[1]) >= 0) {
    const float* r0 = base + std::size_t(ry[0]) * stride;
    const float* r1 = base + std::size_t(ry[1]) * stride;
    acc.add(w[0], r0 + c0);
    acc.add(w[1], r0 + c1);
    acc.add(w[2], r1 + c0);
    acc.add(w[3], r1 + c1);
    return;
  }
  for (int j = 0; j < 2; ++j) {
    const float* row = base + std::size_t(ry[j] < 0 ? 0 : ry[j]) * stride;
    for (int k = 0; k < 2; ++k) {
      const bool is_border = ry[j] < 0 || rx[k] < 0;
      acc.add(w[2 * j + k], is_border ? border : row + (k ? c1 : c0));
    }
  }
}

/// Adds the four taps of one bilinear block (tap weight wx[k] * wy[j]), as
/// `AccumulateSink::quad` does.
inline void add_bilinear(const AccumulateSink& sink, texture_detail::Accum4& acc, const float* base,
                         std::size_t stride, const int rx[2], const int ry[2], const float wx[2],
                         const float wy[2]) {
  const float w[4] = {wx[0] * wy[0], wx[1] * wy[0], wx[0] * wy[1], wx[1] * wy[1]};
  add_bilinear_weights(acc, base, stride, rx, ry, w, sink.border);
}

/// Bilinear or trilinear lookup of a one-probe footprint (the shading hot path): exactly the
/// taps `for_each_tap` generates for it, accumulated in the same order with the same
/// arithmetic as `AccumulateSink`, without materialising `QuadTaps`, so the result is
/// bit-identical to the generic path. With SSE2 the texel coordinates and weights of both
/// levels are computed in one vector (lane-wise the same IEEE operations).
/// `footprint.lod` must be clamped to [0, levels - 1].
std::array<float, 4> sample_one_probe(const AccumulateSink& sink, const SamplerState& sampler,
                                      const Footprint& footprint) {
  using namespace texture_detail;
  const TextureShape& shape = *sink.shape;
  const LevelPlan plan = plan_levels(sampler.filter, footprint.lod, shape.levels);
  // for_each_tap with one probe: inv_probes = 1 and t = 0, kept as operations so that
  // non-finite axes behave the same; level weights times inv_probes = 1 are exact.
  const float t = (0.0f + 0.5f) * 1.0f - 0.5f;
  const float u = footprint.center.u + t * footprint.axis_u;
  const float v = footprint.center.v + t * footprint.axis_v;
  int lv[2] = {plan.level[0], plan.level[plan.count - 1]};
  int w[2], h[2];
  for (int li = 0; li < 2; ++li) {
    w[li] = shape.level_width(lv[li]);
    h[li] = shape.level_height(lv[li]);
  }
  // Per level li: x0, y0, the weights wx[2] (= 1 - ax, ax) and wy[2] (times the level weight).
  int x0[2], y0[2];
  float wx[2][2], wy[2][2];
#if defined(__SSE2__)
  {
    const __m128 size = _mm_set_ps(float(h[1]), float(w[1]), float(h[0]), float(w[0]));
    const __m128 p = _mm_sub_ps(_mm_mul_ps(_mm_set_ps(v, u, v, u), size), _mm_set1_ps(0.5f));
    // clamp_coord: p > -L ? (p < L ? p : L) : -L (NaN -> -L).
    const __m128 lim = _mm_set1_ps(kCoordLimit);
    const __m128 nlim = _mm_set1_ps(-kCoordLimit);
    const __m128 above = _mm_cmpgt_ps(p, nlim);
    const __m128 pc = _mm_or_ps(_mm_and_ps(above, _mm_min_ps(p, lim)), _mm_andnot_ps(above, nlim));
    // floor_to_int: truncate, then subtract 1 where p < float(trunc).
    const __m128i tr = _mm_cvttps_epi32(pc);
    const __m128i fl = _mm_add_epi32(tr, _mm_castps_si128(_mm_cmplt_ps(pc, _mm_cvtepi32_ps(tr))));
    const __m128 frac = _mm_sub_ps(pc, _mm_cvtepi32_ps(fl));
    const __m128 lw = _mm_set_ps(plan.weight[1], 1.0f, plan.weight[0], 1.0f);
    alignas(16) float lo[4], hi[4];
    alignas(16) int ic[4];
    // x lanes: 1 - ax and ax (times 1, exact); y lanes: (1 - ay) * lw and ay * lw.
    _mm_store_ps(lo, _mm_mul_ps(_mm_sub_ps(_mm_set1_ps(1.0f), frac), lw));
    _mm_store_ps(hi, _mm_mul_ps(frac, lw));
    _mm_store_si128(reinterpret_cast<__m128i*>(ic), fl);
    for (int li = 0; li < 2; ++li) {
      x0[li] = ic[2 * li];
      y0[li] = ic[2 * li + 1];
      wx[li][0] = lo[2 * li];
      wx[li][1] = hi[2 * li];
      wy[li][0] = lo[2 * li + 1];
      wy[li][1] = hi[2 * li + 1];
    }
  }
#else
  for (int li = 0; li < 2; ++li) {
    const float px = clamp_coord(u * float(w[li]) - 0.5f);
    const float py = clamp_coord(v * float(h[li]) - 0.5f);
    x0[li] = floor_to_int(px);
    y0[li] = floor_to_int(py);
    const float ax = px - float(x0[li]);
    const float ay = py - float(y0[li]);
    wx[li][0] = 1.0f - ax;
    wx[li][1] = ax;
    wy[li][0] = (1.0f - ay) * plan.weight[li];
    wy[li][1] = ay * plan.weight[li];
  }
#endif
  Accum4 acc;
  for (int li = 0; li < plan.count; ++li) {
    int rx[2], ry[2];
    resolve_pair_fast(x0[li], w[li], sampler.address_u, rx);
    resolve_pair_fast(y0[li], h[li], sampler.address_v, ry);
    add_bilinear(sink, acc, sink.texels + sink.level_offsets[lv[li]], std::size_t(w[li]) * 4, rx,
                 ry, wx[li], wy[li]);
  }
  return acc.value();
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

std::array<float, 4> Texture::sample_footprint(const SamplerState& sampler,
                                               const Footprint& footprint, int layer) const {
  if (empty()) return sampler.border_color;
  layer = std::clamp(layer, 0, shape_.layers - 1);
  Footprint fp = footprint;
  const float last = float(shape_.levels - 1);
  if (!(fp.lod >= 0.0f)) fp.lod = 0.0f;
  if (fp.lod > last) fp.lod = last;
  AccumulateSink sink{texels_.data(),
                      offsets_.data() + std::size_t(layer) * shape_.levels,
                      &shape_,
                      sampler.border_color.data(),
                      {}};
  if ((sampler.filter == TextureFilter::trilinear || sampler.filter == TextureFilter::bilinear) &&
      fp.probes <= 1) {
    return sample_one_probe(sink, sampler, fp);
  }
  texture_detail::for_each_tap(sampler, shape_, fp, layer, sink);
  return sink.acc.value();
}

std::array<float, 4> Texture::sample(const SamplerState& sampler, Uv uv,
                                     const UvGradients& gradients, int layer) const {
  if (!empty() &&
      (sampler.filter == TextureFilter::trilinear || sampler.filter == TextureFilter::bilinear)) {
    // The hot path, inlined: `compute_footprint` for an isotropic filter (one probe, zero
    // axis) followed by `sample_footprint`, with the same operations.
    const float w = float(shape_.width);
    const float h = float(shape_.height);
    const UvGradients texel{gradients.dudx * w, gradients.dvdx * h, gradients.dudy * w,
                            gradients.dvdy * h};
    Footprint fp;
    fp.center = uv;
    fp.lod =
        texture_detail::clamp_lod(sampler, shape_, texture_detail::isotropic_lod_inline(texel));
    layer = std::clamp(layer, 0, shape_.layers - 1);
    const AccumulateSink sink{texels_.data(),
                              offsets_.data() + std::size_t(layer) * shape_.levels,
                              &shape_,
                              sampler.border_color.data(),
                              {}};
    return sample_one_probe(sink, sampler, fp);
  }
  return sample_footprint(sampler, compute_footprint(sampler, shape_, uv, gradients), layer);
}

void Texture::sample4(const SamplerState& sampler, const std::array<Uv, 4>& uv,
                      const std::array<UvGradients, 4>& gradients, std::uint32_t active,
                      std::array<std::array<float, 4>, 4>& out, int layer) const {
  active &= 15u;
#if defined(__SSE2__)
  constexpr int kExact = 1 << 24;  // level sizes stay exact in float (see level_size4)
  if (active && !empty() &&
      (sampler.filter == TextureFilter::trilinear || sampler.filter == TextureFilter::bilinear) &&
      shape_.width < kExact && shape_.height < kExact) {
    using namespace texture_detail;
    // Structure-of-arrays inputs; inactive lanes compute on zeros and their results are dropped.
    alignas(16) static constexpr std::uint32_t kLaneBits[16][4] = {
        {0, 0, 0, 0},     {~0u, 0, 0, 0},     {0, ~0u, 0, 0},     {~0u, ~0u, 0, 0},
        {0, 0, ~0u, 0},   {~0u, 0, ~0u, 0},   {0, ~0u, ~0u, 0},   {~0u, ~0u, ~0u, 0},
        {0, 0, 0, ~0u},   {~0u, 0, 0, ~0u},   {0, ~0u, 0, ~0u},   {~0u, ~0u, 0, ~0u},
        {0, 0, ~0u, ~0u}, {~0u, 0, ~0u, ~0u}, {0, ~0u, ~0u, ~0u}, {~0u, ~0u, ~0u, ~0u}};
    const __m128 lanes = _mm_load_ps(reinterpret_cast<const float*>(kLaneBits[active]));
    float in[16];
    std::memcpy(in, gradients.data(), sizeof in);  // dudx, dvdx, dudy, dvdy per lane
    __m128 dudx = _mm_loadu_ps(in), dvdx = _mm_loadu_ps(in + 4);
    __m128 dudy = _mm_loadu_ps(in + 8), dvdy = _mm_loadu_ps(in + 12);
    _MM_TRANSPOSE4_PS(dudx, dvdx, dudy, dvdy);
    std::memcpy(in, uv.data(), 8 * sizeof(float));  // u, v per lane
    const __m128 uv01 = _mm_loadu_ps(in), uv23 = _mm_loadu_ps(in + 4);
    const __m128 u = _mm_and_ps(lanes, _mm_shuffle_ps(uv01, uv23, _MM_SHUFFLE(2, 0, 2, 0)));
    const __m128 v = _mm_and_ps(lanes, _mm_shuffle_ps(uv01, uv23, _MM_SHUFFLE(3, 1, 3, 1)));
    alignas(16) float len[4], raw_lod[4];
    _mm_store_ps(len, footprint_length4(_mm_and_ps(lanes, dudx), _mm_and_ps(lanes, dvdx),
                                        _mm_and_ps(lanes, dudy), _mm_and_ps(lanes, dvdy),
                                        float(shape_.width), float(shape_.height)));
    // The scalar path's log2, per lane; skipped where the LOD is known to end at level 0.
    const bool shortcut = magnification_shortcut(sampler);
    for (int lane = 0; lane < 4; ++lane) {
      const bool skip = !(active >> lane & 1u) || (shortcut && len[lane] <= 1.0f);
      raw_lod[lane] = skip ? 0.0f : std::log2(len[lane]);
    }
    OneProbe4 plan;
    plan_one_probe4(sampler, shape_, clamp_lod4(sampler, shape_, _mm_load_ps(raw_lod)), u, v, plan);
    layer = std::clamp(layer, 0, shape_.layers - 1);
    const std::size_t* level_offsets = offsets_.data() + std::size_t(layer) * shape_.levels;
    const float* texels = texels_.data();
    if (plan.has_offsets) {
      // Same taps and order as add_bilinear_weights without border reads (the loop below with
      // its address resolution hoisted out).
      for (int lane = 0; lane < 4; ++lane) {
        if (!(active >> lane & 1u)) continue;
        Accum4 acc;
        const int count = plan.count[lane];
        for (int li = 0; li < count; ++li) {
          const float* base = texels + level_offsets[plan.level[li][lane]];
          const float* w4 = plan.weight[li][lane];
          const int* o = plan.offset[li][lane];
          acc.add(w4[0], base + o[0]);
          acc.add(w4[1], base + o[1]);
          acc.add(w4[2], base + o[2]);
          acc.add(w4[3], base + o[3]);
        }
        out[std::size_t(lane)] = acc.value();
      }
      return;
    }
    for (int lane = 0; lane < 4; ++lane) {
      if (!(active >> lane & 1u)) continue;
      Accum4 acc;
      for (int li = 0; li < plan.count[lane]; ++li) {
        const float* base = texels + level_offsets[plan.level[li][lane]];
        const float* w4 = plan.weight[li][lane];
        if (plan.has_offsets) {
          // Same taps and order as add_bilinear_weights without border reads.
          const int* o = plan.offset[li][lane];
          acc.add(w4[0], base + o[0]);
          acc.add(w4[1], base + o[1]);
          acc.add(w4[2], base + o[2]);
          acc.add(w4[3], base + o[3]);
          continue;
        }
        const int w = plan.w[li][lane], h = plan.h[li][lane];
        int rx[2], ry[2];
        resolve_pair_fast(plan.x0[li][lane], w, sampler.address_u, rx);
        resolve_pair_fast(plan.y0[li][lane], h, sampler.address_v, ry);
        add_bilinear_weights(acc, base, std::size_t(w) * 4, rx, ry, w4,
                             sampler.border_color.data());
      }
      out[std::size_t(lane)] = acc.value();
    }
    return;
  }
#endif
  for (int lane = 0; lane < 4; ++lane) {
    if (active >> lane & 1u) {
      out[std::size_t(lane)] =
          sample(sampler, uv[std::size_t(lane)], gradients[std::size_t(lane)], layer);
    }
  }
}

std::array<float, 4> Texture::sample_lod(const SamplerState& sampler, Uv uv, float lod,
                                         int layer) const {
  return sample_footprint(sampler, footprint_at_lod(sampler, shape_, uv, lod), layer);
}

std::array<std::array<float, 4>, 4> Texture::sample_quad(const SamplerState& sampler,
                                                         const std::array<Uv, 4>& quad,
                                                         int layer) const {
  const UvGradients g = quad_gradients(quad);
  std::array<std::array<float, 4>, 4> out;
  for (int i = 0; i < 4; ++i) out[std::size_t(i)] = sample(sampler, quad[std::size_t(i)], g, layer);
  return out;
}

void Texture::taps(const SamplerState& sampler, Uv uv, const UvGradients& gradients, int layer,
                   TapList& out) const {
  generate_taps(sampler, shape_, compute_footprint(sampler, shape_, uv, gradients), layer, out);
}

std::array<float, 4> Texture::fetch(const SamplerState& sampler, const TexelTap& tap) const {
  if (tap.is_border() || empty()) return sampler.border_color;
  const TextureLevelView view = level(tap.layer, tap.level);
  const float* p = view.at(tap.resolved_x, tap.resolved_y);
  return {p[0], p[1], p[2], p[3]};
}

std::array<float, 4> Texture::resolve(const SamplerState& sampler, const TapList& taps) const {
  texture_detail::Accum4 acc;
  for (const TexelTap& tap : taps) {
    const std::array<float, 4> c = fetch(sampler, tap);
    acc.add(tap.weight, c.data());
  }
  return acc.value();
}

}  // namespace tessera
