// The experiments module (tessera/experiments.h) called directly: the seam experiment of Toth
// 2013 on tiny frames (CPU backend), and the multi-frame error CDF of metrics.h it uses. The
// seam experiment through other backends: experiments_seams_backend_test.cpp; the
// adaptive-supersampling experiment of Hollander et al. 2013: experiments_aa_test.cpp.
#include "tessera/experiments.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "experiments_test_util.h"
#include "tessera/metrics.h"

namespace tessera::experiments {
namespace {

using faces::SeamMethod;
using test::seams_result;
using test::tiny_seams;

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
  metrics::ErrorCdfAccumulator acc(xs);
  ASSERT_TRUE(acc.add(a1, b1).ok());
  ASSERT_TRUE(acc.add(a2, b2, mask2).ok());
  EXPECT_EQ(acc.counted(), 5u);
  // Together: 0, 0.1, 0.5, 0.2, 0.05 as one 5x1 pair.
  ImageRGBAF a(5, 1), b(5, 1);
  b.at(1, 0)[0] = 0.1f;
  b.at(2, 0)[1] = 0.5f;
  b.at(3, 0)[2] = 0.2f;
  b.at(4, 0)[1] = 0.05f;
  Result<std::vector<double>> whole = metrics::error_cdf(a, b, xs);
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
  metrics::ErrorCdfAccumulator acc(r.thresholds);
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
    for (SeamMethod m : faces::all_methods()) {
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
    EXPECT_EQ(rate.traverse_vs_discard.counted,
              rate.method(SeamMethod::clamp).vs_reference.counted);
    // Traverse and Discard differ somewhere (near seams), so the CDF leaves 1 after bin 0.
    EXPECT_LT(rate.traverse_vs_discard.cdf[1], 1.0);
    EXPECT_GT(rate.traverse_vs_discard.mean, 0.0);
  }
}

TEST(Seams, TraverseBeatsClampNearSeams) {
  const SeamsResult& r = seams_result();
  for (const SeamsRateResult& rate : r.rates) {
    const ImageRGBAF& clamp = rate.method(SeamMethod::clamp).frame0;
    const ImageRGBAF& trav = rate.method(SeamMethod::traverse).frame0;
    // Near seams: geometry pixels where Clamp and Traverse disagree visibly.
    Result<std::vector<float>> d = metrics::error_norms(clamp, trav);
    ASSERT_TRUE(d.ok());
    std::vector<std::uint8_t> seam(d->size(), 0);
    for (std::size_t i = 0; i < seam.size(); ++i) {
      seam[i] = (*d)[i] > 0.02f && r.reference_frame0.pixels[i * 4 + 3] > 0.01f ? 1 : 0;
    }
    metrics::ErrorCdfAccumulator ec(r.thresholds), et(r.thresholds);
    ASSERT_TRUE(ec.add(clamp, r.reference_frame0, seam).ok());
    ASSERT_TRUE(et.add(trav, r.reference_frame0, seam).ok());
    ASSERT_GT(ec.counted(), 20u) << rate.msaa << "x";
    EXPECT_LT(et.mean(), ec.mean()) << rate.msaa << "x";
    // Over all geometry pixels and quality frames too.
    EXPECT_LE(rate.method(SeamMethod::traverse).vs_reference.mean,
              rate.method(SeamMethod::clamp).vs_reference.mean)
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
      EXPECT_EQ(near.counted, rate.method(SeamMethod::clamp).vs_reference_near_seams.counted);
    }
    // Where the faces meet, Traverse is closer to the reference than Clamp.
    EXPECT_LT(rate.method(SeamMethod::traverse).vs_reference_near_seams.mean,
              rate.method(SeamMethod::clamp).vs_reference_near_seams.mean)
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
  EXPECT_GT(wide->rates[0].method(SeamMethod::clamp).vs_reference_near_seams.counted,
            narrow->rates[0].method(SeamMethod::clamp).vs_reference_near_seams.counted);
  c.near_seam_pixels = 0;
  Result<SeamsResult> off = run_seams(c);
  ASSERT_TRUE(off.ok());
  EXPECT_EQ(off->near_seam_pixels, 0);
  EXPECT_EQ(off->rates[0].method(SeamMethod::clamp).vs_reference_near_seams.counted, 0u);
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
  for (SeamMethod m : faces::all_methods()) {
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
  EXPECT_TRUE(r->rates[0].method(SeamMethod::discard).frame0.pixels.empty());
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
  c.backend = Backend::both;
  EXPECT_EQ(run_seams(c).status().code, ErrorCode::unsupported);
  // A factory's error (e.g. no EGL device) comes back unchanged, for both and gl.
  c.gl_factory = test::seams_factory(
      [](const faces::FaceScene&,
         const faces::FaceTextureSet&) -> Result<std::unique_ptr<SeamsBackend>> {
        return Status::error(ErrorCode::unsupported, "no EGL device 7");
      });
  EXPECT_EQ(run_seams(c).status().message, "no EGL device 7");
  c.backend = Backend::gl;
  EXPECT_EQ(run_seams(c).status().message, "no EGL device 7");
  c.gl_factory = nullptr;
  c.backend = Backend::cpu;
  c.scene = "/nonexistent/mesh.obj";
  EXPECT_FALSE(run_seams(c).ok());
  EXPECT_FALSE(ready);  // no input was good enough to get there
}

// The library writes the reports: seams.json names the backend, every rate and, with the
// images beside it, the zoom window on the worst seam; seams.md opens with its title.
TEST(Seams, ResultsAsJsonAndMarkdown) {
  const SeamsConfig c = tiny_seams();
  const SeamsResult& r = seams_result();
  const std::string j = to_json(c, r);
  EXPECT_NE(j.find("\"backend\": \"cpu\""), std::string::npos);
  EXPECT_NE(j.find("\"4x\""), std::string::npos);
  EXPECT_NE(j.find("\"zoom_window\""), std::string::npos);
  EXPECT_EQ(to_json(c, r, {.images = false}).find("zoom_window"), std::string::npos);
  const SeamsZoomWindow z = seams_zoom_window(c, r);
  EXPECT_EQ(z.w, 40);
  EXPECT_LE(z.x + z.w, c.width);
  EXPECT_LE(z.y + z.h, c.height);
  const std::string md = to_markdown(c, r);
  EXPECT_EQ(md.rfind("# Seams experiment", 0), 0u);
  EXPECT_NE(md.find("## Images"), std::string::npos);
  EXPECT_EQ(to_markdown(c, r, {.images = false}).find("## Images"), std::string::npos);
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
