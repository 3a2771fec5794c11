// Internal to the library: the host side of the GPU deferred renderers that does not depend on
// the GPU API, written once for gl::DeferredRenderer (src/gl/deferred_renderer*) and the Vulkan
// AA backend's renderer (src/vk/deferred_renderer*): the texture-size classes and material
// records of deferred_shading.glsl, the per-vertex static data of deferred_gbuffer.vert, the
// TesseraDeferredParams block with its light and wave buffers, FXAA's pass defines and the
// shading hook both hand to their adaptive supersampler. GL-free, Vulkan-free (core `tessera`
// library). Tests: the backends' (tests/gl/gl_deferred_renderer_test.cpp,
// tests/vk/vk_aa_backend_test.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/adaptive_supersampler.h"
#include "tessera/core.h"
#include "tessera/deferred.h"
#include "tessera/scene.h"
#include "tessera/texture.h"

namespace tessera::deferred {

/// std140 layout of TesseraDeferredParams (deferred_shading.glsl).
struct GpuParams {
  std::int32_t size[4];
  std::int32_t counts[4];
  float eye[4];
  float view[4];
  float ambient[4];
  float metric[4];
  float metric2[4];
  float background[4];
  float inv_view[16];
  std::int32_t order[64];
};
static_assert(sizeof(GpuParams) == 8 * 16 + 64 + 256, "std140 layout");

/// The camera data of a G-buffer pass as the GPU passes read it (column-major inverse view).
struct GpuCamera {
  float eye[3] = {0, 0, 0};
  float tan_half_fov = 0.5f, aspect = 1.0f, far_z = 1000.0f;
  float inv_view[16] = {};
};
GpuCamera gpu_camera(const GBufferCamera& camera, float far_z);

/// At most this many texture-size classes (deferred_shading.glsl's TESSERA_DEFERRED_CLASSES).
inline constexpr int kGpuMaxTextureClasses = 8;

/// The base-colour textures of a scene grouped by (width, height, levels): one texture array
/// per class, one layer per texture.
struct GpuTextureClasses {
  struct Class {
    int width = 0, height = 0, levels = 0;
    std::vector<int> textures;  ///< Texture indices, by layer.
  };
  std::vector<Class> classes;             ///< In (width, height, levels) order; may be empty.
  std::vector<std::array<int, 2>> where;  ///< Per texture: (class, layer), (-1, -1) unused.
};
/// Groups the textures the materials use; too_large ("`who`: ...") past kGpuMaxTextureClasses.
Result<GpuTextureClasses> gpu_texture_classes(const std::vector<scene::Material>& materials,
                                              const std::vector<texture::Texture>& textures,
                                              std::string_view who);

/// One material record: vec4 base colour, ivec4 (class or -1, layer, width, height).
struct GpuMaterial {
  float base[4];
  std::int32_t tex[4];
};
/// The records of `materials` (one untextured white record when there is none).
std::vector<GpuMaterial> gpu_materials(const std::vector<scene::Material>& materials,
                                       const std::vector<texture::Texture>& textures,
                                       const GpuTextureClasses& classes);

/// Per vertex: normal xyz, uv (5 floats; deferred_gbuffer.vert's locations 2 and 3).
std::vector<float> gpu_static_vertices(const scene::Mesh& mesh);

/// The parameter block of a shading call on a (w, h, m) G-buffer; `adaptive` / `edge` null
/// for the other methods (their defaults are written).
GpuParams gpu_params(const GpuCamera& camera, int w, int h, int m, const ShadingOptions& shading,
                     const AdaptiveThresholds* adaptive, const EdgePerSampleOptions* edge);
/// The lights as 2 vec4 each (position + range, colour + intensity), at least 8 floats.
std::vector<float> gpu_lights(const ShadingOptions& shading);
/// The heavy term's waves (vec4 each), at least 4 floats.
std::vector<float> gpu_waves(const ShadingOptions& shading);

/// The defines of deferred_passes.comp's FXAA pass (invalid_argument for an unknown preset).
Result<std::vector<std::string>> gpu_fxaa_defines(const FxaaOptions& fxaa);

/// The experiments' shading methods as the GPU renderers run them.
enum class GpuMethod { reference, first, adaptive, edge_per_sample, fxaa };
/// One pass of deferred_passes.comp: its name (the PassTime's) and defines. `extra`: the
/// extra-sample pass, which each backend runs with its schedule's defines added (GL: loop, tile
/// or the frame list's list, shade and resolve passes; Vulkan: loop).
struct GpuPass {
  std::string name;
  std::vector<std::string> defines;
  bool extra = false;
};
/// The passes of `method`, in order, the one list both backends run (deferred_passes.comp's;
/// at m >= 2 the reference, 1 spp and adaptive run the engine component instead):
/// reference "reference"; first "first"; adaptive "first", "metrics", "extra"; edge per sample
/// "first", "edge_extra"; fxaa "first", "srgb8", "fxaa" (`fxaa`'s preset: invalid_argument
/// when unknown, as gpu_fxaa_defines).
Result<std::vector<GpuPass>> gpu_method_passes(GpuMethod method, const FxaaOptions& fxaa = {});

/// The preamble of a deferred_passes.comp program: its three always-defined macros (for `classes`
/// texture classes and window m), then `#define D` per entry of `defines`.
std::vector<std::string> gpu_passes_preamble(int classes, int m,
                                             const std::vector<std::string>& defines);

/// The options both renderers give their adaptive supersampler for a (w, h, m) G-buffer:
/// RGBA32F output, sample counts, profiling, tessera's G-buffer layout and `gpu_shading_hook`
/// (named `hook_name`); the schedule and the backend's own fields are the caller's.
void gpu_component_options(AdaptiveCommonOptions& o, int w, int h, int m, int classes,
                           std::string_view terms_layout, std::string_view hook_name);

/// The shading hook of the renderers' adaptive passes: deferred_shading.glsl with `classes`
/// texture classes; S's light terms (D, P) kept in the storage buffer DeferredTerms, declared
/// with `terms_layout` (the backend's qualifiers, e.g. "std430, binding = 4"), so that sample 0
/// again repeats only the albedo lookup, as deferred_passes.comp does.
std::string gpu_shading_hook(int classes, std::string_view terms_layout);

}  // namespace tessera::deferred
