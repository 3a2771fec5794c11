// gl::AdaptiveSupersampler (tessera/gl_adaptive.h): with tessera's own G-buffer and Blinn-Phong
// as the hook it gives DeferredRenderer's images bit for bit (every schedule, reference, 1 spp,
// a frame list too small for the frame; DeferredRenderer itself runs a component for m >= 2
// whose hook reuses S's light terms for sample 0 again, this hook shades it in full); with
// a foreign layout the same image; the engine's GL state restored; bad input. The budget and the
// HDR resolve: gl_adaptive_budget_test.cpp. Skips when no OpenGL 4.5 context can be made.
#include "gl_adaptive_test_util.h"

namespace tessera::aa_test {
namespace {

TEST_F(GlAdaptive, SameImagesAsDeferredRenderer) {
  for (int m : {2, 4}) {
    use_deferred(40, 32, m);
    Result<deferred::ShadeResult> ref = deferred_->shade_reference(shading_);
    ASSERT_TRUE(ref.ok()) << ref.status().message;
    ASSERT_NO_FATAL_FAILURE(shade_default_and_adaptive());
    for (AdaptiveSchedule s :
         {AdaptiveSchedule::frame_list, AdaptiveSchedule::tile_list, AdaptiveSchedule::loop}) {
      gl::AdaptiveSupersamplerOptions o = deferred_options(classes_);
      o.schedule = s;
      Result<std::unique_ptr<gl::AdaptiveSupersampler>> c = gl::AdaptiveSupersampler::create(o);
      ASSERT_TRUE(c.ok()) << c.status().message;
      Result<gl::AdaptiveOutput> r = (*c)->dispatch(frame_);
      ASSERT_TRUE(r.ok()) << r.status().message;
      EXPECT_EQ(differing_pixels(read_rgba32f(r->colour), ad_->image), 0u)
          << "m=" << m << " schedule " << int(s);
      EXPECT_EQ(read_counts(r->sample_counts, w_, h_), ad_->samples) << "m=" << m;
      if (s != AdaptiveSchedule::frame_list) continue;
      r = (*c)->dispatch_reference(frame_);
      ASSERT_TRUE(r.ok()) << r.status().message;
      EXPECT_EQ(differing_pixels(read_rgba32f(r->colour), ref->image), 0u) << "m=" << m;
      r = (*c)->dispatch_first_sample(frame_);
      ASSERT_TRUE(r.ok()) << r.status().message;
      EXPECT_EQ(differing_pixels(read_rgba32f(r->colour), one_->image), 0u) << "m=" << m;
    }
    // A frame list too small for the frame: the pixels that do not fit shade their own
    // samples in the resolve pass, the image is the same.
    gl::AdaptiveSupersamplerOptions o = deferred_options(classes_);
    o.list_capacity = 37;
    Result<std::unique_ptr<gl::AdaptiveSupersampler>> c = gl::AdaptiveSupersampler::create(o);
    ASSERT_TRUE(c.ok()) << c.status().message;
    Result<gl::AdaptiveOutput> r = (*c)->dispatch(frame_);
    ASSERT_TRUE(r.ok()) << r.status().message;
    EXPECT_EQ(differing_pixels(read_rgba32f(r->colour), ad_->image), 0u) << "m=" << m;
  }
}

TEST_F(GlAdaptive, ForeignLayoutSameImage) {
  use_deferred(40, 32, 4);
  Result<deferred::ShadeResult> ad = deferred_->shade_adaptive(shading_, AdaptiveThresholds{});
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
      t1.insert(t1.end(),
                {s[d::kChMaterial] / 4.0f, s[d::kChUv], s[d::kChNormal + 1], s[d::kChUv + 1]});
      t2.insert(t2.end(), {s[d::kChDuvDy + 1], s[d::kChDuvDy], s[d::kChDuvDx + 1], s[d::kChDuvDx]});
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
  Result<gl::AdaptiveOutput> r = (*comp)->dispatch(frame);
  ASSERT_TRUE(r.ok()) << r.status().message;
  EXPECT_EQ(differing_pixels(read_rgba32f(r->colour), ad->image), 0u);
  EXPECT_EQ(read_counts(r->sample_counts, w_, h_), ad->samples);
}

// Distinctive engine state on everything a dispatch touches; every piece read back after.
TEST_F(GlAdaptive, RestoresEngineGlState) {
  const int w = 8, h = 8, m = 2;
  Synthetic s =
      synthetic(w, h, m, [](int gx, int gy) { return 1.0f + 0.3f * float((gx ^ gy) & 1); });
  gl::AdaptiveSupersamplerOptions o = synthetic_options(w, h, m);
  auto get_i = get_integeri_v();
  ASSERT_NE(get_i, nullptr);
  auto bind_image =
      reinterpret_cast<PFNGLBINDIMAGETEXTUREPROC>(eglGetProcAddress("glBindImageTexture"));
  auto bind_range =
      reinterpret_cast<PFNGLBINDBUFFERRANGEPROC>(eglGetProcAddress("glBindBufferRange"));
  auto get_i64 = reinterpret_cast<PFNGLGETINTEGER64I_VPROC>(eglGetProcAddress("glGetInteger64i_v"));
  for (AdaptiveSchedule sch : {AdaptiveSchedule::frame_list, AdaptiveSchedule::tile_list}) {
    o.schedule = sch;
    Result<std::unique_ptr<gl::AdaptiveSupersampler>> c = gl::AdaptiveSupersampler::create(o);
    ASSERT_TRUE(c.ok()) << c.status().message;
    const int tu = (*c)->texture_unit(), ub = (*c)->uniform_binding();
    const int sb = (*c)->storage_binding(), iu = (*c)->image_unit();
    // The engine's objects.
    Result<gl::Program> prog = gl::link_program(
        {{glsl::Stage::compute, "#version 450 core\nlayout(local_size_x = 1) in;\nvoid main() {}\n",
          "engine.comp"}});
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
    Result<gl::AdaptiveOutput> r = (*c)->dispatch(s.frame);
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
    Result<gl::AdaptiveOutput> r = (*c)->dispatch(f);
    ASSERT_FALSE(r.ok()) << needle;
    EXPECT_NE(r.status().message.find(needle), std::string::npos) << r.status().message;
  };
  gl::AdaptiveFrame f = s.frame;
  f.gbuffer[1] = 0;
  frame_fails(f, "G-buffer slot 1: texture 0 missing");
  gl::Object small = make_texture(GL_RGBA32F, w, h, {});
  f = s.frame;
  f.gbuffer[0] = small.get();
  frame_fails(f, "is 8x4, smaller than the G-buffer 16x8 (m = 2, render size 8x4)");
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
}  // namespace tessera::aa_test
