// deferred_shading.glsl — public GLSL API: the deferred shader of tessera's adaptive
// supersampling (Hollander, Boubekeur & Eisemann 2013) over an enlarged G-buffer. The same
// arithmetic as the CPU path (src/deferred/shade.cpp, kernels.cpp; include/tessera/deferred.h),
// so GL and CPU images agree to rounding. Used by deferred_passes.comp; an engine can include it
// in its own passes.
//
// Needs (the including shader defines before #include):
//   #define TESSERA_DEFERRED_CLASSES C   number of texture-size classes, 1..8 (>= 1 even when the
//                                        scene has no textures; unit 3 then holds a dummy)
// OpenGL bindings (tessera::gl::DeferredRenderer sets them up):
//   units 0, 1, 2   sampler2D, the G-buffer grid (m*w x m*h, RGBA32F, texelFetch only, row 0 =
//                   the top grid row, x right, y down):
//                     unit 0: (linear view depth, world normal xyz; not renormalised)
//                     unit 1: (material id as float (-1 = background), u, v, unused)
//                     unit 2: (du/dx, dv/dx, du/dy, dv/dy) per grid pixel (fine derivatives)
//   units 3 .. 3+C-1  sampler2DArray, the scene's base-colour textures grouped by size: every
//                   layer holds one texture's full CPU mip chain (RGBA32F, linear light),
//                   GL_LINEAR_MIPMAP_LINEAR, GL_REPEAT, no hardware anisotropy
//   UBO binding 0   TesseraDeferredParams (below; std140)
//   SSBO 0          lights: 2 vec4 each (position xyz + range, colour rgb + intensity)
//   SSBO 1          materials: vec4 base colour, ivec4 (class or -1, layer, width, height)
//   SSBO 2          heavy-term waves: vec4 (kx, ky, kz, phase) per term
//
// Vulkan (SPIR-V through glslangValidator -V or glslc, which define VULKAN; no tessera runtime
// yet): the same resources in one descriptor set, each at its own binding (samplers and
// buffers share a set's binding numbers), all movable by the includer:
//   #define TESSERA_DEFERRED_SET S                 // optional, default 0
//   #define TESSERA_DEFERRED_FIRST_BINDING F       // optional, default 0; the defaults below:
//   TESSERA_DEFERRED_PARAMS_BINDING     F      uniform buffer TesseraDeferredParams
//   TESSERA_DEFERRED_LIGHTS_BINDING     F + 1  storage buffer, lights
//   TESSERA_DEFERRED_MATERIALS_BINDING  F + 2  storage buffer, materials
//   TESSERA_DEFERRED_WAVES_BINDING      F + 3  storage buffer, heavy-term waves
//   TESSERA_DEFERRED_GBUFFER0_BINDING   F + 4  combined image sampler, G-buffer unit 0's
//   TESSERA_DEFERRED_GBUFFER1_BINDING   F + 5  combined image sampler, unit 1's
//   TESSERA_DEFERRED_GBUFFER2_BINDING   F + 6  combined image sampler, unit 2's
//   TESSERA_DEFERRED_TEXTURES_BINDING   F + 7  C combined image samplers (2D arrays), one
//                                              binding with descriptorCount C
// tessera_texture_lod indexes that array with its loop counter (dynamically uniform), which
// needs VkPhysicalDeviceFeatures::shaderSampledImageArrayDynamicIndexing. Without VULKAN
// defined, OpenGL compiles exactly the declarations it always did.
//
// Conventions: a sample is addressed by its grid pixel ivec2(gx, gy); output pixel (x, y) owns
// the window gx in [m*x, m*x+m), gy in [m*y, m*y+m). Colours are linear RGB.

#if defined(VULKAN)
#ifndef TESSERA_DEFERRED_SET
#define TESSERA_DEFERRED_SET 0
#endif
#ifndef TESSERA_DEFERRED_FIRST_BINDING
#define TESSERA_DEFERRED_FIRST_BINDING 0
#endif
#ifndef TESSERA_DEFERRED_PARAMS_BINDING
#define TESSERA_DEFERRED_PARAMS_BINDING (TESSERA_DEFERRED_FIRST_BINDING)
#endif
#ifndef TESSERA_DEFERRED_LIGHTS_BINDING
#define TESSERA_DEFERRED_LIGHTS_BINDING (TESSERA_DEFERRED_FIRST_BINDING + 1)
#endif
#ifndef TESSERA_DEFERRED_MATERIALS_BINDING
#define TESSERA_DEFERRED_MATERIALS_BINDING (TESSERA_DEFERRED_FIRST_BINDING + 2)
#endif
#ifndef TESSERA_DEFERRED_WAVES_BINDING
#define TESSERA_DEFERRED_WAVES_BINDING (TESSERA_DEFERRED_FIRST_BINDING + 3)
#endif
#ifndef TESSERA_DEFERRED_GBUFFER0_BINDING
#define TESSERA_DEFERRED_GBUFFER0_BINDING (TESSERA_DEFERRED_FIRST_BINDING + 4)
#endif
#ifndef TESSERA_DEFERRED_GBUFFER1_BINDING
#define TESSERA_DEFERRED_GBUFFER1_BINDING (TESSERA_DEFERRED_FIRST_BINDING + 5)
#endif
#ifndef TESSERA_DEFERRED_GBUFFER2_BINDING
#define TESSERA_DEFERRED_GBUFFER2_BINDING (TESSERA_DEFERRED_FIRST_BINDING + 6)
#endif
#ifndef TESSERA_DEFERRED_TEXTURES_BINDING
#define TESSERA_DEFERRED_TEXTURES_BINDING (TESSERA_DEFERRED_FIRST_BINDING + 7)
#endif
layout(std140, set = TESSERA_DEFERRED_SET, binding = TESSERA_DEFERRED_PARAMS_BINDING)
uniform TesseraDeferredParams {
#else
layout(std140, binding = 0) uniform TesseraDeferredParams {
#endif
  ivec4 tessera_size;        // w, h (output pixels), m, n = m*m
  ivec4 tessera_counts;      // lights, heavy terms (0 = off), force_k (-1 = off),
                             // flags (1: geometry metric, 2: shading metric)
  vec4 tessera_eye;          // camera position (world), tan(fov_y / 2)
  vec4 tessera_view;         // aspect (w / h), exposure, specular, shininess
  vec4 tessera_ambient;      // ambient rgb, max anisotropic probes (1..16)
  vec4 tessera_metric;       // c_depth, c_normal, c_shade, t_min
  vec4 tessera_metric2;      // t_edge, seam_factor, edge min_normal_dot, edge depth_slack
  vec4 tessera_background;   // linear rgb of empty pixels
  mat4 tessera_inv_view;     // camera to world
  ivec4 tessera_order[16];   // sample_order(m): entry p (p = 4*i + c) = row-major window cell
};

struct TesseraLight {
  vec4 position_range;
  vec4 color_intensity;
};
struct TesseraMaterial {
  vec4 base;
  ivec4 texture;  // class (-1: untextured), layer, level-0 width, height
};
#if defined(VULKAN)
layout(std430, set = TESSERA_DEFERRED_SET, binding = TESSERA_DEFERRED_LIGHTS_BINDING)
readonly buffer TesseraLights { TesseraLight tessera_lights[]; };
layout(std430, set = TESSERA_DEFERRED_SET, binding = TESSERA_DEFERRED_MATERIALS_BINDING)
readonly buffer TesseraMaterials {
  TesseraMaterial tessera_materials[];
};
layout(std430, set = TESSERA_DEFERRED_SET, binding = TESSERA_DEFERRED_WAVES_BINDING)
readonly buffer TesseraWaves { vec4 tessera_waves[]; };

layout(set = TESSERA_DEFERRED_SET, binding = TESSERA_DEFERRED_GBUFFER0_BINDING)
uniform sampler2D tessera_gbuffer0;
layout(set = TESSERA_DEFERRED_SET, binding = TESSERA_DEFERRED_GBUFFER1_BINDING)
uniform sampler2D tessera_gbuffer1;
layout(set = TESSERA_DEFERRED_SET, binding = TESSERA_DEFERRED_GBUFFER2_BINDING)
uniform sampler2D tessera_gbuffer2;
#else
layout(std430, binding = 0) readonly buffer TesseraLights { TesseraLight tessera_lights[]; };
layout(std430, binding = 1) readonly buffer TesseraMaterials {
  TesseraMaterial tessera_materials[];
};
layout(std430, binding = 2) readonly buffer TesseraWaves { vec4 tessera_waves[]; };

layout(binding = 0) uniform sampler2D tessera_gbuffer0;
layout(binding = 1) uniform sampler2D tessera_gbuffer1;
layout(binding = 2) uniform sampler2D tessera_gbuffer2;
#endif

#ifndef TESSERA_DEFERRED_CLASSES
#error "define TESSERA_DEFERRED_CLASSES (1..8) before including deferred_shading.glsl"
#endif
#if TESSERA_DEFERRED_CLASSES < 1 || TESSERA_DEFERRED_CLASSES > 8
#error "TESSERA_DEFERRED_CLASSES must be in 1..8"
#endif
#if defined(VULKAN)
layout(set = TESSERA_DEFERRED_SET, binding = TESSERA_DEFERRED_TEXTURES_BINDING)
uniform sampler2DArray tessera_textures[TESSERA_DEFERRED_CLASSES];
#else
layout(binding = 3) uniform sampler2DArray tessera_textures[TESSERA_DEFERRED_CLASSES];
#endif

/// One G-buffer sample.
struct TesseraSample {
  float depth;   // linear view depth
  vec3 normal;   // world normal, not renormalised (0 for background)
  int material;  // -1 = background
  vec2 uv;
  vec4 duv;      // du/dx, dv/dx, du/dy, dv/dy
};

int tessera_material_id(float v) {
  // As the CPU: lround, then -1 outside [0, materials).
  int id = int(floor(abs(v) + 0.5)) * (v < 0.0 ? -1 : 1);
  return id >= 0 && id < tessera_materials.length() ? id : -1;
}

TesseraSample tessera_fetch(ivec2 g) {
  vec4 a = texelFetch(tessera_gbuffer0, g, 0);
  vec4 b = texelFetch(tessera_gbuffer1, g, 0);
  TesseraSample s;
  s.depth = a.x;
  s.normal = a.yzw;
  s.material = tessera_material_id(b.x);
  s.uv = b.yz;
  s.duv = texelFetch(tessera_gbuffer2, g, 0);
  return s;
}

/// Material id of a grid pixel (-1 = background).
int tessera_fetch_material(ivec2 g) { return tessera_material_id(texelFetch(tessera_gbuffer1, g, 0).x); }

/// World position of grid pixel g from its linear depth (GBuffer::position).
vec3 tessera_position(ivec2 g, float depth) {
  vec2 grid = vec2(tessera_size.xy * tessera_size.z);
  float nx = 2.0 * (float(g.x) + 0.5) / grid.x - 1.0;
  float ny = 1.0 - 2.0 * (float(g.y) + 0.5) / grid.y;
  float t = tessera_eye.w;
  vec3 v = vec3(nx * t * tessera_view.x * depth, ny * t * depth, -depth);
  return (tessera_inv_view * vec4(v, 1.0)).xyz;
}

/// The heavy per-sample term in [0.55, 1] (1 when heavy shading is off).
float tessera_heavy_factor(vec3 p) {
  int terms = tessera_counts.y;
  if (terms <= 0) return 1.0;
  float sum = 0.0;
  for (int i = 0; i < terms; ++i) {
    vec4 w = tessera_waves[i];
    sum += sin(w.x * p.x + w.y * p.y + w.z * p.z + w.w);
  }
  float t = sum * sqrt(2.0 / float(terms));
  return 0.775 + 0.225 * clamp(t, -1.0, 1.0);
}

/// Blinn-Phong over the point lights: colour = albedo * d + p. `n` need not be unit length and
/// is turned towards the viewer.
void tessera_blinn_phong(vec3 position, vec3 normal, float heavy, out vec3 d, out vec3 p) {
  vec3 n = normalize(normal);
  vec3 v = normalize(tessera_eye.xyz - position);
  if (dot(n, v) < 0.0) n = -n;
  d = tessera_ambient.rgb;
  p = vec3(0.0);
  for (int i = 0; i < tessera_counts.x; ++i) {
    TesseraLight light = tessera_lights[i];
    vec3 to = light.position_range.xyz - position;
    float dist2 = max(dot(to, to), 1e-8);
    float dist = sqrt(dist2);
    float atten = light.color_intensity.w / dist2;
    float range = light.position_range.w;
    if (range > 0.0) {
      float q = dist / range, q4 = q * q * q * q;
      float w = clamp(1.0 - q4, 0.0, 1.0);
      atten *= w * w;
    }
    if (atten <= 0.0) continue;
    vec3 l = to * (1.0 / dist);
    float ndl = dot(n, l);
    if (ndl <= 0.0) continue;
    vec3 h = normalize(l + v);
    float ndh = max(dot(n, h), 0.0);
    float spec = tessera_view.z * pow(ndh, tessera_view.w);
    vec3 e = light.color_intensity.rgb * atten;
    d += e * ndl;
    p += e * ndl * spec;
  }
  d *= heavy * tessera_view.y;
  p *= tessera_view.y;
}

/// Lighting terms of a (non-background) sample at grid pixel g.
void tessera_lighting(ivec2 g, TesseraSample s, out vec3 d, out vec3 p) {
  vec3 pos = tessera_position(g, s.depth);
  tessera_blinn_phong(pos, s.normal, tessera_heavy_factor(pos), d, p);
}

vec4 tessera_texture_lod(int cls, vec3 uvl, float lod) {
  vec4 r = vec4(0.0);
  // Sampler arrays need dynamically uniform indices: one branch per class.
  for (int c = 0; c < TESSERA_DEFERRED_CLASSES; ++c) {
    if (c == cls) r = textureLod(tessera_textures[c], uvl, lod);
  }
  return r;
}

/// The CPU sampler's anisotropic filter (EXT_texture_filter_anisotropic footprint, N trilinear
/// probes along the major axis at centre + ((i + 0.5) / N - 0.5) * axis, equal weights), built
/// from textureLod so that GL and CPU filter identically (hardware anisotropy is
/// implementation-defined). `g` = (du/dx, dv/dx, du/dy, dv/dy), normalised units.
vec4 tessera_sample_aniso(int cls, int layer, ivec2 size, vec2 uv, vec4 g) {
  vec2 gx = g.xy * vec2(size), gy = g.zw * vec2(size);
  float px = sqrt(gx.x * gx.x + gx.y * gx.y), py = sqrt(gy.x * gy.x + gy.y * gy.y);
  bool x_major = px >= py;
  float pmax = x_major ? px : py, pmin = x_major ? py : px;
  int probes = 1;
  float lod = 0.0;
  vec2 axis = vec2(0.0);
  if (pmax > 0.0 && !isinf(pmax)) {
    int limit = int(tessera_ambient.w);
    probes = limit;
    if (pmin > 0.0) {
      float ratio = pmax / pmin;
      if (ratio < float(limit)) probes = max(1, int(ceil(ratio - 1e-4)));
    }
    lod = log2(pmax / float(probes));
    axis = x_major ? g.xy : g.zw;
  } else if (isinf(pmax)) {
    lod = 1000.0;
  }
  if (isnan(lod) || !(lod >= 0.0)) lod = 0.0;  // clamped to [0, levels - 1] by textureLod
  if (probes <= 1) return tessera_texture_lod(cls, vec3(uv, float(layer)), lod);
  vec4 sum = vec4(0.0);
  float inv = 1.0 / float(probes);
  for (int i = 0; i < probes; ++i) {
    float t = (float(i) + 0.5) * inv - 0.5;
    sum += tessera_texture_lod(cls, vec3(uv + t * axis, float(layer)), lod);
  }
  return sum * inv;
}

/// Albedo of a (non-background) sample with its texture footprint scaled by `scale`.
vec3 tessera_albedo(TesseraSample s, float scale) {
  TesseraMaterial mat = tessera_materials[s.material];
  vec3 a = mat.base.rgb;
  if (mat.texture.x >= 0) {
    a *= tessera_sample_aniso(mat.texture.x, mat.texture.y, mat.texture.zw, s.uv,
                              s.duv * scale).rgb;
  }
  return a;
}

/// Full shading of grid pixel g with footprint scale `scale` (background colour if empty).
vec3 tessera_shade(ivec2 g, float scale) {
  TesseraSample s = tessera_fetch(g);
  if (s.material < 0) return tessera_background.rgb;
  vec3 d, p;
  tessera_lighting(g, s, d, p);
  return tessera_albedo(s, scale) * d + p;
}

/// Grid pixel of sample p (index order) of the window of output pixel `pixel`.
ivec2 tessera_window_sample(ivec2 pixel, int p) {
  int cell = tessera_order[p >> 2][p & 3];
  int m = tessera_size.z;
  return ivec2(m * pixel.x + cell % m, m * pixel.y + cell / m);
}
