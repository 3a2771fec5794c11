// tessera/adaptive_thresholds.h — the thresholds of adaptive supersampling (Hollander, Boubekeur
// & Eisemann 2013, §3.1): one struct for the CPU renderer (deferred::DeferredRenderer, tessera/
// deferred.h), the GPU experiments' renderers and both engine components (gl:: and
// vk::AdaptiveSupersampler, tessera/adaptive_supersampler.h). The GLSL of the same formulas:
// share/tessera/glsl/adaptive_metrics.glsl (tessera_adaptive_metric). Plain struct, no
// dependency. Tests: tests/unit/deferred_test.cpp (the kernels' formulas),
// tests/gl/gl_deferred_renderer_test.cpp and tests/vk/vk_adaptive_test.cpp (GPU = CPU k maps).
#pragma once

namespace tessera {

/// Constants of the metrics. With n = m^2 the window size and K = n - 1 the most extra samples,
/// per pixel (the paper's formulas; the constants c are expressed in units of K so that one set
/// serves every m, and depth is made scale-free by dividing by the mean):
///   k_d = c_depth  * K * Var(d_i / mean(d))                       (over the n window samples)
///   k_n = c_normal * K * sqrt(1 - min_ij |nbar . n_ij|)           (nbar: normalised mean)
///   k_s = 0 if r < max(t_min, l_max * t_edge), else c_shade * K * r
///         with l_max, l_min, r = l_max - l_min over the luma of S at the pixel and its four
///         direct neighbours (luma: Rec.601 weights on sRGB-encoded, clamped colour, as FXAA)
///   k   = clamp(round(max(k_d, k_n, k_s)), 0, K)
/// Background samples (no geometry) take part in k_d with the far-plane depth and are skipped
/// by k_n; a window mixing background and geometry gets k = K. The unrounded max is the pixel's
/// metric strength (what a sample budget ranks).
/// The defaults were chosen on the built-in scene and the dungeon benchmark scene: at m = 4 they
/// shade a fraction of the samples for a PSNR against the reference close to full
/// supersampling's (docs/benchmarks/aa.md has both).
struct AdaptiveThresholds {
  float c_depth = 200.0f;
  float c_normal = 2.0f;
  float c_shade = 8.0f;
  float t_min = 0.0312f;     ///< As FXAA's "edge threshold min" ("visible limit").
  float t_edge = 0.0625f;    ///< As FXAA's "edge threshold" ("overkill": texture detail too).
  bool use_geometry = true;  ///< k_d and k_n (Figure 8 ablation: shading only when false).
  bool use_shading = true;   ///< k_s (Figure 8 ablation: geometry only when false).
  /// UV seam detection for the material-boundary rule (the texture footprint of a sample,
  /// adaptive_samples.glsl on the GPU): a jump larger than this many times the derivative
  /// prediction (plus 1e-6) between adjacent window samples is a seam.
  float seam_factor = 4.0f;
  /// Tests and experiments: when >= 0, every pixel uses k = min(force_k, m^2 - 1) (strength
  /// force_k).
  int force_k = -1;
};

}  // namespace tessera
