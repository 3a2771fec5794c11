// The loaded OpenGL entry points (see gl_api.h): the table, `gl::load_entry_points` and the
// default from the GL library's exports. No EGL here.
#include "gl/gl_api.h"

#if defined(__unix__)
#include <dlfcn.h>
#endif

#include <atomic>
#include <cstring>
#include <mutex>

namespace tessera::gl::api {

#define TESSERA_GL_DEFINE(name, type) type name = nullptr;
TESSERA_GL_FUNCTIONS(TESSERA_GL_DEFINE)
#undef TESSERA_GL_DEFINE

namespace {

std::mutex g_load_mutex;
std::atomic<bool> g_loaded{false};

// The table as values, so that a load is all or nothing.
struct Table {
#define TESSERA_GL_MEMBER(name, type) type name = nullptr;
  TESSERA_GL_FUNCTIONS(TESSERA_GL_MEMBER)
#undef TESSERA_GL_MEMBER
};

// Resolves every name with `loader` into `t`; "" or the first missing name.
std::string resolve(detail::ErasedLoader loader, const void* context, Table& t) {
#define TESSERA_GL_RESOLVE(name, type)                     \
  t.name = reinterpret_cast<type>(loader(context, #name)); \
  if (t.name == nullptr) return #name;
  TESSERA_GL_FUNCTIONS(TESSERA_GL_RESOLVE)
#undef TESSERA_GL_RESOLVE
  return "";
}

void commit(const Table& t) {
#define TESSERA_GL_COMMIT(name, type) name = t.name;
  TESSERA_GL_FUNCTIONS(TESSERA_GL_COMMIT)
#undef TESSERA_GL_COMMIT
  g_loaded.store(true, std::memory_order_release);
}

#if defined(__unix__)
// GLVND's libOpenGL.so.0 exports every core function through 4.6 as a stub that dispatches to
// the context current on the calling thread (GLX or EGL); a legacy libGL.so.1 does the same for
// its own contexts. RTLD_NOLOAD first: the library the engine already loaded.
void* gl_library() {
  for (const char* name : {"libOpenGL.so.0", "libGL.so.1"}) {
    if (void* h = dlopen(name, RTLD_NOW | RTLD_LOCAL | RTLD_NOLOAD)) return h;
  }
  for (const char* name : {"libOpenGL.so.0", "libGL.so.1"}) {
    if (void* h = dlopen(name, RTLD_NOW | RTLD_LOCAL)) return h;
  }
  return nullptr;
}

ProcAddress library_symbol(const void* handle, const char* name) {
  void* p = dlsym(const_cast<void*>(handle), name);
  static_assert(sizeof(void*) == sizeof(ProcAddress), "object and function pointers differ");
  ProcAddress f = nullptr;
  std::memcpy(&f, &p, sizeof f);
  return f;
}
#endif

}  // namespace

std::string load_with(detail::ErasedLoader loader, const void* context) {
  std::lock_guard<std::mutex> lock(g_load_mutex);
  Table t;
  if (std::string missing = resolve(loader, context, t); !missing.empty()) return missing;
  commit(t);
  return "";
}

bool loaded() { return g_loaded.load(std::memory_order_acquire); }

bool ensure_loaded() {
  if (g_loaded.load(std::memory_order_acquire)) return true;
#if defined(__unix__)
  static std::once_flag once;
  std::call_once(once, [] {
    void* handle = gl_library();
    if (handle == nullptr) return;
    std::lock_guard<std::mutex> lock(g_load_mutex);
    if (g_loaded.load(std::memory_order_acquire)) return;  // a loader was given meanwhile
    Table t;
    if (resolve(&library_symbol, handle, t).empty()) commit(t);
  });
#endif
  return g_loaded.load(std::memory_order_acquire);
}

}  // namespace tessera::gl::api

namespace tessera::gl {

Status detail::load_entry_points(ErasedLoader loader, const void* context) {
  if (loader == nullptr) {
    return Status::error(ErrorCode::invalid_argument, "gl::load_entry_points: no loader");
  }
  if (const std::string missing = api::load_with(loader, context); !missing.empty()) {
    return Status::error(ErrorCode::unsupported,
                         "gl::load_entry_points: the loader does not know " + missing +
                             " (OpenGL 4.5 core is needed)");
  }
  return Status::success();
}

namespace {
struct UserLoader {
  ProcAddress (*loader)(void*, const char*);
  void* user;
};
}  // namespace

Status load_entry_points(ProcAddress (*loader)(void* user, const char* name), void* user) {
  if (loader == nullptr) {
    return Status::error(ErrorCode::invalid_argument, "gl::load_entry_points: no loader");
  }
  const UserLoader l{loader, user};
  return detail::load_entry_points(
      [](const void* context, const char* name) {
        const auto* u = static_cast<const UserLoader*>(context);
        return u->loader(u->user, name);
      },
      &l);
}

bool entry_points_loaded() { return api::loaded(); }

}  // namespace tessera::gl
