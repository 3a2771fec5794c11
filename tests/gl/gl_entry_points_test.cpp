// gl::load_entry_points and gl::check_current_context on an EGL context the test makes itself
// (tessera/gl.h's rules: the host's GetProcAddress of any of the usual signatures, all or
// nothing, and a one-line error without a current context).
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "gl/gl_api.h"
#include "tessera/gl.h"
#include "test_support.h"

namespace tessera::gl {
namespace {

#ifndef EGL_PLATFORM_SURFACELESS_MESA
#define EGL_PLATFORM_SURFACELESS_MESA 0x31DD
#endif

// The test's own context (what an engine would make), current until destroyed.
struct OwnContext {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  bool ok() const { return context != EGL_NO_CONTEXT; }
  OwnContext() {
    display = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY || !eglInitialize(display, nullptr, nullptr)) return;
    eglBindAPI(EGL_OPENGL_API);
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                              4,
                              EGL_CONTEXT_MINOR_VERSION,
                              5,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK,
                              EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                              EGL_NONE};
    context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
    if (context != EGL_NO_CONTEXT) {
      eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context);
    }
  }
  ~OwnContext() {
    if (context == EGL_NO_CONTEXT) return;
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display, context);
  }
};

#define REQUIRE_OWN_CONTEXT(ctx) \
  OwnContext ctx;                \
  if (!ctx.ok()) TESSERA_SKIP_OR_FAIL("gl", "no OpenGL 4.5 core EGL context here")

// Loaders of the usual shapes: SDL_GL_GetProcAddress returns void*, glXGetProcAddressARB takes
// const GLubyte*; both wrap EGL's here.
void* sdl_like(const char* name) {
  const auto f = eglGetProcAddress(name);
  void* p = nullptr;
  std::memcpy(&p, &f, sizeof p);
  return p;
}
void (*glx_like(const unsigned char* name))() {
  return eglGetProcAddress(reinterpret_cast<const char*>(name));
}

int g_calls = 0;
ProcAddress without_viewport(void* user, const char* name) {
  ++*static_cast<int*>(user);
  return std::strcmp(name, "glViewport") == 0 ? nullptr : eglGetProcAddress(name);
}

TEST(GlEntryPoints, AcceptsTheHostLoadersWithoutCasts) {
  REQUIRE_OWN_CONTEXT(ctx);
  ASSERT_TRUE(load_entry_points(sdl_like).ok());
  ASSERT_TRUE(load_entry_points(glx_like).ok());
  ASSERT_TRUE(load_entry_points(eglGetProcAddress).ok());
  EXPECT_TRUE(entry_points_loaded());
  EXPECT_TRUE(check_current_context("test").ok());
  // The table calls into this context: GL_VERSION through tessera's pointer.
  ASSERT_NE(api::glGetString, nullptr);
  EXPECT_NE(api::glGetString(GL_VERSION), nullptr);
}

TEST(GlEntryPoints, AllOrNothingNamingTheMissingFunction) {
  REQUIRE_OWN_CONTEXT(ctx);
  ASSERT_TRUE(load_entry_points(eglGetProcAddress).ok());
  const auto viewport = api::glViewport;
  ASSERT_NE(viewport, nullptr);
  Status s = load_entry_points(without_viewport, &g_calls);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message.find("glViewport"), std::string::npos) << s.message;
  EXPECT_EQ(s.message.find('\n'), std::string::npos) << s.message;
  EXPECT_GT(g_calls, 0);
  EXPECT_EQ(api::glViewport, viewport) << "a failed load must leave the previous table";
  EXPECT_TRUE(check_current_context("test").ok());
}

TEST(GlEntryPoints, ResolvedOnFirstUseWithoutALoader) {
  REQUIRE_OWN_CONTEXT(ctx);
  // No load_entry_points in this test (under CTest each test is its own process): the first
  // call resolves the table from libOpenGL.so.0, whose stubs reach this EGL context.
  EXPECT_TRUE(check_current_context("first use").ok());
  EXPECT_TRUE(entry_points_loaded());
  EXPECT_TRUE(check_errors("first use").ok());
}

TEST(GlEntryPoints, NoCurrentContextIsOneLineNotACrash) {
  REQUIRE_OWN_CONTEXT(ctx);
  ASSERT_TRUE(load_entry_points(eglGetProcAddress).ok());
  eglMakeCurrent(ctx.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  for (const Status& s : {check_current_context("probe"), check_errors("probe")}) {
    EXPECT_FALSE(s.ok());
    EXPECT_EQ(s.message, "probe: no OpenGL context is current on this thread");
  }
  Result<RenderTarget> t = create_render_target({});
  ASSERT_FALSE(t.ok());
  EXPECT_NE(t.status().message.find("no OpenGL context is current"), std::string::npos);
  GpuTimer timer;
  EXPECT_FALSE(timer.begin("pass").ok());
  Result<Program> p =
      link_program({{glsl::Stage::compute, "#version 450\nvoid main() {}\n", "probe.comp"}});
  ASSERT_FALSE(p.ok());
  EXPECT_NE(p.status().message.find("no OpenGL context is current"), std::string::npos);
}

}  // namespace
}  // namespace tessera::gl
