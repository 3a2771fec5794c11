// vk::AdaptiveSupersampler against gl::AdaptiveSupersampler on the same G-buffer and hook: the
// k maps (sample counts) >= 99.9 % identical and the images >= 60 dB apart or closer, for the
// adaptive image (frame list, tile list, m = 2 and 8; loop schedule with the HDR resolve and a
// budget), full supersampling and 1 spp. Negative control: other thresholds give a k map far
// from GL's.
// Needs a Vulkan device with the validation layer and an OpenGL 4.5 context (llvmpipe).
#include <cstdio>

#include "gl/gl_api.h"
#include "tessera/gl.h"
#include "tessera/gl_adaptive.h"
#include "vk_adaptive_test_util.h"

namespace tessera::vk_test {
namespace {

using namespace gl::api;

struct GlFrameOut {
  std::vector<float> colour, counts;
};

/// The GL component's frame on the same G-buffer (RGBA32F textures).
GlFrameOut run_gl(gl::AdaptiveSupersamplerOptions o, const SceneGBuffer& g, Which which,
                  std::optional<std::int64_t> budget = std::nullopt) {
  GlFrameOut out;
  std::array<gl::Object, 3> tex;
  gl::AdaptiveFrame frame;
  for (std::size_t s = 0; s < 3; ++s) {
    tex[s] = gl::create_object(gl::ObjectType::texture, GL_TEXTURE_2D);
    glTextureStorage2D(tex[s].get(), 1, GL_RGBA32F, g.w * g.m, g.h * g.m);
    glTextureSubImage2D(tex[s].get(), 0, 0, 0, g.w * g.m, g.h * g.m, GL_RGBA, GL_FLOAT,
                        g.slots[s].data());
    frame.gbuffer[s] = tex[s].get();
  }
  frame.budget = budget;
  auto c = gl::AdaptiveSupersampler::create(o);
  EXPECT_TRUE(c.ok()) << c.status().message;
  if (!c) return out;
  Result<gl::AdaptiveOutput> r = which == Which::adaptive    ? (*c)->dispatch(frame)
                                 : which == Which::reference ? (*c)->dispatch_reference(frame)
                                                             : (*c)->dispatch_first_sample(frame);
  EXPECT_TRUE(r.ok()) << r.status().message;
  if (!r) return out;
  Result<ImageRGBAF> img = gl::read_texture_rgbaf(r->colour);
  EXPECT_TRUE(img.ok()) << img.status().message;
  if (img) out.colour = img->pixels;
  std::vector<std::uint8_t> k(std::size_t(g.w) * std::size_t(g.h));
  glGetTextureSubImage(r->sample_counts, 0, 0, 0, 0, g.w, g.h, 1, GL_RED_INTEGER, GL_UNSIGNED_BYTE,
                       GLsizei(k.size()), k.data());
  out.counts.assign(k.begin(), k.end());
  return out;
}

class VkAgainstGl : public ::testing::Test {
 protected:
  void SetUp() override {
    auto c = gl::Context::create();
    if (!c) TESSERA_SKIP_OR_FAIL("gl", "no OpenGL 4.5 context: " << c.status().message);
    gl_ = std::move(*c);
    std::string missing;
    auto e = Engine::create({}, &missing);
    if (!e) TESSERA_SKIP_OR_FAIL(missing, e.status().message);
    engine_ = std::move(*e);
    g_ = scene_gbuffer(48, 36, 4);
  }
  void TearDown() override {
    if (!engine_) return;
    engine_->shutdown();
    EXPECT_EQ(engine_->messages(), 0) << "validation messages:" << engine_->first_messages();
  }
  void compare(const vk::AdaptiveSupersamplerOptions& vo, const gl::AdaptiveSupersamplerOptions& go,
               Which which, std::optional<std::int64_t> budget, const char* what) {
    const VkFrameOut v = run_vk(*engine_, vo, g_, which, budget);
    const GlFrameOut l = run_gl(go, g_, which, budget);
    const double same = same_fraction(v.counts, l.counts), db = psnr_rgb(v.colour, l.colour);
    std::printf("%s: k maps %.3f %% identical, image %.1f dB against GL's\n", what, 100 * same, db);
    EXPECT_GE(same, 0.999) << what;
    EXPECT_GE(db, 60.0) << what;
  }
  std::unique_ptr<gl::Context> gl_;
  std::unique_ptr<Engine> engine_;
  SceneGBuffer g_;
};

TEST_F(VkAgainstGl, SameImagesAsTheGlComponent) {
  const auto vo = scene_options<vk::AdaptiveSupersamplerOptions>(g_);
  const auto go = scene_options<gl::AdaptiveSupersamplerOptions>(g_);
  compare(vo, go, Which::adaptive, std::nullopt, "adaptive, frame list");
  auto vt = vo;
  auto gt = go;
  vt.schedule = gt.schedule = AdaptiveSchedule::tile_list;
  compare(vt, gt, Which::adaptive, std::nullopt, "adaptive, tile list");
  compare(vo, go, Which::reference, std::nullopt, "full supersampling");
  compare(vo, go, Which::first, std::nullopt, "1 spp");
  // The image is not trivially uniform: adaptive differs from 1 spp, and shades some pixels.
  const VkFrameOut ad = run_vk(*engine_, vo, g_, Which::adaptive);
  const VkFrameOut one = run_vk(*engine_, vo, g_, Which::first);
  EXPECT_LT(psnr_rgb(ad.colour, one.colour), 50.0);
  EXPECT_GT(ad.extra, 0u);
  EXPECT_LT(ad.extra, std::uint64_t(g_.w * g_.h * 15));
}

TEST_F(VkAgainstGl, LoopScheduleHdrAndBudget) {
  auto vo = scene_options<vk::AdaptiveSupersamplerOptions>(g_);
  auto go = scene_options<gl::AdaptiveSupersamplerOptions>(g_);
  vo.schedule = go.schedule = AdaptiveSchedule::loop;
  vo.resolve = go.resolve = AdaptiveResolve::tonemap_weighted;
  vo.hdr_exposure = go.hdr_exposure = 0.5f;
  const VkFrameOut all = run_vk(*engine_, vo, g_, Which::adaptive);
  const std::int64_t budget = std::int64_t(all.extra / 3);
  ASSERT_GT(budget, 0);
  compare(vo, go, Which::adaptive, budget, "loop, HDR, budget");
  const VkFrameOut b = run_vk(*engine_, vo, g_, Which::adaptive, budget);
  EXPECT_EQ(b.extra, std::uint64_t(budget));  // exactly the budget
}

TEST_F(VkAgainstGl, WindowSizes2And8) {
  for (int m : {2, 8}) {
    g_ = scene_gbuffer(20, 16, m);
    const auto vo = scene_options<vk::AdaptiveSupersamplerOptions>(g_);
    const auto go = scene_options<gl::AdaptiveSupersamplerOptions>(g_);
    compare(vo, go, Which::adaptive, std::nullopt, m == 2 ? "m = 2" : "m = 8");
  }
}

TEST_F(VkAgainstGl, NegativeControlOtherThresholdsDiffer) {
  auto vo = scene_options<vk::AdaptiveSupersamplerOptions>(g_);
  const auto go = scene_options<gl::AdaptiveSupersamplerOptions>(g_);
  vo.thresholds.c_shade = 0.5f;
  vo.thresholds.c_normal = 0.2f;
  const VkFrameOut v = run_vk(*engine_, vo, g_, Which::adaptive);
  const GlFrameOut l = run_gl(go, g_, Which::adaptive);
  EXPECT_LT(same_fraction(v.counts, l.counts), 0.99);
}

}  // namespace
}  // namespace tessera::vk_test
