// Internal to src/gl: the state of tessera::gl::DeferredRenderer, shared by
// deferred_renderer_scene.cpp (textures, meshes, geometry pass) and deferred_renderer.cpp (compute
// passes).
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "deferred/gpu_host.h"
#include "tessera/gl.h"
#include "tessera/gl_adaptive.h"
#include "tessera/gl_deferred.h"
#include "tessera/texture.h"

namespace tessera::gl {

struct GlMesh {
  Object vao, dynamic_vbo, static_vbo, ebo;
  std::size_t vertices = 0, indices = 0;
  int material = 0;
};

struct DeferredRenderer::State {
  const scene::Scene* scene = nullptr;
  DeferredRendererOptions options;
  std::vector<texture::Texture> cpu_textures;  // the CPU chains (render::build_scene_textures)
  std::vector<Object> class_arrays;            // one GL_TEXTURE_2D_ARRAY per texture size
  Object materials_ssbo;
  std::vector<GlMesh> meshes;
  std::vector<float> scratch;  // per-frame vertex data
  Program gbuffer_program;
  int material_location = -1;

  // The G-buffer of the last render_gbuffer.
  int w = 0, h = 0, m = 0;
  Object fbo, g0, g1, g2, depth;
  double gbuffer_ms = 0.0, gbuffer_wall_ms = 0.0;
  deferred::GpuCamera camera;

  // Compute resources, reallocated with the output size.
  int buffers_w = 0, buffers_h = 0;
  Object s_buf, terms_buf, k_buf, out_buf, rgba8_buf, rgba8_out_buf;
  Object params_ubo, lights_ssbo, waves_ssbo;
  // ExtraSchedule::frame_list: count, capacity and base per pixel; items; colour slots.
  Object list_base_buf, list_items_buf, list_colours_buf;
  std::size_t list_base_pixels = 0, list_capacity = 0;
  std::map<std::string, Program> programs;  // by preamble
  // The adaptive, reference and 1 spp passes for m >= 2: gl::AdaptiveSupersampler with this
  // G-buffer and deferred_shading.glsl's shading as its hook (deferred_renderer_component.cpp),
  // made again when (w, h, m, schedule, texture classes) change.
  std::unique_ptr<AdaptiveSupersampler> component;
  std::array<int, 5> component_key{};
};

/// The component's image (RGBA32F, alpha 1) and per-pixel sample counts into `r`, after
/// binding the shading inputs; `mode`: 0 adaptive, 1 reference, 2 first sample.
Status shade_with_component(DeferredRenderer::State& st, int mode,
                            const AdaptiveThresholds* adaptive, deferred::ShadeResult& r);

}  // namespace tessera::gl
