// seams.glsl — seamless per-face texturing on the GPU: Clamp, Discard (Toth 2013), Traverse
// (McDonald 2013, Listing 1 of Toth's paper) and Traverse+corners, over the packed faces of
// tessera::gl::FaceTextureSet (include/tessera/gl_faces.h). Pure functions of (face, uv, gradients);
// the GLSL twin of tessera::faces::sample_face (include/tessera/faces.h), with which it agrees
// to float rounding under trilinear filtering (tests/gl/gl_faces_test.cpp).
//
// OpenGL setup (host side: `FaceTextureSet::upload(set)`, then `bind(first_unit, ssbo_binding)`):
//   #define TESSERA_SEAMS_CLASSES N         // face classes = FaceTextureSet::class_count(), 1..16
//   #define TESSERA_SEAMS_FIRST_UNIT U      // optional, default 0 (bind's first_unit)
//   #define TESSERA_SEAMS_CLAMP_UNIT V      // optional, default U + N
//   #define TESSERA_SEAMS_FACES_BINDING B   // optional, default 0 (bind's ssbo_binding)
//   #include "seams.glsl"                   // tessera::gl::link_program resolves it
// (FaceTextureSet::glsl_defines(FaceTextureSetBindings) writes these lines for the binding points an
// engine chose; gl_faces.h has the recipe.) Units U .. U+N-1 hold class c's GL_TEXTURE_2D_ARRAY
// with the clamp-to-border (0,0,0,0) sampler, units V .. V+N-1 the same arrays with the
// clamp-to-edge sampler (Clamp and the zero-coverage fallback). Both samplers are trilinear
// with anisotropy as uploaded (FaceTextureSetOptions::max_anisotropy): hardware anisotropic
// filtering is implementation-defined, so only trilinear is expected to match the CPU sampler.
//
// Conventions (those of tessera and Ptex): a face's (u, v) is (0,0), (1,0), (1,1), (0,1) at its
// vertices 0..3; edge e joins vertex e and e+1; texel row 0 is v = 0. `dx`, `dy` are the UV
// derivatives per pixel (dFdx(uv), dFdy(uv) in a fragment shader, in the face's normalised
// units) — explicit gradients, so a neighbour's lookup uses the transformed footprint and the
// lookups stay well-defined in non-uniform control flow (a class switch per face).
//
// Every function returns vec4(rgb, coverage): linear RGB normalised by the summed filter
// weight of the in-face taps (Equation 6), and that weight in .a (1 for Clamp; 0 after the
// zero-coverage fallback; NaN rgb when the fallback is off and nothing was covered).
// Textures must carry alpha = 1 inside every face (FaceTextureSet does).
//
// Vulkan (SPIR-V through glslangValidator -V or glslc, which define VULKAN; no tessera runtime
// yet): the same functions over three bindings of one descriptor set; the includer may move
// them with these macros:
//   #define TESSERA_SEAMS_SET S              // optional, default 0
//   #define TESSERA_SEAMS_FIRST_BINDING F    // optional, default 0
//   #define TESSERA_SEAMS_FACES_BINDING B    // optional, default F: storage buffer, the faces
//   #define TESSERA_SEAMS_BORDER_BINDING B   // optional, default F + 1: N combined image
//                                            // samplers (2D arrays), the clamp-to-border ones
//   #define TESSERA_SEAMS_CLAMP_BINDING B    // optional, default F + 2: N combined image
//                                            // samplers, the same images clamp-to-edge
// A sampler array takes one binding (descriptorCount N), and samplers and buffers share a
// set's binding numbers, so the defaults are F, F + 1, F + 2; TESSERA_SEAMS_FIRST_UNIT is
// OpenGL's and is ignored. Border sampler: VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK. glslc
// resolves the #include itself, glslangValidator with GL_GOOGLE_include_directive. Without
// VULKAN defined, OpenGL compiles exactly the declarations it always did.

#ifndef TESSERA_SEAMS_GLSL
#define TESSERA_SEAMS_GLSL

#ifndef TESSERA_SEAMS_CLASSES
#error "define TESSERA_SEAMS_CLASSES (FaceTextureSet::class_count(), 1..16) before seams.glsl"
#endif
#if TESSERA_SEAMS_CLASSES < 1 || TESSERA_SEAMS_CLASSES > 16
#error "TESSERA_SEAMS_CLASSES must be 1..16 (two texture units per class)"
#endif
#if defined(VULKAN)
#ifndef TESSERA_SEAMS_SET
#define TESSERA_SEAMS_SET 0
#endif
#ifndef TESSERA_SEAMS_FIRST_BINDING
#define TESSERA_SEAMS_FIRST_BINDING 0
#endif
#ifndef TESSERA_SEAMS_FACES_BINDING
#define TESSERA_SEAMS_FACES_BINDING (TESSERA_SEAMS_FIRST_BINDING)
#endif
#ifndef TESSERA_SEAMS_BORDER_BINDING
#define TESSERA_SEAMS_BORDER_BINDING (TESSERA_SEAMS_FIRST_BINDING + 1)
#endif
#ifndef TESSERA_SEAMS_CLAMP_BINDING
#define TESSERA_SEAMS_CLAMP_BINDING (TESSERA_SEAMS_FIRST_BINDING + 2)
#endif
#else
#ifndef TESSERA_SEAMS_FIRST_UNIT
#define TESSERA_SEAMS_FIRST_UNIT 0
#endif
#ifndef TESSERA_SEAMS_CLAMP_UNIT
#define TESSERA_SEAMS_CLAMP_UNIT (TESSERA_SEAMS_FIRST_UNIT + TESSERA_SEAMS_CLASSES)
#endif
#ifndef TESSERA_SEAMS_FACES_BINDING
#define TESSERA_SEAMS_FACES_BINDING 0
#endif
#endif

/// One face record (std430, 80 bytes): tessera::faces::FaceRecord (tessera/faces_gpu.h).
struct TesseraFaceRecord {
  ivec4 info;            // class, layer, level-0 width, height
  ivec4 neighbour;       // face across edge e, -1 on a border
  ivec4 mapping;         // e * 4 + neighbour's edge: index into tessera_seams_uv; -1 border
  ivec4 corner;          // diagonal face at corner c (valence-4 vertex), -1 none
  ivec4 corner_mapping;  // m1 * 16 + m2: across edge c (m1), then the next edge (m2); -1 none
};

#if defined(VULKAN)
layout(std430, set = TESSERA_SEAMS_SET, binding = TESSERA_SEAMS_FACES_BINDING)
readonly buffer TesseraSeamsFaces {
  TesseraFaceRecord tessera_seams_faces[];
};

layout(set = TESSERA_SEAMS_SET, binding = TESSERA_SEAMS_BORDER_BINDING)
uniform sampler2DArray tessera_seams_border[TESSERA_SEAMS_CLASSES];
layout(set = TESSERA_SEAMS_SET, binding = TESSERA_SEAMS_CLAMP_BINDING)
uniform sampler2DArray tessera_seams_clamp[TESSERA_SEAMS_CLASSES];
#else
layout(std430, binding = TESSERA_SEAMS_FACES_BINDING) readonly buffer TesseraSeamsFaces {
  TesseraFaceRecord tessera_seams_faces[];
};

layout(binding = TESSERA_SEAMS_FIRST_UNIT)
uniform sampler2DArray tessera_seams_border[TESSERA_SEAMS_CLASSES];
layout(binding = TESSERA_SEAMS_CLAMP_UNIT)
uniform sampler2DArray tessera_seams_clamp[TESSERA_SEAMS_CLASSES];
#endif

/// The 16 edge-to-edge UV transforms (tessera::faces::edge_transform_table): entry
/// my_edge * 4 + neighbour_edge maps my (u, v, 1) to the neighbour's (u, v).
const mat3x2 tessera_seams_uv[16] = mat3x2[16](
    mat3x2(-1, 0, 0, -1, 1, 0),   //  0: my edge 0 -> neighbour edge 0
    mat3x2(0, -1, 1, 0, 1, 1),    //  1: 0 -> 1
    mat3x2(1, 0, 0, 1, 0, 1),     //  2: 0 -> 2
    mat3x2(0, 1, -1, 0, 0, 0),    //  3: 0 -> 3
    mat3x2(0, 1, -1, 0, 1, -1),   //  4: 1 -> 0
    mat3x2(-1, 0, 0, -1, 2, 1),   //  5: 1 -> 1
    mat3x2(0, -1, 1, 0, 0, 2),    //  6: 1 -> 2
    mat3x2(1, 0, 0, 1, -1, 0),    //  7: 1 -> 3
    mat3x2(1, 0, 0, 1, 0, -1),    //  8: 2 -> 0
    mat3x2(0, 1, -1, 0, 2, 0),    //  9: 2 -> 1
    mat3x2(-1, 0, 0, -1, 1, 2),   // 10: 2 -> 2
    mat3x2(0, -1, 1, 0, -1, 1),   // 11: 2 -> 3
    mat3x2(0, -1, 1, 0, 0, 0),    // 12: 3 -> 0
    mat3x2(1, 0, 0, 1, 1, 0),     // 13: 3 -> 1
    mat3x2(0, 1, -1, 0, 1, 1),    // 14: 3 -> 2
    mat3x2(-1, 0, 0, -1, 0, 1));  // 15: 3 -> 3

/// My UV -> the UV of the face reached through `mapping`.
vec2 tessera_seams_map(int mapping, vec2 uv) {
  return tessera_seams_uv[mapping] * vec3(uv, 1.0);
}
/// The linear part, for gradients.
vec2 tessera_seams_map_gradient(int mapping, vec2 g) {
  return mat2(tessera_seams_uv[mapping]) * g;
}

/// Border (0,0,0,0) lookup of layer `layer` of class `cls` (Σ w·T in rgb, Σ w in alpha).
vec4 tessera_seams_border_lookup(int cls, int layer, vec2 uv, vec2 dx, vec2 dy) {
  vec3 p = vec3(uv, float(layer));
  switch (cls) {
#if TESSERA_SEAMS_CLASSES > 0
    case 0: return textureGrad(tessera_seams_border[0], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 1
    case 1: return textureGrad(tessera_seams_border[1], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 2
    case 2: return textureGrad(tessera_seams_border[2], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 3
    case 3: return textureGrad(tessera_seams_border[3], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 4
    case 4: return textureGrad(tessera_seams_border[4], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 5
    case 5: return textureGrad(tessera_seams_border[5], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 6
    case 6: return textureGrad(tessera_seams_border[6], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 7
    case 7: return textureGrad(tessera_seams_border[7], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 8
    case 8: return textureGrad(tessera_seams_border[8], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 9
    case 9: return textureGrad(tessera_seams_border[9], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 10
    case 10: return textureGrad(tessera_seams_border[10], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 11
    case 11: return textureGrad(tessera_seams_border[11], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 12
    case 12: return textureGrad(tessera_seams_border[12], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 13
    case 13: return textureGrad(tessera_seams_border[13], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 14
    case 14: return textureGrad(tessera_seams_border[14], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 15
    case 15: return textureGrad(tessera_seams_border[15], p, dx, dy);
#endif
  }
  return vec4(0.0);
}

/// Clamp-to-edge lookup of layer `layer` of class `cls`.
vec4 tessera_seams_clamp_lookup(int cls, int layer, vec2 uv, vec2 dx, vec2 dy) {
  vec3 p = vec3(uv, float(layer));
  switch (cls) {
#if TESSERA_SEAMS_CLASSES > 0
    case 0: return textureGrad(tessera_seams_clamp[0], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 1
    case 1: return textureGrad(tessera_seams_clamp[1], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 2
    case 2: return textureGrad(tessera_seams_clamp[2], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 3
    case 3: return textureGrad(tessera_seams_clamp[3], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 4
    case 4: return textureGrad(tessera_seams_clamp[4], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 5
    case 5: return textureGrad(tessera_seams_clamp[5], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 6
    case 6: return textureGrad(tessera_seams_clamp[6], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 7
    case 7: return textureGrad(tessera_seams_clamp[7], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 8
    case 8: return textureGrad(tessera_seams_clamp[8], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 9
    case 9: return textureGrad(tessera_seams_clamp[9], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 10
    case 10: return textureGrad(tessera_seams_clamp[10], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 11
    case 11: return textureGrad(tessera_seams_clamp[11], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 12
    case 12: return textureGrad(tessera_seams_clamp[12], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 13
    case 13: return textureGrad(tessera_seams_clamp[13], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 14
    case 14: return textureGrad(tessera_seams_clamp[14], p, dx, dy);
#endif
#if TESSERA_SEAMS_CLASSES > 15
    case 15: return textureGrad(tessera_seams_clamp[15], p, dx, dy);
#endif
  }
  return vec4(0.0);
}

/// Border lookup of face `face` in its own UV space.
vec4 tessera_seams_face_lookup(int face, vec2 uv, vec2 dx, vec2 dy) {
  ivec4 info = tessera_seams_faces[face].info;
  return tessera_seams_border_lookup(info.x, info.y, uv, dx, dy);
}

/// Normalises a border-lookup sum (Listing 1, line 17), or falls back to a clamped lookup of
/// `face` when no tap was covered (lines 13-15, helper pixels): coverage 0 then.
vec4 tessera_seams_resolve(vec4 c, int face, vec2 uv, vec2 dx, vec2 dy, bool clamp_fallback) {
  if (!(c.a > 0.0)) {
    if (!clamp_fallback) return vec4(c.rgb / c.a, 0.0);
    ivec4 info = tessera_seams_faces[face].info;
    return vec4(tessera_seams_clamp_lookup(info.x, info.y, uv, dx, dy).rgb, 0.0);
  }
  return vec4(c.rgb / c.a, c.a);
}

/// Clamp: the face alone with clamp-to-edge addressing (the seam-artefact baseline).
vec4 tessera_seams_sample_clamp(int face, vec2 uv, vec2 dx, vec2 dy) {
  ivec4 info = tessera_seams_faces[face].info;
  return vec4(tessera_seams_clamp_lookup(info.x, info.y, uv, dx, dy).rgb, 1.0);
}

/// Discard (Toth 2013): the taps outside the face read the zero border and are divided out.
vec4 tessera_seams_sample_discard(int face, vec2 uv, vec2 dx, vec2 dy, bool clamp_fallback) {
  vec4 c = tessera_seams_face_lookup(face, uv, dx, dy);
  return tessera_seams_resolve(c, face, uv, dx, dy, clamp_fallback);
}

/// The four edge neighbours' border lookups in their own UV spaces (Listing 1, lines 4-12).
vec4 tessera_seams_edge_sum(int face, vec2 uv, vec2 dx, vec2 dy) {
  TesseraFaceRecord f = tessera_seams_faces[face];
  vec4 c = vec4(0.0);
  for (int e = 0; e < 4; ++e) {
    int id = f.neighbour[e];
    if (id < 0) continue;
    int m = f.mapping[e];
    c += tessera_seams_face_lookup(id, tessera_seams_map(m, uv),
                                   tessera_seams_map_gradient(m, dx),
                                   tessera_seams_map_gradient(m, dy));
  }
  return c;
}

/// Traverse (McDonald 2013): my face plus the four edge neighbours, normalised.
vec4 tessera_seams_sample_traverse(int face, vec2 uv, vec2 dx, vec2 dy) {
  vec4 c = tessera_seams_face_lookup(face, uv, dx, dy) + tessera_seams_edge_sum(face, uv, dx, dy);
  return tessera_seams_resolve(c, face, uv, dx, dy, true);
}

/// Traverse+corners: Traverse plus the diagonal face at each valence-4 corner (two edge steps,
/// transforms composed); the diagonal region is dropped at other valences.
vec4 tessera_seams_sample_traverse_corners(int face, vec2 uv, vec2 dx, vec2 dy) {
  vec4 c = tessera_seams_face_lookup(face, uv, dx, dy) + tessera_seams_edge_sum(face, uv, dx, dy);
  TesseraFaceRecord f = tessera_seams_faces[face];
  for (int k = 0; k < 4; ++k) {
    int id = f.corner[k];
    if (id < 0) continue;
    int m1 = f.corner_mapping[k] / 16, m2 = f.corner_mapping[k] % 16;
    c += tessera_seams_face_lookup(
        id, tessera_seams_map(m2, tessera_seams_map(m1, uv)),
        tessera_seams_map_gradient(m2, tessera_seams_map_gradient(m1, dx)),
        tessera_seams_map_gradient(m2, tessera_seams_map_gradient(m1, dy)));
  }
  return tessera_seams_resolve(c, face, uv, dx, dy, true);
}

/// Method by number (0 clamp, 1 discard, 2 traverse, 3 traverse_corners: faces::SeamMethod order).
vec4 tessera_seams_sample(int method, int face, vec2 uv, vec2 dx, vec2 dy) {
  if (method == 0) return tessera_seams_sample_clamp(face, uv, dx, dy);
  if (method == 1) return tessera_seams_sample_discard(face, uv, dx, dy, true);
  if (method == 2) return tessera_seams_sample_traverse(face, uv, dx, dy);
  return tessera_seams_sample_traverse_corners(face, uv, dx, dy);
}

#endif  // TESSERA_SEAMS_GLSL
