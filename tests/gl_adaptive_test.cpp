// gl::AdaptiveSupersampler (tessera/gl_adaptive.h): with tessera's own G-buffer and Blinn-Phong
// as the hook it gives DeferredGlRenderer's images bit for bit (every schedule, reference, 1 spp,
// a full frame list), with a foreign layout the same image; the budget (0, binding, not
// binding, rank and tie rules, repeatable); the HDR resolve's formula; the engine's GL state
// restored; bad input. Skips when no OpenGL 4.5 context can be made.
#include "tessera/gl_adaptive.h"

#include <EGL/egl.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include "gl/gl_api.h"
#include "tessera/deferred.h"
#include "tessera/gl.h"
#include "tessera/gl_deferred.h"
#include "tessera/scene.h"
#include "test_support.h"

namespace tessera {
namespace {

using namespace gl::api;
namespace d = deferred;

PFNGLGETINTEGERI_VPROC get_integeri_v() {
  return reinterpret_cast<PFNGLGETINTEGERI_VPROC>(eglGetProcAddress("glGetIntegeri_v"));
}

/// A GL_TEXTURE_2D of `format` holding `texels` (RGBA floats per texel, w x h).
gl::Object make_texture(GLenum format, int w, int h, const std::vector<float>& texels,
                        GLenum upload_format = GL_RGBA) {
  gl::Object t = gl::create_object(gl::ObjectType::texture, GL_TEXTURE_2D);
  glTextureStorage2D(t.get(), 1, format, w, h);
  if (!texels.empty()) {
    glTextureSubImage2D(t.get(), 0, 0, 0, w, h, upload_format, GL_FLOAT, texels.data());
  }
  return t;
}

std::vector<float> read_rgba32f(std::uint32_t tex) {
  Result<ImageRGBAF> img = gl::read_texture_rgbaf(tex);
  EXPECT_TRUE(img.ok()) << img.status().message;
  return img ? img->pixels : std::vector<float>{};
}

std::vector<std::uint8_t> read_counts(std::uint32_t tex, int w, int h) {
  std::vector<std::uint8_t> c(std::size_t(w) * std::size_t(h));
  glGetTextureSubImage(tex, 0, 0, 0, 0, w, h, 1, GL_RED_INTEGER, GL_UNSIGNED_BYTE,
                       GLsizei(c.size()), c.data());
  return c;
}

/// Rgb of an RGBA image equal bit for bit to DeferredGl's (alpha: 1 in both).
std::size_t differing_pixels(const std::vector<float>& a, const ImageRGBAF& b) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < b.pixel_count(); ++i) {
    for (int c = 0; c < 4; ++c) {
      if (std::memcmp(&a[i * 4 + std::size_t(c)], &b.pixels[i * 4 + std::size_t(c)], 4) != 0) {
        ++n;
        break;
      }
    }
  }
  return n;
}

gl::AdaptiveGBufferLayout tessera_layout() {
  gl::AdaptiveGBufferLayout l;
  l.depth = {0, "r"};
  l.normal = {0, "gba"};
  l.id = {1, "r"};
  l.uv = {1, "gb"};
  l.uv_derivatives = {2, "rgba"};
  return l;
}

class GlAdaptive : public ::testing::Test {
 protected:
  void SetUp() override {
    Result<std::unique_ptr<gl::Context>> c = gl::Context::create();
    if (!c) TESSERA_SKIP_OR_FAIL("gl", "no OpenGL 4.5 context: " << c.status().message);
    ctx_ = std::move(*c);
  }
  void TearDown() override {
    deferred_.reset();
    ctx_.reset();
  }

  // DeferredGlRenderer on the built-in scene, its G-buffer at w x h x m, its adaptive image.
  void use_deferred(int w, int h, int m) {
    scene_ = std::make_unique<scene::Scene>(scene::builtin_scene());
    camera_ = scene::orbit_camera(*scene_, 1, 8);
    gl::DeferredGlOptions o;
    o.glsl_dir = TESSERA_GLSL_DIR;
    Result<std::unique_ptr<gl::DeferredGlRenderer>> g = gl::DeferredGlRenderer::create(*scene_, o);
    ASSERT_TRUE(g.ok()) << g.status().message;
    deferred_ = std::move(*g);
    shading_ = d::scene_shading(*scene_, 8, &camera_);
    ASSERT_TRUE(deferred_->render_gbuffer(camera_, w, h, m).ok());
    w_ = w;
    h_ = h;
    m_ = m;
  }
  // After a DeferredGl shade call its G-buffer sits on units 0..2 and its texture arrays on
  // units 3..: the component reads the same textures, the hook shades through the same
  // bindings.
  std::array<std::uint32_t, 4> deferred_textures(int* classes) {
    std::array<std::uint32_t, 4> t{};
    GLint active = 0;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    for (int u = 0; u < 3; ++u) {
      glActiveTexture(GLenum(GL_TEXTURE0 + u));
      GLint name = 0;
      glGetIntegerv(GL_TEXTURE_BINDING_2D, &name);
      t[std::size_t(u)] = std::uint32_t(name);
    }
    *classes = 0;
    for (int u = 3; u < 11; ++u) {
      glActiveTexture(GLenum(GL_TEXTURE0 + u));
      GLint name = 0;
      glGetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &name);
      if (name == 0) break;
      ++*classes;
    }
    glActiveTexture(GLenum(active));
    return t;
  }
  gl::AdaptiveSupersamplerOptions deferred_options(int classes) const {
    gl::AdaptiveSupersamplerOptions o;
    o.width = w_;
    o.height = h_;
    o.m = m_;
    o.output = gl::AdaptiveOutputFormat::rgba32f;
    o.sample_count_texture = true;
    o.glsl_dir = TESSERA_GLSL_DIR;
    o.layout = tessera_layout();
    o.hook.name = "blinn_phong_hook";
    o.hook.source = "#define TESSERA_DEFERRED_CLASSES " + std::to_string(std::max(classes, 1)) +
                    "\n#include \"deferred_shading.glsl\"\n"
                    "vec4 tessera_shade_sample(ivec2 g, float footprint) {\n"
                    "  return vec4(tessera_shade(g, footprint), 1.0);\n}\n";
    return o;
  }

  std::unique_ptr<gl::Context> ctx_;
  std::unique_ptr<scene::Scene> scene_;
  scene::Camera camera_;
  std::unique_ptr<gl::DeferredGlRenderer> deferred_;
  d::ShadingOptions shading_;
  int w_ = 0, h_ = 0, m_ = 0;
};

TEST_F(GlAdaptive, SameImagesAsDeferredGlRenderer) {
  for (int m : {2, 4}) {
    use_deferred(40, 32, m);
    Result<gl::GlShadeResult> ref = deferred_->shade_reference(shading_);
    ASSERT_TRUE(ref.ok()) << ref.status().message;
    Result<gl::GlShadeResult> one = deferred_->shade_default(shading_);
    ASSERT_TRUE(one.ok()) << one.status().message;
    Result<gl::GlShadeResult> ad = deferred_->shade_adaptive(shading_, d::AdaptiveOptions{});
    ASSERT_TRUE(ad.ok()) << ad.status().message;
    int classes = 0;
    gl::AdaptiveFrame frame;
    frame.gbuffer = deferred_textures(&classes);
    for (gl::AdaptiveSchedule s : {gl::AdaptiveSchedule::frame_list,
                                   gl::AdaptiveSchedule::tile_list, gl::AdaptiveSchedule::loop}) {
      gl::AdaptiveSupersamplerOptions o = deferred_options(classes);
      o.schedule = s;
      Result<std::unique_ptr<gl::AdaptiveSupersampler>> c = gl::AdaptiveSupersampler::create(o);
      ASSERT_TRUE(c.ok()) << c.status().message;
      Result<gl::AdaptiveFrameResult> r = (*c)->dispatch(frame);
      ASSERT_TRUE(r.ok()) << r.status().message;
      EXPECT_EQ(differing_pixels(read_rgba32f(r->colour), ad->image), 0u)
          << "m=" << m << " schedule " << int(s);
      EXPECT_EQ(read_counts(r->sample_counts, w_, h_), ad->samples) << "m=" << m;
      if (s != gl::AdaptiveSchedule::frame_list) continue;
      r = (*c)->dispatch_reference(frame);
      ASSERT_TRUE(r.ok()) << r.status().message;
      EXPECT_EQ(differing_pixels(read_rgba32f(r->colour), ref->image), 0u) << "m=" << m;
      r = (*c)->dispatch_first_sample(frame);
      ASSERT_TRUE(r.ok()) << r.status().message;
      EXPECT_EQ(differing_pixels(read_rgba32f(r->colour), one->image), 0u) << "m=" << m;
    }
    // A frame list too small for the frame: the pixels that do not fit shade their own
    // samples in the resolve pass, the image is the same.
    gl::AdaptiveSupersamplerOptions o = deferred_options(classes);
    o.list_capacity = 37;
    Result<std::unique_ptr<gl::AdaptiveSupersampler>> c = gl::AdaptiveSupersampler::create(o);
    ASSERT_TRUE(c.ok()) << c.status().message;
    Result<gl::AdaptiveFrameResult> r = (*c)->dispatch(frame);
    ASSERT_TRUE(r.ok()) << r.status().message;
    EXPECT_EQ(differing_pixels(read_rgba32f(r->colour), ad->image), 0u) << "m=" << m;
  }
}

TEST_F(GlAdaptive, ForeignLayoutSameImage) {
  use_deferred(40, 32, 4);
  Result<gl::GlShadeResult> ad = deferred_->shade_adaptive(shading_, d::AdaptiveOptions{});
  ASSERT_TRUE(ad.ok()) << ad.status().message;
  int classes = 0;
  deferred_textures(&classes);
  Result<d::GBuffer> gb = deferred_->read_gbuffer();
  ASSERT_TRUE(gb.ok()) << gb.status().message;
  // Another engine's layout, every quantity in another texture and order than tessera's:
  //   slot 0 = (v, n.z, n.x, depth)       depth "a"
  //   slot 1 = (id / 4, u, n.y, v)        id "r" scale 4, uv "ga"
  //   slot 2 = (dv/dy, du/dy, dv/dx, du/dx)  uv_derivatives "wzyx"
  //   slot 3 = (n.z, n.y, n.x, 0)         normal "bgr"
  const int gw = w_ * m_, gh = h_ * m_;
  std::vector<float> t0, t1, t2, t3;
  for (int y = 0; y < gh; ++y) {
    for (int x = 0; x < gw; ++x) {
      const float* s = gb->sample(x, y);
      t0.insert(t0.end(), {s[d::kChUv + 1], s[d::kChNormal + 2], s[d::kChNormal], s[d::kChDepth]});
      t1.insert(t1.end(), {s[d::kChMaterial] / 4.0f, s[d::kChUv], s[d::kChNormal + 1],
                           s[d::kChUv + 1]});
      t2.insert(t2.end(),
                {s[d::kChDuvDy + 1], s[d::kChDuvDy], s[d::kChDuvDx + 1], s[d::kChDuvDx]});
      t3.insert(t3.end(), {s[d::kChNormal + 2], s[d::kChNormal + 1], s[d::kChNormal], 0.0f});
    }
  }
  gl::Object a = make_texture(GL_RGBA32F, gw, gh, t0), b = make_texture(GL_RGBA32F, gw, gh, t1);
  gl::Object c = make_texture(GL_RGBA32F, gw, gh, t2), e = make_texture(GL_RGBA32F, gw, gh, t3);
  gl::AdaptiveSupersamplerOptions o = deferred_options(classes);
  o.layout.depth = {0, "a"};
  o.layout.id = {1, "r", 4.0f};
  o.layout.uv = {1, "ga"};
  o.layout.uv_derivatives = {2, "wzyx"};
  o.layout.normal = {3, "bgr"};
  Result<std::unique_ptr<gl::AdaptiveSupersampler>> comp = gl::AdaptiveSupersampler::create(o);
  ASSERT_TRUE(comp.ok()) << comp.status().message;
  gl::AdaptiveFrame frame;
  frame.gbuffer = {a.get(), b.get(), c.get(), e.get()};
  Result<gl::AdaptiveFrameResult> r = (*comp)->dispatch(frame);
  ASSERT_TRUE(r.ok()) << r.status().message;
  EXPECT_EQ(differing_pixels(read_rgba32f(r->colour), ad->image), 0u);
  EXPECT_EQ(read_counts(r->sample_counts, w_, h_), ad->samples);
}

// A synthetic G-buffer: slot 0 = (depth, normal), slot 1 = (id, 0, 0, 0), RGBA32F.
struct Synthetic {
  gl::Object t0, t1;
  gl::AdaptiveFrame frame;
};
template <class Depth>
Synthetic synthetic(int w, int h, int m, Depth depth) {
  std::vector<float> a, b;
  for (int gy = 0; gy < h * m; ++gy) {
    for (int gx = 0; gx < w * m; ++gx) {
      a.insert(a.end(), {depth(gx, gy), 0.0f, 0.0f, 1.0f});
      b.insert(b.end(), {0.0f, 0.0f, 0.0f, 0.0f});
    }
  }
  Synthetic s;
  s.t0 = make_texture(GL_RGBA32F, w * m, h * m, a);
  s.t1 = make_texture(GL_RGBA32F, w * m, h * m, b);
  s.frame.gbuffer = {s.t0.get(), s.t1.get(), 0, 0};
  return s;
}

gl::AdaptiveSupersamplerOptions synthetic_options(int w, int h, int m) {
  gl::AdaptiveSupersamplerOptions o;
  o.width = w;
  o.height = h;
  o.m = m;
  o.output = gl::AdaptiveOutputFormat::rgba32f;
  o.sample_count_texture = true;
  o.glsl_dir = TESSERA_GLSL_DIR;
  o.layout.depth = {0, "r"};
  o.layout.normal = {0, "gba"};
  o.layout.id = {1, "r"};
  o.hook.name = "analytic_hook";
  // A colour per grid texel, HDR values included.
  o.hook.source =
      "vec4 tessera_shade_sample(ivec2 g, float footprint) {\n"
      "  return vec4(float(g.x) * 4.0, float(g.y) * 0.25 + 0.1, float(g.x + g.y) * 2.0, 1.0);\n"
      "}\n";
  return o;
}

std::vector<int> extra_of(const std::vector<std::uint8_t>& counts) {
  std::vector<int> k;
  for (std::uint8_t c : counts) k.push_back(int(c) - 1);
  return k;
}

TEST_F(GlAdaptive, BudgetOnDeferredFrame) {
  use_deferred(40, 32, 4);
  Result<gl::GlShadeResult> one = deferred_->shade_default(shading_);
  ASSERT_TRUE(one.ok()) << one.status().message;
  Result<gl::GlShadeResult> ad = deferred_->shade_adaptive(shading_, d::AdaptiveOptions{});
  ASSERT_TRUE(ad.ok()) << ad.status().message;
  int classes = 0;
  gl::AdaptiveFrame frame;
  frame.gbuffer = deferred_textures(&classes);
  const std::vector<int> asked = extra_of(ad->samples);
  const std::int64_t total = std::accumulate(asked.begin(), asked.end(), std::int64_t(0));
  ASSERT_GT(total, 100);
  for (gl::AdaptiveSchedule sch : {gl::AdaptiveSchedule::frame_list, gl::AdaptiveSchedule::loop}) {
    gl::AdaptiveSupersamplerOptions o = deferred_options(classes);
    o.schedule = sch;
    o.profile = true;
    Result<std::unique_ptr<gl::AdaptiveSupersampler>> c = gl::AdaptiveSupersampler::create(o);
    ASSERT_TRUE(c.ok()) << c.status().message;
    // Budget 0: the 1 spp image.
    frame.budget = 0;
    Result<gl::AdaptiveFrameResult> r = (*c)->dispatch(frame);
    ASSERT_TRUE(r.ok()) << r.status().message;
    EXPECT_EQ(differing_pixels(read_rgba32f(r->colour), one->image), 0u);
    EXPECT_EQ(r->extra_samples, 0u);
    // Not binding (exactly the total, and far above): the unbudgeted image.
    for (std::int64_t b : {total, std::int64_t(1) << 40}) {
      frame.budget = b;
      r = (*c)->dispatch(frame);
      ASSERT_TRUE(r.ok()) << r.status().message;
      EXPECT_EQ(differing_pixels(read_rgba32f(r->colour), ad->image), 0u) << b;
      EXPECT_EQ(r->extra_samples, std::uint64_t(total));
    }
    // Binding: exactly the budget; every pixel keeps all its samples or none, but one; the
    // same result twice.
    for (std::int64_t b : {total / 3, total - 1, std::int64_t(1)}) {
      frame.budget = b;
      r = (*c)->dispatch(frame);
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
      Result<gl::AdaptiveFrameResult> again = (*c)->dispatch(frame);
      ASSERT_TRUE(again.ok());
      EXPECT_EQ(read_rgba32f(again->colour), img);
      EXPECT_EQ(extra_of(read_counts(again->sample_counts, w_, h_)), got);
    }
    // Strength ranks before k: at the budget total - 1 the dropped samples are one pixel's
    // last, i.e. the weakest pixel is cut first.
  }
  gl::AdaptiveSupersamplerOptions o = deferred_options(classes);
  Result<std::unique_ptr<gl::AdaptiveSupersampler>> c = gl::AdaptiveSupersampler::create(o);
  ASSERT_TRUE(c.ok());
  frame.budget = -1;
  Result<gl::AdaptiveFrameResult> r = (*c)->dispatch(frame);
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
  Result<gl::AdaptiveFrameResult> r = (*c)->dispatch(s.frame);
  ASSERT_TRUE(r.ok()) << r.status().message;
  const std::vector<int> got = extra_of(read_counts(r->sample_counts, w, h));
  std::vector<int> rank(std::size_t(w * h));
  std::iota(rank.begin(), rank.end(), 0);
  std::sort(rank.begin(), rank.end(), [&](int x, int y) { return a[std::size_t(x)] > a[std::size_t(y)]; });
  std::vector<int> want(std::size_t(w * h), 0);
  for (int j = 0; j < 5; ++j) want[std::size_t(rank[std::size_t(j)])] = 3;
  want[std::size_t(rank[5])] = 2;
  EXPECT_EQ(got, want);
  // Equal strengths (force_k): the lower pixel index first.
  o.thresholds.force_k = 2;
  c = gl::AdaptiveSupersampler::create(o);
  ASSERT_TRUE(c.ok()) << c.status().message;
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
  o.resolve = gl::AdaptiveResolve::tonemap_weighted;
  o.hdr_exposure = 0.5f;
  for (bool reference : {false, true}) {
    Result<std::unique_ptr<gl::AdaptiveSupersampler>> c = gl::AdaptiveSupersampler::create(o);
    ASSERT_TRUE(c.ok()) << c.status().message;
    Result<gl::AdaptiveFrameResult> r =
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

// Distinctive engine state on everything a dispatch touches; every piece read back after.
TEST_F(GlAdaptive, RestoresEngineGlState) {
  const int w = 8, h = 8, m = 2;
  Synthetic s = synthetic(w, h, m, [](int gx, int gy) { return 1.0f + 0.3f * float((gx ^ gy) & 1); });
  gl::AdaptiveSupersamplerOptions o = synthetic_options(w, h, m);
  auto get_i = get_integeri_v();
  ASSERT_NE(get_i, nullptr);
  auto bind_image = reinterpret_cast<PFNGLBINDIMAGETEXTUREPROC>(eglGetProcAddress("glBindImageTexture"));
  auto bind_range = reinterpret_cast<PFNGLBINDBUFFERRANGEPROC>(eglGetProcAddress("glBindBufferRange"));
  auto get_i64 = reinterpret_cast<PFNGLGETINTEGER64I_VPROC>(eglGetProcAddress("glGetInteger64i_v"));
  for (gl::AdaptiveSchedule sch : {gl::AdaptiveSchedule::frame_list, gl::AdaptiveSchedule::tile_list}) {
    o.schedule = sch;
    Result<std::unique_ptr<gl::AdaptiveSupersampler>> c = gl::AdaptiveSupersampler::create(o);
    ASSERT_TRUE(c.ok()) << c.status().message;
    const int tu = (*c)->texture_unit(), ub = (*c)->uniform_binding();
    const int sb = (*c)->storage_binding(), iu = (*c)->image_unit();
    // The engine's objects.
    Result<gl::Program> prog = gl::link_program(
        {{gl::ShaderStage::compute, "#version 450 core\nlayout(local_size_x = 1) in;\nvoid main() {}\n", "engine.comp"}});
    ASSERT_TRUE(prog.ok()) << prog.status().message;
    std::vector<gl::Object> texs;
    for (int i = 0; i < 6; ++i) texs.push_back(make_texture(GL_RGBA8, 4, 4, {}));
    gl::Object smp = gl::create_object(gl::ObjectType::sampler);
    gl::Object buf = gl::create_object(gl::ObjectType::buffer);
    glNamedBufferData(buf.get(), 4096, nullptr, GL_DYNAMIC_DRAW);
    gl::Object generic_buf = gl::create_object(gl::ObjectType::buffer);
    glNamedBufferData(generic_buf.get(), 256, nullptr, GL_DYNAMIC_DRAW);
    gl::Object fbo = gl::create_object(gl::ObjectType::framebuffer);
    glNamedFramebufferTexture(fbo.get(), GL_COLOR_ATTACHMENT0, texs[5].get(), 0);
    // Set it.
    glUseProgram(prog->get());
    for (int u = 0; u < 4; ++u) {
      glBindTextureUnit(GLuint(tu + u), texs[std::size_t(u)].get());
      glBindSampler(GLuint(tu + u), smp.get());
    }
    glActiveTexture(GL_TEXTURE3);
    bind_range(GL_UNIFORM_BUFFER, GLuint(ub), buf.get(), 256, 512);
    bind_range(GL_SHADER_STORAGE_BUFFER, GLuint(sb), buf.get(), 1024, 64);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GLuint(sb + 1), buf.get());
    glBindBuffer(GL_UNIFORM_BUFFER, generic_buf.get());
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, generic_buf.get());
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, generic_buf.get());
    bind_image(GLuint(iu), texs[4].get(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA8);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.get());
    glViewport(1, 2, 3, 4);
    s.frame.budget = 5;
    Result<gl::AdaptiveFrameResult> r = (*c)->dispatch(s.frame);
    ASSERT_TRUE(r.ok()) << r.status().message;
    r = (*c)->dispatch_reference(s.frame);
    ASSERT_TRUE(r.ok()) << r.status().message;
    // Read it back.
    GLint v = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &v);
    EXPECT_EQ(GLuint(v), prog->get());
    glGetIntegerv(GL_ACTIVE_TEXTURE, &v);
    EXPECT_EQ(v, GL_TEXTURE3);
    for (int u = 0; u < 4; ++u) {
      glActiveTexture(GLenum(GL_TEXTURE0 + tu + u));
      glGetIntegerv(GL_TEXTURE_BINDING_2D, &v);
      EXPECT_EQ(GLuint(v), texs[std::size_t(u)].get()) << "unit " << tu + u;
      glGetIntegerv(GL_SAMPLER_BINDING, &v);
      EXPECT_EQ(GLuint(v), smp.get()) << "unit " << tu + u;
    }
    glActiveTexture(GL_TEXTURE3);
    GLint64 v64 = 0;
    get_i(GL_UNIFORM_BUFFER_BINDING, GLuint(ub), &v);
    EXPECT_EQ(GLuint(v), buf.get());
    get_i64(GL_UNIFORM_BUFFER_START, GLuint(ub), &v64);
    EXPECT_EQ(v64, 256);
    get_i64(GL_UNIFORM_BUFFER_SIZE, GLuint(ub), &v64);
    EXPECT_EQ(v64, 512);
    get_i(GL_SHADER_STORAGE_BUFFER_BINDING, GLuint(sb), &v);
    EXPECT_EQ(GLuint(v), buf.get());
    get_i64(GL_SHADER_STORAGE_BUFFER_START, GLuint(sb), &v64);
    EXPECT_EQ(v64, 1024);
    get_i64(GL_SHADER_STORAGE_BUFFER_SIZE, GLuint(sb), &v64);
    EXPECT_EQ(v64, 64);
    get_i(GL_SHADER_STORAGE_BUFFER_BINDING, GLuint(sb + 1), &v);
    EXPECT_EQ(GLuint(v), buf.get());
    glGetIntegerv(GL_UNIFORM_BUFFER_BINDING, &v);
    EXPECT_EQ(GLuint(v), generic_buf.get());
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &v);
    EXPECT_EQ(GLuint(v), generic_buf.get());
    glGetIntegerv(GL_DISPATCH_INDIRECT_BUFFER_BINDING, &v);
    EXPECT_EQ(GLuint(v), generic_buf.get());
    get_i(GL_IMAGE_BINDING_NAME, GLuint(iu), &v);
    EXPECT_EQ(GLuint(v), texs[4].get());
    get_i(GL_IMAGE_BINDING_ACCESS, GLuint(iu), &v);
    EXPECT_EQ(v, GL_READ_WRITE);
    get_i(GL_IMAGE_BINDING_FORMAT, GLuint(iu), &v);
    EXPECT_EQ(v, GL_RGBA8);
    get_i(GL_IMAGE_BINDING_NAME, GLuint(iu + 1), &v);
    EXPECT_EQ(v, 0);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &v);
    EXPECT_EQ(GLuint(v), fbo.get());
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &v);
    EXPECT_EQ(GLuint(v), fbo.get());
    GLint vp[4] = {};
    glGetIntegerv(GL_VIEWPORT, vp);
    EXPECT_EQ(vp[0] * 1000 + vp[1] * 100 + vp[2] * 10 + vp[3], 1234);
    // Put the context back to defaults for the next round.
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glActiveTexture(GL_TEXTURE0);
    bind_image(GLuint(iu), 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R8);
    EXPECT_TRUE(gl::check_errors("state test").ok());
  }
}

TEST_F(GlAdaptive, BadInputIsOneLineError) {
  const int w = 8, h = 4, m = 2;
  Synthetic s = synthetic(w, h, m, [](int, int) { return 1.0f; });
  auto fails = [](const gl::AdaptiveSupersamplerOptions& o, const std::string& needle) {
    Result<std::unique_ptr<gl::AdaptiveSupersampler>> c = gl::AdaptiveSupersampler::create(o);
    ASSERT_FALSE(c.ok()) << needle;
    EXPECT_NE(c.status().message.find(needle), std::string::npos) << c.status().message;
    EXPECT_EQ(c.status().message.find('\n'), std::string::npos) << c.status().message;
  };
  gl::AdaptiveSupersamplerOptions o = synthetic_options(w, h, m);
  o.m = 1;
  fails(o, "m = 1 (2..8)");
  o.m = 9;
  fails(o, "m = 9 (2..8)");
  o = synthetic_options(w, h, m);
  o.layout.normal.channels = "rg";
  fails(o, "layout.normal.channels = \"rg\": needs 3 channels");
  o = synthetic_options(w, h, m);
  o.layout.id.texture = 4;
  fails(o, "layout.id.texture = 4");
  o = synthetic_options(w, h, m);
  o.layout.uv = {1, "gb"};
  fails(o, "both or neither");
  o = synthetic_options(w, h, m);
  o.sample_order = {0, 1, 1, 3};
  fails(o, "sample_order is not a permutation");
  o = synthetic_options(w, h, m);
  o.hook.source = "vec4 something_else() { return vec4(1.0); }\n";
  fails(o, "does not define vec4 tessera_shade_sample");
  // A hook that does not compile: the GLSL compiler's message at the hook's own line.
  o = synthetic_options(w, h, m);
  o.hook.name = "my_shading.glsl";
  o.hook.source =
      "// engine shading\n"
      "vec4 tessera_shade_sample(ivec2 g, float footprint) {\n"
      "  return vec4(undeclared_thing, 1.0);\n"
      "}\n";
  fails(o, "my_shading.glsl:3:");
  o = synthetic_options(w, h, m);
  o.first_texture_unit = 100000;
  fails(o, "first_texture_unit = 100000");

  // Frame textures that do not match the layout.
  o = synthetic_options(w, h, m);
  Result<std::unique_ptr<gl::AdaptiveSupersampler>> c = gl::AdaptiveSupersampler::create(o);
  ASSERT_TRUE(c.ok()) << c.status().message;
  auto frame_fails = [&](const gl::AdaptiveFrame& f, const std::string& needle) {
    Result<gl::AdaptiveFrameResult> r = (*c)->dispatch(f);
    ASSERT_FALSE(r.ok()) << needle;
    EXPECT_NE(r.status().message.find(needle), std::string::npos) << r.status().message;
  };
  gl::AdaptiveFrame f = s.frame;
  f.gbuffer[1] = 0;
  frame_fails(f, "G-buffer slot 1: texture 0 missing");
  gl::Object small = make_texture(GL_RGBA32F, w, h, {});
  f = s.frame;
  f.gbuffer[0] = small.get();
  frame_fails(f, "is 8x4, the G-buffer is 16x8 (m = 2)");
  gl::Object integer = make_texture(GL_RGBA32UI, w * m, h * m, {});
  f = s.frame;
  f.gbuffer[1] = integer.get();
  frame_fails(f, "not a float or normalised colour format");
  gl::Object rg = make_texture(GL_RG16F, w * m, h * m, {});
  f = s.frame;
  f.gbuffer[0] = rg.get();
  frame_fails(f, "has 2 channels, the layout reads channel 4");
  gl::Object array = gl::create_object(gl::ObjectType::texture, GL_TEXTURE_2D_ARRAY);
  glTextureStorage3D(array.get(), 1, GL_RGBA32F, w * m, h * m, 1);
  f = s.frame;
  f.gbuffer[0] = array.get();
  frame_fails(f, "is not a GL_TEXTURE_2D");
  f = s.frame;
  f.budget = -5;
  frame_fails(f, "budget = -5");
  EXPECT_TRUE(gl::check_errors("bad input").ok());
}

}  // namespace
}  // namespace tessera
