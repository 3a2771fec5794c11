// gl::AdaptiveSupersampler's per-frame budget (0 = the 1 spp image, not binding = the
// unbudgeted image, binding = exactly the budget, rank by metric strength then pixel index,
// repeatable), its tonemap-weighted HDR resolve against the documented formula, a caller's sample
// order and a hook's own shading-metric luma.
#include "gl_adaptive_test_util.h"

namespace tessera::aa_test {
namespace {

TEST_F(GlAdaptive, BudgetOnDeferredFrame) {
  use_deferred(40, 32, 4);
  ASSERT_NO_FATAL_FAILURE(shade_default_and_adaptive());
  const std::vector<int> asked = extra_of(ad_->samples);
  const std::int64_t total = std::accumulate(asked.begin(), asked.end(), std::int64_t(0));
  ASSERT_GT(total, 100);
  for (AdaptiveSchedule sch : {AdaptiveSchedule::frame_list, AdaptiveSchedule::loop}) {
    gl::AdaptiveSupersamplerOptions o = deferred_options(classes_);
    o.schedule = sch;
    o.profile = true;
    Result<std::unique_ptr<gl::AdaptiveSupersampler>> c = gl::AdaptiveSupersampler::create(o);
    ASSERT_TRUE(c.ok()) << c.status().message;
    // Budget 0: the 1 spp image.
    frame_.budget = 0;
    Result<gl::AdaptiveOutput> r = (*c)->dispatch(frame_);
    ASSERT_TRUE(r.ok()) << r.status().message;
    EXPECT_EQ(differing_pixels(read_rgba32f(r->colour), one_->image), 0u);
    EXPECT_EQ(r->extra_samples, 0u);
    // Not binding (exactly the total, and far above): the unbudgeted image.
    for (std::int64_t b : {total, std::int64_t(1) << 40}) {
      frame_.budget = b;
      r = (*c)->dispatch(frame_);
      ASSERT_TRUE(r.ok()) << r.status().message;
      EXPECT_EQ(differing_pixels(read_rgba32f(r->colour), ad_->image), 0u) << b;
      EXPECT_EQ(r->extra_samples, std::uint64_t(total));
    }
    // Binding: exactly the budget; every pixel keeps all its samples or none, but one; the
    // same result twice.
    for (std::int64_t b : {total / 3, total - 1, std::int64_t(1)}) {
      frame_.budget = b;
      r = (*c)->dispatch(frame_);
      ASSERT_TRUE(r.ok()) << r.status().message;
      const std::vector<float> img = read_rgba32f(r->colour);
      const std::vector<int> got = extra_of(read_counts(r->sample_counts, w_, h_));
      EXPECT_EQ(std::accumulate(got.begin(), got.end(), std::int64_t(0)), b);
      EXPECT_EQ(r->extra_samples, std::uint64_t(b));
      int partial = 0;
      for (std::size_t i = 0; i < got.size(); ++i) {
        ASSERT_LE(got[i], asked[i]);
        partial += got[i] != 0 && got[i] != asked[i];
      }
      EXPECT_LE(partial, 1);
      Result<gl::AdaptiveOutput> again = (*c)->dispatch(frame_);
      ASSERT_TRUE(again.ok());
      EXPECT_EQ(read_rgba32f(again->colour), img);
      EXPECT_EQ(extra_of(read_counts(again->sample_counts, w_, h_)), got);
    }
  }
  gl::AdaptiveSupersamplerOptions o = deferred_options(classes_);
  Result<std::unique_ptr<gl::AdaptiveSupersampler>> c = gl::AdaptiveSupersampler::create(o);
  ASSERT_TRUE(c.ok());
  frame_.budget = -1;
  Result<gl::AdaptiveOutput> r = (*c)->dispatch(frame_);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message.find("budget = -1"), std::string::npos) << r.status().message;
}

TEST_F(GlAdaptive, BudgetRanksByMetricStrengthThenPixelIndex) {
  const int w = 8, h = 4, m = 2;
  // Pixel i's window has depths {1, 1, 1, 1 + a_i}, a_i distinct: strength grows with a_i;
  // c_depth is so large that every pixel asks for K = 3.
  std::vector<float> a(std::size_t(w * h));
  for (int i = 0; i < w * h; ++i) a[std::size_t(i)] = 0.01f * float((i * 13) % (w * h) + 1);
  Synthetic s = synthetic(w, h, m, [&](int gx, int gy) {
    const bool last = gx % m == m - 1 && gy % m == m - 1;
    return last ? 1.0f + a[std::size_t((gy / m) * w + gx / m)] : 1.0f;
  });
  gl::AdaptiveSupersamplerOptions o = synthetic_options(w, h, m);
  o.thresholds.c_depth = 1e6f;
  o.thresholds.use_shading = false;
  Result<std::unique_ptr<gl::AdaptiveSupersampler>> c = gl::AdaptiveSupersampler::create(o);
  ASSERT_TRUE(c.ok()) << c.status().message;
  s.frame.budget = 3 * 5 + 2;
  Result<gl::AdaptiveOutput> r = (*c)->dispatch(s.frame);
  ASSERT_TRUE(r.ok()) << r.status().message;
  const std::vector<int> got = extra_of(read_counts(r->sample_counts, w, h));
  std::vector<int> rank(std::size_t(w * h));
  std::iota(rank.begin(), rank.end(), 0);
  std::sort(rank.begin(), rank.end(),
            [&](int x, int y) { return a[std::size_t(x)] > a[std::size_t(y)]; });
  std::vector<int> want(std::size_t(w * h), 0);
  for (int j = 0; j < 5; ++j) want[std::size_t(rank[std::size_t(j)])] = 3;
  want[std::size_t(rank[5])] = 2;
  EXPECT_EQ(got, want);
  // Equal strengths (force_k, set on the same component): the lower pixel index first.
  o.thresholds.force_k = 2;
  (*c)->set_thresholds(o.thresholds);
  s.frame.budget = 7;
  r = (*c)->dispatch(s.frame);
  ASSERT_TRUE(r.ok()) << r.status().message;
  want.assign(std::size_t(w * h), 0);
  want[0] = want[1] = want[2] = 2;
  want[3] = 1;
  EXPECT_EQ(extra_of(read_counts(r->sample_counts, w, h)), want);
}

TEST_F(GlAdaptive, TonemapWeightedResolveFormula) {
  const int w = 4, h = 2, m = 2;
  Synthetic s = synthetic(w, h, m, [](int, int) { return 1.0f; });
  gl::AdaptiveSupersamplerOptions o = synthetic_options(w, h, m);
  o.thresholds.force_k = 3;  // every sample of every window
  o.resolve = AdaptiveResolve::tonemap_weighted;
  o.hdr_exposure = 0.5f;
  for (bool reference : {false, true}) {
    Result<std::unique_ptr<gl::AdaptiveSupersampler>> c = gl::AdaptiveSupersampler::create(o);
    ASSERT_TRUE(c.ok()) << c.status().message;
    Result<gl::AdaptiveOutput> r =
        reference ? (*c)->dispatch_reference(s.frame) : (*c)->dispatch(s.frame);
    ASSERT_TRUE(r.ok()) << r.status().message;
    const std::vector<float> img = read_rgba32f(r->colour);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        double sum[4] = {0, 0, 0, 0}, wsum = 0, plain[4] = {0, 0, 0, 0};
        for (int q = 0; q < m * m; ++q) {
          const int gx = m * x + q % m, gy = m * y + q / m;
          const double col[4] = {gx * 4.0, gy * 0.25 + 0.1, (gx + gy) * 2.0, 1.0};
          const double lum = 0.2126 * col[0] + 0.7152 * col[1] + 0.0722 * col[2];
          const double wt = 1.0 / (1.0 + 0.5 * lum);
          for (int ch = 0; ch < 4; ++ch) {
            sum[ch] += wt * col[ch];
            plain[ch] += col[ch] / (m * m);
          }
          wsum += wt;
        }
        for (int ch = 0; ch < 4; ++ch) {
          const double want = sum[ch] / wsum;
          const float got = img[std::size_t((y * w + x) * 4 + ch)];
          EXPECT_NEAR(got, want, 2e-6 * (1.0 + std::fabs(want))) << x << "," << y << " " << ch;
          if (ch < 3 && x + y > 0) {
            EXPECT_LT(got, plain[ch]);  // bright samples weigh less
          }
        }
      }
    }
  }
}

TEST_F(GlAdaptive, CallersSampleOrder) {
  const int w = 4, h = 3, m = 3;
  Synthetic s = synthetic(w, h, m, [](int, int) { return 1.0f; });
  gl::AdaptiveSupersamplerOptions o = synthetic_options(w, h, m);
  o.sample_order = {8, 0, 1, 2, 3, 4, 5, 6, 7};  // S = the bottom-right cell
  Result<std::unique_ptr<gl::AdaptiveSupersampler>> c = gl::AdaptiveSupersampler::create(o);
  ASSERT_TRUE(c.ok()) << c.status().message;
  Result<gl::AdaptiveOutput> r = (*c)->dispatch_first_sample(s.frame);
  ASSERT_TRUE(r.ok()) << r.status().message;
  const std::vector<float> img = read_rgba32f(r->colour);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const int gx = m * x + 2, gy = m * y + 2;
      EXPECT_EQ(img[std::size_t((y * w + x) * 4)], float(gx) * 4.0f) << x << "," << y;
      EXPECT_EQ(img[std::size_t((y * w + x) * 4 + 1)], float(gy) * 0.25f + 0.1f) << x << "," << y;
    }
  }
}

TEST_F(GlAdaptive, HookLumaDrivesTheShadingMetric) {
  const int w = 8, h = 8, m = 2;
  Synthetic s = synthetic(w, h, m, [](int, int) { return 1.0f; });  // flat: no geometry term
  gl::AdaptiveSupersamplerOptions o = synthetic_options(w, h, m);
  o.thresholds.use_geometry = false;
  // Default luma: the analytic hook's colours vary from pixel to pixel, k_s > 0 somewhere.
  Result<std::unique_ptr<gl::AdaptiveSupersampler>> c = gl::AdaptiveSupersampler::create(o);
  ASSERT_TRUE(c.ok()) << c.status().message;
  Result<gl::AdaptiveOutput> r = (*c)->dispatch(s.frame);
  ASSERT_TRUE(r.ok()) << r.status().message;
  const std::vector<int> with_default = extra_of(read_counts(r->sample_counts, w, h));
  EXPECT_GT(std::accumulate(with_default.begin(), with_default.end(), 0), 0);
  // A hook luma that is constant: no shading contrast, no extra samples.
  o.hook.source =
      "#define TESSERA_ADAPTIVE_CUSTOM_LUMA 1\n"
      "float tessera_shade_luma(vec4 c) { return 0.5; }\n" +
      o.hook.source;
  c = gl::AdaptiveSupersampler::create(o);
  ASSERT_TRUE(c.ok()) << c.status().message;
  r = (*c)->dispatch(s.frame);
  ASSERT_TRUE(r.ok()) << r.status().message;
  const std::vector<int> with_hook = extra_of(read_counts(r->sample_counts, w, h));
  EXPECT_EQ(std::accumulate(with_hook.begin(), with_hook.end(), 0), 0);
}

}  // namespace
}  // namespace tessera::aa_test
