// GPU adaptive supersampling (tessera/gl_deferred.h) against the CPU path (tessera/deferred.h):
// G-buffer, k maps, forced-k identities, images, the edge-per-sample baseline, FXAA and the
// framebuffer-size check. Skips when no OpenGL 4.5 context can be made.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "gl_test_fixture.h"
#include "tessera/deferred.h"
#include "tessera/gl.h"
#include "tessera/gl_deferred.h"
#include "tessera/metrics.h"
#include "tessera/scene.h"
#include "test_support.h"

namespace tessera {
namespace {

namespace d = deferred;

double psnr(const ImageRGBAF& a, const ImageRGBAF& b) {
  metrics::CompareOptions o;
  o.compute_ssim = false;
  Result<metrics::ImageComparison> c = metrics::compare_images(to_srgb8(a), to_srgb8(b), o);
  EXPECT_TRUE(c.ok());
  return c ? c->psnr_rgb : 0.0;
}

float max_abs_diff(const ImageRGBAF& a, const ImageRGBAF& b) {
  float m = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    m = std::max(m, std::fabs(a.pixels[i] - b.pixels[i]));
  return m;
}

double agreement(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
  EXPECT_EQ(a.size(), b.size());
  std::size_t same = 0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) same += a[i] == b[i];
  return a.empty() ? 1.0 : double(same) / double(a.size());
}

class GlDeferred : public test::GlTest {
 protected:
  void TearDown() override {
    gl_.reset();
    test::GlTest::TearDown();
  }
  // Loads the scene and makes the GL and CPU renderers and shading options.
  void use_scene(scene::Scene sc, const scene::Camera& cam, bool heavy) {
    scene_ = std::make_unique<scene::Scene>(std::move(sc));
    camera_ = cam;
    gl::DeferredRendererOptions o;
    o.glsl_dir = TESSERA_GLSL_DIR;
    Result<std::unique_ptr<gl::DeferredRenderer>> g = gl::DeferredRenderer::create(*scene_, o);
    ASSERT_TRUE(g.ok()) << g.status().message;
    gl_ = std::move(*g);
    Result<std::unique_ptr<d::DeferredRenderer>> r = d::DeferredRenderer::create(*scene_);
    ASSERT_TRUE(r.ok()) << r.status().message;
    cpu_ = std::move(*r);
    shading_ = d::scene_shading(*scene_, 8, &camera_);
    shading_.heavy = heavy;
    shading_.heavy_terms = 32;
  }
  void use_builtin(bool heavy = false) {
    scene::Scene sc = scene::builtin_scene();
    const scene::Camera cam = scene::orbit_camera(sc, 1, 8);
    use_scene(std::move(sc), cam, heavy);
  }
  // Renders both G-buffers at w x h, window m.
  void render(int w, int h, int m) {
    const Status rs = gl_->render_gbuffer(camera_, w, h, m);
    ASSERT_TRUE(rs.ok()) << rs.message;
    ASSERT_TRUE(cpu_->render_gbuffer(camera_, w, h, m, cpu_gb_).ok());
    Result<d::GBuffer> g = gl_->read_gbuffer();
    ASSERT_TRUE(g.ok()) << g.status().message;
    gl_gb_ = std::move(*g);
  }
  // GL vs CPU adaptive: k-map agreement and PSNR, on the CPU's own G-buffer (the whole
  // pipeline) and on the GL G-buffer read back (the shading passes alone).
  void compare_adaptive(const char* what, double min_k_own, double min_k_same, double min_psnr) {
    const AdaptiveThresholds a;
    Result<deferred::ShadeResult> g = gl_->shade_adaptive(shading_, a);
    ASSERT_TRUE(g.ok()) << g.status().message;
    const d::AdaptiveResult own = cpu_->shade_adaptive(cpu_gb_, shading_, a);
    const d::AdaptiveResult same = cpu_->shade_adaptive(gl_gb_, shading_, a);
    const double k_own = agreement(g->samples, own.samples);
    const double k_same = agreement(g->samples, same.samples);
    const double p_own = psnr(g->image, own.image), p_same = psnr(g->image, same.image);
    std::printf(
        "%s: k agreement %.4f (CPU G-buffer), %.4f (GL G-buffer); PSNR %.2f / %.2f dB; "
        "samples GL %.1f %% CPU %.1f %%\n",
        what, k_own, k_same, p_own, p_same,
        100.0 * double(g->samples_shaded) /
            double(g->samples.size() * std::size_t(gl_->m() * gl_->m())),
        100.0 * double(own.samples_shaded) /
            double(own.samples.size() * std::size_t(gl_->m() * gl_->m())));
    EXPECT_GE(k_own, min_k_own);
    EXPECT_GE(k_same, min_k_same);
    EXPECT_GE(p_own, min_psnr);
    EXPECT_GE(p_same, min_psnr);
  }

  std::unique_ptr<scene::Scene> scene_;
  scene::Camera camera_;
  std::unique_ptr<gl::DeferredRenderer> gl_;
  std::unique_ptr<d::DeferredRenderer> cpu_;
  d::ShadingOptions shading_;
  d::GBuffer cpu_gb_, gl_gb_;
};

TEST_F(GlDeferred, GBufferMatchesCpu) {
  use_builtin();
  for (int m : {2, 4}) {
    render(64, 48, m);
    const int gw = 64 * m, gh = 48 * m;
    std::size_t same_material = 0, close_depth = 0, close_uv = 0, both = 0;
    for (int y = 0; y < gh; ++y) {
      for (int x = 0; x < gw; ++x) {
        const float* a = gl_gb_.sample(x, y);
        const float* b = cpu_gb_.sample(x, y);
        if (a[d::kChMaterial] != b[d::kChMaterial]) continue;
        ++same_material;
        close_depth += std::fabs(a[d::kChDepth] - b[d::kChDepth]) <= 1e-4f * b[d::kChDepth];
        if (b[d::kChMaterial] >= 0) {
          ++both;
          close_uv +=
              std::fabs(a[d::kChUv] - b[d::kChUv]) + std::fabs(a[d::kChUv + 1] - b[d::kChUv + 1]) <
              1e-3f * (1.0f + std::fabs(b[d::kChUv]) + std::fabs(b[d::kChUv + 1]));
        }
      }
    }
    const double n = double(gw) * gh;
    std::printf("m=%d: material %.5f, depth(1e-4 rel) %.5f, uv(1e-3 rel) %.5f\n", m,
                double(same_material) / n, double(close_depth) / n,
                double(close_uv) / double(both));
    EXPECT_GE(double(same_material) / n, 0.995);
    EXPECT_GE(double(close_depth) / n, 0.995);
    EXPECT_GE(double(close_uv) / double(both), 0.99);
  }
}

TEST_F(GlDeferred, AdaptiveMatchesCpuBuiltin) {
  use_builtin();
  for (int m : {2, 4}) {
    render(64, 48, m);
    compare_adaptive(m == 2 ? "builtin m=2" : "builtin m=4", 0.99, 0.995, 40.0);
  }
}

TEST_F(GlDeferred, HeavyShadingMatchesCpu) {
  use_builtin(/*heavy=*/true);
  render(64, 48, 2);
  compare_adaptive("builtin m=2 heavy", 0.99, 0.995, 40.0);
}

TEST_F(GlDeferred, ForcedKIdentities) {
  use_builtin();
  for (int m : {2, 4}) {
    render(64, 48, m);
    Result<deferred::ShadeResult> ref = gl_->shade_reference(shading_);
    ASSERT_TRUE(ref.ok()) << ref.status().message;
    Result<deferred::ShadeResult> one = gl_->shade_default(shading_);
    ASSERT_TRUE(one.ok()) << one.status().message;
    AdaptiveThresholds a;
    a.force_k = m * m - 1;
    Result<deferred::ShadeResult> all = gl_->shade_adaptive(shading_, a);
    ASSERT_TRUE(all.ok()) << all.status().message;
    a.force_k = 0;
    Result<deferred::ShadeResult> none = gl_->shade_adaptive(shading_, a);
    ASSERT_TRUE(none.ok()) << none.status().message;
    // k = m^2 - 1 runs the same shading of the same samples as the reference (the first sample's
    // light terms come from S, computed by the same function), summed in the same order.
    EXPECT_EQ(max_abs_diff(all->image, ref->image), 0.0f) << "m=" << m;
    EXPECT_EQ(max_abs_diff(none->image, one->image), 0.0f) << "m=" << m;
    EXPECT_EQ(all->samples_shaded, ref->samples_shaded);
    EXPECT_EQ(none->samples_shaded, one->samples_shaded);
    // And against the CPU's reference / 1x on the same (GL) G-buffer.
    const double pr = psnr(ref->image, cpu_->shade_reference(gl_gb_, shading_));
    const double p1 = psnr(one->image, cpu_->shade_default(gl_gb_, shading_));
    std::printf("m=%d: GL vs CPU on the GL G-buffer: reference %.2f dB, 1x %.2f dB\n", m, pr, p1);
    EXPECT_GE(pr, 45.0);
    EXPECT_GE(p1, 45.0);
  }
}

// The loop and the frame list (the default) give the tile list's images and k maps, bit for
// bit: adaptive, adaptive with every pixel at k = m^2 - 1 (the frame list's buffers must grow:
// m^2 - 1 items per pixel against a first capacity of one), and edge-per-sample, at m = 2, 4.
TEST_F(GlDeferred, EveryScheduleGivesTheTileScheduleImage) {
  use_builtin();
  for (int m : {2, 4}) {
    render(64, 48, m);
    AdaptiveThresholds all;
    all.force_k = 15;
    // A renderer with `schedule` on this G-buffer, and its adaptive, forced-k and edge results.
    struct Results {
      std::unique_ptr<gl::DeferredRenderer> renderer;
      Result<deferred::ShadeResult> adaptive, all, edge;
    };
    auto shade_with = [&](gl::ExtraSchedule schedule) -> Result<Results> {
      gl::DeferredRendererOptions o;
      o.glsl_dir = TESSERA_GLSL_DIR;
      o.schedule = schedule;
      Result<std::unique_ptr<gl::DeferredRenderer>> g = gl::DeferredRenderer::create(*scene_, o);
      if (!g) return g.status();
      if (Status s = (*g)->render_gbuffer(camera_, 64, 48, m); !s.ok()) return s;
      Result<deferred::ShadeResult> adaptive = (*g)->shade_adaptive(shading_, {});
      Result<deferred::ShadeResult> forced = (*g)->shade_adaptive(shading_, all);
      Result<deferred::ShadeResult> edge = (*g)->shade_edge_per_sample(shading_);
      return Results{std::move(*g), std::move(adaptive), std::move(forced), std::move(edge)};
    };
    Result<Results> tiles = shade_with(gl::ExtraSchedule::tile_list);
    ASSERT_TRUE(tiles.ok()) << tiles.status().message;
    ASSERT_TRUE(tiles->adaptive.ok() && tiles->all.ok() && tiles->edge.ok());
    const deferred::ShadeResult& tile = *tiles->adaptive;
    const deferred::ShadeResult& tile_all = *tiles->all;
    const deferred::ShadeResult& tile_edge = *tiles->edge;
    ASSERT_EQ(tile.passes.back().pass, "extra");
    for (gl::ExtraSchedule schedule : {gl::ExtraSchedule::loop, gl::ExtraSchedule::frame_list}) {
      SCOPED_TRACE("m=" + std::to_string(m) +
                   (schedule == gl::ExtraSchedule::loop ? " loop" : " frame_list"));
      Result<Results> g = shade_with(schedule);
      ASSERT_TRUE(g.ok()) << g.status().message;
      Result<deferred::ShadeResult>& r = g->adaptive;
      Result<deferred::ShadeResult>& r_all = g->all;
      Result<deferred::ShadeResult>& r_edge = g->edge;
      ASSERT_TRUE(r.ok()) << r.status().message;
      ASSERT_TRUE(r_all.ok()) << r_all.status().message;
      ASSERT_TRUE(r_edge.ok()) << r_edge.status().message;
      EXPECT_EQ(r->samples, tile.samples);
      EXPECT_EQ(max_abs_diff(r->image, tile.image), 0.0f);
      EXPECT_EQ(r_all->samples, tile_all.samples);
      EXPECT_EQ(max_abs_diff(r_all->image, tile_all.image), 0.0f);
      EXPECT_EQ(r_edge->samples, tile_edge.samples);
      EXPECT_EQ(max_abs_diff(r_edge->image, tile_edge.image), 0.0f);
      if (schedule == gl::ExtraSchedule::frame_list) {
        // Once grown (by r_all), a frame runs each pass once, named after its part of the work.
        Result<deferred::ShadeResult> again = g->renderer->shade_adaptive(shading_, {});
        ASSERT_TRUE(again.ok());
        EXPECT_EQ(max_abs_diff(again->image, tile.image), 0.0f);
        std::vector<std::string> names;
        for (const PassTime& t : again->passes) names.push_back(t.pass);
        EXPECT_EQ(names, (std::vector<std::string>{"first", "metrics", "extra_list", "extra_shade",
                                                   "extra_resolve"}));
      }
    }
  }
}

TEST_F(GlDeferred, EdgePerSampleMatchesCpu) {
  use_builtin();
  for (int m : {2, 4}) {
    render(64, 48, m);
    Result<deferred::ShadeResult> g = gl_->shade_edge_per_sample(shading_);
    ASSERT_TRUE(g.ok()) << g.status().message;
    const d::AdaptiveResult same = d::shade_edge_per_sample(*cpu_, gl_gb_, shading_);
    const d::AdaptiveResult own = d::shade_edge_per_sample(*cpu_, cpu_gb_, shading_);
    const double a_same = agreement(g->samples, same.samples);
    const double a_own = agreement(g->samples, own.samples);
    const double p_same = psnr(g->image, same.image), p_own = psnr(g->image, own.image);
    std::printf(
        "edge m=%d: classification agreement %.4f (GL G-buffer) %.4f (CPU G-buffer); "
        "PSNR %.2f / %.2f dB; complex pixels %.1f %%\n",
        m, a_same, a_own, p_same, p_own,
        100.0 * double(std::count(g->samples.begin(), g->samples.end(), m * m)) /
            double(g->samples.size()));
    EXPECT_GE(a_same, 0.995);
    EXPECT_GE(a_own, 0.99);
    EXPECT_GE(p_same, 45.0);
    EXPECT_GE(p_own, 40.0);
  }
}

TEST_F(GlDeferred, FxaaMatchesCpu) {
  use_builtin();
  render(64, 48, 2);
  Result<deferred::ShadeResult> one = gl_->shade_default(shading_);
  ASSERT_TRUE(one.ok());
  const ImageRGBA8 in = to_srgb8(one->image);
  Result<deferred::FxaaResult> g = gl_->fxaa(in);
  ASSERT_TRUE(g.ok()) << g.status().message;
  Result<ImageRGBA8> c = d::fxaa(in);
  ASSERT_TRUE(c.ok());
  std::size_t same = 0, changed = 0;
  int worst = 0;
  for (std::size_t i = 0; i < in.pixels.size(); i += 4) {
    bool eq = true;
    for (int k = 0; k < 4; ++k) {
      const int diff = std::abs(int(g->image.pixels[i + k]) - int(c->pixels[i + k]));
      worst = std::max(worst, diff);
      eq = eq && diff == 0;
    }
    same += eq;
    changed += std::equal(&in.pixels[i], &in.pixels[i + 4], &c->pixels[i]) ? 0 : 1;
  }
  const double frac = double(same) / double(in.pixel_count());
  std::printf("fxaa: %zu pixels changed by FXAA; GL == CPU on %.5f of pixels, max diff %d\n",
              changed, frac, worst);
  EXPECT_GT(changed, 20u);  // the test image has edges for FXAA to act on
  EXPECT_GE(frac, 0.995);
  EXPECT_LE(worst, 2);
  // The all-GPU pipeline (1x, sRGB8, FXAA) gives the same bytes as FXAA of the read-back.
  Result<deferred::FxaaResult> pipe = gl_->shade_default_fxaa(shading_);
  ASSERT_TRUE(pipe.ok()) << pipe.status().message;
  ASSERT_EQ(pipe->passes.size(), 3u);
  std::size_t pipe_same = 0;
  for (std::size_t i = 0; i < in.pixels.size(); ++i)
    pipe_same += pipe->image.pixels[i] == g->image.pixels[i];
  EXPECT_GE(double(pipe_same) / double(in.pixels.size()), 0.999);
}

TEST_F(GlDeferred, SizeBeyondTheFramebufferLimitIsAClearError) {
  use_builtin();
  const int limit = ctx_->limits().max_texture_size;
  const int w = limit / 2 + 1;
  const Status s = gl_->check_size(w, 4, 2);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.code, ErrorCode::too_large);
  EXPECT_NE(s.message.find("GL_MAX_"), std::string::npos) << s.message;
  EXPECT_NE(s.message.find(std::to_string(2 * w) + "x8"), std::string::npos) << s.message;
  const Status r = gl_->render_gbuffer(camera_, w, 4, 2);
  EXPECT_EQ(r.code, ErrorCode::too_large) << r.message;
  EXPECT_EQ(gl_->check_size(64, 48, 9).code, ErrorCode::invalid_argument);
  EXPECT_TRUE(gl_->check_size(64, 48, 4).ok());
}

TEST_F(GlDeferred, DungeonMatchesCpu) {
  TESSERA_REQUIRE_SHARED_DATA(data);
  Result<scene::Scene> sc =
      scene::load_scene((data / "scenes/dungeon/level-dungeon.gltf").string());
  ASSERT_TRUE(sc.ok()) << sc.status().message;
  const scene::Camera cam = scene::orbit_camera(*sc, 1, 8);
  use_scene(std::move(*sc), cam, false);
  for (int m : {2, 4}) {
    render(128, 96, m);
    compare_adaptive(m == 2 ? "dungeon m=2" : "dungeon m=4", 0.99, 0.995, 40.0);
  }
}

}  // namespace
}  // namespace tessera
