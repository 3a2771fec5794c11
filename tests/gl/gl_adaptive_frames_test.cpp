// gl::AdaptiveSupersampler with dynamic resolution: one component created for the largest size
// renders a new size every frame from G-buffer textures of the largest size (the frame's
// G-buffer in their top-left texels, other values around it), with and without a budget; each
// frame's image and sample counts equal, bit for bit, those of a component created for that size
// over a G-buffer of exactly that size. A render size above the largest is an error.
#include "gl_adaptive_test_util.h"

namespace tessera::aa_test {
namespace {

/// Depth edges on a grid (the geometry metric asks for samples along them).
float edgy_depth(int gx, int gy) { return 1.0f + 0.5f * float((gx / 3 + gy / 5) % 3); }

/// The synthetic G-buffer of w x h pixels in the top-left of textures of the largest grid.
Synthetic padded(int w, int h, int m, int grid_w, int grid_h) {
  std::vector<float> a, b;
  for (int gy = 0; gy < grid_h; ++gy) {
    for (int gx = 0; gx < grid_w; ++gx) {
      const bool inside = gx < w * m && gy < h * m;
      a.insert(a.end(), {inside ? edgy_depth(gx, gy) : 9.0f + float(gx % 4), 0.0f, 0.0f, 1.0f});
      b.insert(b.end(), {inside ? 0.0f : 3.0f, 0.0f, 0.0f, 0.0f});
    }
  }
  Synthetic s;
  s.t0 = make_texture(GL_RGBA32F, grid_w, grid_h, a);
  s.t1 = make_texture(GL_RGBA32F, grid_w, grid_h, b);
  s.frame.gbuffer = {s.t0.get(), s.t1.get(), 0, 0};
  return s;
}

/// The top-left w x h texels of a row-major image `stride` texels wide, `channels` each.
template <class T>
std::vector<T> crop(const std::vector<T>& img, int stride, int w, int h, int channels) {
  std::vector<T> out;
  for (int y = 0; y < h; ++y) {
    const auto row = img.begin() + std::ptrdiff_t(y) * stride * channels;
    out.insert(out.end(), row, row + std::ptrdiff_t(w) * channels);
  }
  return out;
}

TEST_F(GlAdaptive, DynamicResolutionEveryFrame) {
  const int W = 24, H = 16, m = 2;
  struct Step {
    int w, h;
    std::optional<std::int64_t> budget;
  };
  const Step steps[] = {{24, 16, {}}, {17, 11, {}}, {20, 13, 40},
                        {12, 8, {}},  {24, 16, 25}, {9, 7, {}}};
  gl::AdaptiveSupersamplerOptions o = synthetic_options(W, H, m);
  o.profile = true;
  Result<std::unique_ptr<gl::AdaptiveSupersampler>> dynamic = gl::AdaptiveSupersampler::create(o);
  ASSERT_TRUE(dynamic.ok()) << dynamic.status().message;
  std::size_t adaptive_pixels = 0;
  for (const Step& st : steps) {
    const std::string at = std::to_string(st.w) + "x" + std::to_string(st.h);
    // Alone: a component created for this size, a G-buffer of exactly this size.
    Synthetic exact = synthetic(st.w, st.h, m, edgy_depth);
    exact.frame.budget = st.budget;
    gl::AdaptiveSupersamplerOptions oa = synthetic_options(st.w, st.h, m);
    oa.profile = true;
    Result<std::unique_ptr<gl::AdaptiveSupersampler>> alone = gl::AdaptiveSupersampler::create(oa);
    ASSERT_TRUE(alone.ok()) << alone.status().message;
    Result<gl::AdaptiveOutput> want = (*alone)->dispatch(exact.frame);
    ASSERT_TRUE(want.ok()) << want.status().message;
    // The same frame on the component of the largest size.
    Synthetic big = padded(st.w, st.h, m, W * m, H * m);
    big.frame.render_size = {st.w, st.h};
    big.frame.budget = st.budget;
    Result<gl::AdaptiveOutput> got = (*dynamic)->dispatch(big.frame);
    ASSERT_TRUE(got.ok()) << at << ": " << got.status().message;
    EXPECT_EQ(got->render_size.width, st.w);
    EXPECT_EQ(got->render_size.height, st.h);
    EXPECT_EQ(got->extra_samples, want->extra_samples) << at;
    EXPECT_EQ(crop(read_rgba32f(got->colour), W, st.w, st.h, 4), read_rgba32f(want->colour)) << at;
    const std::vector<std::uint8_t> counts = read_counts(want->sample_counts, st.w, st.h);
    EXPECT_EQ(crop(read_counts(got->sample_counts, W, H), W, st.w, st.h, 1), counts) << at;
    for (std::uint8_t c : counts) adaptive_pixels += c > 1 ? 1 : 0;
  }
  EXPECT_GT(adaptive_pixels, 50u);  // the depth edges asked for samples: the images differ
  // Beyond the largest size: one line, nothing dispatched.
  Synthetic big = padded(W, H, m, W * m, H * m);
  big.frame.render_size = {W + 1, H};
  Result<gl::AdaptiveOutput> r = (*dynamic)->dispatch(big.frame);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message.find("render size 25x16 (1..24 x 1..16"), std::string::npos)
      << r.status().message;
}

}  // namespace
}  // namespace tessera::aa_test
