// Internal to src/deferred: the per-sample shading context shared by the drivers. The kernel
// (lighting, albedo, combine) is written once here so that the reference, default and adaptive
// paths run exactly the same floating-point operations for the same sample.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "tessera/deferred.h"

namespace tessera::deferred {

/// Lighting of one sample: colour = albedo * d + p.
struct LightTerms {
  std::array<float, 3> d{};  ///< Ambient + diffuse (times the heavy term), times exposure.
  std::array<float, 3> p{};  ///< Specular, times exposure.
};

inline std::array<float, 3> combine(const std::array<float, 3>& albedo, const LightTerms& l) {
  return {albedo[0] * l.d[0] + l.p[0], albedo[1] * l.d[1] + l.p[1], albedo[2] * l.d[2] + l.p[2]};
}

/// Blinn-Phong lighting of a surface point (kernel): `n` need not be unit length and is turned
/// towards the viewer (double-sided surfaces).
LightTerms blinn_phong(const ShadingOptions& o, const Vec3& position, const Vec3& normal,
                       const Vec3& eye, float heavy_factor);

/// The heavy per-sample term in [0.55, 1]: `terms` smooth sinusoids of the position, `waves`
/// holding 4 floats (kx, ky, kz, phase) per term.
float heavy_factor(const std::vector<float>& waves, const Vec3& position);
/// Deterministic wave vectors for `heavy_factor`.
std::vector<float> make_heavy_waves(int terms, float wavelength);

/// Everything the drivers need to shade G-buffer samples. Read-only after construction.
struct ShadeContext {
  const GBuffer& gb;
  const ShadingOptions& o;
  const std::vector<DeferredRenderer::MaterialInfo>& materials;
  texture::SamplerState sampler;
  std::vector<float> waves;

  ShadeContext(const DeferredRenderer& r, const GBuffer& g, const ShadingOptions& opt)
      : gb(g), o(opt), materials(r.materials_) {
    sampler.filter = opt.filter;
    sampler.max_aniso = opt.max_aniso;
    if (opt.heavy) waves = make_heavy_waves(opt.heavy_terms, opt.heavy_wavelength);
  }

  /// Material index of a sample; -1 for background (or an out-of-range id).
  int material(const float* s) const {
    const int id = int(std::lround(s[kChMaterial]));
    return id >= 0 && id < int(materials.size()) ? id : -1;
  }
  bool textured(const float* s) const {
    const int id = material(s);
    return id >= 0 && materials[std::size_t(id)].texture != nullptr;
  }

  LightTerms lighting(int gx, int gy, const float* s) const {
    const Vec3 p = gb.position(gx, gy);
    const float h = waves.empty() ? 1.0f : heavy_factor(waves, p);
    return blinn_phong(o, p, {s[kChNormal], s[kChNormal + 1], s[kChNormal + 2]}, gb.eye, h);
  }

  /// Base colour of a (non-background) sample: factor x anisotropic lookup with the stored
  /// derivatives times `scale`.
  std::array<float, 3> albedo(const float* s, float scale) const {
    const DeferredRenderer::MaterialInfo& mi = materials[std::size_t(material(s))];
    std::array<float, 3> a = mi.base;
    if (mi.texture) {
      const texture::UvGradients g{s[kChDuvDx] * scale, s[kChDuvDx + 1] * scale,
                                   s[kChDuvDy] * scale, s[kChDuvDy + 1] * scale};
      const std::array<float, 4> t = mi.texture->sample(sampler, {s[kChUv], s[kChUv + 1]}, g);
      a[0] *= t[0];
      a[1] *= t[1];
      a[2] *= t[2];
    }
    return a;
  }

  /// Full shading of grid pixel (gx, gy) with texture-footprint scale `scale`.
  std::array<float, 3> shade(int gx, int gy, float scale) const {
    const float* s = gb.sample(gx, gy);
    if (material(s) < 0) return kBackground;
    return combine(albedo(s, scale), lighting(gx, gy, s));
  }
};

}  // namespace tessera::deferred
