// What gl::AdaptiveSupersampler compiles per pass (src/gl/adaptive_supersampler.cpp: the
// preamble generated from the layout, then the hook, then adaptive_component.glsl), written out
// for the offline compilers: glslangValidator for OpenGL 4.5 and for Vulkan
// (tests/glsl/CMakeLists.txt, one CTest per pass). The pass and the options come as -D defines.
#version 450 core
#extension GL_GOOGLE_include_directive : require
#define TESSERA_ADAPTIVE_M 4
#define TESSERA_ADAPTIVE_N 16
#define TESSERA_ADAPTIVE_MAX_N 16
#define TESSERA_ADAPTIVE_WIDTH 64
#define TESSERA_ADAPTIVE_HEIGHT 48
#define TESSERA_ADAPTIVE_LIST_CAPACITY 1024
#define TESSERA_ADAPTIVE_UBO_BINDING 30
#define TESSERA_ADAPTIVE_WORK_BINDING 14
#define TESSERA_ADAPTIVE_IMAGE_UNIT 6
#define TESSERA_ADAPTIVE_OUT_FORMAT rgba16f
#if defined(VULKAN)
#define TESSERA_ADAPTIVE_GBUFFER(b) set = 0, binding = (b)
#else
#define TESSERA_ADAPTIVE_GBUFFER(b) binding = (b)
#endif
// The generated G-buffer accessors of a layout (depth, normal, id, uv, uv derivatives).
layout(TESSERA_ADAPTIVE_GBUFFER(20)) uniform sampler2D tessera_adaptive_gbuffer0;
layout(TESSERA_ADAPTIVE_GBUFFER(21)) uniform sampler2D tessera_adaptive_gbuffer1;
float tessera_adaptive_depth(ivec2 g) { return texelFetch(tessera_adaptive_gbuffer0, g, 0).w; }
vec3 tessera_adaptive_normal(ivec2 g) { return texelFetch(tessera_adaptive_gbuffer0, g, 0).xyz * 2.0 + vec3(-1.0); }
float tessera_adaptive_id_value(ivec2 g) { return (texelFetch(tessera_adaptive_gbuffer1, g, 0).w * 255.0 + -1.0); }
int tessera_adaptive_id(ivec2 g) { float v = tessera_adaptive_id_value(g); return int(floor(abs(v) + 0.5)) * (v < 0.0 ? -1 : 1); }
vec2 tessera_adaptive_uv(ivec2 g) { return texelFetch(tessera_adaptive_gbuffer1, g, 0).xy; }
vec4 tessera_adaptive_uv_derivatives(ivec2 g) { return texelFetch(tessera_adaptive_gbuffer1, g, 0).zwxy; }
// A hook.
vec4 tessera_shade_sample(ivec2 g, float footprint) {
  return vec4(tessera_adaptive_normal(g) * 0.5 + 0.5, 1.0) / footprint;
}
#include "adaptive_component.glsl"
