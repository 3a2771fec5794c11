// The adaptive supersampler's backend-neutral host code (src/adaptive/adaptive_host.h): option
// checks, the GLSL generated from the G-buffer layout, the parameter block and a frame's passes.
#include "adaptive/adaptive_host.h"

#include <algorithm>
#include <cmath>
#include <span>

#include "tessera/deferred.h"

namespace tessera::adaptive {

namespace {

Status error(ErrorCode code, std::string_view who, const std::string& what) {
  return Status::error(code, std::string(who) + ": " + what);
}

/// The GLSL swizzle (xyzw letters) of `c`, checked against `width` channels.
Result<std::string> swizzle(const AdaptiveChannel& c, int width, const char* what,
                            std::string_view who) {
  const std::string field = std::string("layout.") + what;
  const ErrorCode bad = ErrorCode::invalid_argument;
  if (c.texture < 0 || c.texture > 3) {
    return error(bad, who, field + ".texture = " + std::to_string(c.texture) + " (a slot 0..3)");
  }
  if (int(c.channels.size()) != width) {
    return error(bad, who,
                 field + ".channels = \"" + c.channels + "\": needs " + std::to_string(width) +
                     " channel" + (width > 1 ? "s" : ""));
  }
  const bool rgba = c.channels.find_first_of("rgba") != std::string::npos;
  const std::string set = rgba ? "rgba" : "xyzw";
  std::string out;
  for (char ch : c.channels) {
    const std::size_t at = set.find(ch);
    if (at == std::string::npos) {
      return error(
          bad, who,
          field + ".channels = \"" + c.channels + "\": use the letters of one set, rgba or xyzw");
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

Status check_sample_order(const AdaptiveCommonOptions& o, std::string_view who, Derived& d) {
  if (o.sample_order.empty()) {
    const std::span<const std::uint8_t> def = deferred::sample_order(o.m);
    d.order.assign(def.begin(), def.end());
    return Status::success();
  }
  d.order = o.sample_order;
  std::vector<std::uint8_t> sorted = d.order;
  std::sort(sorted.begin(), sorted.end());
  bool perm = int(sorted.size()) == d.n;
  for (int i = 0; perm && i < d.n; ++i) perm = sorted[std::size_t(i)] == i;
  if (!perm) {
    return error(ErrorCode::invalid_argument, who,
                 "sample_order is not a permutation of 0.." + std::to_string(d.n - 1));
  }
  return Status::success();
}

/// The layout's quantities with their widths (uv and its derivatives when present).
struct Quantity {
  const AdaptiveChannel* c;
  int width;
  const char* what;
};
std::vector<Quantity> quantities(const AdaptiveGBufferLayout& l) {
  std::vector<Quantity> qs = {{&l.depth, 1, "depth"}, {&l.normal, 3, "normal"}, {&l.id, 1, "id"}};
  if (l.uv.texture >= 0) {
    qs.push_back({&l.uv, 2, "uv"});
    qs.push_back({&l.uv_derivatives, 4, "uv_derivatives"});
  }
  return qs;
}

Status check_layout(const AdaptiveGBufferLayout& l, std::string_view who, Derived& d) {
  if ((l.uv.texture >= 0) != (l.uv_derivatives.texture >= 0)) {
    return error(ErrorCode::invalid_argument, who,
                 "layout.uv and layout.uv_derivatives: both or neither");
  }
  for (const Quantity& q : quantities(l)) {
    Result<std::string> sw = swizzle(*q.c, q.width, q.what, who);
    if (!sw) return sw.status();
    d.slot_used[q.c->texture] = true;
    d.slot_channels[q.c->texture] = std::max(d.slot_channels[q.c->texture], max_channel(*sw));
  }
  return Status::success();
}

/// One accessor: `type name(ivec2 g)` reading `c` (checked) with its swizzle, scale and bias.
std::string accessor(const char* type, const char* name, const AdaptiveChannel& c, int width) {
  const std::string sw = *swizzle(c, width, name, "");
  std::string expr =
      "texelFetch(tessera_adaptive_gbuffer" + std::to_string(c.texture) + ", g, 0)." + sw;
  if (c.scale != 1.0f) expr = "(" + expr + " * " + glsl::float_literal(c.scale) + ")";
  if (c.bias != 0.0f) {
    const std::string b = glsl::float_literal(c.bias);
    expr = "(" + expr + " + " + (width > 1 ? std::string(type) + "(" + b + ")" : b) + ")";
  }
  return std::string(type) + " " + name + "(ivec2 g) { return " + expr + "; }";
}

/// The preamble: version, defines, G-buffer samplers and accessors.
std::vector<std::string> preamble(const AdaptiveCommonOptions& o, const Derived& d,
                                  const GlslBindings& b, const std::string& pass) {
  std::vector<std::string> p = {
      "#version 450 core",
      "#define TESSERA_ADAPTIVE_M " + std::to_string(o.m),
      "#define TESSERA_ADAPTIVE_N " + std::to_string(d.n),
      "#define TESSERA_ADAPTIVE_MAX_N " + std::to_string(d.n),
      "#define TESSERA_ADAPTIVE_WIDTH " + std::to_string(o.width),
      "#define TESSERA_ADAPTIVE_HEIGHT " + std::to_string(o.height),
      "#define TESSERA_ADAPTIVE_LIST_CAPACITY " + std::to_string(d.list_capacity)};
  if (b.set) p.push_back("#define TESSERA_ADAPTIVE_SET " + std::to_string(*b.set));
  p.insert(p.end(), {"#define TESSERA_ADAPTIVE_UBO_BINDING " + std::to_string(b.params),
                     "#define TESSERA_ADAPTIVE_WORK_BINDING " + std::to_string(b.work),
                     "#define TESSERA_ADAPTIVE_IMAGE_UNIT " + std::to_string(b.image),
                     std::string("#define TESSERA_ADAPTIVE_OUT_FORMAT ") +
                         (o.output == AdaptiveOutputFormat::rgba32f ? "rgba32f" : "rgba16f"),
                     "#define TESSERA_ADAPTIVE_PASS_" + pass});
  if (o.layout.uv.texture >= 0) p.push_back("#define TESSERA_ADAPTIVE_HAS_UV 1");
  if (o.sample_count_texture) p.push_back("#define TESSERA_ADAPTIVE_SAMPLE_COUNTS 1");
  if (o.resolve == AdaptiveResolve::tonemap_weighted) p.push_back("#define TESSERA_ADAPTIVE_HDR 1");
  if (!d.float64) p.push_back("#define TESSERA_ADAPTIVE_NO_FP64 1");
  if (pass == "EXTRA") {
    p.push_back(d.tile ? "#define TESSERA_ADAPTIVE_SCHEDULE_TILE 1"
                       : "#define TESSERA_ADAPTIVE_SCHEDULE_LOOP 1");
  }
  const std::string set = b.set ? "set = " + std::to_string(*b.set) + ", " : "";
  for (int s = 0; s < 4; ++s) {
    if (!d.slot_used[s]) continue;
    p.push_back("layout(" + set + "binding = " + std::to_string(b.gbuffer + s) +
                ") uniform sampler2D tessera_adaptive_gbuffer" + std::to_string(s) + ";");
  }
  const AdaptiveGBufferLayout& l = o.layout;
  p.push_back(accessor("float", "tessera_adaptive_depth", l.depth, 1));
  p.push_back(accessor("vec3", "tessera_adaptive_normal", l.normal, 3));
  p.push_back(accessor("float", "tessera_adaptive_id_value", l.id, 1));
  // As the CPU's lround: half away from zero.
  p.push_back(
      "int tessera_adaptive_id(ivec2 g) { float v = tessera_adaptive_id_value(g); "
      "return int(floor(abs(v) + 0.5)) * (v < 0.0 ? -1 : 1); }");
  if (l.uv.texture >= 0) {
    p.push_back(accessor("vec2", "tessera_adaptive_uv", l.uv, 2));
    p.push_back(accessor("vec4", "tessera_adaptive_uv_derivatives", l.uv_derivatives, 4));
  }
  return p;
}

/// Passes that shade (compiled with the hook); the others get a stand-in.
bool shades(const std::string& pass) {
  return pass == "FIRST" || pass == "EXTRA" || pass == "SHADE" || pass == "RESOLVE" ||
         pass == "REFERENCE";
}

}  // namespace

Status check_options(const AdaptiveCommonOptions& o, std::string_view who, Derived& d) {
  const ErrorCode bad = ErrorCode::invalid_argument;
  if (o.m < 2 || o.m > 8) return error(bad, who, "m = " + std::to_string(o.m) + " (2..8)");
  if (o.width <= 0 || o.height <= 0) {
    return error(bad, who, "size " + std::to_string(o.width) + "x" + std::to_string(o.height));
  }
  const std::size_t pixels = std::size_t(o.width) * std::size_t(o.height);
  if (pixels > kMaxPixels) {
    return error(ErrorCode::too_large, who, std::to_string(pixels) + " pixels exceed 2^26");
  }
  if (!(o.hdr_exposure > 0.0f) || !std::isfinite(o.hdr_exposure)) {
    return error(bad, who, "hdr_exposure = " + glsl::float_literal(o.hdr_exposure) + " (> 0)");
  }
  if (o.hook.source.find("tessera_shade_sample") == std::string::npos) {
    return error(bad, who,
                 "hook '" + o.hook.name +
                     "' does not define vec4 tessera_shade_sample(ivec2 grid_texel, float "
                     "footprint)");
  }
  d.n = o.m * o.m;
  d.tile = o.schedule == AdaptiveSchedule::tile_list && o.m <= 4;
  if (Status s = check_sample_order(o, who, d); !s.ok()) return s;
  return check_layout(o.layout, who, d);
}

std::size_t work_buffer_bytes(const AdaptiveCommonOptions& o) {
  const std::size_t pixels = std::size_t(o.width) * std::size_t(o.height);
  return (kHeaderUints + kHistogramUints + 4 * pixels) * 4;
}

std::size_t list_capacity(const AdaptiveCommonOptions& o, int n, std::size_t max_items) {
  if (o.schedule != AdaptiveSchedule::frame_list) return 1;  // no list
  const std::size_t pixels = std::size_t(o.width) * std::size_t(o.height);
  const std::size_t asked = o.list_capacity > 0 ? o.list_capacity : pixels * std::size_t(n / 2);
  return std::max<std::size_t>(std::min<std::size_t>({asked, max_items, 0x7fffffffu}), 1);
}

std::vector<std::string> pass_programs(AdaptiveSchedule schedule) {
  std::vector<std::string> passes = {"FIRST",  "METRICS", "HISTOGRAM",
                                     "SELECT", "APPLY",   "REFERENCE"};
  if (schedule == AdaptiveSchedule::frame_list) {
    passes.insert(passes.end(), {"LIST", "ARGS", "SHADE", "RESOLVE"});
  } else {
    passes.push_back("EXTRA");
  }
  return passes;
}

glsl::Source pass_source(const AdaptiveCommonOptions& o, const std::string& pass) {
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
  return src;
}

glsl::ExpandOptions pass_expand_options(const AdaptiveCommonOptions& o, const Derived& d,
                                        const GlslBindings& b, const std::string& pass) {
  glsl::ExpandOptions eo;
  eo.include_paths = o.hook.include_paths;
  eo.preamble = preamble(o, d, b, pass);
  return eo;
}

std::size_t tile_shared_bytes(int n) {
  // adaptive_component.glsl: a uint count, then per item (64 * n) a uint, a float and a vec4.
  return 4 + std::size_t(64) * std::size_t(n) * (4 + 4 + 16);
}

Params params(const AdaptiveCommonOptions& o, const Derived& d, int w, int h) {
  Params p{};
  p.size[0] = w;
  p.size[1] = h;
  p.size[2] = o.m;
  p.size[3] = d.n;
  p.flags[0] = o.thresholds.force_k >= 0 ? std::min(o.thresholds.force_k, d.n - 1) : -1;
  p.flags[1] = (o.thresholds.use_geometry ? 1 : 0) | (o.thresholds.use_shading ? 2 : 0);
  p.flags[3] = int(d.list_capacity);
  p.metric[0] = o.thresholds.c_depth;
  p.metric[1] = o.thresholds.c_normal;
  p.metric[2] = o.thresholds.c_shade;
  p.metric[3] = o.thresholds.t_min;
  p.metric2[0] = o.thresholds.t_edge;
  p.metric2[1] = o.thresholds.seam_factor;
  p.metric2[2] = o.hdr_exposure;
  for (int i = 0; i < d.n; ++i) p.order[i] = d.order[std::size_t(i)];
  return p;
}

Status check_budget(const std::optional<std::int64_t>& budget, std::string_view who) {
  if (budget && *budget < 0) {
    return error(ErrorCode::invalid_argument, who,
                 "budget = " + std::to_string(*budget) + " (>= 0 extra samples, or none)");
  }
  return Status::success();
}

std::array<std::uint32_t, kHeaderUints> work_header(const std::optional<std::int64_t>& budget) {
  std::array<std::uint32_t, kHeaderUints> header{};
  if (budget) {
    header[5] = 1;
    header[6] = std::uint32_t(std::min<std::int64_t>(*budget, 0xffffffffLL));
  }
  return header;
}

std::vector<Step> frame_steps(Mode mode, AdaptiveSchedule schedule, bool budgeted) {
  if (mode == Mode::reference) return {{"reference", "REFERENCE"}};
  std::vector<Step> steps = {{"first", "FIRST"}};
  if (mode != Mode::adaptive) return steps;
  steps.push_back({"metrics", "METRICS"});
  if (budgeted) {
    // Eight histogram + select rounds over the rank key's digits (the select pass advances the
    // digit in the work buffer), then the apply pass.
    for (int d = 0; d < 8; ++d) {
      steps.push_back({"budget_histogram" + std::to_string(d), "HISTOGRAM"});
      steps.push_back({"budget_select" + std::to_string(d), "SELECT", 1});
    }
    steps.push_back({"budget_apply", "APPLY"});
  }
  if (schedule == AdaptiveSchedule::frame_list) {
    // The list, then the shade pass's group counts (one invocation).
    steps.push_back({"extra_list", "LIST", 0, false, "ARGS"});
    steps.push_back({"extra_shade", "SHADE", 0, true});
    steps.push_back({"extra_resolve", "RESOLVE"});
  } else {
    steps.push_back({"extra", "EXTRA"});
  }
  return steps;
}

std::uint64_t extra_samples(const AdaptiveCommonOptions& o, Mode mode, std::uint64_t counted,
                            std::uint64_t pixels) {
  return mode == Mode::adaptive    ? counted
         : mode == Mode::reference ? pixels * std::uint64_t(o.m * o.m - 1)
                                   : 0;
}

}  // namespace tessera::adaptive

namespace tessera {

AdaptiveGBufferLayout deferred_gbuffer_layout() {
  AdaptiveGBufferLayout l;
  l.depth = {0, "r"};
  l.normal = {0, "gba"};
  l.id = {1, "r"};
  l.uv = {1, "gb"};
  l.uv_derivatives = {2, "rgba"};
  return l;
}

}  // namespace tessera
