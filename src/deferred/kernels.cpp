// Pure kernels of deferred shading: the adaptive metrics (k_d, k_n, k_s), Blinn-Phong lighting,
// the heavy per-sample term, position reconstruction and the scene's default lights.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "deferred_internal.h"

namespace tessera::deferred {

// ---------------------------------------------------------------------------------------------
// Metrics
// ---------------------------------------------------------------------------------------------

float metric_depth(std::span<const float> depths, float c_depth) {
  const std::size_t n = depths.size();
  if (n < 2) return 0.0f;
  double sum = 0;
  for (float d : depths) sum += d;
  const double mean = sum / double(n);
  if (!(mean > 0)) return 0.0f;
  // Variance of d / mean (two-pass: the paper's E[d^2] - E[d]^2, without the cancellation).
  double var = 0;
  for (float d : depths) {
    const double t = (double(d) - mean) / mean;
    var += t * t;
  }
  var /= double(n);
  return float(double(c_depth) * double(n - 1) * var);
}

float metric_normal(std::span<const float> normals, float c_normal, int n) {
  const std::size_t count = normals.size() / 3;
  const float k_max = c_normal * float(n - 1);
  Vec3 sum{0, 0, 0};
  int valid = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3 v{normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]};
    if (dot(v, v) <= 0.0f) continue;
    sum = sum + normalize(v);
    ++valid;
  }
  if (valid < 2) return 0.0f;
  if (length(sum) < 1e-3f * float(valid)) return k_max;  // the normals cancel out
  const Vec3 mean = normalize(sum);
  float min_dot = 1.0f;
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3 v{normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]};
    if (dot(v, v) <= 0.0f) continue;
    min_dot = std::min(min_dot, std::fabs(dot(mean, normalize(v))));
  }
  // Rounding leaves 1 - min_dot at a few ulps on a flat window; treat that as 0.
  const float t = 1.0f - min_dot;
  return t <= 4e-7f ? 0.0f : k_max * std::sqrt(t);
}

float metric_shading(float luma_m, float luma_n, float luma_s, float luma_w, float luma_e,
                     float t_min, float t_edge, float c_shade, int n) {
  const float l_max = std::max({luma_m, luma_n, luma_s, luma_w, luma_e});
  const float l_min = std::min({luma_m, luma_n, luma_s, luma_w, luma_e});
  const float r = l_max - l_min;
  if (r < std::max(t_min, l_max * t_edge)) return 0.0f;
  return c_shade * float(n - 1) * r;
}

// ---------------------------------------------------------------------------------------------
// Shading
// ---------------------------------------------------------------------------------------------

LightTerms blinn_phong(const ShadingOptions& o, const Vec3& position, const Vec3& normal,
                       const Vec3& eye, float heavy) {
  Vec3 n = normalize(normal);
  const Vec3 v = normalize(eye - position);
  if (dot(n, v) < 0.0f) n = -n;
  float d[3] = {o.ambient[0], o.ambient[1], o.ambient[2]};
  float p[3] = {0, 0, 0};
  for (const Light& light : o.lights) {
    const Vec3 to = light.position - position;
    const float dist2 = std::max(dot(to, to), 1e-8f);
    const float dist = std::sqrt(dist2);
    float atten = light.intensity / dist2;
    if (light.range > 0.0f) {
      const float q = dist / light.range, q4 = q * q * q * q;
      const float w = std::clamp(1.0f - q4, 0.0f, 1.0f);
      atten *= w * w;
    }
    if (atten <= 0.0f) continue;
    const Vec3 l = to * (1.0f / dist);
    const float ndl = dot(n, l);
    if (ndl <= 0.0f) continue;
    const Vec3 h = normalize(l + v);
    const float ndh = std::max(dot(n, h), 0.0f);
    const float spec = o.specular * std::pow(ndh, o.shininess);
    for (int c = 0; c < 3; ++c) {
      const float e = light.color[std::size_t(c)] * atten;
      d[c] += e * ndl;
      p[c] += e * ndl * spec;
    }
  }
  LightTerms t;
  for (int c = 0; c < 3; ++c) {
    t.d[std::size_t(c)] = d[c] * heavy * o.exposure;
    t.p[std::size_t(c)] = p[c] * o.exposure;
  }
  return t;
}

namespace {
// SplitMix64-style hash to [0, 1).
float hash01(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  x ^= x >> 31;
  return float(double(x >> 40) / double(1ull << 24));
}
}  // namespace

std::vector<float> make_heavy_waves(int terms, float wavelength) {
  std::vector<float> w;
  const float twopi = 2.0f * std::numbers::pi_v<float>;
  for (int i = 0; i < std::max(terms, 0); ++i) {
    const std::uint64_t s = std::uint64_t(i) * 4;
    const float z = 2.0f * hash01(s) - 1.0f, a = twopi * hash01(s + 1);
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float lambda = wavelength * (0.125f + 0.375f * hash01(s + 2));
    const float k = twopi / std::max(lambda, 1e-6f);
    w.insert(w.end(), {k * r * std::cos(a), k * r * std::sin(a), k * z, twopi * hash01(s + 3)});
  }
  return w;
}

float heavy_factor(const std::vector<float>& waves, const Vec3& p) {
  const std::size_t terms = waves.size() / 4;
  if (terms == 0) return 1.0f;
  float sum = 0.0f;
  for (std::size_t i = 0; i < terms; ++i) {
    const float* w = &waves[4 * i];
    sum += std::sin(w[0] * p.x + w[1] * p.y + w[2] * p.z + w[3]);
  }
  // The sum of `terms` random-phase sinusoids has standard deviation sqrt(terms / 2).
  const float t = sum * std::sqrt(2.0f / float(terms));
  return 0.775f + 0.225f * std::clamp(t, -1.0f, 1.0f);
}

Vec3 GBuffer::position(int gx, int gy) const {
  const float d = sample(gx, gy)[kChDepth];
  const float gw = float(fb.grid_width()), gh = float(fb.grid_height());
  const float nx = 2.0f * (float(gx) + 0.5f) / gw - 1.0f;
  const float ny = 1.0f - 2.0f * (float(gy) + 0.5f) / gh;
  const Vec3 view{nx * tan_half_fov_y * aspect * d, ny * tan_half_fov_y * d, -d};
  return inv_view.transform_point(view);
}

ShadingOptions scene_shading(const scene::Scene& sc, int extra_lights,
                             const scene::Camera* camera) {
  ShadingOptions o;
  for (const scene::PointLight& l : sc.lights) {
    o.lights.push_back({l.position, {l.color[0], l.color[1], l.color[2]}, l.intensity, l.range});
  }
  if (o.lights.empty() && extra_lights <= 0) extra_lights = 4;
  const Vec3 ext = sc.bounds_max - sc.bounds_min;
  const float half_diag = std::max(1e-3f, length(ext) * 0.5f);
  Vec3 centre = (sc.bounds_min + sc.bounds_max) * 0.5f;
  float rx = 0.35f * ext.x, rz = 0.35f * ext.z, height = 0.25f * ext.y;
  if (camera) {
    centre = camera->target;
    const float d = std::max(1e-3f, length(camera->eye - camera->target));
    rx = rz = 0.5f * d;
    height = 0.35f * d;
  }
  for (int i = 0; i < extra_lights; ++i) {
    const float a = 2.0f * std::numbers::pi_v<float> * (float(i) + 0.5f) / float(extra_lights);
    Light l;
    l.position = {centre.x + rx * std::cos(a), centre.y + height, centre.z + rz * std::sin(a)};
    l.color = {0.9f + 0.1f * hash01(std::uint64_t(i) * 3), 0.85f + 0.15f * hash01(i * 3 + 1ull),
               0.8f + 0.2f * hash01(i * 3 + 2ull)};
    const Vec3 to = l.position - centre;
    const float d2 = std::max(dot(to, to), 1e-6f);
    const float cosine = std::max(0.2f, height / std::sqrt(d2));
    l.intensity = 0.8f * d2 / (cosine * float(extra_lights));
    o.lights.push_back(l);
  }
  o.heavy_wavelength = half_diag * 0.25f;
  return o;
}

}  // namespace tessera::deferred
