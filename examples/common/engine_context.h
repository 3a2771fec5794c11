// engine_context.h — the examples' platform layer, the part an engine already has before it
// adopts tessera: it makes an OpenGL 4.5 core context (a GLFW window through GLX, or with
// --headless a surfaceless EGL context), makes it current, and hands the context's
// GetProcAddress to tessera with gl::load_entry_points. tessera never sees the window, the EGL
// display or the context: its components work on whatever context is current.
//
// The engine's own GL calls go through GLVND's libOpenGL (GL_GLEXT_PROTOTYPES, linked with
// OpenGL::OpenGL), whose stubs dispatch to the current GLX or EGL context; an engine using glad
// would call gladLoadGL(glfwGetProcAddress) here and give tessera the same function.
// Header-only, shared by examples/engine_aa and examples/engine_ptex (with their shader
// compilation, compile_program).
#pragma once

#define GL_GLEXT_PROTOTYPES 1
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>
#if ENGINE_HAVE_GLFW
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#endif

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "tessera/gl.h"

#ifndef EGL_PLATFORM_SURFACELESS_MESA
#define EGL_PLATFORM_SURFACELESS_MESA 0x31DD
#endif

namespace engine {

class Platform {
 public:
  Platform() = default;
  Platform(const Platform&) = delete;
  Platform& operator=(const Platform&) = delete;
  ~Platform() { close(); }

  /// Opens a w x h window (or, headless, an EGL context without a surface), current on this
  /// thread, and loads tessera's GL entry points from it. "" on success, else why not.
  std::string open(bool headless, int w, int h, const char* title) {
    std::string why = headless ? open_egl() : open_window(w, h, title);
    if (!why.empty()) return why;
      // tessera: the context's own GetProcAddress, no cast (glfwGetProcAddress returns a
      // function pointer, SDL_GL_GetProcAddress a void*: both are accepted).
#if ENGINE_HAVE_GLFW
    tessera::Status s = window_ ? tessera::gl::load_entry_points(glfwGetProcAddress)
                                : tessera::gl::load_entry_points(eglGetProcAddress);
#else
    tessera::Status s = tessera::gl::load_entry_points(eglGetProcAddress);
#endif
    if (!s.ok()) return s.message;
    const GLubyte* renderer = glGetString(GL_RENDERER);
    renderer_ = renderer != nullptr ? reinterpret_cast<const char*>(renderer) : "";
    return "";
  }

  bool windowed() const { return window_ != nullptr; }
  const std::string& renderer() const { return renderer_; }
  /// "glfw" (a GLX window) or "egl".
  const char* kind() const { return window_ != nullptr ? "glfw" : "egl"; }

  /// Draws `texture` (w x h, linear RGB; `reinhard`: c / (1 + c) first) with its own program,
  /// vertex array and texture unit 15 (bindings it leaves changed) into the window's
  /// default framebuffer with the sRGB encoding, reads the back buffer back as a top-down RGBA8
  /// image (`out`, w*h*4 bytes) and shows it. `top_down`: texel row 0 is the image's top row.
  void present(GLuint texture, int w, int h, bool reinhard, bool top_down,
               std::vector<std::uint8_t>& out) {
#if ENGINE_HAVE_GLFW
    if (present_program_ == 0) present_program_ = make_present_program();
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, w, h);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glUseProgram(present_program_);
    glUniform1i(glGetUniformLocation(present_program_, "flags"),
                (reinhard ? 1 : 0) | (top_down ? 2 : 0));
    glUniform1i(glGetUniformLocation(present_program_, "height"), h);
    glBindTextureUnit(kPresentUnit, texture);  // not unit 0: the engine's shading reads that one
    glBindSampler(kPresentUnit, 0);
    glBindVertexArray(vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    std::vector<std::uint8_t> rows(std::size_t(w) * std::size_t(h) * 4);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    out.resize(rows.size());
    const std::size_t row = std::size_t(w) * 4;
    for (int y = 0; y < h; ++y) {
      std::copy_n(rows.data() + std::size_t(h - 1 - y) * row, row,
                  out.data() + std::size_t(y) * row);
    }
    glfwSwapBuffers(window_);
    glfwPollEvents();
    glBindVertexArray(0);
    glDeleteVertexArrays(1, &vao);
#else
    (void)texture, (void)w, (void)h, (void)reinhard, (void)top_down, (void)out;
#endif
  }

  void close() {
#if ENGINE_HAVE_GLFW
    if (window_ != nullptr) {
      if (present_program_ != 0) glDeleteProgram(present_program_);
      glfwDestroyWindow(window_);
      glfwTerminate();
      window_ = nullptr;
    }
#endif
    if (context_ != EGL_NO_CONTEXT) {
      eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      eglDestroyContext(display_, context_);
      eglTerminate(display_);
      context_ = EGL_NO_CONTEXT;
    }
  }

 private:
  static constexpr GLuint kPresentUnit = 15;

  std::string open_egl() {
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    const bool surfaceless =
        client != nullptr &&
        std::string(client).find("EGL_MESA_platform_surfaceless") != std::string::npos;
    display_ = surfaceless ? eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA,
                                                   EGL_DEFAULT_DISPLAY, nullptr)
                           : eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (display_ == EGL_NO_DISPLAY || !eglInitialize(display_, nullptr, nullptr)) {
      return "no EGL display";
    }
    if (!eglBindAPI(EGL_OPENGL_API)) return "EGL without desktop OpenGL";
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                              4,
                              EGL_CONTEXT_MINOR_VERSION,
                              5,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK,
                              EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                              EGL_NONE};
    context_ = eglCreateContext(display_, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
    if (context_ == EGL_NO_CONTEXT) return "no OpenGL 4.5 core EGL context";
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
      return "eglMakeCurrent without a surface failed";
    }
    return "";
  }

  std::string open_window(int w, int h, const char* title) {
#if ENGINE_HAVE_GLFW
    static std::string glfw_error;
    glfwSetErrorCallback([](int, const char* text) { glfw_error = text; });
    if (!glfwInit()) return "no window system (" + glfw_error + "); --headless runs without one";
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_CONTEXT_CREATION_API, GLFW_NATIVE_CONTEXT_API);  // GLX on X11
    glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
    glfwWindowHint(GLFW_DOUBLEBUFFER, GLFW_TRUE);
    window_ = glfwCreateWindow(w, h, title, nullptr, nullptr);
    if (window_ == nullptr) {
      glfwTerminate();
      return "no OpenGL 4.5 core window (" + glfw_error + ")";
    }
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(0);
    return "";
#else
    (void)w, (void)h, (void)title;
    return "built without GLFW (libglfw3-dev): only --headless";
#endif
  }

  static GLuint make_present_program() {
    const char* vs = R"(#version 450 core
void main() {
  vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
  gl_Position = vec4(p, 0.0, 1.0);
})";
    const char* fs = R"(#version 450 core
layout(binding = 15) uniform sampler2D image;  // kPresentUnit
uniform int flags, height;
out vec4 colour;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  if ((flags & 2) != 0) p.y = height - 1 - p.y;
  vec3 c = max(texelFetch(image, p, 0).rgb, vec3(0.0));
  if ((flags & 1) != 0) c = c / (1.0 + c);
  c = clamp(c, 0.0, 1.0);
  c = mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
  colour = vec4(c, 1.0);
})";
    const GLuint p = glCreateProgram();
    for (const auto& [stage, src] : {std::pair{GL_VERTEX_SHADER, vs}, {GL_FRAGMENT_SHADER, fs}}) {
      const GLuint s = glCreateShader(stage);
      glShaderSource(s, 1, &src, nullptr);
      glCompileShader(s);
      glAttachShader(p, s);
      glDeleteShader(s);
    }
    glLinkProgram(p);
    return p;
  }

#if ENGINE_HAVE_GLFW
  GLFWwindow* window_ = nullptr;
#else
  void* window_ = nullptr;
#endif
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  GLuint present_program_ = 0;
  std::string renderer_;
};

/// The engine's own shader compilation (a vertex and a fragment stage, linked); 0 with the
/// driver's log in `log` on failure.
inline GLuint compile_program(const char* vs, const char* fs, std::string& log) {
  const GLuint p = glCreateProgram();
  for (const auto& [stage, src] : {std::pair{GL_VERTEX_SHADER, vs}, {GL_FRAGMENT_SHADER, fs}}) {
    const GLuint s = glCreateShader(stage);
    glShaderSource(s, 1, &src, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      char text[4096] = {};
      glGetShaderInfoLog(s, sizeof text, nullptr, text);
      log = text;
      glDeleteShader(s);
      glDeleteProgram(p);
      return 0;
    }
    glAttachShader(p, s);
    glDeleteShader(s);
  }
  glLinkProgram(p);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    log = "the program does not link";
    glDeleteProgram(p);
    return 0;
  }
  return p;
}

/// The largest difference of the R, G and B bytes of two RGBA8 images of the same size.
inline int max_rgb_difference(const std::vector<std::uint8_t>& a, const std::uint8_t* b) {
  int d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (i % 4 != 3) d = std::max(d, std::abs(int(a[i]) - int(b[i])));
  }
  return d;
}

}  // namespace engine
