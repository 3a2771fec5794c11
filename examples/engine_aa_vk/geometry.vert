#version 450 core
// engine_aa_vk's geometry pass: world normal, linear view depth, albedo and id into the
// enlarged G-buffer (Vulkan clip space: z in [0, 1]; y negated so row 0 is the top row).
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 albedo;
layout(location = 3) in float id;
layout(push_constant) uniform Camera { mat4 view; mat4 proj; };
layout(location = 0) out vec3 v_normal;
layout(location = 1) out vec3 v_albedo;
layout(location = 2) out float v_depth;
layout(location = 3) out float v_id;
void main() {
  vec4 view_pos = view * vec4(position, 1.0);
  v_normal = normal;
  v_albedo = albedo;
  v_id = id;
  v_depth = -view_pos.z;
  gl_Position = proj * view_pos;
  gl_Position.y = -gl_Position.y;
}
