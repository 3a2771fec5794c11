// The API-neutral host side of the GPU deferred renderers (src/deferred/gpu_host.h).
#include "deferred/gpu_host.h"

#include <algorithm>
#include <map>
#include <tuple>

#include "deferred/deferred_internal.h"
#include "tessera/glsl.h"

namespace tessera::deferred {

double ShadeResult::total_gpu_ms() const { return tessera::total_gpu_ms(passes); }
double ShadeResult::total_wall_ms() const { return tessera::total_wall_ms(passes); }
double FxaaResult::total_gpu_ms() const { return tessera::total_gpu_ms(passes); }
double FxaaResult::total_wall_ms() const { return tessera::total_wall_ms(passes); }

GpuCamera gpu_camera(const GBufferCamera& cam, float far_z) {
  GpuCamera g;
  g.aspect = cam.aspect;
  g.tan_half_fov = cam.tan_half_fov_y;
  g.far_z = far_z;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) g.inv_view[c * 4 + r] = cam.inv_view.m[c][r];
  g.eye[0] = cam.eye.x;
  g.eye[1] = cam.eye.y;
  g.eye[2] = cam.eye.z;
  return g;
}

Result<GpuTextureClasses> gpu_texture_classes(const std::vector<scene::Material>& materials,
                                              const std::vector<texture::Texture>& textures,
                                              std::string_view who) {
  std::map<std::tuple<int, int, int>, std::vector<int>> classes;
  std::vector<int> used(textures.size(), 0);
  for (const scene::Material& mat : materials) {
    const int t = mat.base_color_texture;
    if (t >= 0 && std::size_t(t) < textures.size() && !used[std::size_t(t)]) {
      used[std::size_t(t)] = 1;
      const texture::Texture& tex = textures[std::size_t(t)];
      classes[{tex.width(), tex.height(), tex.level_count()}].push_back(t);
    }
  }
  if (int(classes.size()) > kGpuMaxTextureClasses) {
    return Status::error(ErrorCode::too_large,
                         std::string(who) + ": the scene's base-colour textures come in " +
                             std::to_string(classes.size()) + " sizes; at most " +
                             std::to_string(kGpuMaxTextureClasses) +
                             " texture arrays are supported");
  }
  GpuTextureClasses out;
  out.where.assign(textures.size(), {-1, -1});
  for (const auto& [key, members] : classes) {
    const auto [tw, th, levels] = key;
    for (std::size_t layer = 0; layer < members.size(); ++layer) {
      out.where[std::size_t(members[layer])] = {int(out.classes.size()), int(layer)};
    }
    out.classes.push_back({tw, th, levels, members});
  }
  return out;
}

std::vector<GpuMaterial> gpu_materials(const std::vector<scene::Material>& materials,
                                       const std::vector<texture::Texture>& textures,
                                       const GpuTextureClasses& classes) {
  std::vector<GpuMaterial> mats;
  for (const scene::Material& mat : materials) {
    GpuMaterial rec{{mat.base_color[0], mat.base_color[1], mat.base_color[2], 1.0f}, {-1, 0, 1, 1}};
    const int t = mat.base_color_texture;
    if (t >= 0 && std::size_t(t) < textures.size()) {
      const texture::Texture& tex = textures[std::size_t(t)];
      rec.tex[0] = classes.where[std::size_t(t)][0];
      rec.tex[1] = classes.where[std::size_t(t)][1];
      rec.tex[2] = tex.width();
      rec.tex[3] = tex.height();
    }
    mats.push_back(rec);
  }
  if (mats.empty()) mats.push_back({{1, 1, 1, 1}, {-1, 0, 1, 1}});
  return mats;
}

std::vector<float> gpu_static_vertices(const scene::Mesh& mesh) {
  std::vector<float> v(mesh.positions.size() * 5);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    v[i * 5 + 0] = mesh.normals[i].x;
    v[i * 5 + 1] = mesh.normals[i].y;
    v[i * 5 + 2] = mesh.normals[i].z;
    v[i * 5 + 3] = mesh.uvs[i].x;
    v[i * 5 + 4] = mesh.uvs[i].y;
  }
  return v;
}

GpuParams gpu_params(const GpuCamera& cam, int w, int h, int m, const ShadingOptions& o,
                     const AdaptiveThresholds* a, const EdgePerSampleOptions* e) {
  const int n = m * m;
  GpuParams p{};
  p.size[0] = w;
  p.size[1] = h;
  p.size[2] = m;
  p.size[3] = n;
  p.counts[0] = int(o.lights.size());
  p.counts[1] = o.heavy ? std::max(o.heavy_terms, 0) : 0;
  p.counts[2] = a ? a->force_k : -1;
  p.counts[3] = a ? (a->use_geometry ? 1 : 0) | (a->use_shading ? 2 : 0) : 3;
  std::copy(cam.eye, cam.eye + 3, p.eye);
  p.eye[3] = cam.tan_half_fov;
  p.view[0] = cam.aspect;
  p.view[1] = o.exposure;
  p.view[2] = o.specular;
  p.view[3] = o.shininess;
  p.ambient[0] = o.ambient[0];
  p.ambient[1] = o.ambient[1];
  p.ambient[2] = o.ambient[2];
  p.ambient[3] = float(std::clamp(o.max_aniso, 1, texture::kMaxAnisotropy));
  const AdaptiveThresholds def_a;
  const EdgePerSampleOptions def_e;
  const AdaptiveThresholds& aa = a ? *a : def_a;
  const EdgePerSampleOptions& ee = e ? *e : def_e;
  p.metric[0] = aa.c_depth;
  p.metric[1] = aa.c_normal;
  p.metric[2] = aa.c_shade;
  p.metric[3] = aa.t_min;
  p.metric2[0] = aa.t_edge;
  p.metric2[1] = aa.seam_factor;
  p.metric2[2] = ee.min_normal_dot;
  p.metric2[3] = ee.depth_slack;
  p.background[0] = kBackground[0];
  p.background[1] = kBackground[1];
  p.background[2] = kBackground[2];
  std::copy(cam.inv_view, cam.inv_view + 16, p.inv_view);
  const std::span<const std::uint8_t> order = sample_order(m);
  for (int i = 0; i < n; ++i) p.order[i] = order[std::size_t(i)];
  return p;
}

std::vector<float> gpu_lights(const ShadingOptions& o) {
  std::vector<float> lights;
  for (const Light& l : o.lights) {
    lights.insert(lights.end(), {l.position.x, l.position.y, l.position.z, l.range, l.color[0],
                                 l.color[1], l.color[2], l.intensity});
  }
  lights.resize(std::max<std::size_t>(lights.size(), 8), 0.0f);
  return lights;
}

std::vector<float> gpu_waves(const ShadingOptions& o) {
  std::vector<float> waves =
      o.heavy ? make_heavy_waves(o.heavy_terms, o.heavy_wavelength) : std::vector<float>{};
  waves.resize(std::max<std::size_t>(waves.size(), 4), 0.0f);
  return waves;
}

Result<std::vector<std::string>> gpu_fxaa_defines(const FxaaOptions& f) {
  const FxaaPresetSteps* preset = fxaa_preset_steps(f.preset);
  if (!preset) {
    return Status::error(
        ErrorCode::invalid_argument,
        "fxaa: unknown quality preset " + std::to_string(f.preset) + " (10..15, 20..29 or 39)");
  }
  std::string table = "float[12](";
  for (int i = 0; i < 12; ++i) table += (i ? ", " : "") + glsl::float_literal(preset->p[i]);
  table += ")";
  return std::vector<std::string>{
      "TESSERA_PASS_FXAA",
      "TESSERA_FXAA_STEPS " + std::to_string(preset->steps),
      "TESSERA_FXAA_P " + table,
      "TESSERA_FXAA_SUBPIX " + glsl::float_literal(f.subpix),
      "TESSERA_FXAA_EDGE " + glsl::float_literal(f.edge_threshold),
      "TESSERA_FXAA_EDGE_MIN " + glsl::float_literal(f.edge_threshold_min)};
}

Result<std::vector<GpuPass>> gpu_method_passes(GpuMethod method, const FxaaOptions& fxaa) {
  const GpuPass first{"first", {"TESSERA_PASS_FIRST"}};
  switch (method) {
    case GpuMethod::reference:
      return std::vector<GpuPass>{{"reference", {"TESSERA_PASS_REFERENCE"}}};
    case GpuMethod::first:
      return std::vector<GpuPass>{first};
    case GpuMethod::adaptive:
      return std::vector<GpuPass>{
          first, {"metrics", {"TESSERA_PASS_METRICS"}}, {"extra", {"TESSERA_PASS_EXTRA"}, true}};
    case GpuMethod::edge_per_sample:
      return std::vector<GpuPass>{first,
                                  {"edge_extra", {"TESSERA_PASS_EXTRA", "TESSERA_EDGE"}, true}};
    case GpuMethod::fxaa: {
      Result<std::vector<std::string>> fd = gpu_fxaa_defines(fxaa);
      if (!fd) return fd.status();
      return std::vector<GpuPass>{
          first, {"srgb8", {"TESSERA_PASS_SRGB8", "TESSERA_SRGB_FROM_S"}}, {"fxaa", *fd}};
    }
  }
  return Status::error(ErrorCode::invalid_argument, "unknown GPU method");
}

std::vector<std::string> gpu_passes_preamble(int classes, int m,
                                             const std::vector<std::string>& defines) {
  std::vector<std::string> pre = {
      "#define TESSERA_DEFERRED_CLASSES " + std::to_string(classes),
      "#define TESSERA_WINDOW_N " + std::to_string(m * m),
      "#define TESSERA_ADAPTIVE_MAX_N " + std::to_string(std::max(1, m * m))};
  for (const std::string& d : defines) pre.push_back("#define " + d);
  return pre;
}

void gpu_component_options(AdaptiveCommonOptions& o, int w, int h, int m, int classes,
                           std::string_view terms_layout, std::string_view hook_name) {
  o.width = w;
  o.height = h;
  o.m = m;
  o.output = AdaptiveOutputFormat::rgba32f;
  o.sample_count_texture = true;
  o.profile = true;  // the pass times
  o.layout = deferred_gbuffer_layout();
  o.hook.name = std::string(hook_name);
  o.hook.source = gpu_shading_hook(classes, terms_layout);
}

std::string gpu_shading_hook(int classes, std::string_view terms_layout) {
  return "#define TESSERA_DEFERRED_CLASSES " + std::to_string(classes) +
         "\n#include \"deferred_shading.glsl\"\n"
         "layout(" +
         std::string(terms_layout) +
         ") buffer DeferredTerms { vec4 deferred_terms[]; };\n"
         "#define TESSERA_ADAPTIVE_SAMPLE0_AGAIN 1\n"
         "int deferred_pixel(ivec2 g) {\n"
         "  return (g.y / TESSERA_ADAPTIVE_M) * TESSERA_ADAPTIVE_WIDTH + g.x / "
         "TESSERA_ADAPTIVE_M;\n"
         "}\n"
         "vec4 tessera_shade_sample(ivec2 g, float footprint) {\n"
         "  TesseraSample s = tessera_fetch(g);\n"
         "  vec3 c = tessera_background.rgb, d = vec3(0.0), p = vec3(0.0);\n"
         "  if (s.material >= 0) {\n"
         "    tessera_lighting(g, s, d, p);\n"
         "    c = tessera_albedo(s, footprint) * d + p;\n"
         "  }\n"
         "#if defined(TESSERA_ADAPTIVE_PASS_FIRST)\n"
         "  int i = deferred_pixel(g);\n"
         "  deferred_terms[2 * i] = vec4(d, 0.0);\n"
         "  deferred_terms[2 * i + 1] = vec4(p, 0.0);\n"
         "#endif\n"
         "  return vec4(c, 1.0);\n"
         "}\n"
         "vec4 tessera_shade_sample0_again(ivec2 g, float footprint) {\n"
         "  TesseraSample s = tessera_fetch(g);\n"
         "  if (s.material < 0) return vec4(tessera_background.rgb, 1.0);\n"
         "  int i = deferred_pixel(g);\n"
         "  return vec4(tessera_albedo(s, footprint) * deferred_terms[2 * i].rgb +\n"
         "              deferred_terms[2 * i + 1].rgb, 1.0);\n"
         "}\n";
}

}  // namespace tessera::deferred
