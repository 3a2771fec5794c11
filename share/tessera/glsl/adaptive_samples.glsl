// adaptive_samples.glsl — public GLSL API: which samples of a window the adaptive method shades
// and with which texture footprint (Hollander et al. 2013, §3.2 and §4.1), as the CPU's
// DeferredRenderer::shade_adaptive. Pure functions; the index matrices themselves come from
// tessera::deferred::sample_order(m) (Figure 3 for m = 2, 3, 4), passed in as `order`.
//
// Sample p (0 = the one already shaded into S) of a window is cell order[p] (row-major j*m + i).
// Footprint scale of a sample, with k extra samples (k + 1 shaded) in an n = m*m window:
//   * UV seam in the window (two adjacent samples of one material whose UV jump exceeds
//     seam_factor x what their derivatives predict, + 1e-6): 1;
//   * one material (background counts as one id): sqrt(n / (k + 1));
//   * several materials (§4.1 material-boundary rule): sqrt(A / N), A = the window's cells of the
//     sample's material, N = the shaded samples (p <= k) of that material.

#ifndef TESSERA_ADAPTIVE_MAX_N
#define TESSERA_ADAPTIVE_MAX_N 64
#endif

/// True when the window has a UV seam. `mats`, `uvs` and `duvs` hold the window row-major
/// (duv = du/dx, dv/dx, du/dy, dv/dy).
bool tessera_window_seam(int m, int mats[TESSERA_ADAPTIVE_MAX_N],
                         vec2 uvs[TESSERA_ADAPTIVE_MAX_N], vec4 duvs[TESSERA_ADAPTIVE_MAX_N],
                         float seam_factor) {
  int n = m * m;
  for (int q = 0; q < n; ++q) {
    if (mats[q] < 0) continue;
    int cx = q % m, cy = q / m;
    for (int dir = 0; dir < 2; ++dir) {
      int nx = cx + (dir == 0 ? 1 : 0), ny = cy + (dir == 1 ? 1 : 0);
      if (nx >= m || ny >= m) continue;
      int q2 = ny * m + nx;
      if (mats[q2] != mats[q]) continue;
      vec2 ds = dir == 0 ? duvs[q].xy : duvs[q].zw;
      vec2 dt = dir == 0 ? duvs[q2].xy : duvs[q2].zw;
      float jump = abs(uvs[q2].x - uvs[q].x) + abs(uvs[q2].y - uvs[q].y);
      float predicted = 0.5 * (abs(ds.x) + abs(ds.y) + abs(dt.x) + abs(dt.y));
      if (jump > seam_factor * predicted + 1e-6) return true;
    }
  }
  return false;
}

/// Footprint scale of sample p (0 <= p <= k) of a window with k extra samples.
float tessera_sample_scale(int p, int k, int m, int order[TESSERA_ADAPTIVE_MAX_N],
                           int mats[TESSERA_ADAPTIVE_MAX_N], bool seam) {
  int n = m * m;
  if (seam) return 1.0;
  bool uniform_mat = true;
  for (int q = 1; q < n; ++q) uniform_mat = uniform_mat && mats[q] == mats[0];
  if (uniform_mat) return sqrt(float(n) / float(k + 1));
  int mine = mats[order[p]];
  int area = 0, shaded = 0;
  for (int q = 0; q < n; ++q) area += mats[q] == mine ? 1 : 0;
  for (int r = 0; r <= k; ++r) shaded += mats[order[r]] == mine ? 1 : 0;
  return sqrt(float(area) / float(shaded));
}
