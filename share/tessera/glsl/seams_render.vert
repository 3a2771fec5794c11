// seams_render.vert — vertex stage of the GL face renderer (tessera::gl::FaceRenderer,
// include/tessera/gl_face_renderer.h); public GLSL API, installed with seams.glsl.
//
// Input layout: every face of the quad mesh has four unshared vertices, face f owning vertices
// 4f .. 4f+3 in the face's vertex order 0..3, so the face id and the per-face UV corner follow
// from gl_VertexID (glDrawElements: the index value) and the index buffer may list the faces
// in any order (the renderer groups them by face class, one draw per class).
//   location 0: vec4 clip-space position, computed on the CPU exactly as
//               tessera::faces::FaceRenderer does (OpenGL clip space, y up)
//   location 1: vec3 unit vertex normal (smooth, area-weighted)
// Output: perspective-correct UV (Ptex corners (0,0), (1,0), (1,1), (0,1)) and normal, and the
// face id (flat).
//
// Orientation: clip y is negated, so framebuffer row 0 holds the image's top row (tessera's
// top-down images read back without a flip) and the driver's memory-order sample positions are
// those of tessera's rasteriser (Direct3D patterns, y down). The negation mirrors the winding:
// the host lists each triangle in reversed order so that front faces stay counter-clockwise.
//
// Vulkan (VULKAN defined by glslangValidator -V, glslc or shaderc; the experiment's Vulkan
// backend, src/vk/face_renderer.h): outputs at locations 0 (uv), 1 (normal), 2 (face); the face
// id from gl_VertexIndex (vkCmdDrawIndexed with vertexOffset 0). The same y negation puts the
// image's top row in framebuffer row 0 (Vulkan's row 0 is at NDC y = -1); as Vulkan's
// framebuffer y runs down, the CPU's own triangle order is front-facing (counter-clockwise)
// there, not reversed. Clip z stays OpenGL's [-w, w] (the host remaps it or uses
// VK_EXT_depth_clip_control). OpenGL compiles exactly what it always did.
#version 450 core

layout(location = 0) in vec4 tessera_clip;
layout(location = 1) in vec3 tessera_normal;

#if defined(VULKAN)
layout(location = 0) out vec2 tessera_uv;
layout(location = 1) out vec3 tessera_vnormal;
layout(location = 2) flat out int tessera_face;
#define gl_VertexID gl_VertexIndex
#else
out vec2 tessera_uv;
out vec3 tessera_vnormal;
flat out int tessera_face;
#endif

const vec2 tessera_corner_uv[4] = vec2[4](vec2(0.0, 0.0), vec2(1.0, 0.0), vec2(1.0, 1.0),
                                          vec2(0.0, 1.0));

void main() {
  tessera_face = gl_VertexID >> 2;
  tessera_uv = tessera_corner_uv[gl_VertexID & 3];
  tessera_vnormal = tessera_normal;
  gl_Position = vec4(tessera_clip.x, -tessera_clip.y, tessera_clip.z, tessera_clip.w);
}
