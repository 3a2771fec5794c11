#version 450 core
layout(location = 0) in vec3 v_normal;
layout(location = 1) in vec3 v_albedo;
layout(location = 2) in float v_depth;
layout(location = 3) in float v_id;
layout(location = 0) out vec4 rt0;  // RGBA16F: world normal, linear view depth
layout(location = 1) out vec4 rt1;  // RGBA8: albedo, (id + 1) / 255 (0 = sky)
void main() {
  rt0 = vec4(normalize(v_normal), v_depth);
  rt1 = vec4(v_albedo, (v_id + 1.0) / 255.0);
}
