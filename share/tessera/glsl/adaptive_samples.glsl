// adaptive_samples.glsl — public GLSL API: which samples of a window the adaptive method shades
// and with which texture footprint (Hollander et al. 2013, §3.2 and §4.1), as the CPU's
// DeferredRenderer::shade_adaptive. Pure functions; the index matrices themselves come from
// tessera::deferred::sample_order(m) (Figure 3 for m = 2, 3, 4), which the driver passes in
// (deferred_passes.comp: tessera_order in its parameter block).
//
// Sample p (0 = the one already shaded into S) of a window is cell order[p] (row-major j*m + i).
// Footprint scale of a sample, with k extra samples (k + 1 shaded) in an n = m*m window:
//   * UV seam in the window (two adjacent samples of one material whose UV jump exceeds
//     seam_factor x what their derivatives predict, + 1e-6): 1;
//   * one material (background counts as one id): sqrt(n / (k + 1));
//   * several materials (§4.1 material-boundary rule): sqrt(A / N), A = the window's cells of the
//     sample's material, N = the shaded samples (p <= k) of that material.
// Vulkan (glslangValidator -V, glslc): the same source; no bindings, no macros.

// A driver loops over its window reading these from its G-buffer (deferred_passes.comp's
// tessera_window_seam_gbuffer and tessera_window_scales). Keep per-window arrays of UVs and
// derivatives out of the shading pass: on a hardware GPU their registers cost the whole pass
// its occupancy, and the extra-sample pass is several times slower with them
// (docs/benchmarks/aa_history.md).

/// True when two horizontally (dir 0) or vertically (dir 1) adjacent window samples of one
/// material have a UV seam between them: their UV jump exceeds seam_factor x what their
/// derivatives predict, + 1e-6 (duv = du/dx, dv/dx, du/dy, dv/dy). The caller skips
/// background samples and pairs of different materials.
bool tessera_seam_between(vec2 uv_a, vec4 duv_a, vec2 uv_b, vec4 duv_b, int dir,
                          float seam_factor) {
  vec2 ds = dir == 0 ? duv_a.xy : duv_a.zw;
  vec2 dt = dir == 0 ? duv_b.xy : duv_b.zw;
  float jump = abs(uv_b.x - uv_a.x) + abs(uv_b.y - uv_a.y);
  float predicted = 0.5 * (abs(ds.x) + abs(ds.y) + abs(dt.x) + abs(dt.y));
  return jump > seam_factor * predicted + 1e-6;
}

/// Footprint scale of every shaded sample of a one-material window (background counts as one
/// material) of n samples with k extra samples: sqrt(n / (k + 1)).
float tessera_scale_uniform(int n, int k) { return sqrt(float(n) / float(k + 1)); }

/// Footprint scale of a sample in a window of several materials (§4.1): `area` = the window's
/// samples of its material, `shaded` = the shaded samples (p <= k) of that material.
float tessera_scale_material(int area, int shaded) { return sqrt(float(area) / float(shaded)); }
