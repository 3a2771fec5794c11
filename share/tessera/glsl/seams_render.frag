// seams_render.frag — fragment stage of the GL face renderer (tessera::gl::FaceRenderer,
// include/tessera/gl_face_renderer.h); public GLSL API, installed with seams.glsl.
//
// One compiled variant per configuration (the host inserts these after #version):
//   #define TESSERA_SEAMS_CLASSES N       // FaceTextureSet::class_count() (seams.glsl)
//   #define TESSERA_RENDER_METHOD M       // 0 clamp, 1 discard, 2 traverse, 3 traverse_corners
//   #define TESSERA_RENDER_FALLBACK B     // discard: 1 = clamp lookup where coverage is 0
//   #define TESSERA_RENDER_OUTPUT O       // 0 shaded colour, 1 zero-coverage flag
// Compile-time variants rather than uniforms: a SIMD software rasteriser (llvmpipe) executes
// both sides of every branch under a mask, so a run-time method switch would cost all methods.
//
// Uniform: tessera_render_class, the face class of every face in the current draw (the host
// draws one class per call). The own face's lookups index seams.glsl's sampler arrays with it
// — a dynamically uniform index, valid without bindless or non-uniform indexing — instead of
// seams.glsl's switch over the classes; the neighbours of Traverse can be of any class and go
// through seams.glsl (tessera_seams_edge_sum, tessera_seams_face_lookup).
//
// Vulkan (VULKAN defined by glslangValidator -V, glslc or shaderc; the experiment's Vulkan
// backend, src/vk/face_renderer.h): the class is a push constant (block TesseraRenderPush, int
// at offset 0), the inputs are at locations 0, 1, 2 (seams_render.vert), seams.glsl's bindings
// are its Vulkan defaults unless the host defines them; indexing the sampler arrays by the class
// needs shaderSampledImageArrayDynamicIndexing. Where the device lacks it the host defines
// TESSERA_RENDER_CLASS_CONSTANT and sets the class as specialization constant 0 instead, one
// pipeline per class. OpenGL compiles exactly what it always did.
//
// Per pixel (the CPU renderer's shader, faces::FaceRenderer): UV gradients are the fine 2x2
// quad derivatives (helper pixels included), the method's sample is (linear rgb, coverage)
// exactly as seams.glsl defines it, and the colour is rgb * (0.35 + 0.65 max(N.L, 0)) with the
// interpolated normal normalised and L = (0.42, 0.82, 0.39); alpha 1 (the clear has alpha 0, so
// the resolved alpha is the geometry coverage).
#version 450 core
// Offline checks (glslangValidator -l -DTESSERA_GLSLANG -I<this folder>, tests/glsl/CMakeLists.txt)
// resolve the include with glslang's extension; tessera::gl::link_program resolves it for the
// driver.
#if defined(TESSERA_GLSLANG)
#extension GL_GOOGLE_include_directive : require
#endif

#ifndef TESSERA_RENDER_METHOD
#define TESSERA_RENDER_METHOD 1
#endif
#ifndef TESSERA_RENDER_FALLBACK
#define TESSERA_RENDER_FALLBACK 1
#endif
#ifndef TESSERA_RENDER_OUTPUT
#define TESSERA_RENDER_OUTPUT 0
#endif

#include "seams.glsl"

#if defined(VULKAN)
#if defined(TESSERA_RENDER_CLASS_CONSTANT)
// Devices without shaderSampledImageArrayDynamicIndexing (Mesa 22.3 lavapipe): the class is
// specialization constant 0, a constant index, one pipeline per class.
layout(constant_id = 0) const int tessera_render_class = 0;
#else
layout(push_constant) uniform TesseraRenderPush { int tessera_render_class; };
#endif

layout(location = 0) in vec2 tessera_uv;
layout(location = 1) in vec3 tessera_vnormal;
layout(location = 2) flat in int tessera_face;
#else
uniform int tessera_render_class;

in vec2 tessera_uv;
in vec3 tessera_vnormal;
flat in int tessera_face;
#endif

layout(location = 0) out vec4 tessera_colour;

/// Border (0,0,0,0) lookup of the own face (Listing 1, line 2).
vec4 tessera_render_own_border(int layer, vec2 uv, vec2 dx, vec2 dy) {
  return textureGrad(tessera_seams_border[tessera_render_class], vec3(uv, float(layer)), dx, dy);
}

/// Clamp-to-edge lookup of the own face (Clamp, and the zero-coverage fallback).
vec4 tessera_render_own_clamp(int layer, vec2 uv, vec2 dx, vec2 dy) {
  return textureGrad(tessera_seams_clamp[tessera_render_class], vec3(uv, float(layer)), dx, dy);
}

/// seams.glsl's tessera_seams_resolve with the own-class fallback lookup (Listing 1, 13-17).
vec4 tessera_render_resolve(vec4 c, int layer, vec2 uv, vec2 dx, vec2 dy, bool fallback) {
  if (!(c.a > 0.0)) {
    if (!fallback) return vec4(c.rgb / c.a, 0.0);
    return vec4(tessera_render_own_clamp(layer, uv, dx, dy).rgb, 0.0);
  }
  return vec4(c.rgb / c.a, c.a);
}

/// The configured method: vec4(linear rgb, coverage), as tessera_seams_sample.
vec4 tessera_render_sample(int face, vec2 uv, vec2 dx, vec2 dy) {
  int layer = tessera_seams_faces[face].info.y;
#if TESSERA_RENDER_METHOD == 0
  return vec4(tessera_render_own_clamp(layer, uv, dx, dy).rgb, 1.0);
#elif TESSERA_RENDER_METHOD == 1
  return tessera_render_resolve(tessera_render_own_border(layer, uv, dx, dy), layer, uv, dx, dy,
                                TESSERA_RENDER_FALLBACK != 0);
#else
  vec4 c = tessera_render_own_border(layer, uv, dx, dy) + tessera_seams_edge_sum(face, uv, dx, dy);
#if TESSERA_RENDER_METHOD == 3
  // The diagonal faces at valence-4 corners (tessera_seams_sample_traverse_corners).
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
#endif
  return tessera_render_resolve(c, layer, uv, dx, dy, true);
#endif
}

void main() {
  vec2 dx = dFdxFine(tessera_uv), dy = dFdyFine(tessera_uv);
  vec4 s = tessera_render_sample(tessera_face, tessera_uv, dx, dy);
#if TESSERA_RENDER_OUTPUT == 1
  tessera_colour = vec4(vec3(s.a > 0.0 ? 0.0 : 1.0), 1.0);
#else
  vec3 n = tessera_vnormal;
  float nl = (n.x * 0.42 + n.y * 0.82 + n.z * 0.39) / sqrt(dot(n, n) + 1e-20);
  float shade = 0.35 + 0.65 * max(nl, 0.0);
  tessera_colour = vec4(s.rgb * shade, 1.0);
#endif
}
