// gl::AdaptiveSupersampler: GL's option checks (the driver's limits, the binding points; the
// shared checks and GLSL are src/adaptive/), the programs (one per pass) and the GL objects.
#include <algorithm>
#include <mutex>

#include "gl/adaptive_internal.h"
#include "gl/gl_api.h"
#include "tessera/glsl.h"

namespace tessera::gl {

using namespace api;

AdaptiveGlExtra adaptive_gl_extra() {
  AdaptiveGlExtra t;
  t.GetIntegeri_v = glGetIntegeri_v;
  t.GetInteger64i_v = glGetInteger64i_v;
  t.BindImageTexture = glBindImageTexture;
  t.BindBufferRange = glBindBufferRange;
  t.DispatchComputeIndirect = glDispatchComputeIndirect;
  t.IsTexture = glIsTexture;
  return t;
}

namespace {

constexpr const char* kWho = "adaptive supersampler";

Status invalid(const std::string& what) {
  return Status::error(ErrorCode::invalid_argument, std::string(kWho) + ": " + what);
}

/// A binding point: `given` checked against [0, limit - count], or the top of the range.
Result<int> binding(int given, int count, GLenum limit_enum, const char* field,
                    const char* limit_name) {
  GLint limit = 0;
  glGetIntegerv(limit_enum, &limit);
  if (given < 0) {
    if (limit < count) return invalid(std::string(limit_name) + " = " + std::to_string(limit));
    return limit - count;
  }
  if (given + count > limit) {
    return invalid(std::string(field) + " = " + std::to_string(given) + ": needs " +
                   std::to_string(count) + " below " + limit_name + " = " + std::to_string(limit));
  }
  return given;
}

/// Checks everything that needs no GL object; fills the state's derived fields.
Status check_options(AdaptiveSupersampler::State& st) {
  const AdaptiveSupersamplerOptions& o = st.options;
  if (Status s = adaptive::check_options(o, kWho, st.derived); !s.ok()) return s;
  // Limits (queries only, no objects).
  GLint max_tex = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_tex);
  if (std::int64_t(o.m) * o.width > max_tex || std::int64_t(o.m) * o.height > max_tex) {
    return Status::error(ErrorCode::too_large,
                         "adaptive supersampler: G-buffer " + std::to_string(o.m * o.width) + "x" +
                             std::to_string(o.m * o.height) +
                             " exceeds GL_MAX_TEXTURE_SIZE = " + std::to_string(max_tex));
  }
  GLint64 max_block = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
  const std::size_t work_bytes = adaptive::work_buffer_bytes(o);
  if (work_bytes > std::size_t(std::max<GLint64>(max_block, 0))) {
    return Status::error(
        ErrorCode::too_large,
        "adaptive supersampler: work buffer of " + std::to_string(work_bytes) +
            " bytes exceeds GL_MAX_SHADER_STORAGE_BLOCK_SIZE = " + std::to_string(max_block));
  }
  st.derived.list_capacity =
      adaptive::list_capacity(o, st.derived.n, std::size_t(max_block) / adaptive::kListItemBytes);
  Result<int> tu = binding(o.first_texture_unit, 4, GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS,
                           "first_texture_unit", "GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS");
  if (!tu) return tu.status();
  Result<int> ub = binding(o.uniform_binding, 1, GL_MAX_UNIFORM_BUFFER_BINDINGS, "uniform_binding",
                           "GL_MAX_UNIFORM_BUFFER_BINDINGS");
  if (!ub) return ub.status();
  Result<int> sb = binding(o.first_storage_binding, 2, GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS,
                           "first_storage_binding", "GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS");
  if (!sb) return sb.status();
  Result<int> iu =
      binding(o.first_image_unit, 2, GL_MAX_IMAGE_UNITS, "first_image_unit", "GL_MAX_IMAGE_UNITS");
  if (!iu) return iu.status();
  st.texture_unit = *tu;
  st.uniform_binding = *ub;
  st.storage_binding = *sb;
  st.image_unit = *iu;
  return Status::success();
}

/// One pass's program: the shared source and preamble (src/adaptive/) with GL's bindings.
Status compile(AdaptiveSupersampler::State& st, const std::string& pass) {
  const AdaptiveSupersamplerOptions& o = st.options;
  adaptive::GlslBindings b;
  b.gbuffer = st.texture_unit;
  b.params = st.uniform_binding;
  b.work = st.storage_binding;
  b.image = st.image_unit;
  glsl::ExpandOptions so = adaptive::pass_expand_options(o, st.derived, b, pass);
  so.shipped_dir = o.glsl_dir;
  Result<Program> p = link_program({adaptive::pass_source(o, pass)}, so);
  if (!p) {
    return Status::error(p.status().code, std::string(kWho) + ": " + p.status().message);
  }
  st.programs.emplace(pass, std::move(*p));
  return Status::success();
}

Object make_buffer(std::size_t bytes) {
  Object b = create_object(ObjectType::buffer);
  glNamedBufferData(b.get(), GLsizeiptr(std::max<std::size_t>(bytes, 16)), nullptr,
                    GL_DYNAMIC_COPY);
  return b;
}

Object make_texture(GLenum format, int w, int h) {
  Object t = create_object(ObjectType::texture, GL_TEXTURE_2D);
  glTextureStorage2D(t.get(), 1, format, w, h);
  glTextureParameteri(t.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(t.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  return t;
}

/// The parameter block (TesseraAdaptiveParams) from the options; (re)uploaded.
void upload_params(AdaptiveSupersampler::State& st) {
  const adaptive::Params params =
      adaptive::params(st.options, st.derived, st.options.width, st.options.height);
  glNamedBufferData(st.params_ubo.get(), sizeof params, &params, GL_DYNAMIC_DRAW);
}

}  // namespace

double AdaptiveOutput::total_gpu_ms() const { return tessera::total_gpu_ms(passes); }
double AdaptiveOutput::total_wall_ms() const { return tessera::total_wall_ms(passes); }

AdaptiveSupersampler::~AdaptiveSupersampler() = default;

const AdaptiveSupersamplerOptions& AdaptiveSupersampler::options() const { return state_->options; }
int AdaptiveSupersampler::texture_unit() const { return state_->texture_unit; }
int AdaptiveSupersampler::uniform_binding() const { return state_->uniform_binding; }
int AdaptiveSupersampler::storage_binding() const { return state_->storage_binding; }
int AdaptiveSupersampler::image_unit() const { return state_->image_unit; }

void AdaptiveSupersampler::set_thresholds(const AdaptiveThresholds& thresholds) {
  state_->options.thresholds = thresholds;
  upload_params(*state_);
}

Result<std::unique_ptr<AdaptiveSupersampler>> AdaptiveSupersampler::create(
    const AdaptiveSupersamplerOptions& options) {
  auto st = std::make_unique<State>();
  st->options = options;
  if (Status s = check_current_context("adaptive supersampler"); !s.ok()) return s;
  st->gl = adaptive_gl_extra();
  if (Status s = check_options(*st); !s.ok()) return s;

  for (const std::string& p : adaptive::pass_programs(options.schedule)) {
    if (Status s = compile(*st, p); !s.ok()) return s;
  }

  const AdaptiveSupersamplerOptions& o = st->options;
  st->params_ubo = create_object(ObjectType::buffer);
  upload_params(*st);

  st->work_buf = make_buffer(adaptive::work_buffer_bytes(o));
  // std430: the items (8 bytes each), the colours from the next multiple of 16 bytes.
  const std::size_t items = st->derived.list_capacity;
  st->list_buf = make_buffer((items * 8 + 15) / 16 * 16 + items * 16);
  st->colour_tex = make_texture(o.output == AdaptiveOutputFormat::rgba32f ? GL_RGBA32F : GL_RGBA16F,
                                o.width, o.height);
  if (o.sample_count_texture) st->counts_tex = make_texture(GL_R8UI, o.width, o.height);
  // Nearest, clamped: texelFetch ignores filtering, but a mipmap filter on a one-level
  // mutable texture would make it incomplete (reads of 0).
  st->sampler = create_object(ObjectType::sampler);
  glSamplerParameteri(st->sampler.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glSamplerParameteri(st->sampler.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glSamplerParameteri(st->sampler.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glSamplerParameteri(st->sampler.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  if (Status s = check_errors("adaptive supersampler: creating its buffers and textures");
      !s.ok()) {
    return s;
  }
  std::unique_ptr<AdaptiveSupersampler> r(new AdaptiveSupersampler());
  r->state_ = std::move(st);
  return r;
}

}  // namespace tessera::gl
