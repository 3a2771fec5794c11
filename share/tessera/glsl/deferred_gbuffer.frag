// deferred_gbuffer.frag — writes one G-buffer sample per grid pixel (see deferred_shading.glsl
// for the layout): perspective-correct linear depth, normal and UV, the draw's material id, and
// the fine screen-space derivatives of the UV (per grid pixel, from the 2x2 quad, as the CPU
// rasteriser's default).
// Vulkan (VULKAN defined by glslangValidator -V or glslc; no tessera runtime yet): the material
// id is a push constant (block TesseraGbufferPush, int at offset 0), the inputs are at
// locations 0, 1, 2 (deferred_gbuffer.vert). OpenGL compiles exactly what it always did.
#version 450 core

#if defined(VULKAN)
layout(location = 0) in float tessera_v_depth;
layout(location = 1) in vec3 tessera_v_normal;
layout(location = 2) in vec2 tessera_v_uv;

layout(push_constant) uniform TesseraGbufferPush { int tessera_material; };
#else
in float tessera_v_depth;
in vec3 tessera_v_normal;
in vec2 tessera_v_uv;

uniform int tessera_material;
#endif

layout(location = 0) out vec4 tessera_g0;  // depth, normal xyz
layout(location = 1) out vec4 tessera_g1;  // material, u, v, 0
layout(location = 2) out vec4 tessera_g2;  // du/dx, dv/dx, du/dy, dv/dy

void main() {
  tessera_g0 = vec4(tessera_v_depth, tessera_v_normal);
  tessera_g1 = vec4(float(tessera_material), tessera_v_uv, 0.0);
  tessera_g2 = vec4(dFdxFine(tessera_v_uv), dFdyFine(tessera_v_uv));
}
