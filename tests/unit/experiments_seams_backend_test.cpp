// The seam experiment of tessera/experiments.h through the SeamsBackend interface: fake GL
// backends that refuse some MSAA rates, perturb or round their frames, and Backend::both's
// agreement measures against the CPU renderer. (The CPU backend: experiments_test.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "experiments_test_util.h"
#include "tessera/experiments.h"
#include "tessera/metrics.h"

namespace tessera::experiments {
namespace {

using faces::SeamMethod;
using raster::SampleOffset;
using test::seams_result;
using test::tiny_seams;

std::vector<SampleOffset> standard_positions(int n) {
  const std::span<const SampleOffset> p = raster::sample_positions(n);
  return {p.begin(), p.end()};
}

/// What every stand-in for the GL backend below shares: the CPU renderer under another name,
/// with GL's version string, no shading-only pass and the CPU's reference.
class CpuBackedFakeGl : public SeamsBackend {
 public:
  CpuBackedFakeGl(std::unique_ptr<SeamsBackend> cpu, std::string name)
      : cpu_(std::move(cpu)), name_(std::move(name)) {}
  Backend backend() const override { return kind_; }
  /// Stand in for a Vulkan backend instead.
  void set_backend(Backend kind) { kind_ = kind; }
  std::string device_name() const override { return name_; }
  std::string device_version() const override { return "9.9"; }
  bool has_shading_only() const override { return false; }
  Result<ImageRGBAF> render_reference(const scene::Camera& camera, int width, int height,
                                      const faces::ReferenceOptions& options) override {
    return cpu_->render_reference(camera, width, height, options);
  }

 protected:
  std::unique_ptr<SeamsBackend> cpu_;

 private:
  std::string name_;
  Backend kind_ = Backend::gl;
};

/// A stand-in for the GL backend: the CPU renderer under another name that refuses some MSAA
/// rates and has no shading-only pass, as a GL driver may.
class FakeGlRenderer final : public CpuBackedFakeGl {
 public:
  /// `perturb`: add 0.02 to the red channel of pixel (0, 0) of every frame.
  FakeGlRenderer(std::unique_ptr<SeamsBackend> cpu, std::vector<int> refused, bool perturb)
      : CpuBackedFakeGl(std::move(cpu), "fake renderer"),
        refused_(std::move(refused)),
        perturb_(perturb) {}
  bool msaa_supported(int samples) override {
    return std::find(refused_.begin(), refused_.end(), samples) == refused_.end();
  }
  Result<SeamsBackendFrame> render(const scene::Camera& camera,
                                   const FaceFrameOptions& options) override {
    EXPECT_FALSE(options.shading_only);
    EXPECT_TRUE(msaa_supported(options.msaa));
    Result<SeamsBackendFrame> f = cpu_->render(camera, options);
    if (!f) return f;
    f->wall_ms = f->ms + 1.0;
    if (perturb_ && !f->image.pixels.empty()) f->image.pixels[0] += 0.02f;
    return f;
  }

 private:
  std::vector<int> refused_;
  bool perturb_ = false;
};

/// A factory of `FakeGlRenderer`s standing in for `kind` (gl or vk).
std::shared_ptr<const GpuBackendFactory> fake_gl_factory(std::vector<int> refused,
                                                         bool perturb = false,
                                                         Backend kind = Backend::gl,
                                                         Status status = Status::success()) {
  return test::seams_factory(
      [refused, perturb, kind](const faces::FaceScene& scene, const faces::FaceTextureSet& set)
          -> Result<std::unique_ptr<SeamsBackend>> {
        Result<std::unique_ptr<SeamsBackend>> cpu = create_cpu_seams_backend(scene, set);
        if (!cpu) return cpu.status();
        auto fake = std::make_unique<FakeGlRenderer>(std::move(*cpu), refused, perturb);
        fake->set_backend(kind);
        return std::unique_ptr<SeamsBackend>(std::move(fake));
      },
      kind, std::move(status));
}

// Backend::vk goes through `vk_factory` alone, reports as "vk" with exactly the keys of a GL
// report (its timing note says Vulkan), and a device that reported validation messages fails
// the run after it.
TEST(Seams, VulkanBackendHasTheKeysOfGlAndItsDeviceStatusDecides) {
  SeamsConfig c = tiny_seams();
  c.frames = 1;
  c.backend = Backend::vk;
  c.gl_factory = fake_gl_factory({});
  Result<SeamsResult> none = run_seams(c);
  ASSERT_FALSE(none.ok());
  EXPECT_NE(none.status().message.find("backend 'vk': not built with the Vulkan runtime"),
            std::string::npos)
      << none.status().message;
  c.vk_factory = fake_gl_factory({}, false, Backend::vk);
  Result<SeamsResult> vk = run_seams(c);
  ASSERT_TRUE(vk.ok()) << vk.status().message;
  EXPECT_EQ(vk->backend, Backend::vk);
  EXPECT_EQ(vk->gpu_renderer, "fake renderer");
  ASSERT_EQ(vk->rates.size(), 2u);
  c.backend = Backend::gl;
  Result<SeamsResult> gl = run_seams(c);
  ASSERT_TRUE(gl.ok()) << gl.status().message;
  const nlohmann::json jv = nlohmann::json::parse(to_json(c, *vk));
  const nlohmann::json jg = nlohmann::json::parse(to_json(c, *gl));
  test::expect_twin_reports(jv, jg);
  EXPECT_NE(jv["timing_note"].get<std::string>().find("Vulkan"), std::string::npos);
  EXPECT_NE(to_markdown(c, *vk).find("**Vulkan**: fake renderer"), std::string::npos);
  c.backend = Backend::vk;
  c.vk_factory = fake_gl_factory({}, false, Backend::vk,
                                 Status::error(ErrorCode::unsupported, "vulkan validation: 1"));
  Result<SeamsResult> bad = run_seams(c);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message, "vulkan validation: 1");
}

TEST(Seams, GlBackendThroughTheFactorySkipsRefusedRates) {
  SeamsConfig c = tiny_seams();
  c.backend = Backend::gl;
  c.gl_factory = fake_gl_factory({4});
  Result<SeamsResult> r = run_seams(c);
  ASSERT_TRUE(r.ok()) << r.status().message;
  EXPECT_EQ(r->backend, Backend::gl);
  EXPECT_EQ(r->gpu_renderer, "fake renderer");
  EXPECT_EQ(r->gpu_version, "9.9");
  EXPECT_EQ(r->msaa_unsupported, std::vector<int>{4});
  ASSERT_EQ(r->rates.size(), 1u);  // 4x skipped, not failed
  const SeamsResult& cpu = seams_result();
  ASSERT_EQ(cpu.rates.size(), 2u);
  const SeamsRateResult& g = r->rates[0];
  EXPECT_EQ(g.msaa, 1);
  EXPECT_TRUE(g.shading_only.frame_ms.empty());  // no shading-only pass there
  for (SeamMethod m : faces::all_methods()) {
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
  c.gl_factory = fake_gl_factory({1, 4});
  Result<SeamsResult> none = run_seams(c);
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.status().code, ErrorCode::unsupported);
  EXPECT_NE(none.status().message.find("refuses every MSAA rate"), std::string::npos);
  EXPECT_FALSE(ready);
}

TEST(Seams, CompareGlKeepsTheCpuResultAndMeasuresAgreement) {
  SeamsConfig c = tiny_seams();
  c.backend = Backend::both;
  c.gl_factory = fake_gl_factory({4}, true);
  Result<SeamsResult> r = run_seams(c);
  ASSERT_TRUE(r.ok()) << r.status().message;
  EXPECT_EQ(r->backend, Backend::both);
  EXPECT_EQ(r->msaa_unsupported, std::vector<int>{4});
  const SeamsResult& cpu = seams_result();
  ASSERT_EQ(r->rates.size(), cpu.rates.size());  // the CPU renders every rate
  for (std::size_t ri = 0; ri < cpu.rates.size(); ++ri) {
    for (SeamMethod m : faces::all_methods()) {
      EXPECT_EQ(r->rates[ri].method(m).vs_reference.cdf, cpu.rates[ri].method(m).vs_reference.cdf);
      EXPECT_TRUE(r->rates[ri].method(m).wall.frame_ms.empty());
    }
    EXPECT_EQ(r->rates[ri].shading_only.frame_ms.size(), std::size_t(c.frames));
  }
  ASSERT_EQ(r->gl_rates.size(), 1u);  // GL skips the refused 4x
  EXPECT_EQ(r->gl_rates[0].msaa, 1);
  // A backend that does not say otherwise draws the standard pattern of the rate.
  EXPECT_EQ(r->gl_rates[0].compared_with, SeamsGlComparison::cpu_rate);
  ASSERT_EQ(r->gpu_sample_patterns.size(), 1u);
  EXPECT_EQ(r->gpu_sample_patterns[0].positions,
            std::vector<raster::SampleOffset>{raster::SampleOffset{}});
  for (SeamMethod m : faces::all_methods()) {
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

/// A stand-in for a driver that draws 2x with its 4x samples, as Mesa llvmpipe does: the CPU
/// renderer at 4x for 2x. `report`: say so in `sample_pattern` (as the GL backend does).
class RoundingFakeGlRenderer final : public CpuBackedFakeGl {
 public:
  RoundingFakeGlRenderer(std::unique_ptr<SeamsBackend> cpu, bool report)
      : CpuBackedFakeGl(std::move(cpu), "rounding renderer"), report_(report) {}
  bool msaa_supported(int samples) override { return samples == 2 || samples == 4; }
  SeamsSamplePattern sample_pattern(int msaa) override {
    return report_ ? SeamsSamplePattern{msaa, 4, 4, standard_positions(4)}
                   : SeamsSamplePattern{msaa, msaa, msaa, standard_positions(msaa)};
  }
  Result<SeamsBackendFrame> render(const scene::Camera& camera,
                                   const FaceFrameOptions& options) override {
    FaceFrameOptions o = options;
    o.msaa = 4;
    return cpu_->render(camera, o);
  }

 private:
  bool report_ = true;
};

// Backend::both compares a GL frame with the CPU frame of the driver's sample positions: a 2x
// frame drawn with 4x samples against the CPU's 4x frame (here the very same frame: identical),
// not the CPU's 2x one (which differs at every edge).
TEST(Seams, CompareGlUsesTheDriversSamplePositions) {
  for (bool report : {true, false}) {
    SeamsConfig c = tiny_seams();
    c.msaa = {2, 4};
    c.frames = 1;
    c.backend = Backend::both;
    c.gl_factory = test::seams_factory(
        [report](const faces::FaceScene& scene,
                 const faces::FaceTextureSet& set) -> Result<std::unique_ptr<SeamsBackend>> {
          Result<std::unique_ptr<SeamsBackend>> cpu = create_cpu_seams_backend(scene, set);
          if (!cpu) return cpu.status();
          return std::unique_ptr<SeamsBackend>(
              std::make_unique<RoundingFakeGlRenderer>(std::move(*cpu), report));
        });
    Result<SeamsResult> r = run_seams(c);
    ASSERT_TRUE(r.ok()) << r.status().message;
    ASSERT_EQ(r->gpu_sample_patterns.size(), 2u);
    EXPECT_EQ(r->gpu_sample_patterns[0].msaa, 2);
    EXPECT_EQ(r->gpu_sample_patterns[0].samples, report ? 4 : 2);
    EXPECT_EQ(r->gpu_sample_patterns[0].cpu_msaa, report ? 4 : 2);
    EXPECT_EQ(r->gpu_sample_patterns[1].msaa, 4);
    ASSERT_EQ(r->gl_rates.size(), 2u);
    for (SeamMethod m : faces::all_methods()) {
      const SeamsGlMethodResult& g2 = r->gl_rates[0].method(m);
      const SeamsGlMethodResult& g4 = r->gl_rates[1].method(m);
      EXPECT_FALSE(std::isfinite(g4.psnr_db)) << faces::method_name(m);  // identical
      if (report) {
        EXPECT_FALSE(std::isfinite(g2.psnr_db)) << faces::method_name(m);
        EXPECT_EQ(g2.fraction_ge_001, 0.0);
      } else {
        EXPECT_TRUE(std::isfinite(g2.psnr_db)) << faces::method_name(m);
        EXPECT_GT(g2.fraction_ge_001, 0.0);
      }
    }
  }
}

/// A stand-in for a driver whose 2x pattern is none of the standard ones: the CPU renderer
/// drawing at `draws` (empty: the standard 2x), reporting `reported` as its positions and
/// `cpu_msaa` as the CPU rate with them.
class PatternFakeGlRenderer final : public CpuBackedFakeGl {
 public:
  PatternFakeGlRenderer(std::unique_ptr<SeamsBackend> cpu, std::vector<SampleOffset> draws,
                        std::vector<SampleOffset> reported, int cpu_msaa)
      : CpuBackedFakeGl(std::move(cpu), "pattern renderer"),
        draws_(std::move(draws)),
        reported_(std::move(reported)),
        cpu_msaa_(cpu_msaa) {}
  bool msaa_supported(int samples) override { return samples == 2; }
  SeamsSamplePattern sample_pattern(int msaa) override { return {msaa, 2, cpu_msaa_, reported_}; }
  Result<SeamsBackendFrame> render(const scene::Camera& camera,
                                   const FaceFrameOptions& options) override {
    EXPECT_TRUE(options.sample_pattern.empty());  // GL frames are drawn at the driver's
    FaceFrameOptions o = options;
    o.sample_pattern = draws_;
    return cpu_->render(camera, o);
  }

 private:
  std::vector<SampleOffset> draws_, reported_;
  int cpu_msaa_ = 0;
};

/// Backend::both at 2x with a PatternFakeGlRenderer.
Result<SeamsResult> run_pattern_fake(const std::vector<SampleOffset>& draws,
                                     const std::vector<SampleOffset>& reported, int cpu_msaa) {
  SeamsConfig c = tiny_seams();
  c.msaa = {2};
  c.frames = 1;
  c.backend = Backend::both;
  c.gl_factory = test::seams_factory(
      [=](const faces::FaceScene& scene,
          const faces::FaceTextureSet& set) -> Result<std::unique_ptr<SeamsBackend>> {
        Result<std::unique_ptr<SeamsBackend>> cpu = create_cpu_seams_backend(scene, set);
        if (!cpu) return cpu.status();
        return std::unique_ptr<SeamsBackend>(
            std::make_unique<PatternFakeGlRenderer>(std::move(*cpu), draws, reported, cpu_msaa));
      });
  return run_seams(c);
}

// The standard 2x mirrored: no CPU rate has these positions.
const std::vector<SampleOffset> kMirrored2x = {{-4, 4}, {4, -4}};

// A driver pattern that is no standard one: the GL frame is compared with a CPU frame drawn at
// the driver's own positions. The stand-in draws its "GL" frames with the CPU renderer at those
// positions, so the agreement is exact only if the comparison frame has them too; the CPU's
// standard 2x frame (what was compared before) differs at the edges.
TEST(Seams, CompareGlDrawsTheCpuAtTheDriversPositionsWhenNoRateHasThem) {
  Result<SeamsResult> r = run_pattern_fake(kMirrored2x, kMirrored2x, 0);
  ASSERT_TRUE(r.ok()) << r.status().message;
  ASSERT_EQ(r->gpu_sample_patterns.size(), 1u);
  EXPECT_EQ(r->gpu_sample_patterns[0].cpu_msaa, 0);
  EXPECT_EQ(r->gpu_sample_patterns[0].positions, kMirrored2x);
  ASSERT_EQ(r->gl_rates.size(), 1u);
  EXPECT_EQ(r->gl_rates[0].compared_with, SeamsGlComparison::driver_positions);
  for (SeamMethod m : faces::all_methods()) {
    const SeamsGlMethodResult& g = r->gl_rates[0].method(m);
    EXPECT_TRUE(std::isinf(g.psnr_db)) << faces::method_name(m) << " " << g.psnr_db;  // identical
    EXPECT_EQ(g.fraction_ge_001, 0.0) << faces::method_name(m);
  }
  // The control: the same frames said to be the CPU's standard 2x are compared with the CPU's
  // 2x frame, which is not at those positions.
  Result<SeamsResult> lied = run_pattern_fake(kMirrored2x, kMirrored2x, 2);
  ASSERT_TRUE(lied.ok()) << lied.status().message;
  EXPECT_EQ(lied->gl_rates[0].compared_with, SeamsGlComparison::cpu_rate);
  for (SeamMethod m : faces::all_methods()) {
    const SeamsGlMethodResult& g = lied->gl_rates[0].method(m);
    EXPECT_TRUE(std::isfinite(g.psnr_db)) << faces::method_name(m);
    EXPECT_GT(g.fraction_ge_001, 0.0) << faces::method_name(m);
  }
}

// A driver pattern that is no standard one and whose positions are not known on the CPU's
// 1/16-pixel grid: GL is still drawn and timed, but not compared with any CPU frame.
TEST(Seams, CompareGlLeavesARateUncomparedWithoutReproduciblePositions) {
  Result<SeamsResult> r = run_pattern_fake({}, {}, 0);
  ASSERT_TRUE(r.ok()) << r.status().message;
  ASSERT_EQ(r->gpu_sample_patterns.size(), 1u);
  EXPECT_TRUE(r->gpu_sample_patterns[0].positions.empty());
  ASSERT_EQ(r->gl_rates.size(), 1u);
  EXPECT_EQ(r->gl_rates[0].msaa, 2);
  EXPECT_EQ(r->gl_rates[0].compared_with, SeamsGlComparison::none);
  for (SeamMethod m : faces::all_methods()) {
    const SeamsGlMethodResult& g = r->gl_rates[0].method(m);
    EXPECT_EQ(g.gpu.frame_ms.size(), 1u) << faces::method_name(m);
    // Not measured, rather than the "identical" of an empty pool: the stand-in draws the
    // CPU's own 2x frame, which the old rule compared with and found identical.
    EXPECT_TRUE(std::isnan(g.psnr_db)) << faces::method_name(m);
    EXPECT_TRUE(std::isnan(g.fraction_ge_001)) << faces::method_name(m);
  }
  // The CPU side is the plain CPU run at 2x.
  ASSERT_EQ(r->rates.size(), 1u);
  EXPECT_EQ(r->rates[0].msaa, 2);
}

TEST(Seams, GlComparisonRule) {
  SeamsSamplePattern p{4, 4, 4, standard_positions(4)};
  EXPECT_EQ(seams_gl_comparison(p), SeamsGlComparison::cpu_rate);
  p.positions.clear();  // the CPU rate decides, positions or not
  EXPECT_EQ(seams_gl_comparison(p), SeamsGlComparison::cpu_rate);
  p = {2, 2, 0, kMirrored2x};
  EXPECT_EQ(seams_gl_comparison(p), SeamsGlComparison::driver_positions);
  p.samples = 4;  // positions for fewer samples than drawn: not like for like
  EXPECT_EQ(seams_gl_comparison(p), SeamsGlComparison::none);
  p = {2, 2, 0, {{-4, 4}, {8, -4}}};  // outside the pixel
  EXPECT_EQ(seams_gl_comparison(p), SeamsGlComparison::none);
  p = {2, 2, 0, {}};
  EXPECT_EQ(seams_gl_comparison(p), SeamsGlComparison::none);
  p = {16, 17, 0, std::vector<SampleOffset>(17)};  // more samples than a coverage mask holds
  EXPECT_EQ(seams_gl_comparison(p), SeamsGlComparison::none);
  p = {4, 6, 0, std::vector<SampleOffset>(6, SampleOffset{3, -1})};  // no standard count
  EXPECT_EQ(seams_gl_comparison(p), SeamsGlComparison::driver_positions);
}

}  // namespace
}  // namespace tessera::experiments
