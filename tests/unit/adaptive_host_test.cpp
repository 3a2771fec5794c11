// The adaptive supersampler's backend-neutral host code (src/adaptive/adaptive_host.h), without
// a GPU: the option checks and their one-line errors, the list capacity, the generated preamble
// (GL bindings vs Vulkan's set), the parameter block and a frame's passes. The GPU behaviour is
// tests/gl/gl_adaptive* and tests/vk/vk_adaptive*.
#include "adaptive/adaptive_host.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "tessera/deferred.h"

namespace tessera {
namespace {

AdaptiveCommonOptions valid() {
  AdaptiveCommonOptions o;
  o.width = 16;
  o.height = 8;
  o.m = 4;
  o.layout = deferred_gbuffer_layout();
  o.hook.source = "vec4 tessera_shade_sample(ivec2 g, float f) { return vec4(1.0); }";
  return o;
}

std::string error_of(const AdaptiveCommonOptions& o) {
  adaptive::Derived d;
  Status s = adaptive::check_options(o, "who", d);
  EXPECT_FALSE(s.ok());
  EXPECT_EQ(s.message.find('\n'), std::string::npos) << s.message;
  EXPECT_EQ(s.message.rfind("who: ", 0), 0u) << s.message;
  return s.message;
}

TEST(AdaptiveHost, ValidOptionsDeriveSlotsAndOrder) {
  adaptive::Derived d;
  ASSERT_TRUE(adaptive::check_options(valid(), "who", d).ok());
  EXPECT_EQ(d.n, 16);
  const std::span<const std::uint8_t> def = deferred::sample_order(4);
  EXPECT_TRUE(std::equal(def.begin(), def.end(), d.order.begin(), d.order.end()));
  EXPECT_TRUE(d.slot_used[0] && d.slot_used[1] && d.slot_used[2] && !d.slot_used[3]);
  EXPECT_EQ(d.slot_channels[0], 4);  // normal "gba"
  EXPECT_EQ(d.slot_channels[1], 3);  // uv "gb"
  EXPECT_EQ(d.slot_channels[2], 4);
}

TEST(AdaptiveHost, BadOptionsAreOneLineErrorsNamingTheField) {
  AdaptiveCommonOptions o = valid();
  o.m = 9;
  EXPECT_NE(error_of(o).find("m = 9 (2..8)"), std::string::npos);
  o = valid();
  o.height = 0;
  EXPECT_NE(error_of(o).find("size 16x0"), std::string::npos);
  o = valid();
  o.hdr_exposure = 0.0f;
  EXPECT_NE(error_of(o).find("hdr_exposure"), std::string::npos);
  o = valid();
  o.hook.source = "void main() {}";
  EXPECT_NE(error_of(o).find("does not define vec4 tessera_shade_sample"), std::string::npos);
  o = valid();
  o.sample_order = {0, 1, 2};
  EXPECT_NE(error_of(o).find("sample_order is not a permutation of 0..15"), std::string::npos);
  o = valid();
  o.layout.normal = AdaptiveChannel{0, "rg"};
  EXPECT_NE(error_of(o).find("layout.normal.channels = \"rg\": needs 3 channels"),
            std::string::npos);
  o = valid();
  o.layout.depth = AdaptiveChannel{0, "q"};
  EXPECT_NE(error_of(o).find("one set, rgba or xyzw"), std::string::npos);
  o = valid();
  o.layout.uv_derivatives.texture = -1;
  EXPECT_NE(error_of(o).find("both or neither"), std::string::npos);
}

TEST(AdaptiveHost, ListCapacity) {
  AdaptiveCommonOptions o = valid();
  EXPECT_EQ(adaptive::list_capacity(o, 16, 1u << 30), 16u * 8u * 8u);  // half of 16 samples
  EXPECT_EQ(adaptive::list_capacity(o, 16, 100), 100u);                // the device's limit
  o.list_capacity = 7;
  EXPECT_EQ(adaptive::list_capacity(o, 16, 1u << 30), 7u);
  o.schedule = AdaptiveSchedule::loop;
  EXPECT_EQ(adaptive::list_capacity(o, 16, 1u << 30), 1u);  // no list
}

TEST(AdaptiveHost, PreambleBindsPerBackend) {
  adaptive::Derived d;
  const AdaptiveCommonOptions o = valid();
  ASSERT_TRUE(adaptive::check_options(o, "who", d).ok());
  adaptive::GlslBindings gl{std::nullopt, 60, 1, 2, 3};
  adaptive::GlslBindings vk{2, 5, 0, 1, 3};
  const std::vector<std::string> a = adaptive::pass_expand_options(o, d, gl, "FIRST").preamble;
  const std::vector<std::string> b = adaptive::pass_expand_options(o, d, vk, "FIRST").preamble;
  auto has = [](const std::vector<std::string>& p, const std::string& line) {
    return std::find(p.begin(), p.end(), line) != p.end();
  };
  EXPECT_TRUE(has(a, "layout(binding = 61) uniform sampler2D tessera_adaptive_gbuffer1;"));
  EXPECT_TRUE(has(b, "layout(set = 2, binding = 6) uniform sampler2D tessera_adaptive_gbuffer1;"));
  EXPECT_TRUE(has(b, "#define TESSERA_ADAPTIVE_SET 2"));
  EXPECT_FALSE(has(a, "#define TESSERA_ADAPTIVE_SET 2"));  // negative control
  EXPECT_TRUE(has(a,
                  "vec2 tessera_adaptive_uv(ivec2 g) { return texelFetch("
                  "tessera_adaptive_gbuffer1, g, 0).yz; }"));
  EXPECT_EQ(adaptive::pass_source(o, "METRICS").name, "adaptive_component.glsl (METRICS)");
  EXPECT_EQ(adaptive::pass_source(o, "SHADE").name, o.hook.name);
}

TEST(AdaptiveHost, ParamsHeaderAndSteps) {
  adaptive::Derived d;
  AdaptiveCommonOptions o = valid();
  o.thresholds.force_k = 99;
  ASSERT_TRUE(adaptive::check_options(o, "who", d).ok());
  const adaptive::Params p = adaptive::params(o, d, 7, 5);  // a smaller render size
  EXPECT_EQ(p.size[0], 7);
  EXPECT_EQ(p.size[1], 5);
  EXPECT_EQ(p.flags[0], 15);  // force_k clamped to m*m - 1
  EXPECT_EQ(p.order[1], int(d.order[1]));
  EXPECT_EQ(adaptive::work_header(std::nullopt)[5], 0u);
  EXPECT_EQ(adaptive::work_header(std::int64_t(1) << 40)[6], 0xffffffffu);
  EXPECT_FALSE(adaptive::check_budget(-1, "who").ok());
  EXPECT_TRUE(adaptive::check_budget(0, "who").ok());
  using adaptive::Mode;
  EXPECT_EQ(adaptive::frame_steps(Mode::reference, o.schedule, true).size(), 1u);
  EXPECT_EQ(adaptive::frame_steps(Mode::first, o.schedule, true).size(), 1u);
  EXPECT_EQ(adaptive::frame_steps(Mode::adaptive, o.schedule, false).size(), 5u);
  EXPECT_EQ(adaptive::frame_steps(Mode::adaptive, o.schedule, true).size(), 5u + 17u);
  EXPECT_EQ(adaptive::frame_steps(Mode::adaptive, AdaptiveSchedule::loop, false).size(), 3u);
  EXPECT_EQ(adaptive::extra_samples(o, Mode::reference, 0, 16u * 8u), 16u * 8u * 15u);
  EXPECT_EQ(adaptive::extra_samples(o, Mode::adaptive, 37, 16u * 8u), 37u);
  // tile_list's shared memory: a count, then 24 bytes per item (64 * m*m items).
  EXPECT_EQ(adaptive::tile_shared_bytes(16), 24580u);
  EXPECT_FALSE(d.tile);  // frame_list
  o.schedule = AdaptiveSchedule::tile_list;
  ASSERT_TRUE(adaptive::check_options(o, "who", d).ok());
  EXPECT_TRUE(d.tile);
}

}  // namespace
}  // namespace tessera
