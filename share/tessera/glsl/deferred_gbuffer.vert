// deferred_gbuffer.vert — geometry pass of tessera's GPU adaptive supersampling: rasterises the
// scene into the enlarged G-buffer (m*w x m*h) with the CPU's conventions
// (tessera::deferred::DeferredRenderer::render_gbuffer).
//   location 0: vec4 clip-space position, computed on the CPU as the CPU path does
//               (projection(aspect) * view * position; OpenGL clip space, y up)
//   location 1: float linear view depth (-z of the view-space position)
//   location 2: vec3 world normal (the mesh's vertex normal)
//   location 3: vec2 texture coordinates
// Clip y is negated so that framebuffer row 0 is the top grid row (tessera's top-down grid):
// texelFetch(ivec2(gx, gy)) then reads CPU grid pixel (gx, gy), and dFdy is d/d(grid y, down).
// Culling is off (the CPU draws both sides), so the mirrored winding does not matter.
// Vulkan (VULKAN defined by glslangValidator -V or glslc; no tessera runtime yet): outputs at
// locations 0 (depth), 1 (normal), 2 (uv); the y negation again puts the top grid row in
// framebuffer row 0; clip z stays OpenGL's [-w, w] (the host remaps it or uses
// VK_EXT_depth_clip_control). OpenGL compiles exactly what it always did.
#version 450 core

layout(location = 0) in vec4 tessera_clip;
layout(location = 1) in float tessera_depth;
layout(location = 2) in vec3 tessera_normal;
layout(location = 3) in vec2 tessera_uv;

#if defined(VULKAN)
layout(location = 0) out float tessera_v_depth;
layout(location = 1) out vec3 tessera_v_normal;
layout(location = 2) out vec2 tessera_v_uv;
#else
out float tessera_v_depth;
out vec3 tessera_v_normal;
out vec2 tessera_v_uv;
#endif

void main() {
  tessera_v_depth = tessera_depth;
  tessera_v_normal = tessera_normal;
  tessera_v_uv = tessera_uv;
  gl_Position = vec4(tessera_clip.x, -tessera_clip.y, tessera_clip.z, tessera_clip.w);
}
