// The current-context checks every GL-touching call starts with, and `check_errors`: both read
// only the context current on the calling thread (glGetString, glGetError), whoever made it.
// No EGL here: tessera's own Context adds its debug messages through a hook (context.cpp).
#include <algorithm>
#include <atomic>
#include <cstdio>

#include "gl/gl_api.h"
#include "tessera/gl.h"

namespace tessera::gl {

using namespace api;  // NOLINT(google-build-using-namespace): the loaded GL entry points

namespace {

std::atomic<internal::TakeContextErrors> g_context_errors{nullptr};

const char* gl_error_name(GLenum e) {
  switch (e) {
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_STACK_OVERFLOW:
      return "GL_STACK_OVERFLOW";
    case GL_STACK_UNDERFLOW:
      return "GL_STACK_UNDERFLOW";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
      return "GL_INVALID_FRAMEBUFFER_OPERATION";
    default:
      return "GL error";
  }
}

}  // namespace

void internal::set_context_error_source(TakeContextErrors source) {
  g_context_errors.store(source);
}

bool DebugMessage::is_error() const { return type == GL_DEBUG_TYPE_ERROR; }

Status check_current_context(std::string_view what) {
  if (!ensure_loaded()) {
    return Status::error(ErrorCode::unsupported,
                         std::string(what) +
                             ": no OpenGL entry points: call gl::load_entry_points(your "
                             "GetProcAddress) first (no libOpenGL.so.0 to resolve them from)");
  }
  // Without a current context GLVND's and Mesa's dispatch stubs do nothing and return 0.
  const GLubyte* version = glGetString(GL_VERSION);
  if (version == nullptr) {
    return Status::error(ErrorCode::invalid_argument,
                         std::string(what) + ": no OpenGL context is current on this thread");
  }
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major * 10 + minor < 45) {
    while (glGetError() != GL_NO_ERROR) {  // GL_MAJOR_VERSION is unknown before 3.0
    }
    return Status::error(
        ErrorCode::unsupported,
        std::string(what) + ": OpenGL " + reinterpret_cast<const char*>(version) + " is below 4.5");
  }
  return Status::success();
}

Status check_errors(std::string_view what) {
  if (Status s = check_current_context(what); !s.ok()) return s;
  GLenum first = GL_NO_ERROR;
  for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError()) {
    if (first == GL_NO_ERROR) first = e;
  }
  std::vector<DebugMessage> errors;
  if (internal::TakeContextErrors take = g_context_errors.load(); take != nullptr) errors = take();
  if (first == GL_NO_ERROR && errors.empty()) return Status::success();
  std::string msg = std::string(what) + ": ";
  if (first != GL_NO_ERROR) msg += gl_error_name(first);
  if (!errors.empty()) msg += (first != GL_NO_ERROR ? ": " : "") + errors.front().text;
  std::replace(msg.begin(), msg.end(), '\n', ' ');
  return Status::error(ErrorCode::invalid_argument, msg);
}

}  // namespace tessera::gl
