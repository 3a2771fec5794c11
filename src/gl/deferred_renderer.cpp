// DeferredRenderer: the compute passes (share/tessera/glsl/deferred_passes.comp) — S, the
// metrics, the extra samples, the reference, the edge-per-sample baseline, sRGB8 and FXAA —
// with their parameters, buffers, GL_TIME_ELAPSED timing and read-back.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "core/check.h"
#include "deferred/deferred_internal.h"
#include "gl/deferred_renderer_internal.h"
#include "gl/gl_api.h"
#include "tessera/glsl.h"

namespace tessera::gl {

using namespace api;

namespace {

Object make_buffer(std::size_t bytes) {
  Object b = create_object(ObjectType::buffer);
  glNamedBufferData(b.get(), GLsizeiptr(std::max<std::size_t>(bytes, 16)), nullptr,
                    GL_DYNAMIC_COPY);
  return b;
}

}  // namespace

namespace {

using State = DeferredRenderer::State;

Result<const Program*> program(State& st, const std::vector<std::string>& defines) {
  const std::vector<std::string> pre =
      deferred::gpu_passes_preamble(int(st.class_arrays.size()), st.m, defines);
  std::string key;
  for (const std::string& p : pre) key += p + "\n";
  auto it = st.programs.find(key);
  if (it != st.programs.end()) return &it->second;
  Result<glsl::Source> cs =
      glsl::shipped_shader(glsl::Stage::compute, "deferred_passes.comp", st.options.glsl_dir);
  if (!cs) return cs.status();
  glsl::ExpandOptions so;
  so.shipped_dir = st.options.glsl_dir;
  so.preamble = pre;
  Result<Program> p = link_program({*cs}, so);
  if (!p) return p.status();
  return &st.programs.emplace(key, std::move(*p)).first->second;
}

/// Uploads the parameters, lights and waves and binds everything the passes read.
Status bind_inputs(State& st, const deferred::ShadingOptions& o, const AdaptiveThresholds* a,
                   const deferred::EdgePerSampleOptions* e) {
  if (!st.fbo) return Status::error(ErrorCode::invalid_argument, "deferred GL: no G-buffer yet");
  if (o.filter != texture::TextureFilter::anisotropic) {
    return Status::error(ErrorCode::unsupported,
                         "deferred GL: only TextureFilter::anisotropic shading is implemented");
  }
  const deferred::GpuParams p = deferred::gpu_params(st.camera, st.w, st.h, st.m, o, a, e);
  if (!st.params_ubo) st.params_ubo = create_object(ObjectType::buffer);
  glNamedBufferData(st.params_ubo.get(), sizeof p, &p, GL_DYNAMIC_DRAW);
  const std::vector<float> lights = deferred::gpu_lights(o);
  if (!st.lights_ssbo) st.lights_ssbo = create_object(ObjectType::buffer);
  glNamedBufferData(st.lights_ssbo.get(), GLsizeiptr(lights.size() * 4), lights.data(),
                    GL_DYNAMIC_DRAW);
  const std::vector<float> waves = deferred::gpu_waves(o);
  if (!st.waves_ssbo) st.waves_ssbo = create_object(ObjectType::buffer);
  glNamedBufferData(st.waves_ssbo.get(), GLsizeiptr(waves.size() * 4), waves.data(),
                    GL_DYNAMIC_DRAW);

  const std::size_t pixels = std::size_t(st.w) * std::size_t(st.h);
  if (st.buffers_w != st.w || st.buffers_h != st.h) {
    st.s_buf = make_buffer(pixels * 16);
    st.terms_buf = make_buffer(pixels * 32);
    st.k_buf = make_buffer(pixels * 4);
    st.out_buf = make_buffer(pixels * 16);
    st.rgba8_buf = make_buffer(pixels * 4);
    st.rgba8_out_buf = make_buffer(pixels * 4);
    st.buffers_w = st.w;
    st.buffers_h = st.h;
  }
  glBindBufferBase(GL_UNIFORM_BUFFER, 0, st.params_ubo.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, st.lights_ssbo.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, st.materials_ssbo.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, st.waves_ssbo.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, st.s_buf.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, st.terms_buf.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, st.k_buf.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, st.out_buf.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, st.rgba8_buf.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, st.rgba8_out_buf.get());
  glBindTextureUnit(0, st.g0.get());
  glBindTextureUnit(1, st.g1.get());
  glBindTextureUnit(2, st.g2.get());
  for (std::size_t c = 0; c < st.class_arrays.size(); ++c) {
    glBindTextureUnit(GLuint(3 + c), st.class_arrays[c].get());
  }
  for (GLuint u = 0; u < GLuint(3 + st.class_arrays.size()); ++u) glBindSampler(u, 0);
  return check_errors("deferred GL: binding the shading inputs");
}

/// GpuTimer plus each pass's name and host time (kept when the driver's times are rejected).
struct PassTimer {
  GpuTimer timer;
  std::vector<PassTime> wall;
  Status begin(const std::string& name) { return timer.begin(name); }
  Status end() { return timer.end(); }
};

/// Runs one compute pass over the w x h output pixels, timed as `name`.
/// `groups_x` > 0: that many groups (x groups_y) instead of one per 8x8 pixels.
Status run_pass(State& st, PassTimer& timer, const std::string& name,
                const std::vector<std::string>& defines, GLuint groups_x = 0, GLuint groups_y = 1) {
  Result<const Program*> p = program(st, defines);
  if (!p) return p.status();
  glFinish();
  const auto wall0 = std::chrono::steady_clock::now();
  if (Status s = timer.begin(name); !s.ok()) return s;
  glUseProgram((*p)->get());
  if (groups_x > 0) {
    glDispatchCompute(groups_x, groups_y, 1);
  } else {
    glDispatchCompute(GLuint((st.w + 7) / 8), GLuint((st.h + 7) / 8), 1);
  }
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  // llvmpipe runs a dispatch when the batch is flushed, after the query has ended: glFinish
  // inside the query makes GL_TIME_ELAPSED cover the work (a no-op cost on a GPU's timeline).
  glFinish();
  timer.wall.push_back(
      {name, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wall0)
                 .count()});
  if (Status s = timer.end(); !s.ok()) return s;
  return check_errors("deferred GL: pass " + name);
}

Result<ImageRGBAF> read_rgba(const State& st, const Object& buf) {
  ImageRGBAF img(st.w, st.h);
  glGetNamedBufferSubData(buf.get(), 0, GLsizeiptr(std::size_t(st.w) * std::size_t(st.h) * 16),
                          img.pixels.data());
  for (std::size_t i = 0; i < img.pixel_count(); ++i) img.pixels[i * 4 + 3] = 1.0f;
  if (Status s = check_errors("deferred GL: read-back"); !s.ok()) return s;
  return img;
}

Result<ImageRGBA8> read_rgba8(const State& st, const Object& buf) {
  ImageRGBA8 img(st.w, st.h);
  glGetNamedBufferSubData(buf.get(), 0, GLsizeiptr(std::size_t(st.w) * std::size_t(st.h) * 4),
                          img.pixels.data());
  if (Status s = check_errors("deferred GL: read-back"); !s.ok()) return s;
  return img;
}

/// The extra pass's defines: `base` (gpu_method_passes') and `schedule`'s (tile_list falls back
/// to loop for m > 4).
std::vector<std::string> extra_defines(const State& st, std::vector<std::string> d,
                                       ExtraSchedule schedule) {
  if (schedule == ExtraSchedule::frame_list) {
    d.push_back("TESSERA_SCHEDULE_FRAME");
  } else if (schedule == ExtraSchedule::loop || st.m > 4) {
    d.push_back("TESSERA_SCHEDULE_LOOP");
  }
  return d;
}

/// Sizes the frame list's buffers for `capacity` items; false when a colour-slot buffer that
/// large exceeds the driver's GL_MAX_SHADER_STORAGE_BLOCK_SIZE.
bool size_frame_list(State& st, std::size_t capacity) {
  GLint64 max_block = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
  if (capacity * 16 > std::size_t(std::max<GLint64>(max_block, 0))) return false;
  st.list_items_buf = make_buffer(capacity * 8);
  st.list_colours_buf = make_buffer(capacity * 16);
  st.list_capacity = capacity;
  return true;
}

/// The extra samples (`pass`: "extra" or "edge_extra"): one pass, or with
/// ExtraSchedule::frame_list the list, shade and resolve passes ("<name>_list", ...).
Status run_extra(State& st, PassTimer& timer, const deferred::GpuPass& pass) {
  const std::string& name = pass.name;
  if (st.options.schedule != ExtraSchedule::frame_list) {
    return run_pass(st, timer, name, extra_defines(st, pass.defines, st.options.schedule));
  }
  const std::size_t pixels = std::size_t(st.w) * std::size_t(st.h);
  if (st.list_base_pixels != pixels) {
    st.list_base_buf = make_buffer(8 + pixels * 4);  // count, capacity, base per pixel
    st.list_base_pixels = pixels;
  }
  // First size: one item per pixel (or what the driver allows); grown below when a frame needs
  // more.
  if (st.list_capacity == 0 && !size_frame_list(st, pixels) &&
      !size_frame_list(st, std::size_t(1) << 16)) {
    return run_pass(st, timer, name, extra_defines(st, pass.defines, ExtraSchedule::loop));
  }
  auto bind = [&] {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 9, st.list_base_buf.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 10, st.list_items_buf.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 11, st.list_colours_buf.get());
  };
  const std::vector<std::string> base = extra_defines(st, pass.defines, ExtraSchedule::frame_list);
  auto with = [&](const char* step) {
    std::vector<std::string> d = base;
    d.push_back(step);
    return d;
  };
  std::uint32_t total = 0;
  for (int attempt = 0; attempt < 2; ++attempt) {
    bind();
    const std::uint32_t header[2] = {0, std::uint32_t(st.list_capacity)};
    glNamedBufferSubData(st.list_base_buf.get(), 0, sizeof header, header);
    // A rerun after growing the list is timed as its own pass.
    if (Status s = run_pass(st, timer, name + (attempt == 0 ? "_list" : "_list_retry"),
                            with("TESSERA_FRAME_LIST"));
        !s.ok()) {
      return s;
    }
    glGetNamedBufferSubData(st.list_base_buf.get(), 0, 4, &total);
    if (total <= st.list_capacity) break;
    // The same k map gives the same count, so one regrowth suffices; a list beyond the
    // driver's block size is shaded by the per-pixel loop instead (same image).
    if (attempt > 0 || !size_frame_list(st, std::size_t(total) + total / 4)) {
      return run_pass(st, timer, name, extra_defines(st, pass.defines, ExtraSchedule::loop));
    }
  }
  if (total > 0) {
    const GLuint groups = GLuint((std::size_t(total) + 63) / 64);
    const GLuint gx = std::min<GLuint>(groups, 65535), gy = (groups + gx - 1) / gx;
    if (Status s = run_pass(st, timer, name + "_shade", with("TESSERA_FRAME_SHADE"), gx, gy);
        !s.ok()) {
      return s;
    }
  }
  return run_pass(st, timer, name + "_resolve", with("TESSERA_FRAME_RESOLVE"));
}

/// Runs `method`'s passes (deferred::gpu_method_passes, the list the Vulkan renderer runs too),
/// the extra pass with the options' schedule.
Status run_method(State& st, PassTimer& timer, deferred::GpuMethod method,
                  const deferred::FxaaOptions& fxaa = {}) {
  Result<std::vector<deferred::GpuPass>> passes = deferred::gpu_method_passes(method, fxaa);
  if (!passes) return passes.status();
  for (const deferred::GpuPass& p : *passes) {
    Status s = p.extra ? run_extra(st, timer, p) : run_pass(st, timer, p.name, p.defines);
    if (!s.ok()) return s;
  }
  return Status::success();
}

Status finish(PassTimer& timer, std::vector<PassTime>& passes) {
  passes = timer.wall;  // the names and host times, one per pass
  Result<std::vector<PassTime>> t = timer.timer.collect();
  if (!t) {
    // Mesa 22.3 llvmpipe's occasional impossible GL_TIME_ELAPSED (GpuTimer::collect checks
    // each pass against the wall time): the results stand, the GPU times are unknown (NaN).
    return t.status().code == ErrorCode::unsupported ? Status::success() : t.status();
  }
  TESSERA_DCHECK(t->size() == passes.size());  // one query and one host time per pass
  for (std::size_t i = 0; i < passes.size() && i < t->size(); ++i) {
    TESSERA_DCHECK((*t)[i].pass == passes[i].pass);
    passes[i].gpu_ms = (*t)[i].gpu_ms;
  }
  return Status::success();
}

Status read_samples(const State& st, deferred::ShadeResult& r) {
  const std::size_t pixels = std::size_t(st.w) * std::size_t(st.h);
  std::vector<std::uint32_t> k(pixels);
  glGetNamedBufferSubData(st.k_buf.get(), 0, GLsizeiptr(pixels * 4), k.data());
  r.samples.resize(pixels);
  r.samples_shaded = 0;
  for (std::size_t i = 0; i < pixels; ++i) {
    r.samples[i] = std::uint8_t(k[i] + 1);
    r.samples_shaded += k[i] + 1;
  }
  return check_errors("deferred GL: k map read-back");
}

/// The end of the adaptive and edge-per-sample passes: the timers into `r`, the image (SSBO 6)
/// and the per-pixel sample counts read back.
Status read_timed_result(State& st, PassTimer& timer, deferred::ShadeResult& r) {
  if (Status s = finish(timer, r.passes); !s.ok()) return s;
  Result<ImageRGBAF> img = read_rgba(st, st.out_buf);
  if (!img) return img.status();
  r.image = std::move(*img);
  return read_samples(st, r);
}

/// The reference (component kind 1) or 1 spp (kind 2): the adaptive component where m >= 2,
/// else `method`'s one pass, whose colours land in `buffer`, with `samples_per_pixel` samples
/// shaded per pixel.
Result<deferred::ShadeResult> shade_one_pass(State& st, const deferred::ShadingOptions& o, int kind,
                                             deferred::GpuMethod method, const Object& buffer,
                                             std::uint64_t samples_per_pixel) {
  if (Status s = bind_inputs(st, o, nullptr, nullptr); !s.ok()) return s;
  deferred::ShadeResult r;
  if (st.m >= 2) {
    if (Status s = shade_with_component(st, kind, nullptr, r); !s.ok()) return s;
    return r;
  }
  PassTimer timer;
  if (Status s = run_method(st, timer, method); !s.ok()) return s;
  if (Status s = finish(timer, r.passes); !s.ok()) return s;
  Result<ImageRGBAF> img = read_rgba(st, buffer);
  if (!img) return img.status();
  r.image = std::move(*img);
  r.samples_shaded = std::uint64_t(st.w) * std::uint64_t(st.h) * samples_per_pixel;
  return r;
}

}  // namespace

Result<deferred::ShadeResult> DeferredRenderer::shade_reference(const deferred::ShadingOptions& o) {
  State& st = *state_;
  return shade_one_pass(st, o, 1, deferred::GpuMethod::reference, st.out_buf,
                        std::uint64_t(st.m * st.m));
}

Result<deferred::ShadeResult> DeferredRenderer::shade_default(const deferred::ShadingOptions& o) {
  State& st = *state_;
  return shade_one_pass(st, o, 2, deferred::GpuMethod::first, st.s_buf, 1);
}

Result<deferred::ShadeResult> DeferredRenderer::shade_adaptive(const deferred::ShadingOptions& o,
                                                               const AdaptiveThresholds& a) {
  State& st = *state_;
  if (Status s = bind_inputs(st, o, &a, nullptr); !s.ok()) return s;
  deferred::ShadeResult r;
  // One implementation of the technique: gl::AdaptiveSupersampler (deferred_renderer_component.cpp)
  // with deferred_shading.glsl's shading as its hook; m = 1 has no window to adapt.
  if (st.m >= 2) {
    if (Status s = shade_with_component(st, 0, &a, r); !s.ok()) return s;
    return r;
  }
  PassTimer timer;
  if (Status s = run_method(st, timer, deferred::GpuMethod::adaptive); !s.ok()) return s;
  if (Status s = read_timed_result(st, timer, r); !s.ok()) return s;
  return r;
}

Result<deferred::ShadeResult> DeferredRenderer::shade_edge_per_sample(
    const deferred::ShadingOptions& o, const deferred::EdgePerSampleOptions& e) {
  State& st = *state_;
  if (Status s = bind_inputs(st, o, nullptr, &e); !s.ok()) return s;
  deferred::ShadeResult r;
  PassTimer timer;
  if (Status s = run_method(st, timer, deferred::GpuMethod::edge_per_sample); !s.ok()) return s;
  if (Status s = read_timed_result(st, timer, r); !s.ok()) return s;
  return r;
}

Result<deferred::FxaaResult> DeferredRenderer::shade_default_fxaa(const deferred::ShadingOptions& o,
                                                                  const deferred::FxaaOptions& f) {
  State& st = *state_;
  if (Status s = deferred::gpu_fxaa_defines(f).status(); !s.ok()) return s;
  if (Status s = bind_inputs(st, o, nullptr, nullptr); !s.ok()) return s;
  deferred::FxaaResult r;
  PassTimer timer;
  if (Status s = run_method(st, timer, deferred::GpuMethod::fxaa, f); !s.ok()) return s;
  if (Status s = finish(timer, r.passes); !s.ok()) return s;
  Result<ImageRGBA8> img = read_rgba8(st, st.rgba8_out_buf);
  if (!img) return img.status();
  r.image = std::move(*img);
  return r;
}

Result<deferred::FxaaResult> DeferredRenderer::fxaa(const ImageRGBA8& image,
                                                    const deferred::FxaaOptions& f) {
  State& st = *state_;
  if (image.empty()) return Status::error(ErrorCode::invalid_argument, "fxaa: empty image");
  Result<std::vector<std::string>> fd = deferred::gpu_fxaa_defines(f);
  if (!fd) return fd.status();
  // The pass runs over w x h = the image's size: temporarily use its size for the buffers.
  if (!st.fbo) {
    return Status::error(ErrorCode::invalid_argument,
                         "deferred GL: fxaa needs a G-buffer first (it sets the programs' m)");
  }
  const int saved_w = st.w, saved_h = st.h;
  st.w = image.width;
  st.h = image.height;
  Status bound = bind_inputs(st, deferred::ShadingOptions{}, nullptr, nullptr);
  deferred::FxaaResult r;
  Status s = bound;
  if (s.ok()) {
    std::vector<std::uint8_t> in(image.pixels.begin(), image.pixels.end());
    glNamedBufferData(st.rgba8_buf.get(), GLsizeiptr(in.size()), in.data(), GL_DYNAMIC_COPY);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, st.rgba8_buf.get());
    PassTimer timer;
    s = run_pass(st, timer, "fxaa", *fd);
    if (s.ok()) s = finish(timer, r.passes);
    if (s.ok()) {
      Result<ImageRGBA8> img = read_rgba8(st, st.rgba8_out_buf);
      if (img) {
        r.image = std::move(*img);
        r.image.has_alpha = image.has_alpha;
      } else {
        s = img.status();
      }
    }
  }
  st.w = saved_w;
  st.h = saved_h;
  if (!s.ok()) return s;
  return r;
}

}  // namespace tessera::gl
