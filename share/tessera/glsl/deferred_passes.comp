// deferred_passes.comp — the compute passes of tessera's GPU adaptive supersampling
// (tessera::gl::DeferredRenderer, include/tessera/gl_deferred.h). One source, one pass per
// program, chosen by a define in the preamble:
//   TESSERA_PASS_FIRST      S: shade the first sample (index order) of every window with
//                           footprint scale m -> SSBO 3 (rgb, luma), SSBO 4 (light terms D, P)
//   TESSERA_PASS_METRICS    k per pixel (adaptive_metrics.glsl) -> SSBO 5 (uint)
//   TESSERA_PASS_EXTRA      shade k extra samples (adaptive_samples.glsl footprints), average
//                           with S -> SSBO 6 (rgba, every pixel). With TESSERA_EDGE the pixel's
//                           k is instead n-1 or 0 by Lauritzen's classification
//                           (edge_classify.glsl), written to SSBO 5.
//                           Schedule (TESSERA_SCHEDULE_LOOP unset): per 8x8 tile, the extra
//                           samples of all 64 pixels go into one shared-memory list that the 64
//                           invocations shade round-robin (Lauritzen 2010's redistribution), so
//                           a pixel with k = 15 does not stall its neighbours; colours land in
//                           per-sample slots and each pixel sums its own in index order, so the
//                           result is deterministic. TESSERA_SCHEDULE_LOOP: the paper's §4.2
//                           loop (each invocation shades its pixel's k samples); same result.
//                           TESSERA_SCHEDULE_FRAME: one dense list over the whole frame, in
//                           three passes (same result, bit for bit):
//     TESSERA_FRAME_LIST    per pixel: k, the footprint scales and sample 0 again -> SSBO 6;
//                           the pixel's k items (pixel, p) at a base from one atomic counter
//                           (SSBO 9: count, capacity, then the base per pixel; SSBO 10: items;
//                           SSBO 11: colour slots, .w = the item's footprint scale)
//     TESSERA_FRAME_SHADE   one invocation per item (1-D over the list, 64 per group)
//     TESSERA_FRAME_RESOLVE per pixel: sample 0 + the pixel's slots in p order, / (k + 1)
//   TESSERA_PASS_REFERENCE  all n samples, footprint scale 1, mean in index order -> SSBO 6
//   TESSERA_PASS_SRGB8      SSBO 3's rgb (TESSERA_SRGB_FROM_S) or SSBO 6 -> sRGB8 packed in
//                           SSBO 7 (r | g << 8 | b << 16 | 255 << 24, as tessera::to_srgb8)
//   TESSERA_PASS_FXAA       FXAA 3.11 (fxaa.glsl) of SSBO 7 -> SSBO 8 (packed as SSBO 7)
// Always defined: TESSERA_DEFERRED_CLASSES, TESSERA_WINDOW_N (= m*m), TESSERA_ADAPTIVE_MAX_N.
// Vulkan (VULKAN defined by glslangValidator -V or glslc; no tessera runtime yet): set
// TESSERA_DEFERRED_SET holds deferred_shading.glsl's bindings, then SSBO k (3..11 above) at
// binding TESSERA_PASSES_FIRST_BINDING + k - 3 (default TESSERA_DEFERRED_FIRST_BINDING + 8,
// after deferred_shading.glsl's defaults). OpenGL compiles exactly what it always did.
#version 450 core
// Offline checks (glslangValidator -l -DTESSERA_GLSLANG -I<this folder>) resolve the includes
// with glslang's extension; tessera::gl::expand_includes resolves them for the driver.
#if defined(TESSERA_GLSLANG)
#extension GL_GOOGLE_include_directive : require
#endif

#include "deferred_shading.glsl"
#include "adaptive_metrics.glsl"
#include "adaptive_samples.glsl"
#include "edge_classify.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

#if defined(VULKAN)
#ifndef TESSERA_PASSES_FIRST_BINDING
#define TESSERA_PASSES_FIRST_BINDING (TESSERA_DEFERRED_FIRST_BINDING + 8)
#endif
// OpenGL's SSBO k as a Vulkan set and binding.
#define TESSERA_PASSES_BUFFER(k) \
  std430, set = TESSERA_DEFERRED_SET, binding = TESSERA_PASSES_FIRST_BINDING + (k) - 3
layout(TESSERA_PASSES_BUFFER(3)) buffer TesseraS { vec4 tessera_s[]; };
layout(TESSERA_PASSES_BUFFER(4)) buffer TesseraTerms { vec4 tessera_terms[]; };
layout(TESSERA_PASSES_BUFFER(5)) buffer TesseraK { uint tessera_k[]; };
layout(TESSERA_PASSES_BUFFER(6)) buffer TesseraOut { vec4 tessera_out[]; };
layout(TESSERA_PASSES_BUFFER(7)) buffer TesseraRgba8 { uint tessera_rgba8[]; };
layout(TESSERA_PASSES_BUFFER(8)) buffer TesseraRgba8Out { uint tessera_rgba8_out[]; };
#if defined(TESSERA_SCHEDULE_FRAME)
layout(TESSERA_PASSES_BUFFER(9)) buffer TesseraListBase {
  uint tessera_list_total;
  uint tessera_list_capacity;
  uint tessera_list_base[];
};
layout(TESSERA_PASSES_BUFFER(10)) buffer TesseraListItems { uvec2 tessera_list_items[]; };
layout(TESSERA_PASSES_BUFFER(11)) buffer TesseraListColours { vec4 tessera_list_colours[]; };
#endif
#else
layout(std430, binding = 3) buffer TesseraS { vec4 tessera_s[]; };
layout(std430, binding = 4) buffer TesseraTerms { vec4 tessera_terms[]; };
layout(std430, binding = 5) buffer TesseraK { uint tessera_k[]; };
layout(std430, binding = 6) buffer TesseraOut { vec4 tessera_out[]; };
layout(std430, binding = 7) buffer TesseraRgba8 { uint tessera_rgba8[]; };
layout(std430, binding = 8) buffer TesseraRgba8Out { uint tessera_rgba8_out[]; };
#if defined(TESSERA_SCHEDULE_FRAME)
// One block for the counter and the bases keeps the list pass at 8 storage blocks, the least a
// GL 4.5 driver must allow per compute shader.
layout(std430, binding = 9) buffer TesseraListBase {
  uint tessera_list_total;
  uint tessera_list_capacity;
  uint tessera_list_base[];
};
layout(std430, binding = 10) buffer TesseraListItems { uvec2 tessera_list_items[]; };
layout(std430, binding = 11) buffer TesseraListColours { vec4 tessera_list_colours[]; };
#endif
#endif

const int N = TESSERA_WINDOW_N;

ivec2 tessera_pixel() { return ivec2(gl_GlobalInvocationID.xy); }
bool tessera_inside(ivec2 p) { return p.x < tessera_size.x && p.y < tessera_size.y; }
int tessera_index(ivec2 p) { return p.y * tessera_size.x + p.x; }

#if defined(TESSERA_PASS_EXTRA) && defined(TESSERA_EDGE)
/// Lauritzen's test on the window of `pixel`: true = shade every sample.
bool tessera_edge_complex(ivec2 pixel) {
  int m = tessera_size.z;
  ivec2 g0 = tessera_window_sample(pixel, 0);
  TesseraSample s0 = tessera_fetch(g0);
  int background = 0;
  for (int q = 0; q < N; ++q) {
    ivec2 g = ivec2(m * pixel.x + q % m, m * pixel.y + q / m);
    background += tessera_fetch_material(g) < 0 ? 1 : 0;
  }
  if (background == N) return false;
  if (background > 0) return true;
  vec2 grid = vec2(tessera_size.xy * m);
  float t = tessera_eye.w, aspect = tessera_view.x;
  mat3 rot = mat3(tessera_inv_view);
  float nx = 2.0 * (float(g0.x) + 0.5) / grid.x - 1.0;
  float ny = 1.0 - 2.0 * (float(g0.y) + 0.5) / grid.y;
  vec3 ray = rot * vec3(nx * t * aspect, ny * t, -1.0);
  vec3 ray_dx = rot * vec3(2.0 * t * aspect / grid.x, 0.0, 0.0);
  vec3 ray_dy = rot * vec3(0.0, -2.0 * t / grid.y, 0.0);
  vec2 dd = tessera_plane_depth_derivatives(s0.normal, ray, ray_dx, ray_dy, s0.depth);
  vec3 n0 = normalize(s0.normal);
  float tolerance = tessera_edge_depth_tolerance(s0.depth, dd, m, tessera_metric2.w);
  for (int q = 0; q < N; ++q) {
    ivec2 g = ivec2(m * pixel.x + q % m, m * pixel.y + q / m);
    if (g == g0) continue;
    vec4 a = texelFetch(tessera_gbuffer0, g, 0);
    if (tessera_sample_differs(s0.depth, n0, tolerance, a.x, a.yzw, tessera_metric2.z))
      return true;
  }
  return false;
}
#endif

#if defined(TESSERA_PASS_EXTRA)
/// G-buffer texel of window cell `cell` (row-major) of `pixel`.
ivec2 tessera_cell(ivec2 pixel, int m, int cell) {
  return ivec2(m * pixel.x + cell % m, m * pixel.y + cell / m);
}
/// Window cell of sample p (sample_order(m), from the parameter block).
int tessera_order_cell(int p) { return tessera_order[p >> 2][p & 3]; }

/// True when the window of `pixel` has a UV seam (adaptive_samples.glsl's rule), read straight
/// from the G-buffer: no per-window arrays (see adaptive_samples.glsl).
bool tessera_window_seam_gbuffer(ivec2 pixel, int m, float seam_factor) {
  for (int q = 0; q < m * m; ++q) {
    int cx = q % m, cy = q / m;
    ivec2 gq = tessera_cell(pixel, m, q);
    vec4 bq = texelFetch(tessera_gbuffer1, gq, 0);
    int mq = tessera_material_id(bq.x);
    if (mq < 0) continue;
    vec4 dq = texelFetch(tessera_gbuffer2, gq, 0);
    for (int dir = 0; dir < 2; ++dir) {
      int nx = cx + (dir == 0 ? 1 : 0), ny = cy + (dir == 1 ? 1 : 0);
      if (nx >= m || ny >= m) continue;
      ivec2 g2 = tessera_cell(pixel, m, ny * m + nx);
      vec4 b2 = texelFetch(tessera_gbuffer1, g2, 0);
      if (tessera_material_id(b2.x) != mq) continue;
      if (tessera_seam_between(bq.yz, dq, b2.yz, texelFetch(tessera_gbuffer2, g2, 0), dir,
                               seam_factor))
        return true;
    }
  }
  return false;
}

/// Footprint scales of samples 0..k of the window of `pixel` into `scales`.
void tessera_window_scales(ivec2 pixel, int k, out float scales[TESSERA_ADAPTIVE_MAX_N]) {
  int m = tessera_size.z;
  int mats[TESSERA_ADAPTIVE_MAX_N];
  for (int q = 0; q < TESSERA_ADAPTIVE_MAX_N; ++q) {
    mats[q] = q < N ? tessera_fetch_material(tessera_cell(pixel, m, q)) : -1;
    scales[q] = 1.0;
  }
  if (tessera_window_seam_gbuffer(pixel, m, tessera_metric2.y)) return;
  bool uniform_mat = true;
  for (int q = 1; q < N; ++q) uniform_mat = uniform_mat && mats[q] == mats[0];
  if (uniform_mat) {
    float s = tessera_scale_uniform(N, k);
    for (int p = 0; p <= k; ++p) scales[p] = s;
    return;
  }
  for (int p = 0; p <= k; ++p) {
    int mine = mats[tessera_order_cell(p)];
    int area = 0, shaded = 0;
    for (int q = 0; q < N; ++q) area += mats[q] == mine ? 1 : 0;
    for (int r = 0; r <= k; ++r) shaded += mats[tessera_order_cell(r)] == mine ? 1 : 0;
    scales[p] = tessera_scale_material(area, shaded);
  }
}

/// Sample 0 again with a new footprint: only its albedo lookup is repeated (S's light terms).
vec3 tessera_sample0_again(ivec2 pixel, int i, float scale) {
  TesseraSample s = tessera_fetch(tessera_window_sample(pixel, 0));
  if (s.material < 0) return tessera_background.rgb;
  return tessera_albedo(s, scale) * tessera_terms[2 * i].rgb + tessera_terms[2 * i + 1].rgb;
}

#if !defined(TESSERA_SCHEDULE_LOOP) && !defined(TESSERA_SCHEDULE_FRAME)
shared uint tessera_list_count;
shared uint tessera_list[64 * (N > 1 ? N - 1 : 1)];
shared float tessera_scale_slots[64 * N];
shared vec3 tessera_colour_slots[64 * N];
#endif
#endif

#if defined(TESSERA_PASS_FXAA)
// Preamble: TESSERA_FXAA_STEPS, TESSERA_FXAA_P (a float[12] constructor), TESSERA_FXAA_SUBPIX,
// TESSERA_FXAA_EDGE, TESSERA_FXAA_EDGE_MIN.
const float tessera_fxaa_p[12] = TESSERA_FXAA_P;
vec4 tessera_fxaa_texel(ivec2 p) {
  p = clamp(p, ivec2(0), tessera_size.xy - 1);
  uint t = tessera_rgba8[tessera_index(p)];
  return vec4(float(t & 255u), float((t >> 8) & 255u), float((t >> 16) & 255u),
              float(t >> 24)) / 255.0;
}
float tessera_fxaa_luma(ivec2 p) {
  vec4 c = tessera_fxaa_texel(p);
  return 0.299 * c.r + 0.587 * c.g + 0.114 * c.b;
}
#include "fxaa.glsl"
#endif

void main() {
  ivec2 pixel = tessera_pixel();
  bool inside = tessera_inside(pixel);
  int i = inside ? tessera_index(pixel) : 0;

#if defined(TESSERA_PASS_FIRST)
  if (!inside) return;
  ivec2 g = tessera_window_sample(pixel, 0);
  TesseraSample s = tessera_fetch(g);
  vec3 c = tessera_background.rgb, d = vec3(0.0), p = vec3(0.0);
  if (s.material >= 0) {
    tessera_lighting(g, s, d, p);
    c = tessera_albedo(s, float(tessera_size.z)) * d + p;
  }
  tessera_s[i] = vec4(c, tessera_luma_srgb(c));
  tessera_terms[2 * i] = vec4(d, 0.0);
  tessera_terms[2 * i + 1] = vec4(p, 0.0);

#elif defined(TESSERA_PASS_METRICS)
  if (!inside) return;
  int k_max = N - 1;
  if (tessera_counts.z >= 0) {
    tessera_k[i] = uint(min(tessera_counts.z, k_max));
    return;
  }
  int m = tessera_size.z;
  float k = 0.0;
  if ((tessera_counts.w & 1) != 0) {
    float depths[TESSERA_ADAPTIVE_MAX_N];
    vec3 normals[TESSERA_ADAPTIVE_MAX_N];
    int background = 0;
    for (int q = 0; q < TESSERA_ADAPTIVE_MAX_N; ++q) {
      depths[q] = 0.0;
      normals[q] = vec3(0.0);
    }
    for (int q = 0; q < N; ++q) {
      ivec2 g = ivec2(m * pixel.x + q % m, m * pixel.y + q / m);
      vec4 a = texelFetch(tessera_gbuffer0, g, 0);
      bool bg = tessera_fetch_material(g) < 0;
      depths[q] = a.x;
      normals[q] = bg ? vec3(0.0) : a.yzw;
      background += bg ? 1 : 0;
    }
    if (background > 0 && background < N) {
      k = float(k_max);
    } else if (background == 0) {
      k = max(tessera_metric_depth(depths, N, tessera_metric.x),
              tessera_metric_normal(normals, N, tessera_metric.y, N));
    }
  }
  if ((tessera_counts.w & 2) != 0 && k < float(k_max)) {
    ivec2 lim = tessera_size.xy - 1;
    float lm = tessera_s[i].w;
    float ln = tessera_s[tessera_index(clamp(pixel + ivec2(0, -1), ivec2(0), lim))].w;
    float ls = tessera_s[tessera_index(clamp(pixel + ivec2(0, 1), ivec2(0), lim))].w;
    float lw = tessera_s[tessera_index(clamp(pixel + ivec2(-1, 0), ivec2(0), lim))].w;
    float le = tessera_s[tessera_index(clamp(pixel + ivec2(1, 0), ivec2(0), lim))].w;
    k = max(k, tessera_metric_shading(lm, ln, ls, lw, le, tessera_metric.w, tessera_metric2.x,
                                      tessera_metric.z, N));
  }
  tessera_k[i] = uint(tessera_round_k(k, k_max));

#elif defined(TESSERA_PASS_EXTRA) && defined(TESSERA_FRAME_SHADE)
  // One invocation per list item; groups are laid out 2-D so that long lists stay within the
  // guaranteed 65535 groups per dimension.
  uint e = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 64u +
           gl_LocalInvocationIndex;
  if (e >= tessera_list_total) return;
  uvec2 item = tessera_list_items[e];
  int owner_index = int(item.x);
  ivec2 owner = ivec2(owner_index % tessera_size.x, owner_index / tessera_size.x);
  float scale = tessera_list_colours[e].w;
  tessera_list_colours[e] = vec4(tessera_shade(tessera_window_sample(owner, int(item.y)), scale),
                                 scale);

#elif defined(TESSERA_PASS_EXTRA)
  int k = 0;
  if (inside) {
#if defined(TESSERA_EDGE) && !defined(TESSERA_FRAME_RESOLVE)
    k = tessera_edge_complex(pixel) ? N - 1 : 0;
    tessera_k[i] = uint(k);
#else
    k = int(tessera_k[i]);
#endif
  }
#if defined(TESSERA_SCHEDULE_FRAME) && defined(TESSERA_FRAME_LIST)
  if (!inside) return;
  if (k == 0) {
    tessera_out[i] = vec4(tessera_s[i].rgb, 1.0);
    return;
  }
  float scales[TESSERA_ADAPTIVE_MAX_N];
  tessera_window_scales(pixel, k, scales);
  tessera_out[i] = vec4(tessera_sample0_again(pixel, i, scales[0]), 1.0);
  uint base = atomicAdd(tessera_list_total, uint(k));
  tessera_list_base[i] = base;
  if (base + uint(k) > tessera_list_capacity) return;  // the host grows the list and reruns
  for (int p = 1; p <= k; ++p) {
    tessera_list_items[base + uint(p - 1)] = uvec2(uint(i), uint(p));
    tessera_list_colours[base + uint(p - 1)] = vec4(0.0, 0.0, 0.0, scales[p]);
  }
#elif defined(TESSERA_SCHEDULE_FRAME)
  // TESSERA_FRAME_RESOLVE (the shading of the items has its own branch of main()).
  if (!inside || k == 0) return;
  vec3 sum = tessera_out[i].rgb;
  uint base = tessera_list_base[i];
  for (int p = 1; p <= k; ++p) sum += tessera_list_colours[base + uint(p - 1)].rgb;
  tessera_out[i] = vec4(sum / float(k + 1), 1.0);
#elif defined(TESSERA_SCHEDULE_LOOP)
  if (!inside) return;
  if (k == 0) {
    tessera_out[i] = vec4(tessera_s[i].rgb, 1.0);
    return;
  }
  float scales[TESSERA_ADAPTIVE_MAX_N];
  tessera_window_scales(pixel, k, scales);
  vec3 sum = tessera_sample0_again(pixel, i, scales[0]);
  for (int p = 1; p <= k; ++p) sum += tessera_shade(tessera_window_sample(pixel, p), scales[p]);
  tessera_out[i] = vec4(sum / float(k + 1), 1.0);
#else
  uint local = gl_LocalInvocationIndex;
  if (local == 0u) tessera_list_count = 0u;
  barrier();
  if (k > 0) {
    float scales[TESSERA_ADAPTIVE_MAX_N];
    tessera_window_scales(pixel, k, scales);
    for (int p = 0; p <= k; ++p) tessera_scale_slots[local * uint(N) + uint(p)] = scales[p];
    tessera_colour_slots[local * uint(N)] = tessera_sample0_again(pixel, i, scales[0]);
    uint base = atomicAdd(tessera_list_count, uint(k));
    for (int p = 1; p <= k; ++p) tessera_list[base + uint(p - 1)] = (local << 8) | uint(p);
  }
  barrier();
  uint count = tessera_list_count;
  ivec2 tile = ivec2(gl_WorkGroupID.xy) * 8;
  for (uint e = local; e < count; e += 64u) {
    uint item = tessera_list[e];
    uint pl = item >> 8;
    int p = int(item & 255u);
    ivec2 owner = tile + ivec2(int(pl % 8u), int(pl / 8u));
    tessera_colour_slots[pl * uint(N) + uint(p)] =
        tessera_shade(tessera_window_sample(owner, p), tessera_scale_slots[pl * uint(N) + uint(p)]);
  }
  barrier();
  if (!inside) return;
  if (k == 0) {
    tessera_out[i] = vec4(tessera_s[i].rgb, 1.0);
    return;
  }
  vec3 sum = vec3(0.0);
  for (int p = 0; p <= k; ++p) sum += tessera_colour_slots[local * uint(N) + uint(p)];
  tessera_out[i] = vec4(sum / float(k + 1), 1.0);
#endif

#elif defined(TESSERA_PASS_REFERENCE)
  if (!inside) return;
  vec3 sum = vec3(0.0);
  for (int p = 0; p < N; ++p) sum += tessera_shade(tessera_window_sample(pixel, p), 1.0);
  tessera_out[i] = vec4(sum / float(N), 1.0);

#elif defined(TESSERA_PASS_SRGB8)
  if (!inside) return;
#if defined(TESSERA_SRGB_FROM_S)
  vec3 c = tessera_s[i].rgb;
#else
  vec3 c = tessera_out[i].rgb;
#endif
  uvec3 b;
  for (int ch = 0; ch < 3; ++ch) {
    float v = isnan(c[ch]) ? 0.0 : c[ch];
    b[ch] = uint(floor(tessera_linear_to_srgb(v) * 255.0 + 0.5));
  }
  tessera_rgba8[i] = b.r | (b.g << 8) | (b.b << 16) | (255u << 24);

#elif defined(TESSERA_PASS_FXAA)
  if (!inside) return;
  bool early;
  vec2 pos = tessera_fxaa_position(pixel, TESSERA_FXAA_SUBPIX, TESSERA_FXAA_EDGE,
                                   TESSERA_FXAA_EDGE_MIN, early);
  uint in_texel = tessera_rgba8[i];
  if (early) {
    tessera_rgba8_out[i] = in_texel;
    return;
  }
  vec2 f = pos - 0.5;
  vec2 f0 = floor(f);
  vec2 a = f - f0;
  ivec2 i0 = ivec2(f0);
  vec4 c00 = tessera_fxaa_texel(i0), c10 = tessera_fxaa_texel(i0 + ivec2(1, 0));
  vec4 c01 = tessera_fxaa_texel(i0 + ivec2(0, 1)), c11 = tessera_fxaa_texel(i0 + ivec2(1, 1));
  vec4 v = (c00 * (1.0 - a.x) + c10 * a.x) * (1.0 - a.y) + (c01 * (1.0 - a.x) + c11 * a.x) * a.y;
  uvec3 b = uvec3(clamp(floor(v.rgb * 255.0 + 0.5), 0.0, 255.0));
  tessera_rgba8_out[i] = b.r | (b.g << 8) | (b.b << 16) | (in_texel & 0xff000000u);
#else
#error "deferred_passes.comp: no known TESSERA_PASS_* is defined"
#endif
}
