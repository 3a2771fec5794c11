// adaptive_component.glsl — the compute passes of tessera::gl::AdaptiveSupersampler
// (include/tessera/gl_adaptive.h; host: src/gl/adaptive_supersampler.cpp, adaptive_dispatch.cpp):
// adaptive supersampling (Hollander, Boubekeur & Eisemann 2013) over an engine's own G-buffer
// with the engine's own shading. Its twin over tessera's own G-buffer and Blinn-Phong is
// deferred_passes.comp (tessera::gl::DeferredRenderer); with that shading as the hook both give
// the same image (tests/gl/gl_adaptive_test.cpp).
//
// Not a stand-alone shader: the host compiles, per pass,
//   #version 450 core
//   <defines and G-buffer accessors, generated from the AdaptiveGBufferLayout>
//   <the engine's hook: vec4 tessera_shade_sample(ivec2 grid_texel, float footprint)>
//   #include "adaptive_component.glsl"
// Defines from the host: TESSERA_ADAPTIVE_M, TESSERA_ADAPTIVE_N (= m*m), TESSERA_ADAPTIVE_MAX_N (= N),
// TESSERA_ADAPTIVE_WIDTH/HEIGHT, TESSERA_ADAPTIVE_LIST_CAPACITY, TESSERA_ADAPTIVE_UBO_BINDING, TESSERA_ADAPTIVE_WORK_BINDING (+ 1: the list),
// TESSERA_ADAPTIVE_IMAGE_UNIT (+ 1: sample counts), TESSERA_ADAPTIVE_OUT_FORMAT (rgba16f | rgba32f),
// optional TESSERA_ADAPTIVE_HAS_UV, TESSERA_ADAPTIVE_SAMPLE_COUNTS, TESSERA_ADAPTIVE_HDR, and one pass:
//   TESSERA_ADAPTIVE_PASS_FIRST      S = hook(sample 0, footprint m) -> output image; luma -> work
//   TESSERA_ADAPTIVE_PASS_METRICS    k and the metric strength per pixel -> work
//   TESSERA_ADAPTIVE_PASS_HISTOGRAM  budget: histogram of the current digit (work [9]) of the rank key
//   TESSERA_ADAPTIVE_PASS_SELECT     budget: one invocation narrows the threshold key by that digit
//                              and moves on to the next (run 8 times, alternating)
//   TESSERA_ADAPTIVE_PASS_APPLY      budget: k = k (above the threshold), remainder (at), 0 (below)
//   TESSERA_ADAPTIVE_PASS_EXTRA      with TESSERA_ADAPTIVE_SCHEDULE_LOOP / _TILE: the extra samples and
//                              the resolve of pixels with k > 0 -> output image
//   TESSERA_ADAPTIVE_PASS_LIST       frame list: per pixel k + 1 items (sample 0 again, then 1..k)
//   TESSERA_ADAPTIVE_PASS_ARGS       frame list: the shade pass's indirect group counts
//   TESSERA_ADAPTIVE_PASS_SHADE      frame list: one invocation per item
//   TESSERA_ADAPTIVE_PASS_RESOLVE    frame list: per pixel, its slots in sample order -> output image
//   TESSERA_ADAPTIVE_PASS_REFERENCE  all N samples, footprint 1 -> output image
// Built-in passes (Vulkan): METRICS and LIST are also compiled when tessera is built, with
// TESSERA_ADAPTIVE_SPECIALIZED and a preamble (adaptive_specialized.cpp) that declares m, the
// presence of UVs and the layout's channels, scales and biases as specialization constants and
// one sampler per G-buffer quantity (its binding set at create): one module serves every window
// size and layout.
// Sample 0 is shaded again with its adaptive footprint when k > 0 (S used footprint m), so a
// pixel's average is over k + 1 samples of consistent footprint (§4.1): by the hook, or by its
// tessera_shade_sample0_again when it defines TESSERA_ADAPTIVE_SAMPLE0_AGAIN (e.g. the albedo lookup alone,
// with light terms the hook kept while compiled for TESSERA_ADAPTIVE_PASS_FIRST).
//
// Budget (AdaptiveFrame::budget): pixels are ranked by a unique 64-bit key (hi = the float bits
// of the metric strength, which order like the floats for strengths >= 0; lo = ~pixel index,
// so the lower index wins a tie). A radix select over its eight 8-bit digits, each a histogram
// weighted by k and a one-invocation scan from the top bucket, finds the key T whose pixel
// crosses the budget and the remainder R it keeps; no sort, no read-back.

#include "adaptive_metrics.glsl"
#include "adaptive_samples.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// Vulkan (VULKAN defined; host: tessera::vk::AdaptiveSupersampler, vk_adaptive.h): every
// resource in descriptor set TESSERA_ADAPTIVE_SET (default 0) at the same binding numbers.
#if defined(VULKAN)
#ifndef TESSERA_ADAPTIVE_SET
#define TESSERA_ADAPTIVE_SET 0
#endif
#define TESSERA_ADAPTIVE_LAYOUT(b) set = TESSERA_ADAPTIVE_SET, binding = (b)
#else
#define TESSERA_ADAPTIVE_LAYOUT(b) binding = (b)
#endif

layout(std140, TESSERA_ADAPTIVE_LAYOUT(TESSERA_ADAPTIVE_UBO_BINDING)) uniform TesseraAdaptiveParams {
  ivec4 tessera_adaptive_size;     // w, h, m, n
  ivec4 tessera_adaptive_flags;    // force_k (-1 off), metrics (1 geometry, 2 shading), budget on,
                             // list capacity (items)
  vec4 tessera_adaptive_metric;    // c_depth, c_normal, c_shade, t_min
  vec4 tessera_adaptive_metric2;   // t_edge, seam_factor, hdr exposure, unused
  uvec4 tessera_adaptive_budget;   // budget (clamped to 2^32 - 1), unused
  ivec4 tessera_adaptive_order[16];  // sample order: entry p (= 4*i + c) = row-major window cell
};

// Work buffer (uints): [0] list items used, [1] extra samples (sum of k), [2..4] the shade
// pass's group counts, [5] budget still binding, [6] remainder R, [7] key hi, [8] key lo,
// [9] the budget's current digit (0 = most significant .. 7),
// [16 .. 16 + 8*256) digit histograms, then per pixel (P = w*h): luma, k, strength, list base.
layout(std430, TESSERA_ADAPTIVE_LAYOUT(TESSERA_ADAPTIVE_WORK_BINDING)) buffer TesseraAdaptiveWork { uint tessera_adaptive_work[]; };
// Frame list of TESSERA_ADAPTIVE_LIST_CAPACITY items: (pixel | sample << 26, footprint bits) each,
// then their colours.
#if defined(TESSERA_ADAPTIVE_PASS_LIST)
// The list pass writes items only (below the capacity in the parameter block).
layout(std430, TESSERA_ADAPTIVE_LAYOUT(TESSERA_ADAPTIVE_WORK_BINDING + 1)) buffer TesseraAdaptiveList {
  uvec2 tessera_adaptive_items[];
};
#else
layout(std430, TESSERA_ADAPTIVE_LAYOUT(TESSERA_ADAPTIVE_WORK_BINDING + 1)) buffer TesseraAdaptiveList {
  uvec2 tessera_adaptive_items[TESSERA_ADAPTIVE_LIST_CAPACITY];
  vec4 tessera_adaptive_colours[];
};
#endif
layout(TESSERA_ADAPTIVE_LAYOUT(TESSERA_ADAPTIVE_IMAGE_UNIT), TESSERA_ADAPTIVE_OUT_FORMAT) uniform writeonly image2D
    tessera_adaptive_out;
#if defined(TESSERA_ADAPTIVE_SAMPLE_COUNTS)
layout(TESSERA_ADAPTIVE_LAYOUT(TESSERA_ADAPTIVE_IMAGE_UNIT + 1), r8ui) uniform writeonly uimage2D
    tessera_adaptive_counts;
#endif

const int TESSERA_ADAPTIVE_HIST = 16;
const uint TESSERA_ADAPTIVE_NONE = 0xffffffffu;

int tessera_adaptive_pixels() { return tessera_adaptive_size.x * tessera_adaptive_size.y; }
uint tessera_adaptive_luma_at(int i) { return uint(16 + 8 * 256 + i); }
uint tessera_adaptive_k_at(int i) { return uint(16 + 8 * 256 + tessera_adaptive_pixels() + i); }
uint tessera_adaptive_strength_at(int i) { return uint(16 + 8 * 256 + 2 * tessera_adaptive_pixels() + i); }
uint tessera_adaptive_base_at(int i) { return uint(16 + 8 * 256 + 3 * tessera_adaptive_pixels() + i); }

ivec2 tessera_adaptive_pixel() { return ivec2(gl_GlobalInvocationID.xy); }
bool tessera_adaptive_inside(ivec2 p) { return p.x < tessera_adaptive_size.x && p.y < tessera_adaptive_size.y; }
int tessera_adaptive_index(ivec2 p) { return p.y * tessera_adaptive_size.x + p.x; }

/// Row-major window cell of sample p.
int tessera_adaptive_order_cell(int p) { return tessera_adaptive_order[p >> 2][p & 3]; }
/// Grid texel of window cell `cell` of `pixel`.
ivec2 tessera_adaptive_cell(ivec2 pixel, int cell) {
  return ivec2(TESSERA_ADAPTIVE_M * pixel.x + cell % TESSERA_ADAPTIVE_M,
               TESSERA_ADAPTIVE_M * pixel.y + cell / TESSERA_ADAPTIVE_M);
}
/// Grid texel of sample p of `pixel`.
ivec2 tessera_adaptive_sample(ivec2 pixel, int p) {
  return tessera_adaptive_cell(pixel, tessera_adaptive_order_cell(p));
}

float tessera_adaptive_luminance(vec4 c) { return dot(max(c.rgb, vec3(0.0)), vec3(0.2126, 0.7152, 0.0722)); }

/// The shading metric's luma of a colour of S.
float tessera_adaptive_luma(vec4 c) {
#if defined(TESSERA_ADAPTIVE_CUSTOM_LUMA)
  return tessera_shade_luma(c);
#elif defined(TESSERA_ADAPTIVE_HDR)
  float e = tessera_adaptive_metric2.z;
  return tessera_luma_srgb(c.rgb * (e / (1.0 + e * tessera_adaptive_luminance(c))));
#else
  return tessera_luma_srgb(c.rgb);
#endif
}

/// Resolve accumulation: plain sum, or tonemap-weighted (sum of w*c, sum of w in .w of `wsum`).
void tessera_adaptive_accumulate(inout vec4 sum, inout float wsum, vec4 c) {
#if defined(TESSERA_ADAPTIVE_HDR)
  float w = 1.0 / (1.0 + tessera_adaptive_metric2.z * tessera_adaptive_luminance(c));
  sum += c * w;
  wsum += w;
#else
  sum += c;
  wsum += 1.0;
#endif
}
vec4 tessera_adaptive_average(vec4 sum, float wsum, int count) {
#if defined(TESSERA_ADAPTIVE_HDR)
  return sum / wsum;
#else
  return sum / float(count);
#endif
}

/// Sample p of `pixel` with `footprint`: sample 0 (already shaded into S with footprint m) goes
/// to the hook's tessera_shade_sample0_again when it defines TESSERA_ADAPTIVE_SAMPLE0_AGAIN.
vec4 tessera_adaptive_shade(ivec2 pixel, int p, float footprint) {
  ivec2 g = tessera_adaptive_sample(pixel, p);
#if defined(TESSERA_ADAPTIVE_SAMPLE0_AGAIN)
  if (p == 0) return tessera_shade_sample0_again(g, footprint);
#endif
  return tessera_shade_sample(g, footprint);
}

void tessera_adaptive_store(ivec2 pixel, vec4 c) { imageStore(tessera_adaptive_out, pixel, c); }
void tessera_adaptive_store_count(ivec2 pixel, int samples) {
#if defined(TESSERA_ADAPTIVE_SAMPLE_COUNTS)
  imageStore(tessera_adaptive_counts, pixel, uvec4(uint(samples), 0u, 0u, 0u));
#endif
}

#if defined(TESSERA_ADAPTIVE_PASS_EXTRA) || defined(TESSERA_ADAPTIVE_PASS_LIST) || defined(TESSERA_ADAPTIVE_PASS_RESOLVE)
/// True when the window of `pixel` has a UV seam (adaptive_samples.glsl's rule).
bool tessera_adaptive_window_seam(ivec2 pixel) {
#if defined(TESSERA_ADAPTIVE_HAS_UV)
#if defined(TESSERA_ADAPTIVE_SPECIALIZED)
  if (!tessera_adaptive_spec_has_uv) return false;
#endif
  const int m = TESSERA_ADAPTIVE_M;
  for (int q = 0; q < m * m; ++q) {
    int cx = q % m, cy = q / m;
    ivec2 gq = tessera_adaptive_cell(pixel, q);
    int mq = tessera_adaptive_id(gq);
    if (mq < 0) continue;
    vec2 uq = tessera_adaptive_uv(gq);
    vec4 dq = tessera_adaptive_uv_derivatives(gq);
    for (int dir = 0; dir < 2; ++dir) {
      int nx = cx + (dir == 0 ? 1 : 0), ny = cy + (dir == 1 ? 1 : 0);
      if (nx >= m || ny >= m) continue;
      ivec2 g2 = tessera_adaptive_cell(pixel, ny * m + nx);
      if (tessera_adaptive_id(g2) != mq) continue;
      if (tessera_seam_between(uq, dq, tessera_adaptive_uv(g2), tessera_adaptive_uv_derivatives(g2), dir,
                               tessera_adaptive_metric2.y))
        return true;
    }
  }
#endif
  return false;
}

/// Footprint scales of samples 0..k of the window of `pixel` (adaptive_samples.glsl).
void tessera_adaptive_scales(ivec2 pixel, int k, out float scales[TESSERA_ADAPTIVE_N]) {
  const int N = TESSERA_ADAPTIVE_N;
  int ids[TESSERA_ADAPTIVE_N];
  for (int q = 0; q < N; ++q) {
    ids[q] = max(tessera_adaptive_id(tessera_adaptive_cell(pixel, q)), -1);
    scales[q] = 1.0;
  }
  if (tessera_adaptive_window_seam(pixel)) return;
  bool uniform_id = true;
  for (int q = 1; q < N; ++q) uniform_id = uniform_id && ids[q] == ids[0];
  if (uniform_id) {
    float s = tessera_scale_uniform(N, k);
    for (int p = 0; p <= k; ++p) scales[p] = s;
    return;
  }
  for (int p = 0; p <= k; ++p) {
    int mine = ids[tessera_adaptive_order_cell(p)];
    int area = 0, shaded = 0;
    for (int q = 0; q < N; ++q) area += ids[q] == mine ? 1 : 0;
    for (int r = 0; r <= k; ++r) shaded += ids[tessera_adaptive_order_cell(r)] == mine ? 1 : 0;
    scales[p] = tessera_scale_material(area, shaded);
  }
}
#endif

#if defined(TESSERA_ADAPTIVE_PASS_HISTOGRAM) || defined(TESSERA_ADAPTIVE_PASS_APPLY)
/// The budget's rank key of pixel i.
uvec2 tessera_adaptive_key(int i) {
  return uvec2(tessera_adaptive_work[tessera_adaptive_strength_at(i)], ~uint(i));
}
#endif

#if defined(TESSERA_ADAPTIVE_PASS_EXTRA) && defined(TESSERA_ADAPTIVE_SCHEDULE_TILE)
shared uint tessera_adaptive_tile_count;
shared uint tessera_adaptive_tile_items[64 * TESSERA_ADAPTIVE_N];
shared float tessera_adaptive_tile_scales[64 * TESSERA_ADAPTIVE_N];
shared vec4 tessera_adaptive_tile_colours[64 * TESSERA_ADAPTIVE_N];
#endif

void main() {
  ivec2 pixel = tessera_adaptive_pixel();
  bool inside = tessera_adaptive_inside(pixel);
  int i = inside ? tessera_adaptive_index(pixel) : 0;

#if defined(TESSERA_ADAPTIVE_PASS_FIRST)
  if (!inside) return;
  vec4 c = tessera_shade_sample(tessera_adaptive_sample(pixel, 0), float(TESSERA_ADAPTIVE_M));
  tessera_adaptive_store(pixel, c);
  tessera_adaptive_work[tessera_adaptive_luma_at(i)] = floatBitsToUint(tessera_adaptive_luma(c));
  tessera_adaptive_store_count(pixel, 1);

#elif defined(TESSERA_ADAPTIVE_PASS_METRICS)
  if (!inside) return;
  const int N = TESSERA_ADAPTIVE_N;
  int k_max = N - 1;
  float k = 0.0;
  if (tessera_adaptive_flags.x >= 0) {
    k = float(tessera_adaptive_flags.x);
  } else {
    if ((tessera_adaptive_flags.y & 1) != 0) {
      float depths[TESSERA_ADAPTIVE_MAX_N];
      vec3 normals[TESSERA_ADAPTIVE_MAX_N];
      int empty = 0;
      for (int q = 0; q < N; ++q) {
        ivec2 g = tessera_adaptive_cell(pixel, q);
        bool bg = tessera_adaptive_id(g) < 0;
        depths[q] = tessera_adaptive_depth(g);
        normals[q] = bg ? vec3(0.0) : tessera_adaptive_normal(g);
        empty += bg ? 1 : 0;
      }
      if (empty > 0 && empty < N) {
        k = float(k_max);
      } else if (empty == 0) {
        k = max(tessera_metric_depth(depths, N, tessera_adaptive_metric.x),
                tessera_metric_normal(normals, N, tessera_adaptive_metric.y, N));
      }
    }
    if ((tessera_adaptive_flags.y & 2) != 0 && k < float(k_max)) {
      ivec2 lim = tessera_adaptive_size.xy - 1;
      float lm = uintBitsToFloat(tessera_adaptive_work[tessera_adaptive_luma_at(i)]);
      float ln = uintBitsToFloat(tessera_adaptive_work[tessera_adaptive_luma_at(
          tessera_adaptive_index(clamp(pixel + ivec2(0, -1), ivec2(0), lim)))]);
      float ls = uintBitsToFloat(tessera_adaptive_work[tessera_adaptive_luma_at(
          tessera_adaptive_index(clamp(pixel + ivec2(0, 1), ivec2(0), lim)))]);
      float lw = uintBitsToFloat(tessera_adaptive_work[tessera_adaptive_luma_at(
          tessera_adaptive_index(clamp(pixel + ivec2(-1, 0), ivec2(0), lim)))]);
      float le = uintBitsToFloat(tessera_adaptive_work[tessera_adaptive_luma_at(
          tessera_adaptive_index(clamp(pixel + ivec2(1, 0), ivec2(0), lim)))]);
      k = max(k, tessera_metric_shading(lm, ln, ls, lw, le, tessera_adaptive_metric.w,
                                        tessera_adaptive_metric2.x, tessera_adaptive_metric.z, N));
    }
  }
  tessera_adaptive_work[tessera_adaptive_k_at(i)] = uint(tessera_round_k(k, k_max));
  tessera_adaptive_work[tessera_adaptive_strength_at(i)] = floatBitsToUint(k > 0.0 ? k : 0.0);

#elif defined(TESSERA_ADAPTIVE_PASS_HISTOGRAM)
  if (!inside || tessera_adaptive_work[5] == 0u) return;
  uint k = tessera_adaptive_work[tessera_adaptive_k_at(i)];
  if (k == 0u) return;
  uvec2 key = tessera_adaptive_key(i);
  uvec2 prefix = uvec2(tessera_adaptive_work[7], tessera_adaptive_work[8]);
  int d = int(tessera_adaptive_work[9]);
  // The digits above d must equal the threshold's (read as a 64-bit number, hi first).
  if (d > 0) {
    if (d <= 4) {
      uint shift = uint(32 - 8 * d);
      if ((key.x >> shift) != (prefix.x >> shift)) return;
    } else {
      uint shift = uint(64 - 8 * d);
      if (key.x != prefix.x || (key.y >> shift) != (prefix.y >> shift)) return;
    }
  }
  uint digit = d < 4 ? (key.x >> uint(24 - 8 * d)) & 255u : (key.y >> uint(56 - 8 * d)) & 255u;
  atomicAdd(tessera_adaptive_work[uint(TESSERA_ADAPTIVE_HIST + 256 * d) + digit], k);

#elif defined(TESSERA_ADAPTIVE_PASS_SELECT)
  if (gl_GlobalInvocationID.x != 0u || gl_GlobalInvocationID.y != 0u) return;
  if (tessera_adaptive_work[5] == 0u) return;
  int d = int(tessera_adaptive_work[9]);
  tessera_adaptive_work[9] = uint(d + 1);
  uint r = tessera_adaptive_work[6];
  for (int b = 255; b >= 0; --b) {
    uint h = tessera_adaptive_work[uint(TESSERA_ADAPTIVE_HIST + 256 * d + b)];
    if (h <= r) {
      r -= h;
      continue;
    }
    // Bucket b holds the crossing pixel: the keys above it fit in full.
    if (d < 4) {
      tessera_adaptive_work[7] |= uint(b) << uint(24 - 8 * d);
    } else {
      tessera_adaptive_work[8] |= uint(b) << uint(56 - 8 * d);
    }
    tessera_adaptive_work[6] = r;
    return;
  }
  tessera_adaptive_work[5] = 0u;  // only at the first digit: everything asked fits the budget

#elif defined(TESSERA_ADAPTIVE_PASS_APPLY)
  if (!inside || tessera_adaptive_work[5] == 0u) return;
  uvec2 key = tessera_adaptive_key(i);
  uvec2 t = uvec2(tessera_adaptive_work[7], tessera_adaptive_work[8]);
  bool above = key.x > t.x || (key.x == t.x && key.y > t.y);
  if (above) return;
  tessera_adaptive_work[tessera_adaptive_k_at(i)] = key == t ? tessera_adaptive_work[6] : 0u;

#elif defined(TESSERA_ADAPTIVE_PASS_ARGS)
  if (gl_GlobalInvocationID.x != 0u || gl_GlobalInvocationID.y != 0u) return;
  uint items = min(tessera_adaptive_work[0], uint(tessera_adaptive_flags.w));
  uint groups = (items + 63u) / 64u;
  uint gx = min(groups, 65535u);
  tessera_adaptive_work[2] = gx;
  tessera_adaptive_work[3] = gx == 0u ? 0u : (groups + gx - 1u) / gx;
  tessera_adaptive_work[4] = 1u;

#elif defined(TESSERA_ADAPTIVE_PASS_SHADE)
  // One invocation per list item; 2-D groups keep long lists within 65535 groups a dimension.
  uint e = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 64u +
           gl_LocalInvocationIndex;
  if (e >= min(tessera_adaptive_work[0], uint(tessera_adaptive_flags.w))) return;
  uvec2 item = tessera_adaptive_items[e];
  if (item.x == TESSERA_ADAPTIVE_NONE) return;  // a slot of a pixel that did not fit
  int owner_index = int(item.x & 0x3ffffffu);
  ivec2 owner = ivec2(owner_index % tessera_adaptive_size.x, owner_index / tessera_adaptive_size.x);
  tessera_adaptive_colours[e] =
      tessera_adaptive_shade(owner, int(item.x >> 26), uintBitsToFloat(item.y));

#elif defined(TESSERA_ADAPTIVE_PASS_LIST)
  if (!inside) return;
  int k = int(tessera_adaptive_work[tessera_adaptive_k_at(i)]);
  tessera_adaptive_store_count(pixel, k + 1);
  if (k == 0) return;  // S is already in the output
  atomicAdd(tessera_adaptive_work[1], uint(k));
  float scales[TESSERA_ADAPTIVE_N];
  tessera_adaptive_scales(pixel, k, scales);
  uint cap = uint(tessera_adaptive_flags.w);
  uint base = atomicAdd(tessera_adaptive_work[0], uint(k + 1));
  bool fits = base <= cap && uint(k + 1) <= cap - base;
  tessera_adaptive_work[tessera_adaptive_base_at(i)] = fits ? base : TESSERA_ADAPTIVE_NONE;
  for (int p = 0; p <= k; ++p) {
    uint e = base + uint(p);
    if (e >= cap) break;
    tessera_adaptive_items[e] =
        uvec2(fits ? (uint(i) | (uint(p) << 26)) : TESSERA_ADAPTIVE_NONE, floatBitsToUint(scales[p]));
  }

#elif defined(TESSERA_ADAPTIVE_PASS_RESOLVE)
  if (!inside) return;
  int k = int(tessera_adaptive_work[tessera_adaptive_k_at(i)]);
  if (k == 0) return;
  uint base = tessera_adaptive_work[tessera_adaptive_base_at(i)];
  vec4 sum = vec4(0.0);
  float wsum = 0.0;
  if (base != TESSERA_ADAPTIVE_NONE) {
    for (int p = 0; p <= k; ++p) tessera_adaptive_accumulate(sum, wsum, tessera_adaptive_colours[base + uint(p)]);
  } else {
    // The list was full: this pixel shades its own samples (the same colours).
    float scales[TESSERA_ADAPTIVE_N];
    tessera_adaptive_scales(pixel, k, scales);
    for (int p = 0; p <= k; ++p)
      tessera_adaptive_accumulate(sum, wsum, tessera_adaptive_shade(pixel, p, scales[p]));
  }
  tessera_adaptive_store(pixel, tessera_adaptive_average(sum, wsum, k + 1));

#elif defined(TESSERA_ADAPTIVE_PASS_EXTRA) && defined(TESSERA_ADAPTIVE_SCHEDULE_TILE)
  // Per 8x8 tile: every pixel's samples in one shared list, shaded round-robin by the 64
  // invocations, then each pixel sums its own slots in sample order.
  int k = inside ? int(tessera_adaptive_work[tessera_adaptive_k_at(i)]) : 0;
  uint local = gl_LocalInvocationIndex;
  if (local == 0u) tessera_adaptive_tile_count = 0u;
  barrier();
  if (k > 0) {
    float scales[TESSERA_ADAPTIVE_N];
    tessera_adaptive_scales(pixel, k, scales);
    for (int p = 0; p <= k; ++p) tessera_adaptive_tile_scales[local * uint(TESSERA_ADAPTIVE_N) + uint(p)] = scales[p];
    uint base = atomicAdd(tessera_adaptive_tile_count, uint(k + 1));
    for (int p = 0; p <= k; ++p) tessera_adaptive_tile_items[base + uint(p)] = (local << 8) | uint(p);
  }
  barrier();
  uint count = tessera_adaptive_tile_count;
  ivec2 tile = ivec2(gl_WorkGroupID.xy) * 8;
  for (uint e = local; e < count; e += 64u) {
    uint item = tessera_adaptive_tile_items[e];
    uint pl = item >> 8;
    int p = int(item & 255u);
    ivec2 owner = tile + ivec2(int(pl % 8u), int(pl / 8u));
    uint slot = pl * uint(TESSERA_ADAPTIVE_N) + uint(p);
    tessera_adaptive_tile_colours[slot] =
        tessera_adaptive_shade(owner, p, tessera_adaptive_tile_scales[slot]);
  }
  barrier();
  if (!inside) return;
  tessera_adaptive_store_count(pixel, k + 1);
  if (k == 0) return;
  atomicAdd(tessera_adaptive_work[1], uint(k));
  vec4 sum = vec4(0.0);
  float wsum = 0.0;
  for (int p = 0; p <= k; ++p)
    tessera_adaptive_accumulate(sum, wsum, tessera_adaptive_tile_colours[local * uint(TESSERA_ADAPTIVE_N) + uint(p)]);
  tessera_adaptive_store(pixel, tessera_adaptive_average(sum, wsum, k + 1));

#elif defined(TESSERA_ADAPTIVE_PASS_EXTRA)
  // TESSERA_ADAPTIVE_SCHEDULE_LOOP: the paper's §4.2 loop.
  if (!inside) return;
  int k = int(tessera_adaptive_work[tessera_adaptive_k_at(i)]);
  tessera_adaptive_store_count(pixel, k + 1);
  if (k == 0) return;
  atomicAdd(tessera_adaptive_work[1], uint(k));
  float scales[TESSERA_ADAPTIVE_N];
  tessera_adaptive_scales(pixel, k, scales);
  vec4 sum = vec4(0.0);
  float wsum = 0.0;
  for (int p = 0; p <= k; ++p)
    tessera_adaptive_accumulate(sum, wsum, tessera_adaptive_shade(pixel, p, scales[p]));
  tessera_adaptive_store(pixel, tessera_adaptive_average(sum, wsum, k + 1));

#elif defined(TESSERA_ADAPTIVE_PASS_REFERENCE)
  if (!inside) return;
  vec4 sum = vec4(0.0);
  float wsum = 0.0;
  for (int p = 0; p < TESSERA_ADAPTIVE_N; ++p)
    tessera_adaptive_accumulate(sum, wsum, tessera_shade_sample(tessera_adaptive_sample(pixel, p), 1.0));
  tessera_adaptive_store(pixel, tessera_adaptive_average(sum, wsum, TESSERA_ADAPTIVE_N));
  tessera_adaptive_store_count(pixel, TESSERA_ADAPTIVE_N);
#else
#error "adaptive_component.glsl: no known TESSERA_ADAPTIVE_PASS_* is defined"
#endif
}
