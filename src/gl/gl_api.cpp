// The loaded OpenGL entry points (see gl_api.h).
#include "gl/gl_api.h"

#include <EGL/egl.h>

#include <mutex>

namespace tessera::gl::api {

#define TESSERA_GL_DEFINE(name, type) type name = nullptr;
TESSERA_GL_FUNCTIONS(TESSERA_GL_DEFINE)
#undef TESSERA_GL_DEFINE

std::string load() {
  static std::once_flag once;
  static std::string missing;
  std::call_once(once, [] {
#define TESSERA_GL_LOAD(name, type)                                  \
  name = reinterpret_cast<type>(eglGetProcAddress(#name));           \
  if (name == nullptr && missing.empty()) missing = #name;
    TESSERA_GL_FUNCTIONS(TESSERA_GL_LOAD)
#undef TESSERA_GL_LOAD
  });
  return missing;
}

}  // namespace tessera::gl::api
