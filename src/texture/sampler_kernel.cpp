// Sampler kernel: gradients, LOD selection (GL / EXT_texture_filter_anisotropic), address modes
// and tap lists. Pure functions; no texture data is touched here.
#include "texture/sampler_kernel.h"

#include <cmath>
#include <limits>

namespace tessera::texture {

namespace {

float length2d(float x, float y) { return std::sqrt(x * x + y * y); }

int clamp_aniso(int max_aniso) {
  return max_aniso < 1 ? 1 : (max_aniso > kMaxAnisotropy ? kMaxAnisotropy : max_aniso);
}

}  // namespace

UvGradients quad_gradients(const std::array<Uv, 4>& quad) {
  UvGradients g;
  g.dudx = quad[1].u - quad[0].u;
  g.dvdx = quad[1].v - quad[0].v;
  g.dudy = quad[2].u - quad[0].u;
  g.dvdy = quad[2].v - quad[0].v;
  return g;
}

float isotropic_lod(const UvGradients& g) { return detail::isotropic_lod_inline(g); }

AnisoFootprint anisotropic_footprint(const UvGradients& g, int max_aniso) {
  const float px = length2d(g.dudx, g.dvdx);
  const float py = length2d(g.dudy, g.dvdy);
  const bool x_major = px >= py;
  const float pmax = x_major ? px : py;
  const float pmin = x_major ? py : px;
  AnisoFootprint fp;
  if (!(pmax > 0.0f) || std::isinf(pmax)) {
    // Zero, NaN or infinite gradients: a single probe; the LOD (-inf, NaN or +inf) is then
    // clamped by the caller.
    fp.lod = std::log2(pmax);
    return fp;
  }
  const int limit = clamp_aniso(max_aniso);
  const float ratio = pmin > 0.0f ? pmax / pmin : std::numeric_limits<float>::infinity();
  int n = limit;
  if (ratio < float(limit)) {
    n = int(std::ceil(ratio - 1e-4f));
    if (n < 1) n = 1;
  }
  fp.probes = n;
  fp.lod = std::log2(pmax / float(n));
  fp.axis_x = x_major ? g.dudx : g.dudy;
  fp.axis_y = x_major ? g.dvdx : g.dvdy;
  return fp;
}

Footprint compute_footprint(const SamplerState& sampler, const TextureShape& shape, Uv uv,
                            const UvGradients& gradients) {
  const float w = float(shape.width);
  const float h = float(shape.height);
  const UvGradients texel{gradients.dudx * w, gradients.dvdx * h, gradients.dudy * w,
                          gradients.dvdy * h};
  Footprint fp;
  fp.centre = uv;
  float lod = 0.0f;
  if (sampler.filter == TextureFilter::anisotropic) {
    const AnisoFootprint aniso = anisotropic_footprint(texel, sampler.max_aniso);
    lod = aniso.lod;
    fp.probes = aniso.probes;
    if (aniso.probes > 1 && w > 0.0f && h > 0.0f) {
      fp.axis_u = aniso.axis_x / w;
      fp.axis_v = aniso.axis_y / h;
    } else {
      fp.probes = 1;
    }
  } else {
    lod = detail::isotropic_lod_inline(texel);
  }
  fp.lod = detail::clamp_lod(sampler, shape, lod);
  return fp;
}

Footprint footprint_at_lod(const SamplerState& sampler, const TextureShape& shape, Uv uv,
                           float lod) {
  Footprint fp;
  fp.centre = uv;
  fp.lod = detail::clamp_lod(sampler, shape, lod);
  return fp;
}

int resolve_address(int x, int size, AddressMode mode) {
  if (size <= 0) return -1;
  return detail::resolve_axis(x, size, mode);
}

int array_layer(float r, int layers) {
  if (layers <= 1) return 0;
  // NaN maps to layer 0 (both comparisons fail).
  const float f = std::floor(r + 0.5f);
  if (!(f > 0.0f)) return 0;
  if (f >= float(layers - 1)) return layers - 1;
  return int(f);
}

float TapList::weight_sum() const {
  float sum = 0.0f;
  for (const TexelTap& tap : *this) sum += tap.weight;
  return sum;
}

void generate_taps(const SamplerState& sampler, const TextureShape& shape,
                   const Footprint& footprint, int layer, TapList& out) {
  out.count = 0;
  if (shape.width <= 0 || shape.height <= 0 || shape.levels <= 0) return;
  const int last_layer = shape.layers > 1 ? shape.layers - 1 : 0;
  layer = layer < 0 ? 0 : (layer > last_layer ? last_layer : layer);
  // Taps are generated from a copy whose LOD is re-clamped to this shape, so a footprint made
  // for another texture cannot address a missing level.
  Footprint fp = footprint;
  const float last = float(shape.levels - 1);
  if (!(fp.lod >= 0.0f)) fp.lod = 0.0f;
  if (fp.lod > last) fp.lod = last;
  detail::for_each_tap(sampler, shape, fp, layer, detail::TapListSink{out});
}

}  // namespace tessera::texture
