// The adaptive-supersampling experiment of Hollander et al. 2013 (tessera/experiments.h,
// run_aa) on tiny frames: every method and rate, the edge-per-sample baseline, heavy mode,
// configuration errors and the backend interface. (The seam experiment: experiments_test.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "experiments_test_util.h"
#include "tessera/experiments.h"
#include "tessera/metrics.h"

namespace tessera::experiments {
namespace {

AaConfig tiny_aa() {
  AaConfig c;
  c.width = 48;
  c.height = 36;
  c.ssaa = {2, 3};
  c.frames = 2;
  c.lights = 4;
  c.threads = 2;
  return c;
}

TEST(Aa, EveryMethodAtEveryRateAndAdaptiveBeatsDefault) {
  const AaConfig c = tiny_aa();
  Result<AaResult> r = run_aa(c);
  ASSERT_TRUE(r.ok()) << r.status().message;
  EXPECT_EQ(r->threads, 2);
  EXPECT_EQ(r->gbuffer_1x1.frame_ms.size(), 2u);
  EXPECT_EQ(r->fxaa_1x1.normal.frame_ms.size(), 2u);
  EXPECT_TRUE(r->fxaa_1x1.heavy.frame_ms.empty());
  ASSERT_EQ(r->rates.size(), 2u);
  for (std::size_t i = 0; i < r->rates.size(); ++i) {
    const AaRateResult& rate = r->rates[i];
    const int n = c.ssaa[i] * c.ssaa[i];
    EXPECT_EQ(rate.m, c.ssaa[i]);
    EXPECT_EQ(rate.gbuffer.frame_ms.size(), 2u);
    for (AaMethod k : kAaMethods) {
      const AaMethodResult& mr = rate.method(k);
      EXPECT_EQ(mr.method, k);
      EXPECT_EQ(mr.timing.normal.frame_ms.size(), 2u) << aa_method_name(k);
      EXPECT_EQ(mr.image.width, c.width) << aa_method_name(k);
      EXPECT_GE(mr.quality.ssim, -1.0);
      EXPECT_LE(mr.quality.ssim, 1.0);
    }
    // The reference against itself: identical.
    const AaMethodResult& ref = rate.method(AaMethod::reference);
    EXPECT_TRUE(ref.quality.identical());
    EXPECT_EQ(ref.quality.mse, 0.0);
    EXPECT_EQ(ref.samples_pct, 100.0);
    EXPECT_DOUBLE_EQ(rate.method(AaMethod::default_1spp).samples_pct, 100.0 / n);
    const AaMethodResult& ad = rate.method(AaMethod::adaptive);
    EXPECT_GT(ad.samples_pct, 100.0 / n);  // some pixels got extra samples
    EXPECT_LT(ad.samples_pct, 100.0);      // and not all of them
    EXPECT_EQ(rate.adaptive_samples.size(), std::size_t(c.width * c.height));
    const AaQuality& qd = rate.method(AaMethod::default_1spp).quality;
    EXPECT_FALSE(qd.identical());
    EXPECT_GE(ad.quality.psnr_db, qd.psnr_db);
    EXPECT_LE(ad.quality.mse, qd.mse);
    EXPECT_GT(rate.ablation_geometry.samples_pct, 100.0 / n);
    EXPECT_LT(rate.ablation_geometry.samples_pct, ad.samples_pct + 1e-9);
    EXPECT_LT(rate.ablation_shading.samples_pct, ad.samples_pct + 1e-9);
    EXPECT_EQ(rate.adaptive_first.frame_ms.size(), 2u);
    // The engine baseline: 1 or n samples per pixel, some edge pixels, better than 1 spp.
    const AaMethodResult& edge = rate.method(AaMethod::edge_per_sample);
    ASSERT_EQ(rate.edge_samples.size(), std::size_t(c.width * c.height));
    std::uint64_t shaded = 0;
    for (std::uint8_t k : rate.edge_samples) {
      EXPECT_TRUE(k == 1 || k == n) << int(k);
      shaded += k;
    }
    EXPECT_GT(shaded, std::uint64_t(c.width * c.height));
    EXPECT_DOUBLE_EQ(edge.samples_pct, 100.0 * double(shaded) / (c.width * c.height * n));
    EXPECT_LT(edge.samples_pct, 100.0);
    EXPECT_LT(edge.quality.mse, qd.mse);
    EXPECT_TRUE(rate.method(AaMethod::default_1spp).passes.empty());
    ASSERT_EQ(ad.passes.size(), 3u);
    EXPECT_EQ(ad.passes[1].pass, "metrics");
    EXPECT_FALSE(rate.gl_vs_cpu.has_value());
    EXPECT_TRUE(rate.gbuffer_gpu.frame_ms.empty());  // the CPU has no GPU timer
  }
  EXPECT_EQ(r->backend, Backend::cpu);
  EXPECT_EQ(r->gl, nullptr);

  // The library writes the reports: aa.json lists every rate and the images that go beside it
  // (aa_rate_images, names only or with pixels), aa.md names the scene.
  Result<std::string> j = to_json(c, *r, {.scene_label = "tiny"});
  ASSERT_TRUE(j.ok()) << j.status().message;
  EXPECT_NE(j->find("\"scene\": \"tiny\""), std::string::npos);
  EXPECT_NE(j->find("\"adaptive-3x3\": \"adaptive-3x3.png\""), std::string::npos);
  EXPECT_EQ(j->find("\"backend\""), std::string::npos);  // written only for gl and both
  Result<std::vector<AaRateImage>> names = aa_rate_images(c, r->rates[0], false);
  Result<std::vector<AaRateImage>> images = aa_rate_images(c, r->rates[0]);
  ASSERT_TRUE(names.ok() && images.ok());
  ASSERT_EQ(names->size(), images->size());
  for (std::size_t i = 0; i < names->size(); ++i) {
    EXPECT_EQ((*names)[i].name, (*images)[i].name);
    EXPECT_TRUE((*names)[i].image.pixels.empty());
    EXPECT_EQ((*images)[i].image.width, c.width) << (*images)[i].name;
    EXPECT_NE(j->find("\"" + (*names)[i].name + ".png\""), std::string::npos);
  }
  Result<std::string> md = to_markdown(c, *r, {.scene_label = "tiny"});
  ASSERT_TRUE(md.ok());
  EXPECT_NE(md->find("Scene `tiny`"), std::string::npos);
}

// The baseline's image is, pixel for pixel, the reference's where a pixel is shaded at every
// sample and 1 spp's elsewhere (deferred::shade_edge_per_sample, here through run_aa).
TEST(Aa, EdgePerSampleMixesReferenceAndDefault) {
  AaConfig c = tiny_aa();
  c.ssaa = {3};
  c.frames = 1;
  Result<AaResult> r = run_aa(c);
  ASSERT_TRUE(r.ok()) << r.status().message;
  const AaRateResult& rate = r->rates[0];
  const ImageRGBA8& edge = rate.method(AaMethod::edge_per_sample).image;
  const ImageRGBA8& ref = rate.method(AaMethod::reference).image;
  const ImageRGBA8& def = rate.method(AaMethod::default_1spp).image;
  int complex = 0;
  for (int y = 0; y < c.height; ++y) {
    for (int x = 0; x < c.width; ++x) {
      const bool all = rate.edge_samples[std::size_t(y * c.width + x)] == 9;
      complex += all;
      const ImageRGBA8& want = all ? ref : def;
      for (int ch = 0; ch < 3; ++ch) {
        ASSERT_EQ(edge.at(x, y)[ch], want.at(x, y)[ch]) << x << "," << y;
      }
    }
  }
  EXPECT_GT(complex, 0);
}

TEST(Aa, AllExtraSamplesEqualsTheReference) {
  AaConfig c = tiny_aa();
  c.ssaa = {3};
  c.frames = 1;
  c.adaptive.force_k = 8;
  Result<AaResult> r = run_aa(c);
  ASSERT_TRUE(r.ok()) << r.status().message;
  const AaRateResult& rate = r->rates[0];
  EXPECT_EQ(rate.method(AaMethod::adaptive).image.pixels,
            rate.method(AaMethod::reference).image.pixels);
  EXPECT_TRUE(rate.method(AaMethod::adaptive).quality.identical());
  EXPECT_DOUBLE_EQ(rate.method(AaMethod::adaptive).samples_pct, 100.0);
  EXPECT_NE(rate.method(AaMethod::default_1spp).image.pixels,
            rate.method(AaMethod::reference).image.pixels);
}

TEST(Aa, HeavyModeIsMeasured) {
  AaConfig c = tiny_aa();
  c.ssaa = {2};
  c.frames = 1;
  c.heavy = true;
  c.heavy_terms = 4;
  Result<AaResult> r = run_aa(c);
  ASSERT_TRUE(r.ok()) << r.status().message;
  EXPECT_EQ(r->heavy_terms, 4);
  const AaRateResult& rate = r->rates[0];
  EXPECT_EQ(rate.method(AaMethod::reference).timing.heavy.frame_ms.size(), 1u);
  EXPECT_NE(rate.method(AaMethod::reference).image_heavy.pixels,
            rate.method(AaMethod::reference).image.pixels);
  EXPECT_GT(rate.adaptive_heavy_samples_pct, 25.0);
  EXPECT_FALSE(r->fxaa_1x1.heavy.frame_ms.empty());
}

TEST(Aa, BadConfigurationAndBackendAreErrors) {
  AaConfig c = tiny_aa();
  c.ssaa = {9};
  EXPECT_EQ(run_aa(c).status().code, ErrorCode::invalid_argument);
  c.ssaa = {2};
  c.fxaa_preset = 7;
  EXPECT_EQ(run_aa(c).status().code, ErrorCode::invalid_argument);
  c.fxaa_preset = 39;
  c.backend = Backend::gl;
  int progress = 0;
  bool ready = false;
  c.progress = [&](const std::string&) { ++progress; };
  c.on_ready = [&] {
    ready = true;
    return Status::success();
  };
  // No GL factory (the main library never links OpenGL): a clean error before on_ready.
  Result<AaResult> gl = run_aa(c);
  ASSERT_FALSE(gl.ok());
  EXPECT_EQ(gl.status().code, ErrorCode::unsupported);
  EXPECT_NE(gl.status().message.find("not built with the OpenGL runtime"), std::string::npos);
  c.backend = Backend::both;
  EXPECT_EQ(run_aa(c).status().code, ErrorCode::unsupported);
  EXPECT_NE(run_aa(c).status().message.find("backend 'both'"), std::string::npos);
  // A factory's error comes back as it is, still before on_ready.
  c.gl_factory = test::aa_factory([](const scene::Scene&) -> Result<std::unique_ptr<AaBackend>> {
    return Status::error(ErrorCode::unsupported, "no EGL device 7");
  });
  Result<AaResult> f = run_aa(c);
  ASSERT_FALSE(f.ok());
  EXPECT_EQ(f.status().message, "no EGL device 7");
  c.backend = Backend::gl;
  EXPECT_EQ(run_aa(c).status().message, "no EGL device 7");
  EXPECT_EQ(progress, 0);
  EXPECT_FALSE(ready);
  EXPECT_STREQ(backend_name(Backend::gl), "gl");
  EXPECT_STREQ(backend_name(Backend::both), "both");
  EXPECT_EQ(*parse_backend("both"), Backend::both);
  EXPECT_EQ(parse_backend("gpu").status().code, ErrorCode::invalid_argument);
  EXPECT_STREQ(aa_method_name(AaMethod::edge_per_sample), "edge_per_sample");
}

// A backend whose size check fails stops the run before on_ready (the GL backend's
// framebuffer limits); the CPU backend is used through the same interface.
/// A CPU backend under a GPU's name whose G-buffer may be at most 64 x 64 (a device limit).
struct Limited final : AaBackend {
  std::unique_ptr<AaBackend> cpu;
  Backend kind = Backend::gl;
  Backend backend() const override { return kind; }
  std::string device_name() const override { return "limited"; }
  std::string device_version() const override { return "1"; }
  Status check_size(int w, int h, int m) const override {
    return w * m > 64 || h * m > 64 ? Status::error(ErrorCode::too_large, "over 64")
                                    : Status::success();
  }
  Result<PassTime> render_gbuffer(const scene::Camera& cam, int w, int h, int m) override {
    return cpu->render_gbuffer(cam, w, h, m);
  }
  Result<AaShadeOutput> shade(AaMethod k, const deferred::ShadingOptions& s,
                              const AaShadeOptions& o) override {
    return cpu->shade(k, s, o);
  }
};

test::AaFactoryFn limited_backend(Backend kind) {
  return [kind](const scene::Scene& sc) -> Result<std::unique_ptr<AaBackend>> {
    auto b = std::make_unique<Limited>();
    b->kind = kind;
    Result<std::unique_ptr<AaBackend>> cpu = create_cpu_aa_backend(sc, {2});
    if (!cpu) return cpu.status();
    b->cpu = std::move(*cpu);
    return std::unique_ptr<AaBackend>(std::move(b));
  };
}

TEST(Aa, BackendSizeCheckComesBeforeReady) {
  AaConfig c = tiny_aa();
  c.frames = 1;
  c.backend = Backend::gl;
  c.gl_factory = test::aa_factory(limited_backend(Backend::gl));
  bool ready = false;
  c.on_ready = [&] {
    ready = true;
    return Status::success();
  };
  c.ssaa = {2};  // 96 x 72 grid pixels: over 64
  EXPECT_EQ(run_aa(c).status().code, ErrorCode::too_large);
  EXPECT_FALSE(ready);
  c.width = c.height = 32;  // 64 x 64: fits; the "GL" result carries the device's name
  Result<AaResult> r = run_aa(c);
  ASSERT_TRUE(r.ok()) << r.status().message;
  EXPECT_TRUE(ready);
  EXPECT_EQ(r->backend, Backend::gl);
  EXPECT_EQ(r->gpu_renderer, "limited");
  EXPECT_EQ(r->rates[0].gbuffer_gpu.frame_ms.size(), 1u);  // GL records the GPU timer
  EXPECT_FALSE(r->rates[0].method(AaMethod::adaptive).passes.empty());
}

// Backend::vk goes through `vk_factory` (never `gl_factory`), reports as "vk" with the keys of
// a GL report, and a device that reported validation messages fails the run after it.
TEST(Aa, VulkanBackendHasTheKeysOfGlAndItsDeviceStatusDecides) {
  AaConfig c = tiny_aa();
  c.frames = 1;
  c.ssaa = {2};
  c.width = c.height = 32;
  c.backend = Backend::vk;
  c.gl_factory = test::aa_factory(limited_backend(Backend::gl));
  Result<AaResult> none = run_aa(c);  // a GL factory does not make a Vulkan run
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.status().code, ErrorCode::unsupported);
  EXPECT_NE(none.status().message.find("backend 'vk': not built with the Vulkan runtime"),
            std::string::npos)
      << none.status().message;
  c.vk_factory = test::aa_factory(limited_backend(Backend::vk), Backend::vk);
  Result<AaResult> vk = run_aa(c);
  ASSERT_TRUE(vk.ok()) << vk.status().message;
  EXPECT_EQ(vk->backend, Backend::vk);
  EXPECT_EQ(vk->gpu_renderer, "limited");
  EXPECT_EQ(vk->rates[0].gbuffer_gpu.frame_ms.size(), 1u);  // GPU times recorded as on GL
  c.backend = Backend::gl;
  Result<AaResult> gl = run_aa(c);
  ASSERT_TRUE(gl.ok()) << gl.status().message;
  Result<std::string> sv = to_json(c, *vk), sg = to_json(c, *gl);
  ASSERT_TRUE(sv.ok() && sg.ok());
  const nlohmann::json jv = nlohmann::json::parse(*sv);
  const nlohmann::json jg = nlohmann::json::parse(*sg);
  test::expect_twin_reports(jv, jg);
  EXPECT_EQ(jv["rates"][0].size(), jg["rates"][0].size());
  // Validation messages on the device: the run fails with the device's line.
  c.backend = Backend::vk;
  c.vk_factory = test::aa_factory(
      limited_backend(Backend::vk), Backend::vk,
      Status::error(ErrorCode::unsupported, "vulkan validation: 2 message(s), the first: x"));
  Result<AaResult> bad = run_aa(c);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message, "vulkan validation: 2 message(s), the first: x");
  EXPECT_EQ(*parse_backend("vk"), Backend::vk);
  EXPECT_STREQ(backend_name(Backend::vk), "vk");
}

}  // namespace
}  // namespace tessera::experiments
