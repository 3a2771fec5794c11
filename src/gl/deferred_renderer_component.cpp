// DeferredRenderer as a user of gl::AdaptiveSupersampler: its adaptive, reference and 1 spp
// passes (m >= 2) run the engine component with tessera's own G-buffer layout and the
// Blinn-Phong / heavy shading of deferred_shading.glsl as the hook, so the technique has one
// implementation (share/tessera/glsl/adaptive_component.glsl). deferred_passes.comp keeps the
// engine baseline (edge-per-sample), sRGB8 and FXAA, and m = 1.
#include <algorithm>

#include "gl/deferred_renderer_internal.h"
#include "gl/gl_api.h"

namespace tessera::gl {

using namespace api;

namespace {

using State = DeferredRenderer::State;

AdaptiveSchedule schedule_of(ExtraSchedule s) {
  switch (s) {
    case ExtraSchedule::tile_list:
      return AdaptiveSchedule::tile_list;
    case ExtraSchedule::loop:
      return AdaptiveSchedule::loop;
    case ExtraSchedule::frame_list:
      break;
  }
  return AdaptiveSchedule::frame_list;
}

Result<AdaptiveSupersampler*> component(State& st) {
  const int classes = std::max(1, int(st.class_arrays.size()));
  const std::array<int, 5> key = {st.w, st.h, st.m, int(st.options.schedule), classes};
  if (st.component && st.component_key == key) return st.component.get();
  st.component.reset();
  AdaptiveSupersamplerOptions o;
  o.width = st.w;
  o.height = st.h;
  o.m = st.m;
  o.schedule = schedule_of(st.options.schedule);
  o.output = AdaptiveOutputFormat::rgba32f;
  o.sample_count_texture = true;
  o.profile = true;  // ShadeResult's pass times
  o.glsl_dir = st.options.glsl_dir;
  // The G-buffer of deferred_shading.glsl (units 0..2 of the renderer's own bindings).
  o.layout = deferred_gbuffer_layout();
  o.hook.name = "DeferredRenderer's shading hook";
  // S keeps its light terms (D, P) in the renderer's SSBO 4 (deferred_passes.comp's layout),
  // and sample 0 again repeats only the albedo lookup, as deferred_passes.comp does.
  o.hook.source = "#define TESSERA_DEFERRED_CLASSES " + std::to_string(classes) +
                  "\n#include \"deferred_shading.glsl\"\n"
                  "layout(std430, binding = 4) buffer DeferredTerms { vec4 deferred_terms[]; };\n"
                  "#define TESSERA_ADAPTIVE_SAMPLE0_AGAIN 1\n"
                  "int deferred_pixel(ivec2 g) {\n"
                  "  return (g.y / TESSERA_ADAPTIVE_M) * TESSERA_ADAPTIVE_WIDTH + g.x / TESSERA_ADAPTIVE_M;\n"
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
  Result<std::unique_ptr<AdaptiveSupersampler>> c = AdaptiveSupersampler::create(o);
  if (!c) return c.status();
  st.component = std::move(*c);
  st.component_key = key;
  return st.component.get();
}

}  // namespace

Status shade_with_component(State& st, int mode, const deferred::AdaptiveOptions* a,
                            ShadeResult& r) {
  Result<AdaptiveSupersampler*> c = component(st);
  if (!c) return c.status();
  if (a) {
    AdaptiveThresholds t;
    t.c_depth = a->c_depth;
    t.c_normal = a->c_normal;
    t.c_shade = a->c_shade;
    t.t_min = a->t_min;
    t.t_edge = a->t_edge;
    t.use_geometry = a->use_geometry;
    t.use_shading = a->use_shading;
    t.seam_factor = a->seam_factor;
    t.force_k = a->force_k;
    (*c)->set_thresholds(t);
  }
  AdaptiveFrame frame;
  frame.gbuffer = {st.g0.get(), st.g1.get(), st.g2.get(), 0};
  Result<AdaptiveFrameResult> f = mode == 0   ? (*c)->dispatch(frame)
                                  : mode == 1 ? (*c)->dispatch_reference(frame)
                                              : (*c)->dispatch_first_sample(frame);
  if (!f) return f.status();
  r.passes = std::move(f->passes);
  r.wall_passes = std::move(f->wall_passes);
  r.image = ImageRGBAF(st.w, st.h);
  glGetTextureSubImage(f->colour, 0, 0, 0, 0, st.w, st.h, 1, GL_RGBA, GL_FLOAT,
                       GLsizei(r.image.pixels.size() * 4), r.image.pixels.data());
  for (std::size_t i = 0; i < r.image.pixel_count(); ++i) r.image.pixels[i * 4 + 3] = 1.0f;
  const std::uint64_t pixels = std::uint64_t(st.w) * std::uint64_t(st.h);
  if (mode == 0) {
    r.samples.assign(std::size_t(pixels), 0);
    glGetTextureSubImage(f->sample_counts, 0, 0, 0, 0, st.w, st.h, 1, GL_RED_INTEGER,
                         GL_UNSIGNED_BYTE, GLsizei(r.samples.size()), r.samples.data());
    r.samples_shaded = 0;
    for (std::uint8_t s : r.samples) r.samples_shaded += s;
  } else {
    r.samples_shaded = pixels * (mode == 1 ? std::uint64_t(st.m * st.m) : 1u);
  }
  return check_errors("deferred GL: read-back");
}

}  // namespace tessera::gl
