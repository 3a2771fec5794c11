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
  // The G-buffer of deferred_shading.glsl (units 0..2 of the renderer's own bindings); S keeps
  // its light terms (D, P) in the renderer's SSBO 4 (deferred_passes.comp's layout).
  deferred::gpu_component_options(o, st.w, st.h, st.m, classes, "std430, binding = 4",
                                  "DeferredRenderer's shading hook");
  o.schedule = schedule_of(st.options.schedule);
  o.glsl_dir = st.options.glsl_dir;
  Result<std::unique_ptr<AdaptiveSupersampler>> c = AdaptiveSupersampler::create(o);
  if (!c) return c.status();
  st.component = std::move(*c);
  st.component_key = key;
  return st.component.get();
}

}  // namespace

Status shade_with_component(State& st, int mode, const AdaptiveThresholds* a,
                            deferred::ShadeResult& r) {
  Result<AdaptiveSupersampler*> c = component(st);
  if (!c) return c.status();
  if (a) {
    (*c)->set_thresholds(*a);
  }
  AdaptiveFrame frame;
  frame.gbuffer = {st.g0.get(), st.g1.get(), st.g2.get(), 0};
  Result<AdaptiveOutput> f = mode == 0   ? (*c)->dispatch(frame)
                             : mode == 1 ? (*c)->dispatch_reference(frame)
                                         : (*c)->dispatch_first_sample(frame);
  if (!f) return f.status();
  r.passes = std::move(f->passes);
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
