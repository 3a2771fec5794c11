// edge_classify.glsl — public GLSL API: the engine baseline's per-pixel test "do this pixel's
// samples differ?" (deferred MSAA with per-sample shading on edges, Lauritzen 2010,
// "Deferred Rendering for Current and Future Rendering Pipelines"), applied to the m x m window
// of the enlarged G-buffer as the pixel's samples. The CPU twin is
// tessera::deferred::classify_edge_per_sample (src/deferred/edge_per_sample.cpp). Pure.
//
// A pixel needs per-sample shading when
//   * its window mixes background and geometry, or
//   * some sample's linear depth differs from sample 0's (the window's first sample in index
//     order) by more than the depth change of one output pixel along sample 0's plane:
//       |d_i - d_0| > slack * m * (|dd/dx| + |dd/dy|) + 1e-4 * d_0
//     with dd/dx, dd/dy the depth derivatives per grid pixel of the plane through sample 0 with
//     sample 0's normal, m grid pixels per output pixel (Lauritzen's maxZDelta = |ddx| + |ddy|
//     of the pixel's surface, from stored derivatives; this G-buffer has none, the plane gives
//     them), or
//   * some sample's normal deviates: dot(normalize(n_i), normalize(n_0)) < min_normal_dot
//     (Lauritzen: 0.99, about 8 degrees).
// Vulkan (glslangValidator -V, glslc): the same source; no bindings, no macros.

/// Depth derivatives per grid pixel (d/dx, d/dy) of the plane through a point at linear depth
/// `depth` seen along the world ray `ray` (view-space z component -1, so depth = ray
/// parameter), with world normal `normal`; `ray_dx`/`ray_dy` = change of the ray per grid pixel.
/// Infinite at grazing angles (the depth test then never fires; the normal test still does).
vec2 tessera_plane_depth_derivatives(vec3 normal, vec3 ray, vec3 ray_dx, vec3 ray_dy,
                                     float depth) {
  vec3 n = normalize(normal);
  float nr = dot(n, ray);
  if (abs(nr) < 1e-12) return vec2(1.0 / 0.0);
  return vec2(-depth * dot(n, ray_dx) / nr, -depth * dot(n, ray_dy) / nr);
}

/// Lauritzen's depth tolerance for a window of m x m grid pixels around sample 0 (depth d0,
/// depth derivatives dd per grid pixel).
float tessera_edge_depth_tolerance(float d0, vec2 dd, int m, float depth_slack) {
  return depth_slack * float(m) * (abs(dd.x) + abs(dd.y)) + 1e-4 * d0;
}

/// True when sample i (depth di, normal ni) fails the Lauritzen tests against sample 0 (depth
/// d0, unit normal n0) with the depth tolerance above.
bool tessera_sample_differs(float d0, vec3 n0, float tolerance, float di, vec3 ni,
                            float min_normal_dot) {
  if (abs(di - d0) > tolerance) return true;
  return dot(normalize(ni), n0) < min_normal_dot;
}
