// engine_ptex_vk's vertex stage (GLSL, compiled at load with shaderc): the engine's vertex layout
// (position, normal, per-face UV, integer face id) and frame block (set 0, binding 0), GL-style
// matrices with the depth mapped to Vulkan's 0..1. tests/vk/vk_faces_test.cpp draws with the
// same stage (it includes this header).
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

}  // namespace engine
