// adaptive_metrics.glsl — public GLSL API: the sample-count metrics of adaptive supersampling
// (Hollander, Boubekeur & Eisemann 2013, §3.1), the same formulas and constants as
// tessera::AdaptiveThresholds (include/tessera/adaptive_thresholds.h). Pure functions: no bindings,
// so an engine can lift them into its own passes. Requires GLSL 4.00 (double precision for the
// depth variance, which the CPU accumulates in double too).
//
// With n = m^2 window samples and K = n - 1 extra samples at most:
//   k_d = c_depth  * K * Var(d_i / mean(d))
//   k_n = c_normal * K * sqrt(1 - min_i |nbar . n_i|)    (nbar: normalised mean normal)
//   k_s = 0 if r < max(t_min, l_max * t_edge) else c_shade * K * r
//         (l over the pixel of S and its four direct neighbours; luma = Rec.601 on sRGB)
//   k   = clamp(round(max(k_d, k_n, k_s)), 0, K)
// A window mixing background and geometry gets k = K; background normals are skipped.
//
// Vulkan (glslangValidator -V, glslc): the same source, no bindings; the SPIR-V declares the
// Float64 capability (the device needs VkPhysicalDeviceFeatures::shaderFloat64) unless
// TESSERA_ADAPTIVE_NO_FP64 is defined, which accumulates the depth variance in float.

#ifndef TESSERA_ADAPTIVE_MAX_N
#define TESSERA_ADAPTIVE_MAX_N 64  // largest window (m = 8)
#endif

/// Exact sRGB encoding of a linear value clamped to [0, 1].
float tessera_linear_to_srgb(float l) {
  l = clamp(l, 0.0, 1.0);
  if (l <= 0.0031308) return l * 12.92;
  return 1.055 * pow(l, 1.0 / 2.4) - 0.055;
}

/// Luma of the shading metric and FXAA: Rec.601 weights on sRGB-encoded clamped colour.
float tessera_luma_srgb(vec3 linear_rgb) {
  return 0.299 * tessera_linear_to_srgb(linear_rgb.r) +
         0.587 * tessera_linear_to_srgb(linear_rgb.g) +
         0.114 * tessera_linear_to_srgb(linear_rgb.b);
}

/// k_d of `n` linear depths: two-pass variance of d / mean, in double as the CPU; with
/// TESSERA_ADAPTIVE_NO_FP64 (devices without shaderFloat64) in float with compensated
/// (Kahan-Babuska) sums, which agrees with the double path on >= 99.9 % of pixels' k.
#if defined(TESSERA_ADAPTIVE_NO_FP64)
/// One step of a compensated sum: `sum` + `c` carry the total, `v` is added.
void tessera_compensated_add(inout float sum, inout float c, float v) {
  precise float t = sum + v;
  precise float lost = abs(sum) >= abs(v) ? (sum - t) + v : (v - t) + sum;
  c += lost;
  sum = t;
}
float tessera_metric_depth(float depths[TESSERA_ADAPTIVE_MAX_N], int n, float c_depth) {
  if (n < 2) return 0.0;
  float sum = 0.0, c = 0.0;
  for (int i = 0; i < n; ++i) tessera_compensated_add(sum, c, depths[i]);
  precise float mean = (sum + c) / float(n);
  if (!(mean > 0.0)) return 0.0;
  float var = 0.0, cv = 0.0;
  for (int i = 0; i < n; ++i) {
    precise float t = (depths[i] - mean) / mean;
    tessera_compensated_add(var, cv, t * t);
  }
  precise float v = (var + cv) / float(n);
  return c_depth * float(n - 1) * v;
}
#else
float tessera_metric_depth(float depths[TESSERA_ADAPTIVE_MAX_N], int n, float c_depth) {
  if (n < 2) return 0.0;
  double sum = 0.0LF;
  for (int i = 0; i < n; ++i) sum += double(depths[i]);
  double mean = sum / double(n);
  if (!(mean > 0.0LF)) return 0.0;
  double var = 0.0LF;
  for (int i = 0; i < n; ++i) {
    double t = (double(depths[i]) - mean) / mean;
    var += t * t;
  }
  var /= double(n);
  return float(double(c_depth) * double(n - 1) * var);
}
#endif

/// k_n of `count` normals (zero normals = background, skipped); n = window size.
float tessera_metric_normal(vec3 normals[TESSERA_ADAPTIVE_MAX_N], int count, float c_normal,
                            int n) {
  float k_max = c_normal * float(n - 1);
  vec3 sum = vec3(0.0);
  int valid = 0;
  for (int i = 0; i < count; ++i) {
    vec3 v = normals[i];
    if (dot(v, v) <= 0.0) continue;
    sum += normalize(v);
    ++valid;
  }
  if (valid < 2) return 0.0;
  if (length(sum) < 1e-3 * float(valid)) return k_max;  // the normals cancel out
  vec3 mean = normalize(sum);
  float min_dot = 1.0;
  for (int i = 0; i < count; ++i) {
    vec3 v = normals[i];
    if (dot(v, v) <= 0.0) continue;
    min_dot = min(min_dot, abs(dot(mean, normalize(v))));
  }
  float t = 1.0 - min_dot;
  return t <= 4e-7 ? 0.0 : k_max * sqrt(t);
}

/// k_s from the luma of the pixel (m) and its north, south, west and east neighbours.
float tessera_metric_shading(float lm, float ln, float ls, float lw, float le, float t_min,
                             float t_edge, float c_shade, int n) {
  float l_max = max(max(max(lm, ln), max(ls, lw)), le);
  float l_min = min(min(min(lm, ln), min(ls, lw)), le);
  float r = l_max - l_min;
  if (r < max(t_min, l_max * t_edge)) return 0.0;
  return c_shade * float(n - 1) * r;
}

/// Rounds a sample count to an integer in [0, k_max] (round half away from zero, as lround).
int tessera_round_k(float k, int k_max) {
  if (!(k > 0.0)) return 0;
  return int(min(floor(k + 0.5), float(k_max)));
}
