// Shared by the vk::AdaptiveSupersampler tests: a G-buffer of tessera's built-in scene
// (rasterised on the CPU, three RGBA32F images), a shading hook that runs unchanged on GL and
// Vulkan (no resources of its own: a filtered procedural checker, two lights, a sharp specular
// term that aliases), and one frame through the Vulkan component.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "tessera/deferred.h"
#include "tessera/metrics.h"
#include "tessera/scene.h"
#include "tessera/vk_adaptive.h"
#include "test_support.h"
#include "vk_harness.h"

namespace tessera::vk_test {

/// The three G-buffer slots as RGBA float texels: (depth, normal), (id, uv, 0), uv derivatives.
struct SceneGBuffer {
  int w = 0, h = 0, m = 0;
  std::array<std::vector<float>, 3> slots;
};

inline SceneGBuffer scene_gbuffer(int w, int h, int m) {
  SceneGBuffer g;
  g.w = w;
  g.h = h;
  g.m = m;
  const scene::Scene sc = scene::builtin_scene();
  auto r = deferred::DeferredRenderer::create(sc);
  EXPECT_TRUE(r.ok()) << r.status().message;
  if (!r) return g;
  deferred::GBuffer gb;
  Status s = (*r)->render_gbuffer(scene::orbit_camera(sc, 1, 8), w, h, m, gb);
  EXPECT_TRUE(s.ok()) << s.message;
  for (int gy = 0; gy < h * m; ++gy) {
    for (int gx = 0; gx < w * m; ++gx) {
      const float* p = gb.sample(gx, gy);
      g.slots[0].insert(g.slots[0].end(), {p[deferred::kChDepth], p[deferred::kChNormal],
                                           p[deferred::kChNormal + 1], p[deferred::kChNormal + 2]});
      g.slots[1].insert(g.slots[1].end(),
                        {p[deferred::kChMaterial], p[deferred::kChUv], p[deferred::kChUv + 1], 0});
      g.slots[2].insert(g.slots[2].end(), {p[deferred::kChDuvDx], p[deferred::kChDuvDx + 1],
                                           p[deferred::kChDuvDy], p[deferred::kChDuvDy + 1]});
    }
  }
  return g;
}

/// The hook: GLSL both components compile (its line 3 is `int id = ...`).
inline const char* kSceneHook = R"(vec4 tessera_shade_sample(ivec2 g, float footprint) {
  // Background, then a checker filtered by the footprint, two lights and a sharp highlight.
  int id = tessera_adaptive_id(g);
  if (id < 0) return vec4(0.05, 0.05, 0.08, 1.0);
  vec3 n = normalize(tessera_adaptive_normal(g));
  vec2 uv = tessera_adaptive_uv(g);
  vec4 d = abs(tessera_adaptive_uv_derivatives(g)) * footprint;
  float blur = max(max(d.x, d.y), max(d.z, d.w)) * 16.0;
  vec2 s = sin(uv * 50.265482);
  float check = 0.5 + 0.5 * clamp(s.x * s.y / (1.0 + 4.0 * blur), -1.0, 1.0);
  vec3 l1 = normalize(vec3(0.4, 0.8, 0.3)), l2 = normalize(vec3(-0.6, 0.3, 0.7));
  vec3 h = normalize(l1 + vec3(0.0, 0.0, 1.0));
  float spec = pow(max(dot(n, h), 0.0), 96.0);
  vec3 base = vec3(0.3 + 0.1 * float(id % 5), 0.5, 0.7 - 0.05 * float(id % 7)) *
              (0.4 + 0.6 * check);
  vec3 c = base * (0.1 + max(dot(n, l1), 0.0) + 0.5 * max(dot(n, l2), 0.0)) + vec3(spec * 3.0);
  return vec4(c, 1.0);
}
)";

/// Options shared by the GL and Vulkan runs.
template <class Options>
Options scene_options(const SceneGBuffer& g) {
  Options o;
  o.width = g.w;
  o.height = g.h;
  o.m = g.m;
  o.output = AdaptiveOutputFormat::rgba32f;
  o.sample_count_texture = true;
  o.layout = deferred_gbuffer_layout();
  o.hook.name = "scene_hook";
  o.hook.source = kSceneHook;
  return o;
}

/// One Vulkan frame's results.
struct VkFrameOut {
  std::vector<float> colour;  // RGBA
  std::vector<float> counts;  // k + 1 per pixel
  std::uint64_t extra = 0;
};

enum class Which { adaptive, reference, first };

/// Runs one frame of `o` on `engine` with the G-buffer `g` (uploaded here).
inline VkFrameOut run_vk(Engine& engine, vk::AdaptiveSupersamplerOptions o, const SceneGBuffer& g,
                         Which which, std::optional<std::int64_t> budget = std::nullopt) {
  VkFrameOut out;
  o.profile = true;
  auto c = vk::AdaptiveSupersampler::create(engine.context(), o);
  EXPECT_TRUE(c.ok()) << c.status().message;
  if (!c) return out;
  std::array<EngineImage, 3> imgs;
  vk::AdaptiveFrame frame;
  for (std::size_t s = 0; s < 3; ++s) {
    imgs[s] = engine.upload_rgba(VK_FORMAT_R32G32B32A32_SFLOAT, g.w * g.m, g.h * g.m, g.slots[s],
                                 VK_IMAGE_USAGE_SAMPLED_BIT);
    frame.gbuffer[s] = imgs[s].resource;
  }
  frame.budget = budget;
  EXPECT_TRUE((*c)->begin_frame(0).ok());
  VkCommandBuffer cmd = engine.begin();
  Result<vk::AdaptiveOutput> r = which == Which::adaptive ? (*c)->record(cmd, frame)
                                 : which == Which::reference
                                     ? (*c)->record_reference(cmd, frame)
                                     : (*c)->record_first_sample(cmd, frame);
  EXPECT_TRUE(r.ok()) << r.status().message;
  engine.submit_and_wait(cmd);
  if (r) {
    out.colour = engine.read_back(r->colour);
    out.counts = engine.read_back(r->sample_counts);
    Result<vk::AdaptiveProfile> p = (*c)->read_profile(r->frame_slot, r->view);
    EXPECT_TRUE(p.ok()) << p.status().message;
    if (p) out.extra = p->extra_samples;
  }
  c->reset();
  for (EngineImage& img : imgs) engine.destroy(img);
  return out;
}

/// PSNR (dB, peak 1) of two RGBA float images over RGB clamped to [0, 1].
inline double psnr_rgb(const std::vector<float>& a, const std::vector<float>& b) {
  if (a.size() != b.size() || a.empty()) return 0.0;
  double se = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (i % 4 == 3) continue;
    const double d = std::clamp(double(a[i]), 0.0, 1.0) - std::clamp(double(b[i]), 0.0, 1.0);
    se += d * d;
    ++n;
  }
  return se == 0 ? INFINITY : metrics::psnr_from_mse(se / double(n), 1.0);
}

/// Fraction of equal entries.
inline double same_fraction(const std::vector<float>& a, const std::vector<float>& b) {
  if (a.size() != b.size() || a.empty()) return 0.0;
  std::size_t same = 0;
  for (std::size_t i = 0; i < a.size(); ++i) same += a[i] == b[i] ? 1 : 0;
  return double(same) / double(a.size());
}

}  // namespace tessera::vk_test
