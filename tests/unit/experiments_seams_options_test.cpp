// The options of the seam experiment beyond `tessera seams`' (tessera/experiments/seams.h),
// which bench/seams_gl_table1.cpp uses: the frames' texture filter, timing repetitions, an
// untimed CPU side, the worst-frame GL-vs-CPU agreement and the GL-vs-CPU reference
// comparison, with a CPU-backed stand-in for the GL backend.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "experiments_test_util.h"
#include "tessera/experiments/aa_backend.h"
#include "tessera/experiments/seams.h"

namespace tessera::experiments {
namespace {

using faces::SeamMethod;

/// A stand-in for the GL backend: the CPU renderer that adds 0.02 to the red channel of the
/// first n pixels of its n-th frame read back (so that frames agree with the CPU differently),
/// and of the first pixel of its references.
class FakeGl final : public SeamsBackend {
 public:
  explicit FakeGl(std::unique_ptr<SeamsBackend> cpu) : cpu_(std::move(cpu)) {}
  Backend backend() const override { return Backend::gl; }
  std::string device_name() const override { return "fake"; }
  std::string device_version() const override { return "1.0"; }
  bool msaa_supported(int) override { return true; }
  bool has_shading_only() const override { return false; }
  Result<SeamsBackendFrame> render(const scene::Camera& camera,
                                   const FaceFrameOptions& options) override {
    Result<SeamsBackendFrame> f = cpu_->render(camera, options);
    if (!f || f->image.pixels.empty()) return f;
    ++read_backs_;
    for (std::size_t i = 0; i < std::size_t(read_backs_) && i < f->image.pixel_count(); ++i) {
      f->image.pixels[i * 4] += 0.02f;
    }
    return f;
  }
  Result<ImageRGBAF> render_reference(const scene::Camera& camera, int width, int height,
                                      const faces::ReferenceOptions& options) override {
    Result<ImageRGBAF> r = cpu_->render_reference(camera, width, height, options);
    if (r) r->pixels[0] += 0.02f;
    return r;
  }

 private:
  std::unique_ptr<SeamsBackend> cpu_;
  int read_backs_ = 0;
};

class FakeGlFactory final : public GpuBackendFactory {
 public:
  Backend backend() const override { return Backend::gl; }
  Result<std::unique_ptr<SeamsBackend>> create_seams(
      const faces::FaceScene& scene, const faces::FaceTextureSet& textures) const override {
    Result<std::unique_ptr<SeamsBackend>> cpu = create_cpu_seams_backend(scene, textures);
    if (!cpu) return cpu.status();
    return std::unique_ptr<SeamsBackend>(std::make_unique<FakeGl>(std::move(*cpu)));
  }
  Result<std::unique_ptr<AaBackend>> create_aa(const scene::Scene&) const override {
    return Status::error(ErrorCode::unsupported, "no fake aa backend");
  }
};

SeamsResult run(const SeamsConfig& c) {
  Result<SeamsResult> r = run_seams(c);
  EXPECT_TRUE(r.ok()) << r.status().message;
  return r.ok() ? std::move(*r) : SeamsResult{};
}

SeamsConfig tiny_both() {
  SeamsConfig c = test::tiny_seams();
  c.backend = Backend::both;
  c.gl_factory = std::make_shared<FakeGlFactory>();
  return c;
}

TEST(SeamsOptions, FilterChangesTheFramesNotTheReference) {
  const SeamsConfig c = test::tiny_seams();
  SeamsConfig t = c;
  t.filter = texture::TextureFilter::trilinear;
  const SeamsResult a = run(c), b = run(t);
  ASSERT_EQ(a.rates.size(), 2u);
  ASSERT_EQ(b.rates.size(), 2u);
  EXPECT_EQ(a.reference_frame0.pixels, b.reference_frame0.pixels);
  for (std::size_t ri = 0; ri < 2; ++ri) {
    for (SeamMethod m : faces::all_methods()) {
      EXPECT_NE(a.rates[ri].method(m).frame0.pixels, b.rates[ri].method(m).frame0.pixels)
          << faces::method_name(m) << " at rate " << a.rates[ri].msaa;
    }
  }
  // The JSON names the filter only where it is not the default.
  EXPECT_NE(to_json(t, b).find("\"filter\": \"trilinear"), std::string::npos);
  EXPECT_EQ(to_json(c, a).find("trilinear (the reference"), std::string::npos);
}

TEST(SeamsOptions, RepetitionsAddTimesNotChanges) {
  const SeamsConfig c = tiny_both();
  SeamsConfig r3 = c;
  r3.repetitions = 3;
  const SeamsResult a = run(c), b = run(r3);
  ASSERT_EQ(b.rates.size(), 2u);
  ASSERT_EQ(b.gl_rates.size(), 2u);
  EXPECT_EQ(a.reference_frame0.pixels, b.reference_frame0.pixels);
  for (std::size_t ri = 0; ri < 2; ++ri) {
    EXPECT_EQ(b.rates[ri].shading_only.frame_ms.size(), std::size_t(3 * c.frames));
    for (SeamMethod m : faces::all_methods()) {
      const SeamsMethodResult& x = a.rates[ri].method(m);
      const SeamsMethodResult& y = b.rates[ri].method(m);
      EXPECT_EQ(x.timing.frame_ms.size(), std::size_t(c.frames));
      EXPECT_EQ(y.timing.frame_ms.size(), std::size_t(3 * c.frames));
      EXPECT_EQ(y.frame0.pixels, x.frame0.pixels);
      EXPECT_EQ(y.vs_reference.cdf, x.vs_reference.cdf);
      EXPECT_EQ(y.vs_reference_near_seams.cdf, x.vs_reference_near_seams.cdf);
      const SeamsGlMethodResult& gx = a.gl_rates[ri].method(m);
      const SeamsGlMethodResult& gy = b.gl_rates[ri].method(m);
      EXPECT_EQ(gy.gpu.frame_ms.size(), std::size_t(3 * c.frames));
      EXPECT_EQ(gy.wall.frame_ms.size(), std::size_t(3 * c.frames));
      EXPECT_EQ(gx.gpu.frame_ms.size(), std::size_t(c.frames));
    }
  }
  EXPECT_NE(to_json(r3, b).find("\"repetitions\": 3"), std::string::npos);
  EXPECT_EQ(to_json(c, a).find("\"repetitions\""), std::string::npos);
}

TEST(SeamsOptions, WorstFrameAgreesLeastAndEqualsThePoolWithOneFrame) {
  SeamsConfig c = tiny_both();
  c.msaa = {1};
  c.frames = 4;
  c.quality_frames = 2;
  const SeamsResult two = run(c);
  c.quality_frames = 1;
  const SeamsResult one = run(c);
  ASSERT_EQ(two.gl_rates.size(), 1u);
  ASSERT_EQ(one.gl_rates.size(), 1u);
  for (SeamMethod m : faces::all_methods()) {
    const SeamsGlMethodResult& g = two.gl_rates[0].method(m);
    ASSERT_TRUE(std::isfinite(g.psnr_db)) << faces::method_name(m);
    // The frames differ (a later frame has more perturbed pixels): the worst is strictly worse.
    EXPECT_LT(g.worst_psnr_db, g.psnr_db) << faces::method_name(m);
    EXPECT_GT(g.worst_psnr_db, 30.0) << faces::method_name(m);  // a few pixels 0.02 apart
    EXPECT_GT(g.worst_fraction_ge_001, g.fraction_ge_001) << faces::method_name(m);
    const SeamsGlMethodResult& o = one.gl_rates[0].method(m);
    EXPECT_DOUBLE_EQ(o.worst_psnr_db, o.psnr_db);
    EXPECT_DOUBLE_EQ(o.worst_fraction_ge_001, o.fraction_ge_001);
  }
}

TEST(SeamsOptions, ReferencesComparedOnlyWhenAsked) {
  SeamsConfig c = tiny_both();
  c.msaa = {1};
  const SeamsResult plain = run(c);
  EXPECT_FALSE(plain.gl_reference_vs_cpu.measured);
  EXPECT_EQ(to_json(c, plain).find("gl_reference_vs_cpu"), std::string::npos);
  c.compare_references = true;
  const SeamsResult r = run(c);
  const SeamsReferenceAgreement& a = r.gl_reference_vs_cpu;
  ASSERT_TRUE(a.measured);
  // One pixel of each reference differs by 0.02 in red (linear): one pixel >= 0.01 apart.
  const double one_pixel = 1.0 / double(c.width * c.height);
  EXPECT_DOUBLE_EQ(a.fraction_ge_001, one_pixel);
  EXPECT_DOUBLE_EQ(a.worst_fraction_ge_001, one_pixel);
  EXPECT_TRUE(std::isfinite(a.psnr_db));
  EXPECT_GT(a.psnr_db, 40.0);
  EXPECT_NE(to_json(c, r).find("gl_reference_vs_cpu"), std::string::npos);
  // The frames and their statistics are those of the plain run.
  EXPECT_EQ(r.rates[0].method(SeamMethod::traverse).vs_reference.cdf,
            plain.rates[0].method(SeamMethod::traverse).vs_reference.cdf);
}

TEST(SeamsOptions, UntimedCpuSideKeepsTheStatistics) {
  SeamsConfig c = tiny_both();
  c.frames = 4;
  c.quality_frames = 2;
  const SeamsResult timed = run(c);
  c.time_cpu = false;
  const SeamsResult untimed = run(c);
  ASSERT_EQ(untimed.rates.size(), 2u);
  for (std::size_t ri = 0; ri < 2; ++ri) {
    EXPECT_TRUE(untimed.rates[ri].shading_only.frame_ms.empty());
    EXPECT_EQ(untimed.rates[ri].nan_pixels_without_fallback,
              timed.rates[ri].nan_pixels_without_fallback);
    for (SeamMethod m : faces::all_methods()) {
      const SeamsMethodResult& u = untimed.rates[ri].method(m);
      EXPECT_TRUE(u.timing.frame_ms.empty());
      EXPECT_EQ(u.vs_reference.cdf, timed.rates[ri].method(m).vs_reference.cdf);
      EXPECT_EQ(u.frame0.pixels, timed.rates[ri].method(m).frame0.pixels);
      EXPECT_EQ(untimed.gl_rates[ri].method(m).gpu.frame_ms.size(), std::size_t(c.frames));
      EXPECT_EQ(untimed.gl_rates[ri].method(m).psnr_db, timed.gl_rates[ri].method(m).psnr_db);
    }
  }
  EXPECT_NE(to_json(c, untimed).find("\"time_cpu\": false"), std::string::npos);
}

TEST(SeamsOptions, BothOnlyOptionsNeedBoth) {
  for (Backend b : {Backend::cpu, Backend::gl}) {
    SeamsConfig c = test::tiny_seams();
    c.backend = b;
    c.gl_factory = std::make_shared<FakeGlFactory>();
    c.compare_references = true;
    EXPECT_EQ(run_seams(c).status().code, ErrorCode::invalid_argument);
    c.compare_references = false;
    c.time_cpu = false;
    EXPECT_EQ(run_seams(c).status().code, ErrorCode::invalid_argument);
  }
  SeamsConfig c = test::tiny_seams();
  c.repetitions = 0;
  EXPECT_EQ(run_seams(c).status().code, ErrorCode::invalid_argument);
}

}  // namespace
}  // namespace tessera::experiments
