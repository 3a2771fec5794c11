// AdaptiveSupersampler: one frame — the G-buffer textures checked, the engine's GL state saved,
// the passes of adaptive_component.glsl (S, metrics, budget, extra samples, resolve) dispatched,
// the state put back.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/check.h"
#include "gl/adaptive_internal.h"
#include "gl/gl_api.h"

namespace tessera::gl {

using namespace api;

namespace {

using State = AdaptiveSupersampler::State;

/// Channel count of the float/normalised colour formats a sampler2D reads; 0 = refused.
int format_channels(GLint f) {
  switch (f) {
    case GL_R8:
    case GL_R8_SNORM:
    case GL_R16:
    case GL_R16_SNORM:
    case GL_R16F:
    case GL_R32F:
      return 1;
    case GL_RG8:
    case GL_RG8_SNORM:
    case GL_RG16:
    case GL_RG16_SNORM:
    case GL_RG16F:
    case GL_RG32F:
      return 2;
    case GL_RGB8:
    case GL_RGB8_SNORM:
    case GL_RGB16:
    case GL_RGB16_SNORM:
    case GL_RGB16F:
    case GL_RGB32F:
    case GL_R11F_G11F_B10F:
    case GL_RGB9_E5:
      return 3;
    case GL_RGBA8:
    case GL_RGBA8_SNORM:
    case GL_RGBA16:
    case GL_RGBA16_SNORM:
    case GL_RGBA16F:
    case GL_RGBA32F:
    case GL_RGB10_A2:
      return 4;
    default:
      return 0;
  }
}

std::string hex(GLint v) {
  char b[16];
  std::snprintf(b, sizeof b, "0x%04X", unsigned(v));
  return b;
}

/// Checks the frame's textures against the layout (no GL state changed, no error raised).
Status check_frame(const State& st, const AdaptiveFrame& f, AdaptiveExtent size) {
  const AdaptiveSupersamplerOptions& o = st.options;
  if (Status s = adaptive::check_budget(f.budget, "adaptive supersampler"); !s.ok()) return s;
  if (size.width <= 0 || size.height <= 0 || size.width > o.width || size.height > o.height) {
    return Status::error(
        ErrorCode::too_large,
        "adaptive supersampler: render size " + std::to_string(f.render_size.width) + "x" +
            std::to_string(f.render_size.height) + " (1.." + std::to_string(o.width) + " x 1.." +
            std::to_string(o.height) + ", the largest size of the options)");
  }
  const int gw = o.m * size.width, gh = o.m * size.height;
  for (int s = 0; s < 4; ++s) {
    if (!st.derived.slot_used[s]) continue;
    const std::string slot = "adaptive supersampler: G-buffer slot " + std::to_string(s);
    const GLuint t = f.gbuffer[std::size_t(s)];
    if (t == 0 || !st.gl.IsTexture(t)) {
      return Status::error(ErrorCode::invalid_argument,
                           slot + ": texture " + std::to_string(t) +
                               (t == 0 ? " missing (the layout reads it)" : " is not a texture"));
    }
    GLint target = 0, w = 0, h = 0, fmt = 0;
    glGetTextureParameteriv(t, GL_TEXTURE_TARGET, &target);
    if (target != GL_TEXTURE_2D) {
      return Status::error(ErrorCode::invalid_argument,
                           slot + ": texture " + std::to_string(t) + " is not a GL_TEXTURE_2D");
    }
    glGetTextureLevelParameteriv(t, 0, GL_TEXTURE_WIDTH, &w);
    glGetTextureLevelParameteriv(t, 0, GL_TEXTURE_HEIGHT, &h);
    glGetTextureLevelParameteriv(t, 0, GL_TEXTURE_INTERNAL_FORMAT, &fmt);
    if (w < gw || h < gh) {
      return Status::error(
          ErrorCode::size_mismatch,
          slot + ": texture " + std::to_string(t) + " is " + std::to_string(w) + "x" +
              std::to_string(h) + ", smaller than the G-buffer " + std::to_string(gw) + "x" +
              std::to_string(gh) + " (m = " + std::to_string(o.m) + ", render size " +
              std::to_string(size.width) + "x" + std::to_string(size.height) + ")");
    }
    const int channels = format_channels(fmt);
    if (channels == 0) {
      return Status::error(ErrorCode::invalid_argument,
                           slot + ": texture " + std::to_string(t) + " has internal format " +
                               hex(fmt) +
                               ", not a float or normalised colour format (integer and sRGB "
                               "formats are not read)");
    }
    if (channels < st.derived.slot_channels[s]) {
      return Status::error(ErrorCode::invalid_argument,
                           slot + ": texture " + std::to_string(t) + " (format " + hex(fmt) +
                               ") has " + std::to_string(channels) +
                               " channels, the layout reads channel " +
                               std::to_string(st.derived.slot_channels[s]) + " of it");
    }
  }
  return Status::success();
}

/// The engine's GL state that a dispatch changes; restored by the destructor.
class StateGuard {
 public:
  StateGuard(const State& st) : st_(st) {
    glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active_);
    for (int u = 0; u < 4; ++u) {
      glActiveTexture(GLenum(GL_TEXTURE0 + st.texture_unit + u));
      glGetIntegerv(GL_TEXTURE_BINDING_2D, &tex_[u]);
      glGetIntegerv(GL_SAMPLER_BINDING, &samplers_[u]);
    }
    glActiveTexture(GLenum(active_));
    save(GL_UNIFORM_BUFFER, GL_UNIFORM_BUFFER_BINDING, GL_UNIFORM_BUFFER_START,
         GL_UNIFORM_BUFFER_SIZE, st.uniform_binding, ubo_);
    for (int i = 0; i < 2; ++i) {
      save(GL_SHADER_STORAGE_BUFFER, GL_SHADER_STORAGE_BUFFER_BINDING,
           GL_SHADER_STORAGE_BUFFER_START, GL_SHADER_STORAGE_BUFFER_SIZE, st.storage_binding + i,
           ssbo_[i]);
    }
    glGetIntegerv(GL_UNIFORM_BUFFER_BINDING, &generic_ubo_);
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &generic_ssbo_);
    glGetIntegerv(GL_DISPATCH_INDIRECT_BUFFER_BINDING, &indirect_);
    for (int i = 0; i < 2; ++i) {
      const GLuint u = GLuint(st.image_unit + i);
      Image& im = images_[i];
      st.gl.GetIntegeri_v(GL_IMAGE_BINDING_NAME, u, &im.name);
      st.gl.GetIntegeri_v(GL_IMAGE_BINDING_LEVEL, u, &im.level);
      st.gl.GetIntegeri_v(GL_IMAGE_BINDING_LAYERED, u, &im.layered);
      st.gl.GetIntegeri_v(GL_IMAGE_BINDING_LAYER, u, &im.layer);
      st.gl.GetIntegeri_v(GL_IMAGE_BINDING_ACCESS, u, &im.access);
      st.gl.GetIntegeri_v(GL_IMAGE_BINDING_FORMAT, u, &im.format);
    }
  }
  ~StateGuard() {
    glUseProgram(GLuint(program_));
    for (int u = 0; u < 4; ++u) {
      glActiveTexture(GLenum(GL_TEXTURE0 + st_.texture_unit + u));
      glBindTexture(GL_TEXTURE_2D, GLuint(tex_[u]));
      glBindSampler(GLuint(st_.texture_unit + u), GLuint(samplers_[u]));
    }
    glActiveTexture(GLenum(active_));
    restore(GL_UNIFORM_BUFFER, st_.uniform_binding, ubo_);
    for (int i = 0; i < 2; ++i)
      restore(GL_SHADER_STORAGE_BUFFER, st_.storage_binding + i, ssbo_[i]);
    glBindBuffer(GL_UNIFORM_BUFFER, GLuint(generic_ubo_));
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, GLuint(generic_ssbo_));
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, GLuint(indirect_));
    for (int i = 0; i < 2; ++i) {
      const Image& im = images_[i];
      // An unbound unit reads back format GL_R8 (the initial value); 0 is not a valid format.
      st_.gl.BindImageTexture(GLuint(st_.image_unit + i), GLuint(im.name), im.level,
                              GLboolean(im.layered != 0), im.layer, GLenum(im.access),
                              GLenum(im.format == 0 ? GL_R8 : im.format));
    }
  }
  StateGuard(const StateGuard&) = delete;
  StateGuard& operator=(const StateGuard&) = delete;

 private:
  struct Range {
    GLint name = 0;
    GLint64 start = 0, size = 0;
  };
  struct Image {
    GLint name = 0, level = 0, layered = 0, layer = 0, access = GL_READ_ONLY, format = GL_R8;
  };
  void save(GLenum, GLenum name_q, GLenum start_q, GLenum size_q, int index, Range& r) {
    st_.gl.GetIntegeri_v(name_q, GLuint(index), &r.name);
    st_.gl.GetInteger64i_v(start_q, GLuint(index), &r.start);
    st_.gl.GetInteger64i_v(size_q, GLuint(index), &r.size);
  }
  void restore(GLenum target, int index, const Range& r) {
    if (r.name != 0 && r.size > 0) {
      st_.gl.BindBufferRange(target, GLuint(index), GLuint(r.name), GLintptr(r.start),
                             GLsizeiptr(r.size));
    } else {
      glBindBufferBase(target, GLuint(index), GLuint(r.name));
    }
  }
  const State& st_;
  GLint program_ = 0, active_ = GL_TEXTURE0, tex_[4] = {}, samplers_[4] = {};
  Range ubo_, ssbo_[2];
  GLint generic_ubo_ = 0, generic_ssbo_ = 0, indirect_ = 0;
  Image images_[2];
};

/// Binds the component's resources (inside a StateGuard).
void bind(const State& st, const AdaptiveFrame& f) {
  for (int s = 0; s < 4; ++s) {
    if (!st.derived.slot_used[s]) continue;
    glBindTextureUnit(GLuint(st.texture_unit + s), f.gbuffer[std::size_t(s)]);
    glBindSampler(GLuint(st.texture_unit + s), st.sampler.get());
  }
  glBindBufferBase(GL_UNIFORM_BUFFER, GLuint(st.uniform_binding), st.params_ubo.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GLuint(st.storage_binding), st.work_buf.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GLuint(st.storage_binding + 1), st.list_buf.get());
  const GLenum out_format =
      st.options.output == AdaptiveOutputFormat::rgba32f ? GL_RGBA32F : GL_RGBA16F;
  st.gl.BindImageTexture(GLuint(st.image_unit), st.colour_tex.get(), 0, GL_FALSE, 0, GL_WRITE_ONLY,
                         out_format);
  if (st.counts_tex) {
    st.gl.BindImageTexture(GLuint(st.image_unit + 1), st.counts_tex.get(), 0, GL_FALSE, 0,
                           GL_WRITE_ONLY, GL_R8UI);
  }
}

constexpr GLbitfield kBarriers = GL_SHADER_STORAGE_BARRIER_BIT |
                                 GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_COMMAND_BARRIER_BIT |
                                 GL_UNIFORM_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT;

/// Dispatches the passes of one frame, timed when profiling.
class Runner {
 public:
  Runner(State& st, AdaptiveExtent size) : st_(st), size_(size) {}

  /// One pass: `groups_x` = 0 means one group per 8x8 output pixels; `indirect` = from the
  /// work buffer's group counts.
  /// `then`: a one-group program dispatched after it within the same timed pass.
  Status pass(const std::string& name, const std::string& program, GLuint groups_x = 0,
              bool indirect = false, const char* then = nullptr) {
    const Program& p = st_.programs.at(program);
    std::chrono::steady_clock::time_point t0;
    if (st_.options.profile) {
      glFinish();
      t0 = std::chrono::steady_clock::now();
      if (Status s = timer_.begin(name); !s.ok()) return s;
    }
    glUseProgram(p.get());
    if (indirect) {
      glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, st_.work_buf.get());
      st_.gl.DispatchComputeIndirect(GLintptr(2 * 4));
    } else if (groups_x > 0) {
      glDispatchCompute(groups_x, 1, 1);
    } else {
      glDispatchCompute(GLuint((size_.width + 7) / 8), GLuint((size_.height + 7) / 8), 1);
    }
    glMemoryBarrier(kBarriers);
    if (then != nullptr) {
      glUseProgram(st_.programs.at(then).get());
      glDispatchCompute(1, 1, 1);
      glMemoryBarrier(kBarriers);
    }
    if (st_.options.profile) {
      // llvmpipe runs a dispatch when the batch is flushed: glFinish inside the query.
      glFinish();
      wall_.push_back(
          {name, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                     .count()});
      if (Status s = timer_.end(); !s.ok()) return s;
    }
    return Status::success();
  }

  Status finish(AdaptiveOutput& r) {
    if (!st_.options.profile) return Status::success();
    r.passes = wall_;  // the names and host times, one per pass
    Result<std::vector<PassTime>> t = timer_.collect();
    if (!t) return t.status().code == ErrorCode::unsupported ? Status::success() : t.status();
    TESSERA_DCHECK(t->size() == r.passes.size());  // one query and one host time per pass
    for (std::size_t i = 0; i < r.passes.size() && i < t->size(); ++i) {
      TESSERA_DCHECK((*t)[i].pass == r.passes[i].pass);
      r.passes[i].gpu_ms = (*t)[i].gpu_ms;
    }
    return Status::success();
  }

 private:
  State& st_;
  AdaptiveExtent size_;
  GpuTimer timer_;
  std::vector<PassTime> wall_;
};

using Mode = adaptive::Mode;

Result<AdaptiveOutput> run_frame(State& st, const AdaptiveFrame& f, Mode mode) {
  if (Status s = check_current_context("adaptive supersampler: dispatch"); !s.ok()) return s;
  const AdaptiveExtent size = f.render_size.width == 0 && f.render_size.height == 0
                                  ? AdaptiveExtent{st.options.width, st.options.height}
                                  : f.render_size;
  if (Status s = check_frame(st, f, size); !s.ok()) return s;
  AdaptiveOutput r;
  Status status = Status::success();
  {
    StateGuard guard(st);
    // The work header; histograms cleared when budgeted.
    const auto head = adaptive::work_header(f.budget);
    std::vector<std::uint32_t> header(head.begin(), head.end());
    if (f.budget) header.resize(header.size() + adaptive::kHistogramUints, 0u);
    glNamedBufferSubData(st.work_buf.get(), 0, GLsizeiptr(header.size() * 4), header.data());
    // The parameter block of this frame's render size and the current thresholds.
    const adaptive::Params params =
        adaptive::params(st.options, st.derived, size.width, size.height);
    glNamedBufferSubData(st.params_ubo.get(), 0, sizeof params, &params);
    bind(st, f);
    Runner run(st, size);
    for (const adaptive::Step& step :
         adaptive::frame_steps(mode, st.options.schedule, f.budget.has_value())) {
      status = run.pass(step.name, step.program, step.groups_x, step.indirect, step.then);
      if (!status.ok()) break;
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                    GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    if (status.ok()) status = run.finish(r);
    if (status.ok() && st.options.profile) {
      std::uint32_t extra = 0;
      glGetNamedBufferSubData(st.work_buf.get(), 4, 4, &extra);
      r.extra_samples = adaptive::extra_samples(
          st.options, mode, extra, std::uint64_t(size.width) * std::uint64_t(size.height));
    }
  }
  if (!status.ok()) return status;
  if (Status s = check_errors("adaptive supersampler: dispatch"); !s.ok()) return s;
  r.render_size = size;
  r.colour = st.colour_tex.get();
  r.sample_counts = st.counts_tex.get();
  return r;
}

}  // namespace

Result<AdaptiveOutput> AdaptiveSupersampler::dispatch(const AdaptiveFrame& frame) {
  return run_frame(*state_, frame, Mode::adaptive);
}
Result<AdaptiveOutput> AdaptiveSupersampler::dispatch_reference(const AdaptiveFrame& frame) {
  return run_frame(*state_, frame, Mode::reference);
}
Result<AdaptiveOutput> AdaptiveSupersampler::dispatch_first_sample(const AdaptiveFrame& frame) {
  return run_frame(*state_, frame, Mode::first);
}

}  // namespace tessera::gl
