// engine_ptex_vk's shaders (GLSL, compiled at load with shaderc): the vertex stage with the
// engine's vertex layout (position, normal, per-face UV, integer face id) and frame block (set 0,
// binding 0), GL-style matrices with the depth mapped to Vulkan's 0..1; the fragment stage with
// tessera's seamless lookup. tests/vk/vk_faces_test.cpp draws with the same stages (it includes
// this header).
#pragma once

namespace engine {

inline constexpr const char* kVertexShader = R"(#version 450
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec2 face_uv;
layout(location = 3) in int face_id;
layout(std140, set = 0, binding = 0) uniform Frame { mat4 view_proj; vec4 light_dir; vec4 shade; };
layout(location = 0) out vec3 v_normal;
layout(location = 1) out vec2 v_uv;
layout(location = 2) flat out int v_face;
void main() {
  v_normal = normal;
  v_uv = face_uv;
  v_face = face_id;
  gl_Position = view_proj * vec4(position, 1.0);
  gl_Position.z = 0.5 * (gl_Position.z + gl_Position.w);  // GL-style depth to Vulkan's 0..1
}
)";

// The fragment stage: the engine's own lighting of tessera_seams_sample_discard, reading face
// (f + ENGINE_FACE_SHIFT) mod ENGINE_FACES (the --face-shift control); tessera's glsl_defines
// go after #version (glsl::ExpandOptions::preamble), then seams.glsl in place of the #include.
inline constexpr const char* kFragmentShader = R"(#version 450
#include "seams.glsl"
layout(std140, set = 0, binding = 0) uniform Frame { mat4 view_proj; vec4 light_dir; vec4 shade; };
layout(location = 0) in vec3 v_normal;
layout(location = 1) in vec2 v_uv;
layout(location = 2) flat in int v_face;
layout(location = 0) out vec4 colour;
void main() {
  // Explicit fine gradients: the lookups sit in non-uniform control flow (a class per face).
  vec2 dx = dFdxFine(v_uv), dy = dFdyFine(v_uv);
  int face = (v_face + ENGINE_FACE_SHIFT) % ENGINE_FACES;
  vec4 tex = tessera_seams_sample_discard(face, v_uv, dx, dy, true);
  float nl = dot(v_normal, light_dir.xyz) / sqrt(dot(v_normal, v_normal) + 1e-20);
  colour = vec4(tex.rgb * (shade.x + shade.y * max(nl, 0.0)), 1.0);
}
)";

}  // namespace engine
