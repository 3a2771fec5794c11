// The OpenGL runtime (tessera/gl.h): context creation and device selection, shader errors that
// name file and line, clear/upload + read-back round trips, timer queries, debug errors.
// Tests that need a context skip with the reason when EGL cannot create one at all.
#include "tessera/gl.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>

#include "gl/gl_api.h"
#include "gl_test_fixture.h"
#include "test_support.h"

namespace {

using namespace tessera;
using namespace tessera::gl;
using namespace tessera::gl::api;  // NOLINT(google-build-using-namespace)

class Gl : public test::GlTest {
 protected:
  void SetUp() override {
    ContextOptions o;
    o.use_environment = true;
    create_context(o);
  }
};

void write_text(const std::filesystem::path& p, const std::string& text) {
  std::ofstream f(p, std::ios::binary);
  f << text;
}

bool one_line(const std::string& s) { return !s.empty() && s.find('\n') == std::string::npos; }

// ---- Pure parts (no GL) ----

TEST(GlPure, ParsesDeviceSelections) {
  EXPECT_EQ(parse_device_selection("")->choice, DeviceChoice::automatic);
  EXPECT_EQ(parse_device_selection("auto")->choice, DeviceChoice::automatic);
  EXPECT_EQ(parse_device_selection("software")->choice, DeviceChoice::software);
  EXPECT_EQ(parse_device_selection("hardware")->choice, DeviceChoice::hardware);
  EXPECT_EQ(parse_device_selection("surfaceless")->choice, DeviceChoice::surfaceless);
  Result<DeviceSelection> i = parse_device_selection("3");
  ASSERT_TRUE(i.ok());
  EXPECT_EQ(i->choice, DeviceChoice::index);
  EXPECT_EQ(i->index, 3);
  EXPECT_FALSE(parse_device_selection("-1").ok());
  EXPECT_FALSE(parse_device_selection("gpu").ok());
  EXPECT_FALSE(parse_device_selection("1x").ok());
}

TEST(GlPure, NonexistentDeviceIndexFailsWithOneLine) {
  ASSERT_EQ(setenv("TESSERA_EGL_DEVICE", "99", 1), 0);
  Result<std::unique_ptr<Context>> c = Context::create();
  unsetenv("TESSERA_EGL_DEVICE");
  ASSERT_FALSE(c.ok());
  EXPECT_TRUE(one_line(c.status().message)) << c.status().message;
  // Without EGL at all the message says so instead; with EGL it names the missing device.
  if (c.status().code == ErrorCode::invalid_argument) {
    EXPECT_NE(c.status().message.find("TESSERA_EGL_DEVICE=99: no EGL device 99"), std::string::npos)
        << c.status().message;
  }
  ContextOptions o;
  o.device = "nonsense";
  Result<std::unique_ptr<Context>> d = Context::create(o);
  ASSERT_FALSE(d.ok());
  EXPECT_TRUE(one_line(d.status().message));
  EXPECT_EQ(d.status().code, ErrorCode::invalid_argument);
}

// ---- With a context ----

TEST_F(Gl, ContextReportsGl45AndRenderer) {
  EXPECT_GE(ctx_->version_major() * 10 + ctx_->version_minor(), 45) << ctx_->version();
  EXPECT_FALSE(ctx_->renderer().empty());
  EXPECT_NE(ctx_->version().find("4."), std::string::npos);
  const Limits& l = ctx_->limits();
  // GL 4.5 minimums.
  EXPECT_GE(l.max_texture_size, 16384);
  EXPECT_GE(l.max_array_layers, 2048);
  EXPECT_GE(l.max_samples, 4);
  EXPECT_GE(l.max_texture_units, 16);
  EXPECT_GE(l.max_ssbo_bytes, std::int64_t{1} << 24);
  EXPECT_TRUE(check_errors("after creation").ok());
  std::printf("renderer: %s | %s | %s | max samples %d, layers %d, size %d, aniso %.0f\n",
              ctx_->renderer().c_str(), ctx_->version().c_str(), ctx_->device_description().c_str(),
              l.max_samples, l.max_array_layers, l.max_texture_size, double(l.max_anisotropy));
}

TEST_F(Gl, ExplicitDeviceChoicesWork) {
  Result<std::vector<DeviceInfo>> devices = list_devices();
  ASSERT_TRUE(devices.ok()) << devices.status().message;
  for (const DeviceInfo& d : *devices) {
    ContextOptions o;
    o.device = std::to_string(d.index);
    Result<std::unique_ptr<Context>> c = Context::create(o);
    if (!c) {
      ADD_FAILURE() << c.status().message;
      continue;
    }
    EXPECT_NE((*c)->device_description().find("EGL device " + o.device), std::string::npos);
    EXPECT_GE((*c)->version_major(), 4);
  }
  ASSERT_TRUE(ctx_->make_current().ok());
  EXPECT_TRUE(check_errors("back on the first context").ok());
}

TEST_F(Gl, ShaderErrorsNameFileAndLine) {
  const auto dir = test::temp_dir("shaders");
  const auto frag = dir / "broken.frag";
  write_text(frag,
             "#version 450 core\n"
             "layout(location = 0) out vec4 colour;\n"
             "void main() {\n"
             "  colour = vec4(1.0);\n"
             "  colour.x = undefined_name;\n"
             "}\n");
  Result<glsl::Source> src = glsl::load_shader(glsl::Stage::fragment, frag);
  ASSERT_TRUE(src.ok());
  Result<Program> p = link_program({*src});
  ASSERT_FALSE(p.ok());
  EXPECT_TRUE(one_line(p.status().message)) << p.status().message;
  EXPECT_EQ(p.status().message.rfind(frag.string() + ":5: ", 0), 0u) << p.status().message;
  EXPECT_NE(p.status().message.find("undefined_name"), std::string::npos);

  // An error inside an included file names that file; one after the include names the main
  // file with its own line number; a preamble does not shift either.
  write_text(dir / "lib.glsl", "float f() {\n  return 1.0;\n}\nfloat g() { return h(); }\n");
  glsl::ExpandOptions o;
  o.include_paths = {dir};
  o.preamble = {"#define A 1", "#define B 2"};
  glsl::Source inc{glsl::Stage::fragment,
                   "#version 450 core\n#include \"lib.glsl\"\nout vec4 c;\n"
                   "void main() { c = vec4(f()); }\n",
                   "inc.frag"};
  p = link_program({inc}, o);
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.status().message.rfind((dir / "lib.glsl").string() + ":4: ", 0), 0u)
      << p.status().message;
  write_text(dir / "lib.glsl", "float f() {\n  return 1.0;\n}\n");
  inc.text = "#version 450 core\n#include \"lib.glsl\"\nout vec4 c;\n\nvoid main() { c = q; }\n";
  p = link_program({inc}, o);
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.status().message.rfind("inc.frag:5: ", 0), 0u) << p.status().message;

  // A correct program links; a link error names the stages.
  inc.text =
      "#version 450 core\n#include \"lib.glsl\"\nout vec4 c;\nvoid main() { c = vec4(f()); }\n";
  glsl::Source vs{glsl::Stage::vertex,
                  "#version 450 core\nvoid main() { gl_Position = vec4(0.0); }\n", "v.vert"};
  p = link_program({vs, inc}, o);
  ASSERT_TRUE(p.ok()) << p.status().message;
  EXPECT_NE(p->get(), 0u);
  glsl::Source vs2 = vs;
  vs2.name = "w.vert";
  Result<Program> twice = link_program({vs, vs2});
  ASSERT_FALSE(twice.ok());
  EXPECT_TRUE(one_line(twice.status().message));
  EXPECT_EQ(twice.status().message.rfind("link error (v.vert, w.vert): ", 0), 0u)
      << twice.status().message;
  EXPECT_TRUE(check_errors("after shaders").ok());
}

TEST_F(Gl, ClearAndReadBackAreExact) {
  RenderTargetOptions o;
  o.width = 7;
  o.height = 5;
  o.colour = ColourFormat::rgba32f;
  Result<RenderTarget> t = create_render_target(o);
  ASSERT_TRUE(t.ok()) << t.status().message;
  const float value[4] = {0.25f, -1.5f, 1.0f / 3.0f, 1e-7f};
  glClearNamedFramebufferfv(t->framebuffer.get(), GL_COLOR, 0, value);
  Result<ImageRGBAF> f = read_framebuffer_rgbaf(t->framebuffer.get(), 0, 7, 5);
  ASSERT_TRUE(f.ok()) << f.status().message;
  ASSERT_EQ(f->width, 7);
  ASSERT_EQ(f->height, 5);
  for (std::size_t i = 0; i < f->pixels.size(); ++i) EXPECT_EQ(f->pixels[i], value[i % 4]);

  o.colour = ColourFormat::rgba8;
  Result<RenderTarget> t8 = create_render_target(o);
  ASSERT_TRUE(t8.ok()) << t8.status().message;
  const float v8[4] = {1.0f, 0.0f, 128.0f / 255.0f, 64.0f / 255.0f};
  glClearNamedFramebufferfv(t8->framebuffer.get(), GL_COLOR, 0, v8);
  Result<ImageRGBA8> b = read_framebuffer_rgba8(t8->framebuffer.get(), 0, 7, 5);
  ASSERT_TRUE(b.ok()) << b.status().message;
  const std::uint8_t expect8[4] = {255, 0, 128, 64};
  for (std::size_t i = 0; i < b->pixels.size(); ++i) EXPECT_EQ(b->pixels[i], expect8[i % 4]);

  // Texture upload -> read back is the identity; the same texture read through a framebuffer
  // comes back flipped (framebuffer images are top-down).
  ImageRGBAF img(5, 3);
  for (std::size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = float(i) * 0.01f - 0.2f;
  Object tex = create_object(ObjectType::texture, GL_TEXTURE_2D);
  glTextureStorage2D(tex.get(), 1, GL_RGBA32F, 5, 3);
  glTextureSubImage2D(tex.get(), 0, 0, 0, 5, 3, GL_RGBA, GL_FLOAT, img.pixels.data());
  Result<ImageRGBAF> back = read_texture_rgbaf(tex.get());
  ASSERT_TRUE(back.ok()) << back.status().message;
  EXPECT_EQ(back->pixels, img.pixels);
  Object fb = create_object(ObjectType::framebuffer);
  glNamedFramebufferTexture(fb.get(), GL_COLOR_ATTACHMENT0, tex.get(), 0);
  Result<ImageRGBAF> flipped = read_framebuffer_rgbaf(fb.get(), 0, 5, 3);
  ASSERT_TRUE(flipped.ok()) << flipped.status().message;
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 5; ++x) {
      for (int k = 0; k < 4; ++k) EXPECT_EQ(flipped->at(x, y)[k], img.at(x, 2 - y)[k]);
    }
  }
  EXPECT_FALSE(read_texture_rgbaf(tex.get(), 0, 1).ok());  // a 2D texture has one layer
  EXPECT_TRUE(check_errors("after read-back").ok());
}

TEST_F(Gl, TimerQueriesGiveNonNegativeTimes) {
  Result<RenderTarget> t = create_render_target({});
  ASSERT_TRUE(t.ok()) << t.status().message;
  GpuTimer timer;
  const float c[4] = {0.5f, 0.5f, 0.5f, 1.0f};
  ASSERT_TRUE(timer.begin("clear").ok());
  EXPECT_FALSE(timer.begin("nested").ok());
  EXPECT_FALSE(timer.collect().ok());  // still open
  glClearNamedFramebufferfv(t->framebuffer.get(), GL_COLOR, 0, c);
  ASSERT_TRUE(timer.end().ok());
  EXPECT_FALSE(timer.end().ok());
  ASSERT_TRUE(timer.begin("clear again").ok());
  glClearNamedFramebufferfv(t->framebuffer.get(), GL_COLOR, 0, c);
  ASSERT_TRUE(timer.end().ok());
  Result<std::vector<PassTime>> times = timer.collect();
  ASSERT_TRUE(times.ok()) << times.status().message;
  ASSERT_EQ(times->size(), 2u);
  EXPECT_EQ((*times)[0].pass, "clear");
  EXPECT_EQ((*times)[1].pass, "clear again");
  for (const PassTime& p : *times) {
    EXPECT_TRUE(std::isfinite(p.gpu_ms));
    EXPECT_GE(p.gpu_ms, 0.0);
  }
  EXPECT_TRUE(timer.collect()->empty());
}

TEST_F(Gl, GlErrorsBecomeStatusWithDebugText) {
  ASSERT_TRUE(check_errors("clean").ok());
  const int before = ctx_->debug_error_count();
  glTextureParameteri(0, GL_TEXTURE_MIN_FILTER, GL_LINEAR);  // texture 0: GL_INVALID_OPERATION
  Status s = check_errors("bad call");
  ASSERT_FALSE(s.ok());
  EXPECT_TRUE(one_line(s.message)) << s.message;
  EXPECT_EQ(s.message.rfind("bad call: GL_INVALID_OPERATION", 0), 0u) << s.message;
  EXPECT_GT(ctx_->debug_error_count(), before);
  bool found = false;
  for (const DebugMessage& m : ctx_->take_debug_messages()) found = found || m.is_error();
  EXPECT_TRUE(found);
  EXPECT_TRUE(check_errors("drained").ok());
}

TEST_F(Gl, TooManySamplesIsAOneLineError) {
  RenderTargetOptions o;
  o.samples = ctx_->limits().max_samples * 2;
  Result<RenderTarget> t = create_render_target(o);
  ASSERT_FALSE(t.ok());
  EXPECT_TRUE(one_line(t.status().message));
  EXPECT_NE(t.status().message.find("GL_MAX_SAMPLES"), std::string::npos);
  o.samples = ctx_->limits().max_samples;
  EXPECT_TRUE(create_render_target(o).ok());
  EXPECT_TRUE(check_errors("after render targets").ok());
}

}  // namespace
