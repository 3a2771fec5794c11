// The adaptive supersampler's built-in passes (adaptive_host.h, "Built-in passes"): METRICS and
// LIST with the window size and the G-buffer layout as specialization constants, so tessera
// compiles them once, when it is built (tools/vk_passes), and `create` only specializes them.
//
// Constant ids: 0 m, 1 UVs present; then per quantity q (0 depth, 1 normal, 2 id, 3 uv,
// 4 uv_derivatives) at 2 + 8q: channels 0..3 (+0..+3), scaled (+4), scale (+5), biased (+6),
// bias (+7). An accessor reads texel.c0.. of its own sampler, then `* scale` when scaled and
// `+ bias` when biased: the same operations as the accessors generated from the layout.
#include <bit>
#include <string>

#include "adaptive/adaptive_host.h"

namespace tessera::adaptive {

namespace {

struct SpecQuantity {
  const char* name;  ///< As in the accessor: tessera_adaptive_<name>.
  const char* type;
  int width;
};
constexpr SpecQuantity kQuantities[] = {{"depth", "float", 1},
                                        {"normal", "vec3", 3},
                                        {"id_value", "float", 1},
                                        {"uv", "vec2", 2},
                                        {"uv_derivatives", "vec4", 4}};

std::uint32_t quantity_id(int q) { return 2 + 8 * std::uint32_t(q); }

const AdaptiveChannel& channel(const AdaptiveGBufferLayout& l, int q) {
  const AdaptiveChannel* c[] = {&l.depth, &l.normal, &l.id, &l.uv, &l.uv_derivatives};
  return *c[q];
}

/// Component index of a swizzle letter (rgba or xyzw; checked by check_options).
std::uint32_t component(char ch) {
  switch (ch) {
    case 'g':
    case 'y':
      return 1;
    case 'b':
    case 'z':
      return 2;
    case 'a':
    case 'w':
      return 3;
    default:
      return 0;
  }
}

/// A quantity's sampler, constants and accessor.
std::vector<std::string> spec_accessor(int q, const GlslBindings& b) {
  const SpecQuantity& s = kQuantities[q];
  const std::string n = std::string("tessera_adaptive_spec_") + s.name;
  const std::string tex = std::string("tessera_adaptive_") + s.name + "_texture";
  const std::uint32_t id = quantity_id(q);
  auto cid = [&](std::uint32_t k) {
    return "layout(constant_id = " + std::to_string(id + k) + ")";
  };
  std::vector<std::string> p = {"layout(set = " + std::to_string(b.set.value_or(0)) +
                                ", binding = " + std::to_string(b.gbuffer) +
                                ") uniform sampler2D " + tex + ";"};
  std::string read;
  for (int c = 0; c < s.width; ++c) {
    p.push_back(cid(std::uint32_t(c)) + " const int " + n + "_c" + std::to_string(c) + " = 0;");
    read += (c ? ", t[" : "t[") + n + "_c" + std::to_string(c) + "]";
  }
  p.push_back(cid(4) + " const bool " + n + "_scaled = false;");
  p.push_back(cid(5) + " const float " + n + "_scale = 1.0;");
  p.push_back(cid(6) + " const bool " + n + "_biased = false;");
  p.push_back(cid(7) + " const float " + n + "_bias = 0.0;");
  const std::string type = s.type;
  p.push_back(type + " tessera_adaptive_" + s.name + "(ivec2 g) { vec4 t = texelFetch(" + tex +
              ", g, 0); " + type + " v = " + (s.width > 1 ? type + "(" + read + ")" : read) +
              "; if (" + n + "_scaled) v = v * " + n + "_scale; if (" + n + "_biased) v = v + " +
              (s.width > 1 ? type + "(" + n + "_bias)" : n + "_bias") + "; return v; }");
  return p;
}

}  // namespace

std::string specialized_variant(const AdaptiveCommonOptions& o, const Derived& d,
                                const std::string& pass) {
  if (pass == "METRICS") return d.float64 ? "METRICS" : "METRICS_NO_FP64";
  if (pass == "LIST") return o.sample_count_texture ? "LIST_COUNTS" : "LIST";
  return pass;
}

std::vector<std::string> specialized_variants() {
  return {"METRICS", "METRICS_NO_FP64", "LIST", "LIST_COUNTS"};
}

glsl::ExpandOptions specialized_expand_options(const std::string& variant, const GlslBindings& b) {
  const std::string pass = variant.substr(0, variant.find('_'));
  std::vector<std::string> p = {
      "#version 450 core",
      "#define TESSERA_ADAPTIVE_SPECIALIZED 1",
      "layout(constant_id = 0) const int tessera_adaptive_spec_m = 4;",
      "layout(constant_id = 1) const bool tessera_adaptive_spec_has_uv = false;",
      "const int tessera_adaptive_spec_n = tessera_adaptive_spec_m * tessera_adaptive_spec_m;",
      "#define TESSERA_ADAPTIVE_M tessera_adaptive_spec_m",
      "#define TESSERA_ADAPTIVE_N tessera_adaptive_spec_n",
      "#define TESSERA_ADAPTIVE_MAX_N tessera_adaptive_spec_n",
      "#define TESSERA_ADAPTIVE_LIST_CAPACITY 1",
      "#define TESSERA_ADAPTIVE_SET " + std::to_string(b.set.value_or(0)),
      "#define TESSERA_ADAPTIVE_UBO_BINDING " + std::to_string(b.params),
      "#define TESSERA_ADAPTIVE_WORK_BINDING " + std::to_string(b.work),
      "#define TESSERA_ADAPTIVE_IMAGE_UNIT " + std::to_string(b.image),
      "#define TESSERA_ADAPTIVE_OUT_FORMAT rgba16f",
      "#define TESSERA_ADAPTIVE_PASS_" + pass,
      "#define TESSERA_ADAPTIVE_HAS_UV 1"};
  if (variant == "METRICS_NO_FP64") p.push_back("#define TESSERA_ADAPTIVE_NO_FP64 1");
  if (variant == "LIST_COUNTS") p.push_back("#define TESSERA_ADAPTIVE_SAMPLE_COUNTS 1");
  for (int q = 0; q < 5; ++q) {
    for (std::string& line : spec_accessor(q, b)) p.push_back(std::move(line));
  }
  // As the CPU's lround: half away from zero (the generated preamble's tessera_adaptive_id).
  p.push_back(
      "int tessera_adaptive_id(ivec2 g) { float v = tessera_adaptive_id_value(g); "
      "return int(floor(abs(v) + 0.5)) * (v < 0.0 ? -1 : 1); }");
  glsl::ExpandOptions eo;
  eo.preamble = std::move(p);
  return eo;
}

std::vector<SpecConstant> specialization(const AdaptiveCommonOptions& o) {
  std::vector<SpecConstant> s = {{0, std::uint32_t(o.m)}, {1, o.layout.uv.texture >= 0 ? 1u : 0u}};
  for (int q = 0; q < 5; ++q) {
    const AdaptiveChannel& c = channel(o.layout, q);
    const std::uint32_t id = quantity_id(q);
    for (int k = 0; k < kQuantities[q].width; ++k) {
      const std::size_t at = std::size_t(k);
      s.push_back({id + std::uint32_t(k), at < c.channels.size() ? component(c.channels[at]) : 0});
    }
    s.push_back({id + 4, c.scale != 1.0f ? 1u : 0u});
    s.push_back({id + 5, std::bit_cast<std::uint32_t>(c.scale)});
    s.push_back({id + 6, c.bias != 0.0f ? 1u : 0u});
    s.push_back({id + 7, std::bit_cast<std::uint32_t>(c.bias)});
  }
  return s;
}

std::vector<std::pair<std::string, std::uint32_t>> specialized_samplers(
    const AdaptiveCommonOptions& o, std::uint32_t gbuffer) {
  std::vector<std::pair<std::string, std::uint32_t>> out;
  for (int q = 0; q < 5; ++q) {
    const AdaptiveChannel& c = channel(o.layout, q);
    const int slot = c.texture >= 0 ? c.texture : o.layout.id.texture;
    out.emplace_back(std::string("tessera_adaptive_") + kQuantities[q].name + "_texture",
                     gbuffer + std::uint32_t(slot));
  }
  return out;
}

}  // namespace tessera::adaptive
