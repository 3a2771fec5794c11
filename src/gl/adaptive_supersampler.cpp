// AdaptiveSupersampler: options checks, the GLSL generated from the G-buffer layout (samplers
// and accessors), the programs (hook + adaptive_component.glsl per pass) and the GL objects.
#include <algorithm>
#include <mutex>

#include "gl/adaptive_internal.h"
#include "gl/gl_api.h"
#include "tessera/glsl.h"
#include "tessera/deferred.h"

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

Status invalid(const std::string& what) {
  return Status::error(ErrorCode::invalid_argument, "adaptive supersampler: " + what);
}

/// The GLSL swizzle (xyzw letters) of `c`, checked against `width` channels.
Result<std::string> swizzle(const AdaptiveChannel& c, int width, const char* what) {
  const std::string field = std::string("layout.") + what;
  if (c.texture < 0 || c.texture > 3) {
    return invalid(field + ".texture = " + std::to_string(c.texture) + " (a slot 0..3)");
  }
  if (int(c.channels.size()) != width) {
    return invalid(field + ".channels = \"" + c.channels + "\": needs " + std::to_string(width) +
                   " channel" + (width > 1 ? "s" : ""));
  }
  const bool rgba = c.channels.find_first_of("rgba") != std::string::npos;
  std::string out;
  for (char ch : c.channels) {
    const std::string set = rgba ? "rgba" : "xyzw";
    const std::size_t at = set.find(ch);
    if (at == std::string::npos) {
      return invalid(field + ".channels = \"" + c.channels +
                     "\": use the letters of one set, rgba or xyzw");
    }
    out += "xyzw"[at];
  }
  return out;
}

int max_channel(const std::string& xyzw) {
  int m = 0;
  for (char ch : xyzw) m = std::max(m, int(std::string("xyzw").find(ch)) + 1);
  return m;
}

/// One accessor: `type name(ivec2 g)` reading `c` with its swizzle, scale and bias.
std::string accessor(const char* type, const char* name, const AdaptiveChannel& c,
                     const std::string& sw, int width) {
  std::string expr = "texelFetch(tessera_aa_gbuffer" + std::to_string(c.texture) + ", g, 0)." + sw;
  if (c.scale != 1.0f) expr = "(" + expr + " * " + glsl::float_literal(c.scale) + ")";
  if (c.bias != 0.0f) {
    expr = "(" + expr + " + " + (width > 1 ? std::string(type) + "(" : "") + glsl::float_literal(c.bias) +
           (width > 1 ? ")" : "") + ")";
  }
  return std::string(type) + " " + name + "(ivec2 g) { return " + expr + "; }";
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
  if (o.m < 2 || o.m > 8) return invalid("m = " + std::to_string(o.m) + " (2..8)");
  if (o.width <= 0 || o.height <= 0) {
    return invalid("size " + std::to_string(o.width) + "x" + std::to_string(o.height));
  }
  const std::size_t pixels = std::size_t(o.width) * std::size_t(o.height);
  if (pixels > kAdaptiveMaxPixels) {
    return Status::error(ErrorCode::too_large, "adaptive supersampler: " + std::to_string(pixels) +
                                                   " pixels exceed 2^26");
  }
  if (!(o.hdr_exposure > 0.0f) || !std::isfinite(o.hdr_exposure)) {
    return invalid("hdr_exposure = " + glsl::float_literal(o.hdr_exposure) + " (> 0)");
  }
  if (o.hook.source.find("tessera_shade_sample") == std::string::npos) {
    return invalid("hook '" + o.hook.name +
                   "' does not define vec4 tessera_shade_sample(ivec2 grid_texel, float "
                   "footprint)");
  }
  st.n = o.m * o.m;
  if (o.sample_order.empty()) {
    const std::span<const std::uint8_t> def = deferred::sample_order(o.m);
    st.order.assign(def.begin(), def.end());
  } else {
    st.order = o.sample_order;
    std::vector<std::uint8_t> sorted = st.order;
    std::sort(sorted.begin(), sorted.end());
    bool perm = int(sorted.size()) == st.n;
    for (int i = 0; perm && i < st.n; ++i) perm = sorted[std::size_t(i)] == i;
    if (!perm) {
      return invalid("sample_order is not a permutation of 0.." + std::to_string(st.n - 1));
    }
  }
  const bool has_uv = o.layout.uv.texture >= 0, has_duv = o.layout.uv_derivatives.texture >= 0;
  if (has_uv != has_duv) return invalid("layout.uv and layout.uv_derivatives: both or neither");
  struct Q {
    const AdaptiveChannel* c;
    int width;
    const char* what;
  };
  std::vector<Q> qs = {
      {&o.layout.depth, 1, "depth"}, {&o.layout.normal, 3, "normal"}, {&o.layout.id, 1, "id"}};
  if (has_uv) {
    qs.push_back({&o.layout.uv, 2, "uv"});
    qs.push_back({&o.layout.uv_derivatives, 4, "uv_derivatives"});
  }
  for (const Q& q : qs) {
    Result<std::string> sw = swizzle(*q.c, q.width, q.what);
    if (!sw) return sw.status();
    st.slot_used[q.c->texture] = true;
    st.slot_channels[q.c->texture] = std::max(st.slot_channels[q.c->texture], max_channel(*sw));
  }
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
  const std::size_t work_bytes = (kAdaptiveHeaderUints + kAdaptiveHistogramUints + 4 * pixels) * 4;
  if (work_bytes > std::size_t(std::max<GLint64>(max_block, 0))) {
    return Status::error(
        ErrorCode::too_large,
        "adaptive supersampler: work buffer of " + std::to_string(work_bytes) +
            " bytes exceeds GL_MAX_SHADER_STORAGE_BLOCK_SIZE = " + std::to_string(max_block));
  }
  st.list_capacity = o.list_capacity > 0 ? o.list_capacity : pixels * std::size_t(o.m * o.m / 2);
  st.list_capacity = std::min<std::size_t>(
      {st.list_capacity, std::size_t(max_block) / kAdaptiveListItemBytes, 0x7fffffffu});
  if (o.schedule != AdaptiveSchedule::frame_list) st.list_capacity = 1;  // no list
  st.list_capacity = std::max<std::size_t>(st.list_capacity, 1);
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

/// The preamble: version, defines, G-buffer samplers and accessors.
std::vector<std::string> preamble(const AdaptiveSupersampler::State& st, const std::string& pass) {
  const AdaptiveSupersamplerOptions& o = st.options;
  std::vector<std::string> p = {
      "#version 450 core",
      "#define TESSERA_AA_M " + std::to_string(o.m),
      "#define TESSERA_AA_N " + std::to_string(st.n),
      "#define TESSERA_ADAPTIVE_MAX_N " + std::to_string(st.n),
      "#define TESSERA_AA_WIDTH " + std::to_string(o.width),
      "#define TESSERA_AA_HEIGHT " + std::to_string(o.height),
      "#define TESSERA_AA_LIST_CAPACITY " + std::to_string(st.list_capacity),
      "#define TESSERA_AA_UBO_BINDING " + std::to_string(st.uniform_binding),
      "#define TESSERA_AA_WORK_BINDING " + std::to_string(st.storage_binding),
      "#define TESSERA_AA_IMAGE_UNIT " + std::to_string(st.image_unit),
      std::string("#define TESSERA_AA_OUT_FORMAT ") +
          (o.output == AdaptiveOutputFormat::rgba32f ? "rgba32f" : "rgba16f"),
      "#define TESSERA_AA_PASS_" + pass};
  if (o.layout.uv.texture >= 0) p.push_back("#define TESSERA_AA_HAS_UV 1");
  if (o.sample_count_texture) p.push_back("#define TESSERA_AA_SAMPLE_COUNTS 1");
  if (o.resolve == AdaptiveResolve::tonemap_weighted) p.push_back("#define TESSERA_AA_HDR 1");
  if (pass == "EXTRA") {
    const bool tile = o.schedule == AdaptiveSchedule::tile_list && o.m <= 4;
    p.push_back(tile ? "#define TESSERA_AA_SCHEDULE_TILE 1" : "#define TESSERA_AA_SCHEDULE_LOOP 1");
  }
  for (int s = 0; s < 4; ++s) {
    if (!st.slot_used[s]) continue;
    p.push_back("layout(binding = " + std::to_string(st.texture_unit + s) +
                ") uniform sampler2D tessera_aa_gbuffer" + std::to_string(s) + ";");
  }
  const AdaptiveGBufferLayout& l = o.layout;
  // The swizzles were checked by check_options.
  p.push_back(accessor("float", "tessera_aa_depth", l.depth, *swizzle(l.depth, 1, "depth"), 1));
  p.push_back(accessor("vec3", "tessera_aa_normal", l.normal, *swizzle(l.normal, 3, "normal"), 3));
  p.push_back(accessor("float", "tessera_aa_id_value", l.id, *swizzle(l.id, 1, "id"), 1));
  // As the CPU's lround: half away from zero.
  p.push_back(
      "int tessera_aa_id(ivec2 g) { float v = tessera_aa_id_value(g); "
      "return int(floor(abs(v) + 0.5)) * (v < 0.0 ? -1 : 1); }");
  if (l.uv.texture >= 0) {
    p.push_back(accessor("vec2", "tessera_aa_uv", l.uv, *swizzle(l.uv, 2, "uv"), 2));
    p.push_back(accessor("vec4", "tessera_aa_uv_derivatives", l.uv_derivatives,
                         *swizzle(l.uv_derivatives, 4, "uv_derivatives"), 4));
  }
  return p;
}

/// Passes that shade (compiled with the hook); the others get a stub.
bool shades(const std::string& pass) {
  return pass == "FIRST" || pass == "EXTRA" || pass == "SHADE" || pass == "RESOLVE" ||
         pass == "REFERENCE";
}

Status compile(AdaptiveSupersampler::State& st, const std::string& pass) {
  const AdaptiveSupersamplerOptions& o = st.options;
  glsl::Source src;
  src.stage = glsl::Stage::compute;
  if (shades(pass)) {
    src.name = o.hook.name;
    src.text = o.hook.source;
  } else {
    src.name = "adaptive_component.glsl (" + pass + ")";
    src.text = "vec4 tessera_shade_sample(ivec2 g, float f) { return vec4(0.0); }";
  }
  src.text += "\n#include \"adaptive_component.glsl\"\n";
  glsl::ExpandOptions so;
  so.include_paths = o.hook.include_paths;
  so.shipped_dir = o.glsl_dir;
  so.preamble = preamble(st, pass);
  Result<Program> p = link_program({src}, so);
  if (!p) {
    return Status::error(p.status().code, "adaptive supersampler: " + p.status().message);
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

/// The parameter block (TesseraAaParams) from the options; (re)uploaded.
void upload_params(AdaptiveSupersampler::State& st) {
  const AdaptiveSupersamplerOptions& o = st.options;
  AdaptiveParams params{};
  params.size[0] = o.width;
  params.size[1] = o.height;
  params.size[2] = o.m;
  params.size[3] = st.n;
  params.flags[0] = o.thresholds.force_k >= 0 ? std::min(o.thresholds.force_k, st.n - 1) : -1;
  params.flags[1] = (o.thresholds.use_geometry ? 1 : 0) | (o.thresholds.use_shading ? 2 : 0);
  params.flags[3] = int(st.list_capacity);
  params.metric[0] = o.thresholds.c_depth;
  params.metric[1] = o.thresholds.c_normal;
  params.metric[2] = o.thresholds.c_shade;
  params.metric[3] = o.thresholds.t_min;
  params.metric2[0] = o.thresholds.t_edge;
  params.metric2[1] = o.thresholds.seam_factor;
  params.metric2[2] = o.hdr_exposure;
  for (int i = 0; i < st.n; ++i) params.order[i] = st.order[std::size_t(i)];
  glNamedBufferData(st.params_ubo.get(), sizeof params, &params, GL_DYNAMIC_DRAW);
}

}  // namespace

double AdaptiveFrameResult::total_wall_ms() const {
  double t = 0;
  for (const PassTime& p : wall_passes) t += p.ms;
  return t;
}

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

  std::vector<std::string> passes = {"FIRST",  "METRICS", "HISTOGRAM",
                                     "SELECT", "APPLY",   "REFERENCE"};
  if (options.schedule == AdaptiveSchedule::frame_list) {
    passes.insert(passes.end(), {"LIST", "ARGS", "SHADE", "RESOLVE"});
  } else {
    passes.push_back("EXTRA");
  }
  for (const std::string& p : passes) {
    if (Status s = compile(*st, p); !s.ok()) return s;
  }

  const AdaptiveSupersamplerOptions& o = st->options;
  st->params_ubo = create_object(ObjectType::buffer);
  upload_params(*st);

  const std::size_t pixels = std::size_t(o.width) * std::size_t(o.height);
  st->work_buf = make_buffer((kAdaptiveHeaderUints + kAdaptiveHistogramUints + 4 * pixels) * 4);
  // std430: the items (8 bytes each), the colours from the next multiple of 16 bytes.
  st->list_buf = make_buffer((st->list_capacity * 8 + 15) / 16 * 16 + st->list_capacity * 16);
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
