// vk::AdaptiveSupersampler: the device and option checks, the GLSL of each pass (the G-buffer
// accessors generated from the layout, the hook, the shipped adaptive_component.glsl) compiled
// to SPIR-V, and the Vulkan objects (pipelines, descriptor sets, buffers, output images).
#include <algorithm>
#include <cmath>

#include "tessera/deferred.h"
#include "tessera/glsl.h"
#include "vk/adaptive_internal.h"
#include "vk/shader.h"

namespace tessera::vk {

namespace {

using State = AdaptiveSupersampler::State;

Status invalid(const std::string& what) {
  return Status::error(ErrorCode::invalid_argument, "vk adaptive supersampler: " + what);
}
Status unsupported(const std::string& what) {
  return Status::error(ErrorCode::unsupported, "vk adaptive supersampler: " + what);
}
Status too_large(const std::string& what) {
  return Status::error(ErrorCode::too_large, "vk adaptive supersampler: " + what);
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
  const std::string set = rgba ? "rgba" : "xyzw";
  std::string out;
  for (char ch : c.channels) {
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
  std::string expr = "texelFetch(tessera_adaptive_gbuffer" + std::to_string(c.texture) + ", g, 0)." + sw;
  if (c.scale != 1.0f) expr = "(" + expr + " * " + glsl::float_literal(c.scale) + ")";
  if (c.bias != 0.0f) {
    const std::string b = glsl::float_literal(c.bias);
    expr = "(" + expr + " + " + (width > 1 ? std::string(type) + "(" + b + ")" : b) + ")";
  }
  return std::string(type) + " " + name + "(ivec2 g) { return " + expr + "; }";
}

Status check_sample_order(State& st) {
  const AdaptiveSupersamplerOptions& o = st.options;
  if (o.sample_order.empty()) {
    const std::span<const std::uint8_t> def = deferred::sample_order(o.m);
    st.order.assign(def.begin(), def.end());
    return Status::success();
  }
  st.order = o.sample_order;
  std::vector<std::uint8_t> sorted = st.order;
  std::sort(sorted.begin(), sorted.end());
  bool perm = int(sorted.size()) == st.n;
  for (int i = 0; perm && i < st.n; ++i) perm = sorted[std::size_t(i)] == i;
  if (!perm) return invalid("sample_order is not a permutation of 0.." + std::to_string(st.n - 1));
  return Status::success();
}

Status check_layout(State& st) {
  const AdaptiveGBufferLayout& l = st.options.layout;
  const bool has_uv = l.uv.texture >= 0, has_duv = l.uv_derivatives.texture >= 0;
  if (has_uv != has_duv) return invalid("layout.uv and layout.uv_derivatives: both or neither");
  struct Q {
    const AdaptiveChannel* c;
    int width;
    const char* what;
  };
  std::vector<Q> qs = {{&l.depth, 1, "depth"}, {&l.normal, 3, "normal"}, {&l.id, 1, "id"}};
  if (has_uv) {
    qs.push_back({&l.uv, 2, "uv"});
    qs.push_back({&l.uv_derivatives, 4, "uv_derivatives"});
  }
  for (const Q& q : qs) {
    Result<std::string> sw = swizzle(*q.c, q.width, q.what);
    if (!sw) return sw.status();
    st.slot_used[q.c->texture] = true;
    st.slot_channels[q.c->texture] = std::max(st.slot_channels[q.c->texture], max_channel(*sw));
  }
  return Status::success();
}

/// A storage-image format the device must support (optimal tiling).
Status check_storage_format(const State& st, VkFormat f, const char* name) {
  VkFormatProperties p{};
  st.api.GetPhysicalDeviceFormatProperties(st.api.ctx.physical_device, f, &p);
  if ((p.optimalTilingFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT) == 0) {
    return unsupported(std::string("the device cannot store to ") + name + " images");
  }
  return Status::success();
}

/// Checks everything that needs no Vulkan object; fills the state's derived fields.
Status check_options(State& st) {
  const AdaptiveSupersamplerOptions& o = st.options;
  if (o.m < 2 || o.m > 8) return invalid("m = " + std::to_string(o.m) + " (2..8)");
  if (o.width <= 0 || o.height <= 0) {
    return invalid("size " + std::to_string(o.width) + "x" + std::to_string(o.height));
  }
  const std::size_t pixels = std::size_t(o.width) * std::size_t(o.height);
  if (pixels > kAdaptiveMaxPixels) return too_large(std::to_string(pixels) + " pixels exceed 2^26");
  if (!(o.hdr_exposure > 0.0f) || !std::isfinite(o.hdr_exposure)) {
    return invalid("hdr_exposure = " + glsl::float_literal(o.hdr_exposure) + " (> 0)");
  }
  if (o.descriptor_sets < 1 || o.descriptor_sets > 1024) {
    return invalid("descriptor_sets = " + std::to_string(o.descriptor_sets) + " (1..1024)");
  }
  if (o.hook.source.find("tessera_shade_sample") == std::string::npos) {
    return invalid("hook '" + o.hook.name +
                   "' does not define vec4 tessera_shade_sample(ivec2 grid_texel, float "
                   "footprint)");
  }
  for (std::size_t i = 0; i < o.hook.set_layouts.size(); ++i) {
    if (o.hook.set_layouts[i] == VK_NULL_HANDLE) {
      return invalid("hook.set_layouts[" + std::to_string(i) + "] is VK_NULL_HANDLE");
    }
  }
  st.n = o.m * o.m;
  st.set_index = std::uint32_t(o.hook.set_layouts.size());
  if (Status s = check_sample_order(st); !s.ok()) return s;
  if (Status s = check_layout(st); !s.ok()) return s;
  const VkPhysicalDeviceLimits& lim = st.api.properties.limits;
  if (st.set_index + 1 > lim.maxBoundDescriptorSets) {
    return unsupported(std::to_string(st.set_index) +
                       " hook sets + 1 exceed maxBoundDescriptorSets = " +
                       std::to_string(lim.maxBoundDescriptorSets));
  }
  if (std::uint64_t(o.m) * std::uint64_t(o.width) > lim.maxImageDimension2D ||
      std::uint64_t(o.m) * std::uint64_t(o.height) > lim.maxImageDimension2D) {
    return too_large("G-buffer " + std::to_string(o.m * o.width) + "x" +
                     std::to_string(o.m * o.height) +
                     " exceeds maxImageDimension2D = " + std::to_string(lim.maxImageDimension2D));
  }
  const std::uint32_t gx = std::uint32_t((o.width + 7) / 8), gy = std::uint32_t((o.height + 7) / 8);
  if (gx > lim.maxComputeWorkGroupCount[0] || gy > lim.maxComputeWorkGroupCount[1]) {
    return too_large("output " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                     " exceeds maxComputeWorkGroupCount");
  }
  const std::size_t work_bytes = (kAdaptiveHeaderUints + kAdaptiveHistogramUints + 4 * pixels) * 4;
  if (work_bytes > lim.maxStorageBufferRange) {
    return too_large(
        "work buffer of " + std::to_string(work_bytes) +
        " bytes exceeds maxStorageBufferRange = " + std::to_string(lim.maxStorageBufferRange));
  }
  st.list_capacity = o.list_capacity > 0 ? o.list_capacity : pixels * std::size_t(st.n / 2);
  st.list_capacity = std::min<std::size_t>(
      {st.list_capacity, (std::size_t(lim.maxStorageBufferRange) - 16) / kAdaptiveListItemBytes,
       0x7fffffffu});
  if (o.schedule != AdaptiveSchedule::frame_list) st.list_capacity = 1;  // no list
  st.list_capacity = std::max<std::size_t>(st.list_capacity, 1);
  if (!st.api.ctx.enabled_features.shaderFloat64) {
    return unsupported(
        "needs the device feature shaderFloat64 (the depth metric's variance is computed in "
        "double, as on the CPU and GL), not enabled in DeviceContext::enabled_features");
  }
  if (o.sample_count_texture) {
    if (!st.api.ctx.enabled_features.shaderStorageImageExtendedFormats) {
      return unsupported(
          "sample_count_texture needs the device feature shaderStorageImageExtendedFormats "
          "(r8ui storage images), not enabled in DeviceContext::enabled_features");
    }
    if (Status s = check_storage_format(st, VK_FORMAT_R8_UINT, "R8_UINT"); !s.ok()) return s;
  }
  const bool f32 = o.output == AdaptiveOutputFormat::rgba32f;
  return check_storage_format(st,
                              f32 ? VK_FORMAT_R32G32B32A32_SFLOAT : VK_FORMAT_R16G16B16A16_SFLOAT,
                              f32 ? "R32G32B32A32_SFLOAT" : "R16G16B16A16_SFLOAT");
}

/// The preamble: version, defines, G-buffer samplers and accessors (the GL component's, with
/// Vulkan's set and bindings).
std::vector<std::string> preamble(const State& st, const std::string& pass) {
  const AdaptiveSupersamplerOptions& o = st.options;
  const std::string set = std::to_string(st.set_index);
  std::vector<std::string> p = {
      "#version 450 core",
      "#define TESSERA_ADAPTIVE_M " + std::to_string(o.m),
      "#define TESSERA_ADAPTIVE_N " + std::to_string(st.n),
      "#define TESSERA_ADAPTIVE_MAX_N " + std::to_string(st.n),
      "#define TESSERA_ADAPTIVE_WIDTH " + std::to_string(o.width),
      "#define TESSERA_ADAPTIVE_HEIGHT " + std::to_string(o.height),
      "#define TESSERA_ADAPTIVE_LIST_CAPACITY " + std::to_string(st.list_capacity),
      "#define TESSERA_ADAPTIVE_SET " + set,
      "#define TESSERA_ADAPTIVE_UBO_BINDING " + std::to_string(kBindParams),
      "#define TESSERA_ADAPTIVE_WORK_BINDING " + std::to_string(kBindWork),
      "#define TESSERA_ADAPTIVE_IMAGE_UNIT " + std::to_string(kBindColour),
      std::string("#define TESSERA_ADAPTIVE_OUT_FORMAT ") +
          (o.output == AdaptiveOutputFormat::rgba32f ? "rgba32f" : "rgba16f"),
      "#define TESSERA_ADAPTIVE_PASS_" + pass};
  if (o.layout.uv.texture >= 0) p.push_back("#define TESSERA_ADAPTIVE_HAS_UV 1");
  if (o.sample_count_texture) p.push_back("#define TESSERA_ADAPTIVE_SAMPLE_COUNTS 1");
  if (o.resolve == AdaptiveResolve::tonemap_weighted) p.push_back("#define TESSERA_ADAPTIVE_HDR 1");
  if (pass == "EXTRA") {
    const bool tile = o.schedule == AdaptiveSchedule::tile_list && o.m <= 4;
    p.push_back(tile ? "#define TESSERA_ADAPTIVE_SCHEDULE_TILE 1" : "#define TESSERA_ADAPTIVE_SCHEDULE_LOOP 1");
  }
  for (int s = 0; s < 4; ++s) {
    if (!st.slot_used[s]) continue;
    p.push_back("layout(set = " + set + ", binding = " + std::to_string(int(kBindGBuffer) + s) +
                ") uniform sampler2D tessera_adaptive_gbuffer" + std::to_string(s) + ";");
  }
  const AdaptiveGBufferLayout& l = o.layout;
  // The swizzles were checked by check_options.
  p.push_back(accessor("float", "tessera_adaptive_depth", l.depth, *swizzle(l.depth, 1, "depth"), 1));
  p.push_back(accessor("vec3", "tessera_adaptive_normal", l.normal, *swizzle(l.normal, 3, "normal"), 3));
  p.push_back(accessor("float", "tessera_adaptive_id_value", l.id, *swizzle(l.id, 1, "id"), 1));
  // As the CPU's lround: half away from zero.
  p.push_back(
      "int tessera_adaptive_id(ivec2 g) { float v = tessera_adaptive_id_value(g); "
      "return int(floor(abs(v) + 0.5)) * (v < 0.0 ? -1 : 1); }");
  if (l.uv.texture >= 0) {
    p.push_back(accessor("vec2", "tessera_adaptive_uv", l.uv, *swizzle(l.uv, 2, "uv"), 2));
    p.push_back(accessor("vec4", "tessera_adaptive_uv_derivatives", l.uv_derivatives,
                         *swizzle(l.uv_derivatives, 4, "uv_derivatives"), 4));
  }
  return p;
}

/// Passes that shade (compiled with the hook); the others get a stand-in.
bool shades(const std::string& pass) {
  return pass == "FIRST" || pass == "EXTRA" || pass == "SHADE" || pass == "RESOLVE" ||
         pass == "REFERENCE";
}

/// One pass to SPIR-V; a compile error is "vk adaptive supersampler: HOOK:LINE: message".
Status compile(State& st, const std::string& pass) {
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
  glsl::ExpandOptions eo;
  eo.include_paths = o.hook.include_paths;
  eo.preamble = preamble(st, pass);
  Result<glsl::Expanded> e = glsl::expand_includes(src, eo);
  if (!e) return Status::error(e.status().code, "vk adaptive supersampler: " + e.status().message);
  Result<std::vector<std::uint32_t>> spirv = compile_compute_spirv(e->text);
  if (!spirv) {
    return Status::error(
        spirv.status().code,
        "vk adaptive supersampler: " + glsl::format_log(spirv.status().message, e->files));
  }
  st.spirv.emplace(pass, std::move(*spirv));
  return Status::success();
}

}  // namespace

AdaptiveParams adaptive_params(const State& st) {
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
  return params;
}

Status create_adaptive_objects(State& st);  // adaptive_objects.cpp

double AdaptiveProfile::total_ms() const {
  double t = 0;
  for (const PassTime& p : passes) t += p.ms;
  return t;
}

AdaptiveSupersampler::~AdaptiveSupersampler() = default;

const AdaptiveSupersamplerOptions& AdaptiveSupersampler::options() const { return state_->options; }
std::uint32_t AdaptiveSupersampler::descriptor_set_index() const { return state_->set_index; }

void AdaptiveSupersampler::set_thresholds(const AdaptiveThresholds& thresholds) {
  state_->options.thresholds = thresholds;  // recorded with the next record
}

Result<std::unique_ptr<AdaptiveSupersampler>> AdaptiveSupersampler::create(
    const DeviceContext& device, const AdaptiveSupersamplerOptions& options) {
  auto st = std::make_unique<State>();
  st->options = options;
  Result<Api> api = load_api(device);
  if (!api)
    return Status::error(api.status().code, "vk adaptive supersampler: " + api.status().message);
  st->api = std::move(*api);
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
  if (Status s = create_adaptive_objects(*st); !s.ok()) return s;
  st->spirv.clear();
  std::unique_ptr<AdaptiveSupersampler> r(new AdaptiveSupersampler());
  r->state_ = std::move(st);
  return r;
}

}  // namespace tessera::vk
