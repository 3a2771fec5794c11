// The experiments module (tessera/experiments.h) called directly: the seam experiment of Toth
// 2013 and the adaptive-supersampling experiment of Hollander et al. 2013 on tiny frames, and
// the multi-frame error CDF of metrics.h they use.
#include "tessera/experiments.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tessera/metrics.h"

namespace tessera::experiments {
namespace {

using faces::Method;

SeamsConfig tiny_seams() {
  SeamsConfig c;
  c.figure1.ground = 6;
  c.figure1.character = 4;
  c.figure1.texels_per_unit = 24.0f;
  c.width = 64;
  c.height = 56;
  c.frames = 2;
  c.msaa = {1, 4};
  c.reference_factor = 3;
  c.threads = 2;
  return c;
}

/// Runs the tiny seam experiment once for the whole suite (each run renders ~20 frames).
const SeamsResult& seams_result() {
  static const SeamsResult r = [] {
    Result<SeamsResult> res = run_seams(tiny_seams());
    EXPECT_TRUE(res.ok()) << res.status().message;
    return res.ok() ? *res : SeamsResult{};
  }();
  return r;
}

void expect_valid_cdf(const ErrorStats& s, const std::string& what) {
  ASSERT_EQ(s.cdf.size(), std::size_t(kSeamsCdfBins)) << what;
  ASSERT_GT(s.counted, 0u) << what;
  EXPECT_DOUBLE_EQ(s.cdf[0], 1.0) << what;  // every error is >= 0
  for (std::size_t i = 0; i < s.cdf.size(); ++i) {
    EXPECT_GE(s.cdf[i], 0.0) << what << " bin " << i;
    EXPECT_LE(s.cdf[i], 1.0) << what << " bin " << i;
    if (i > 0) {
      EXPECT_LE(s.cdf[i], s.cdf[i - 1]) << what << " bin " << i;
    }
  }
  EXPECT_GE(s.mean, 0.0) << what;
  EXPECT_TRUE(std::isfinite(s.mean)) << what;
}

TEST(ErrorCdfAccumulator, EqualsErrorCdfOverAllPairsTogether) {
  // Two pairs of 3x1 images; errors 0, 0.1, 0.5 and 0.2, 0.3, 0.05 (masked: the 0.3 pixel).
  ImageRGBAF a1(3, 1), b1(3, 1), a2(3, 1), b2(3, 1);
  b1.at(1, 0)[0] = 0.1f;
  b1.at(2, 0)[1] = 0.5f;
  b2.at(0, 0)[2] = 0.2f;
  b2.at(1, 0)[0] = 0.3f;
  b2.at(2, 0)[1] = 0.05f;
  const std::vector<std::uint8_t> mask2 = {1, 0, 1};
  const std::vector<double> xs = {0.0, 0.05, 0.1, 0.2, 0.4, 0.6};
  ErrorCdfAccumulator acc(xs);
  ASSERT_TRUE(acc.add(a1, b1).ok());
  ASSERT_TRUE(acc.add(a2, b2, mask2).ok());
  EXPECT_EQ(acc.counted(), 5u);
  // Together: 0, 0.1, 0.5, 0.2, 0.05 as one 5x1 pair.
  ImageRGBAF a(5, 1), b(5, 1);
  b.at(1, 0)[0] = 0.1f;
  b.at(2, 0)[1] = 0.5f;
  b.at(3, 0)[2] = 0.2f;
  b.at(4, 0)[1] = 0.05f;
  Result<std::vector<double>> whole = error_cdf(a, b, xs);
  ASSERT_TRUE(whole.ok());
  EXPECT_EQ(acc.fractions(), *whole);
  EXPECT_DOUBLE_EQ(acc.fractions()[1], 0.8);  // >= 0.05 includes the pixel at exactly 0.05f
  EXPECT_DOUBLE_EQ(acc.fractions()[4], 0.2);
  EXPECT_NEAR(acc.mean(), (0.1 + 0.5 + 0.2 + 0.05) / 5.0, 1e-7);
  // A size mismatch is an error and leaves the accumulator unchanged.
  EXPECT_FALSE(acc.add(a, b1).ok());
  EXPECT_EQ(acc.counted(), 5u);
}

TEST(ErrorCdfAccumulator, ReferenceAgainstItselfHasZeroError) {
  const SeamsResult& r = seams_result();
  ASSERT_FALSE(r.reference_frame0.pixels.empty());
  ErrorCdfAccumulator acc(r.thresholds);
  ASSERT_TRUE(acc.add(r.reference_frame0, r.reference_frame0).ok());
  EXPECT_EQ(acc.counted(), r.reference_frame0.pixel_count());
  EXPECT_EQ(acc.mean(), 0.0);
  const std::vector<double> f = acc.fractions();
  EXPECT_EQ(f[0], 1.0);
  for (std::size_t i = 1; i < f.size(); ++i) EXPECT_EQ(f[i], 0.0) << i;
}

TEST(Seams, EveryMethodAtEveryRate) {
  const SeamsConfig c = tiny_seams();
  const SeamsResult& r = seams_result();
  ASSERT_EQ(r.rates.size(), c.msaa.size());
  EXPECT_EQ(r.quality_frames, c.frames);
  EXPECT_EQ(r.threads, 2);
  EXPECT_TRUE(r.has_character);
  EXPECT_GT(r.ground_faces, 0);
  EXPECT_EQ(r.faces, 6 * 6 + 6 * 4 * 4);
  ASSERT_EQ(r.thresholds.size(), std::size_t(kSeamsCdfBins));
  EXPECT_DOUBLE_EQ(r.thresholds[10], 0.01);
  for (std::size_t ri = 0; ri < r.rates.size(); ++ri) {
    const SeamsRateResult& rate = r.rates[ri];
    EXPECT_EQ(rate.msaa, c.msaa[ri]);
    EXPECT_EQ(rate.shading_only.frame_ms.size(), std::size_t(c.frames));
    for (Method m : faces::all_methods()) {
      const SeamsMethodResult& mr = rate.method(m);
      const std::string what =
          std::string(faces::method_name(m)) + " " + std::to_string(rate.msaa) + "x";
      EXPECT_EQ(mr.method, m) << what;
      EXPECT_EQ(mr.timing.frame_ms.size(), std::size_t(c.frames)) << what;
      EXPECT_EQ(mr.frame0.width, c.width) << what;
      expect_valid_cdf(mr.vs_reference, what);
      expect_valid_cdf(mr.vs_reference_character, what + " character");
      EXPECT_LT(mr.vs_reference_character.counted, mr.vs_reference.counted) << what;
    }
    expect_valid_cdf(rate.traverse_vs_discard, "traverse vs discard");
    // The same geometry pixels are counted for every comparison of a rate.
    EXPECT_EQ(rate.traverse_vs_discard.counted, rate.method(Method::clamp).vs_reference.counted);
    // Traverse and Discard differ somewhere (near seams), so the CDF leaves 1 after bin 0.
    EXPECT_LT(rate.traverse_vs_discard.cdf[1], 1.0);
    EXPECT_GT(rate.traverse_vs_discard.mean, 0.0);
  }
}

TEST(Seams, TraverseBeatsClampNearSeams) {
  const SeamsResult& r = seams_result();
  for (const SeamsRateResult& rate : r.rates) {
    const ImageRGBAF& clamp = rate.method(Method::clamp).frame0;
    const ImageRGBAF& trav = rate.method(Method::traverse).frame0;
    // Near seams: geometry pixels where Clamp and Traverse disagree visibly.
    Result<std::vector<float>> d = error_norms(clamp, trav);
    ASSERT_TRUE(d.ok());
    std::vector<std::uint8_t> seam(d->size(), 0);
    for (std::size_t i = 0; i < seam.size(); ++i) {
      seam[i] = (*d)[i] > 0.02f && r.reference_frame0.pixels[i * 4 + 3] > 0.01f ? 1 : 0;
    }
    ErrorCdfAccumulator ec(r.thresholds), et(r.thresholds);
    ASSERT_TRUE(ec.add(clamp, r.reference_frame0, seam).ok());
    ASSERT_TRUE(et.add(trav, r.reference_frame0, seam).ok());
    ASSERT_GT(ec.counted(), 20u) << rate.msaa << "x";
    EXPECT_LT(et.mean(), ec.mean()) << rate.msaa << "x";
    // Over all geometry pixels and quality frames too.
    EXPECT_LE(rate.method(Method::traverse).vs_reference.mean,
              rate.method(Method::clamp).vs_reference.mean)
        << rate.msaa << "x";
  }
}

TEST(Seams, NearSeamStatisticsCountPixelsByFaceEdges) {
  const SeamsResult& r = seams_result();
  ASSERT_EQ(r.near_seam_pixels, 2);
  for (const SeamsRateResult& rate : r.rates) {
    for (const auto& mr : rate.methods) {
      const ErrorStats& near = mr.vs_reference_near_seams;
      expect_valid_cdf(near, std::string("near seams ") + faces::method_name(mr.method));
      // A subset of the geometry pixels, the same set for every method.
      EXPECT_LT(near.counted, mr.vs_reference.counted);
      EXPECT_EQ(near.counted, rate.method(Method::clamp).vs_reference_near_seams.counted);
    }
    // Where the faces meet, Traverse is closer to the reference than Clamp.
    EXPECT_LT(rate.method(Method::traverse).vs_reference_near_seams.mean,
              rate.method(Method::clamp).vs_reference_near_seams.mean)
        << rate.msaa << "x";
  }
  // A wider band counts more pixels; 0 turns the statistics off.
  SeamsConfig c = tiny_seams();
  c.frames = 1;
  c.msaa = {1};
  c.near_seam_pixels = 4;
  Result<SeamsResult> wide = run_seams(c);
  ASSERT_TRUE(wide.ok()) << wide.status().message;
  c.near_seam_pixels = 1;
  Result<SeamsResult> narrow = run_seams(c);
  ASSERT_TRUE(narrow.ok()) << narrow.status().message;
  EXPECT_GT(wide->rates[0].method(Method::clamp).vs_reference_near_seams.counted,
            narrow->rates[0].method(Method::clamp).vs_reference_near_seams.counted);
  c.near_seam_pixels = 0;
  Result<SeamsResult> off = run_seams(c);
  ASSERT_TRUE(off.ok());
  EXPECT_EQ(off->near_seam_pixels, 0);
  EXPECT_EQ(off->rates[0].method(Method::clamp).vs_reference_near_seams.counted, 0u);
}

TEST(Seams, ThreadCountDoesNotChangeTheNumbers) {
  SeamsConfig c = tiny_seams();
  c.threads = 1;
  c.frames = 1;
  c.msaa = {1};
  Result<SeamsResult> one = run_seams(c);
  c.threads = 3;
  Result<SeamsResult> three = run_seams(c);
  ASSERT_TRUE(one.ok() && three.ok());
  for (Method m : faces::all_methods()) {
    EXPECT_EQ(one->rates[0].method(m).vs_reference.cdf, three->rates[0].method(m).vs_reference.cdf);
    EXPECT_EQ(one->rates[0].method(m).vs_reference.mean,
              three->rates[0].method(m).vs_reference.mean);
    EXPECT_EQ(one->rates[0].method(m).frame0.pixels, three->rates[0].method(m).frame0.pixels);
  }
}

TEST(Seams, ProgressAndReadyCallbacks) {
  SeamsConfig c = tiny_seams();
  c.frames = 1;
  c.msaa = {1};
  c.keep_images = false;
  std::vector<std::string> lines;
  int ready = 0;
  c.progress = [&](const std::string& s) { lines.push_back(s); };
  c.on_ready = [&] {
    ++ready;
    return Status::success();
  };
  Result<SeamsResult> r = run_seams(c);
  ASSERT_TRUE(r.ok()) << r.status().message;
  EXPECT_EQ(ready, 1);
  ASSERT_EQ(lines.size(), 2u);  // the scene, then one line per frame
  EXPECT_EQ(lines[1], "frame 1/1 done");
  EXPECT_TRUE(r->reference_frame0.pixels.empty());
  EXPECT_TRUE(r->rates[0].method(Method::discard).frame0.pixels.empty());
  // An error from on_ready stops the run and comes back unchanged.
  c.on_ready = [] { return Status::error(ErrorCode::io_error, "no folder"); };
  Result<SeamsResult> stopped = run_seams(c);
  ASSERT_FALSE(stopped.ok());
  EXPECT_EQ(stopped.status().code, ErrorCode::io_error);
  EXPECT_EQ(stopped.status().message, "no folder");
}

TEST(Seams, BadConfigurationAndBackendAreErrors) {
  bool ready = false;
  SeamsConfig c = tiny_seams();
  c.on_ready = [&] {
    ready = true;
    return Status::success();
  };
  c.msaa = {3};
  EXPECT_EQ(run_seams(c).status().code, ErrorCode::invalid_argument);
  c.msaa = {1};
  c.width = 4;
  EXPECT_EQ(run_seams(c).status().code, ErrorCode::invalid_argument);
  c.width = 64;
  // GL (or GL beside the CPU) without a renderer factory: the main library has no OpenGL.
  c.backend = Backend::gl;
  Result<SeamsResult> gl = run_seams(c);
  ASSERT_FALSE(gl.ok());
  EXPECT_EQ(gl.status().code, ErrorCode::unsupported);
  EXPECT_NE(gl.status().message.find("not built with the OpenGL runtime"), std::string::npos)
      << gl.status().message;
  c.backend = Backend::cpu;
  c.compare_gl = true;
  EXPECT_EQ(run_seams(c).status().code, ErrorCode::unsupported);
  // A factory's error (e.g. no EGL device) comes back unchanged.
  c.gl_renderer_factory =
      [](const faces::FaceScene&,
         const faces::FaceTextureSet&) -> Result<std::unique_ptr<SeamsFrameRenderer>> {
    return Status::error(ErrorCode::unsupported, "no EGL device 7");
  };
  EXPECT_EQ(run_seams(c).status().message, "no EGL device 7");
  c.backend = Backend::gl;  // GL beside GL: nothing to compare with
  EXPECT_EQ(run_seams(c).status().code, ErrorCode::invalid_argument);
  c.compare_gl = false;
  EXPECT_EQ(run_seams(c).status().message, "no EGL device 7");
  c.gl_renderer_factory = nullptr;
  c.backend = Backend::cpu;
  c.scene = "/nonexistent/mesh.obj";
  EXPECT_FALSE(run_seams(c).ok());
  EXPECT_FALSE(ready);  // no input was good enough to get there
}

/// A stand-in for the GL backend: the CPU renderer under another name that refuses some MSAA
/// rates and has no shading-only pass, as a GL driver may.
class FakeGlRenderer final : public SeamsFrameRenderer {
 public:
  /// `perturb`: add 0.02 to the red channel of pixel (0, 0) of every frame.
  FakeGlRenderer(std::unique_ptr<SeamsFrameRenderer> cpu, std::vector<int> refused, bool perturb)
      : cpu_(std::move(cpu)), refused_(std::move(refused)), perturb_(perturb) {}
  Backend backend() const override { return Backend::gl; }
  std::string device_name() const override { return "fake renderer"; }
  std::string device_version() const override { return "9.9"; }
  bool msaa_supported(int samples) override {
    return std::find(refused_.begin(), refused_.end(), samples) == refused_.end();
  }
  bool has_shading_only() const override { return false; }
  Result<SeamsBackendFrame> render(const scene::Camera& camera,
                                   const SeamsFrameOptions& options) override {
    EXPECT_FALSE(options.shading_only);
    EXPECT_TRUE(msaa_supported(options.msaa));
    Result<SeamsBackendFrame> f = cpu_->render(camera, options);
    if (!f) return f;
    f->wall_ms = f->ms + 1.0;
    if (perturb_ && !f->image.pixels.empty()) f->image.pixels[0] += 0.02f;
    return f;
  }
  Result<ImageRGBAF> render_reference(const scene::Camera& camera, int width, int height,
                                      int factor, int threads) override {
    return cpu_->render_reference(camera, width, height, factor, threads);
  }

 private:
  std::unique_ptr<SeamsFrameRenderer> cpu_;
  std::vector<int> refused_;
  bool perturb_ = false;
};

SeamsRendererFactory fake_gl_factory(std::vector<int> refused, bool perturb = false) {
  return [refused, perturb](
             const faces::FaceScene& scene,
             const faces::FaceTextureSet& set) -> Result<std::unique_ptr<SeamsFrameRenderer>> {
    Result<std::unique_ptr<SeamsFrameRenderer>> cpu = create_cpu_seams_renderer(scene, set);
    if (!cpu) return cpu.status();
    return std::unique_ptr<SeamsFrameRenderer>(
        std::make_unique<FakeGlRenderer>(std::move(*cpu), refused, perturb));
  };
}

TEST(Seams, GlBackendThroughTheFactorySkipsRefusedRates) {
  SeamsConfig c = tiny_seams();
  c.backend = Backend::gl;
  c.gl_renderer_factory = fake_gl_factory({4});
  Result<SeamsResult> r = run_seams(c);
  ASSERT_TRUE(r.ok()) << r.status().message;
  EXPECT_EQ(r->backend, Backend::gl);
  EXPECT_EQ(r->gl_renderer, "fake renderer");
  EXPECT_EQ(r->gl_version, "9.9");
  EXPECT_EQ(r->msaa_unsupported, std::vector<int>{4});
  ASSERT_EQ(r->rates.size(), 1u);  // 4x skipped, not failed
  const SeamsResult& cpu = seams_result();
  ASSERT_EQ(cpu.rates.size(), 2u);
  const SeamsRateResult& g = r->rates[0];
  EXPECT_EQ(g.msaa, 1);
  EXPECT_TRUE(g.shading_only.frame_ms.empty());  // no shading-only pass there
  for (Method m : faces::all_methods()) {
    const SeamsMethodResult& mr = g.method(m);
    ASSERT_EQ(mr.timing.frame_ms.size(), std::size_t(c.frames));
    ASSERT_EQ(mr.wall.frame_ms.size(), std::size_t(c.frames));
    EXPECT_DOUBLE_EQ(mr.wall.frame_ms[0], mr.timing.frame_ms[0] + 1.0);
    // The same frames and reference as the CPU run: the same statistics.
    EXPECT_EQ(mr.vs_reference.cdf, cpu.rates[0].method(m).vs_reference.cdf);
    EXPECT_EQ(mr.vs_reference_near_seams.cdf, cpu.rates[0].method(m).vs_reference_near_seams.cdf);
    EXPECT_EQ(mr.vs_reference_character.cdf, cpu.rates[0].method(m).vs_reference_character.cdf);
  }
  EXPECT_EQ(g.nan_pixels_without_fallback, cpu.rates[0].nan_pixels_without_fallback);
  EXPECT_TRUE(r->gl_rates.empty());

  // Every rate refused: an error before anything is written.
  bool ready = false;
  c.on_ready = [&] {
    ready = true;
    return Status::success();
  };
  c.gl_renderer_factory = fake_gl_factory({1, 4});
  Result<SeamsResult> none = run_seams(c);
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.status().code, ErrorCode::unsupported);
  EXPECT_NE(none.status().message.find("refuses every MSAA rate"), std::string::npos);
  EXPECT_FALSE(ready);
}

TEST(Seams, CompareGlKeepsTheCpuResultAndMeasuresAgreement) {
  SeamsConfig c = tiny_seams();
  c.compare_gl = true;
  c.gl_renderer_factory = fake_gl_factory({4}, true);
  Result<SeamsResult> r = run_seams(c);
  ASSERT_TRUE(r.ok()) << r.status().message;
  EXPECT_EQ(r->backend, Backend::cpu);
  EXPECT_TRUE(r->compared_gl);
  EXPECT_EQ(r->msaa_unsupported, std::vector<int>{4});
  const SeamsResult& cpu = seams_result();
  ASSERT_EQ(r->rates.size(), cpu.rates.size());  // the CPU renders every rate
  for (std::size_t ri = 0; ri < cpu.rates.size(); ++ri) {
    for (Method m : faces::all_methods()) {
      EXPECT_EQ(r->rates[ri].method(m).vs_reference.cdf, cpu.rates[ri].method(m).vs_reference.cdf);
      EXPECT_TRUE(r->rates[ri].method(m).wall.frame_ms.empty());
    }
    EXPECT_EQ(r->rates[ri].shading_only.frame_ms.size(), std::size_t(c.frames));
  }
  ASSERT_EQ(r->gl_rates.size(), 1u);  // GL skips the refused 4x
  EXPECT_EQ(r->gl_rates[0].msaa, 1);
  for (Method m : faces::all_methods()) {
    const SeamsGlMethodResult& g = r->gl_rates[0].method(m);
    EXPECT_EQ(g.method, m);
    EXPECT_EQ(g.gpu.frame_ms.size(), std::size_t(c.frames));
    EXPECT_EQ(g.wall.frame_ms.size(), std::size_t(c.frames));
    // The stand-in renders the CPU's frames with one pixel 0.02 brighter in red: that pixel,
    // of every quality frame, is >= 0.01 apart; the 8-bit PSNR is finite and high.
    EXPECT_DOUBLE_EQ(g.fraction_ge_001, 1.0 / double(c.width * c.height));
    EXPECT_TRUE(std::isfinite(g.psnr_db));
    EXPECT_GT(g.psnr_db, 40.0);
  }
}

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
  c.backend = Backend::cpu;
  c.compare_gl = true;
  EXPECT_EQ(run_aa(c).status().code, ErrorCode::unsupported);
  // A factory's error comes back as it is, still before on_ready.
  c.gl_backend_factory = [](const scene::Scene&) -> Result<std::unique_ptr<AaBackend>> {
    return Status::error(ErrorCode::unsupported, "no EGL device 7");
  };
  Result<AaResult> f = run_aa(c);
  ASSERT_FALSE(f.ok());
  EXPECT_EQ(f.status().message, "no EGL device 7");
  c.backend = Backend::gl;  // gl with compare_gl: nothing to compare with
  EXPECT_EQ(run_aa(c).status().code, ErrorCode::invalid_argument);
  EXPECT_EQ(progress, 0);
  EXPECT_FALSE(ready);
  EXPECT_STREQ(backend_name(Backend::gl), "gl");
  EXPECT_STREQ(aa_method_name(AaMethod::edge_per_sample), "edge_per_sample");
}

// A backend whose size check fails stops the run before on_ready (the GL backend's
// framebuffer limits); the CPU backend is used through the same interface.
TEST(Aa, BackendSizeCheckComesBeforeReady) {
  struct Limited final : AaBackend {
    std::unique_ptr<AaBackend> cpu;
    Backend backend() const override { return Backend::gl; }
    std::string device_name() const override { return "limited"; }
    std::string device_version() const override { return "1"; }
    Status check_size(int w, int h, int m) const override {
      return w * m > 64 || h * m > 64 ? Status::error(ErrorCode::too_large, "over 64")
                                      : Status::success();
    }
    Result<AaPassTime> render_gbuffer(const scene::Camera& cam, int w, int h, int m) override {
      return cpu->render_gbuffer(cam, w, h, m);
    }
    Result<AaShadeOutput> shade(AaMethod k, const deferred::ShadingOptions& s,
                                const AaShadeOptions& o) override {
      return cpu->shade(k, s, o);
    }
  };
  AaConfig c = tiny_aa();
  c.frames = 1;
  c.backend = Backend::gl;
  c.gl_backend_factory = [](const scene::Scene& sc) -> Result<std::unique_ptr<AaBackend>> {
    auto b = std::make_unique<Limited>();
    Result<std::unique_ptr<AaBackend>> cpu = create_cpu_aa_backend(sc, 2);
    if (!cpu) return cpu.status();
    b->cpu = std::move(*cpu);
    return std::unique_ptr<AaBackend>(std::move(b));
  };
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
  EXPECT_EQ(r->gl_renderer, "limited");
  EXPECT_EQ(r->rates[0].gbuffer_gpu.frame_ms.size(), 1u);  // GL records the GPU timer
  EXPECT_FALSE(r->rates[0].method(AaMethod::adaptive).passes.empty());
}

TEST(Experiments, Names) {
  EXPECT_STREQ(aa_method_name(AaMethod::default_1spp), "default");
  EXPECT_STREQ(aa_method_name(AaMethod::adaptive), "adaptive");
  ErrorStats s;
  s.cdf = {1.0, 0.5, 0.25};
  EXPECT_EQ(s.at(0.001), 0.5);
  EXPECT_EQ(s.at(1.0), 0.25);  // clamped to the last bin
}

}  // namespace
}  // namespace tessera::experiments
