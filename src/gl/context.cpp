// Headless OpenGL 4.5 core contexts through EGL: device enumeration and selection, surfaceless
// contexts, the GL_KHR_debug message store and error checks.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <map>
#include <mutex>

#include "gl/gl_api.h"
#include "tessera/gl.h"

#ifndef EGL_PLATFORM_SURFACELESS_MESA
#define EGL_PLATFORM_SURFACELESS_MESA 0x31DD
#endif
#ifndef EGL_PLATFORM_DEVICE_EXT
#define EGL_PLATFORM_DEVICE_EXT 0x313F
#endif

namespace tessera::gl {

using namespace api;  // NOLINT(google-build-using-namespace): the loaded GL entry points

struct Context::State {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  std::mutex mutex;  // guards the message stores (the callback may run on a driver thread)
  std::deque<DebugMessage> messages;
  std::vector<DebugMessage> unchecked_errors;
  int max_messages = 256;
  int error_count = 0;
};

namespace {

thread_local Context::State* g_current = nullptr;

bool has_word(const char* list, std::string_view word) {
  if (list == nullptr) return false;
  std::string_view s(list);
  std::size_t pos = 0;
  while ((pos = s.find(word, pos)) != std::string_view::npos) {
    const bool start = pos == 0 || s[pos - 1] == ' ';
    const std::size_t end = pos + word.size();
    if (start && (end == s.size() || s[end] == ' ')) return true;
    pos = end;
  }
  return false;
}

std::string egl_error_text() {
  const EGLint e = eglGetError();
  char buf[32];
  std::snprintf(buf, sizeof buf, "EGL error 0x%04X", unsigned(e));
  return buf;
}

// eglTerminate is not reference-counted (before EGL_KHR_display_reference): two contexts on the
// same device share one EGLDisplay, so terminate it only when the last user is gone.
std::mutex g_display_mutex;
std::map<EGLDisplay, int> g_display_refs;

bool acquire_display(EGLDisplay d) {
  std::lock_guard<std::mutex> lock(g_display_mutex);
  int& refs = g_display_refs[d];
  if (refs == 0 && !eglInitialize(d, nullptr, nullptr)) {
    g_display_refs.erase(d);
    return false;
  }
  ++refs;
  return true;
}

void release_display(EGLDisplay d) {
  std::lock_guard<std::mutex> lock(g_display_mutex);
  auto it = g_display_refs.find(d);
  if (it == g_display_refs.end()) return;
  if (--it->second == 0) {
    eglTerminate(d);
    g_display_refs.erase(it);
  }
}

struct EglDevices {
  std::vector<EGLDeviceEXT> devices;
  PFNEGLQUERYDEVICESTRINGEXTPROC query_string = nullptr;
};

// Devices in eglQueryDevicesEXT order; empty when enumeration is not available.
EglDevices enumerate_devices(const char* client_extensions) {
  EglDevices r;
  if (!has_word(client_extensions, "EGL_EXT_device_enumeration") &&
      !has_word(client_extensions, "EGL_EXT_device_base")) {
    return r;
  }
  if (!has_word(client_extensions, "EGL_EXT_platform_device")) return r;
  auto query_devices =
      reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  r.query_string = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
      eglGetProcAddress("eglQueryDeviceStringEXT"));
  EGLint count = 0;
  if (query_devices == nullptr || r.query_string == nullptr || !query_devices(0, nullptr, &count) ||
      count <= 0) {
    return r;
  }
  r.devices.resize(std::size_t(count));
  if (!query_devices(count, r.devices.data(), &count)) count = 0;
  r.devices.resize(std::size_t(std::max(count, 0)));
  return r;
}

DeviceInfo describe(const EglDevices& d, int i) {
  DeviceInfo info;
  info.index = i;
  const char* ext = d.query_string(d.devices[std::size_t(i)], EGL_EXTENSIONS);
  info.extensions = ext != nullptr ? ext : "";
  info.software = has_word(ext, "EGL_MESA_device_software");
  if (has_word(ext, "EGL_EXT_device_drm")) {
    const char* file = d.query_string(d.devices[std::size_t(i)], EGL_DRM_DEVICE_FILE_EXT);
    if (file != nullptr) info.drm_file = file;
  }
  return info;
}

std::string device_label(const DeviceInfo& d) {
  return "EGL device " + std::to_string(d.index) + " (" +
         (d.software           ? std::string("software")
          : d.drm_file.empty() ? "hardware"
                               : d.drm_file) +
         ")";
}

void APIENTRY debug_callback(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                             const GLchar* message, const void* user) {
  auto* state = static_cast<Context::State*>(const_cast<void*>(user));
  DebugMessage m;
  m.source = source;
  m.type = type;
  m.id = id;
  m.severity = severity;
  if (message != nullptr) {
    m.text = length >= 0 ? std::string(message, std::size_t(length)) : std::string(message);
  }
  while (!m.text.empty() && (m.text.back() == '\n' || m.text.back() == ' ')) m.text.pop_back();
  std::lock_guard<std::mutex> lock(state->mutex);
  if (m.is_error()) {
    ++state->error_count;
    // Compile and link failures arrive here too (source SHADER_COMPILER); `link_program`
    // reports them from the info log, so they are not left for the next `check_errors`.
    if (source != GL_DEBUG_SOURCE_SHADER_COMPILER && state->unchecked_errors.size() < 64) {
      state->unchecked_errors.push_back(m);
    }
  }
  state->messages.push_back(std::move(m));
  while (int(state->messages.size()) > state->max_messages) state->messages.pop_front();
}

struct Candidate {
  std::string label;
  EGLenum platform = 0;
  void* native = nullptr;
};

}  // namespace

Result<DeviceSelection> parse_device_selection(std::string_view text) {
  DeviceSelection s;
  if (text.empty() || text == "auto") return s;
  if (text == "hardware")
    s.choice = DeviceChoice::hardware;
  else if (text == "software")
    s.choice = DeviceChoice::software;
  else if (text == "surfaceless")
    s.choice = DeviceChoice::surfaceless;
  else {
    int v = -1;
    const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
    if (r.ec != std::errc() || r.ptr != text.data() + text.size() || v < 0) {
      return Status::error(ErrorCode::invalid_argument,
                           "EGL device '" + std::string(text) +
                               "': expected an index, auto, hardware, software or surfaceless");
    }
    s.choice = DeviceChoice::index;
    s.index = v;
  }
  return s;
}

Result<std::vector<DeviceInfo>> list_devices() {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (client == nullptr) {
    return Status::error(ErrorCode::unsupported,
                         "EGL has no client extensions (EGL 1.5 with EGL_EXT_platform_base is "
                         "needed; install libegl-mesa0)");
  }
  const EglDevices d = enumerate_devices(client);
  std::vector<DeviceInfo> out;
  for (int i = 0; i < int(d.devices.size()); ++i) out.push_back(describe(d, i));
  return out;
}

namespace {

// The error-type debug messages of the current tessera Context (the check_errors hook).
std::vector<DebugMessage> take_context_errors() {
  std::vector<DebugMessage> errors;
  if (g_current == nullptr || eglGetCurrentContext() != g_current->context) return errors;
  std::lock_guard<std::mutex> lock(g_current->mutex);
  errors.swap(g_current->unchecked_errors);
  return errors;
}

// The candidates of a selection, in the order they are tried.
Result<std::vector<Candidate>> choose_candidates(const ContextOptions& options) {
  std::string text = options.device, origin = "device";
  if (text.empty() && options.use_environment) {
    if (const char* env = std::getenv("TESSERA_EGL_DEVICE"); env != nullptr && *env != 0) {
      text = env;
      origin = "TESSERA_EGL_DEVICE";
    }
  }
  Result<DeviceSelection> sel = parse_device_selection(text);
  if (!sel) return Status::error(sel.status().code, origin + ": " + sel.status().message);

  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (client == nullptr || !has_word(client, "EGL_EXT_platform_base")) {
    return Status::error(ErrorCode::unsupported,
                         "EGL lacks EGL_EXT_platform_base (EGL 1.5 with the device or "
                         "surfaceless platform is needed; install libegl-mesa0)");
  }
  const EglDevices devices = enumerate_devices(client);
  std::vector<DeviceInfo> infos;
  for (int i = 0; i < int(devices.devices.size()); ++i) infos.push_back(describe(devices, i));
  const bool surfaceless_ok = has_word(client, "EGL_MESA_platform_surfaceless");

  std::vector<Candidate> candidates;
  auto add_device = [&](const DeviceInfo& d) {
    candidates.push_back(
        {device_label(d), EGL_PLATFORM_DEVICE_EXT, devices.devices[std::size_t(d.index)]});
  };
  const DeviceSelection s = *sel;
  if (s.choice == DeviceChoice::index) {
    if (s.index >= int(infos.size())) {
      std::string list;
      for (const DeviceInfo& d : infos) {
        list += (list.empty() ? "" : ", ") + std::to_string(d.index) + " " +
                (d.software ? "software" : "hardware");
      }
      return Status::error(ErrorCode::invalid_argument,
                           origin + "=" + text + ": no EGL device " + std::to_string(s.index) +
                               " (" + std::to_string(infos.size()) + " device" +
                               (infos.size() == 1 ? "" : "s") + (list.empty() ? "" : ": " + list) +
                               ")");
    }
    add_device(infos[std::size_t(s.index)]);
  }
  const bool any = s.choice == DeviceChoice::automatic;
  for (const DeviceInfo& d : infos) {
    if (!d.software && (any || s.choice == DeviceChoice::hardware)) add_device(d);
  }
  for (const DeviceInfo& d : infos) {
    if (d.software && (any || s.choice == DeviceChoice::software)) add_device(d);
  }
  if ((any || s.choice == DeviceChoice::surfaceless) && surfaceless_ok) {
    candidates.push_back(
        {"EGL surfaceless platform", EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY});
  }
  if (candidates.empty()) {
    const char* what = s.choice == DeviceChoice::hardware      ? "no hardware EGL device"
                       : s.choice == DeviceChoice::software    ? "no software EGL device"
                       : s.choice == DeviceChoice::surfaceless ? "no EGL surfaceless platform"
                                                               : "no EGL device or platform";
    return Status::error(ErrorCode::unsupported,
                         std::string(what) + " (" + std::to_string(infos.size()) +
                             " enumerated devices; install libegl-mesa0 libgl1-mesa-dri)");
  }
  return candidates;
}

struct Opened {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
};

// An OpenGL 4.5 core context on `c`, current on the calling thread without a surface; or why
// not (nothing left acquired).
Result<Opened> open_candidate(const Candidate& c, bool debug) {
  auto fail = [&](const std::string& why) {
    return Status::error(ErrorCode::unsupported, c.label + ": " + why);
  };
  EGLDisplay display = eglGetPlatformDisplay(c.platform, c.native, nullptr);
  if (display == EGL_NO_DISPLAY || !acquire_display(display)) {
    return fail("cannot initialise the display (" + egl_error_text() + ")");
  }
  const char* dext = eglQueryString(display, EGL_EXTENSIONS);
  if (!has_word(dext, "EGL_KHR_surfaceless_context")) {
    release_display(display);
    return fail("EGL_KHR_surfaceless_context is missing");
  }
  EGLConfig config = EGL_NO_CONFIG_KHR;
  if (!has_word(dext, "EGL_KHR_no_config_context") &&
      !has_word(dext, "EGL_MESA_configless_context")) {
    const EGLint attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLint n = 0;
    if (!eglChooseConfig(display, attribs, &config, 1, &n) || n < 1) {
      release_display(display);
      return fail("no EGL config renders OpenGL");
    }
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    release_display(display);
    return fail("eglBindAPI(EGL_OPENGL_API) failed: no desktop OpenGL");
  }
  const EGLint ctx_attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                4,
                                EGL_CONTEXT_MINOR_VERSION,
                                5,
                                EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                EGL_CONTEXT_OPENGL_DEBUG,
                                debug ? EGL_TRUE : EGL_FALSE,
                                EGL_NONE};
  EGLContext egl_ctx = eglCreateContext(display, config, EGL_NO_CONTEXT, ctx_attribs);
  if (egl_ctx == EGL_NO_CONTEXT) {
    const std::string why = "cannot create an OpenGL 4.5 core context (" + egl_error_text() + ")";
    release_display(display);
    return fail(why);
  }
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, egl_ctx)) {
    const std::string why = "eglMakeCurrent without a surface failed (" + egl_error_text() + ")";
    eglDestroyContext(display, egl_ctx);
    release_display(display);
    return fail(why);
  }
  return Opened{display, egl_ctx};
}

}  // namespace

Result<std::unique_ptr<Context>> Context::create(const ContextOptions& options) {
  Result<std::vector<Candidate>> candidates = choose_candidates(options);
  if (!candidates) return candidates.status();
  std::string first_error;
  for (const Candidate& c : *candidates) {
    Result<Opened> opened = open_candidate(c, options.debug);
    if (!opened) {
      if (first_error.empty()) first_error = opened.status().message;
      continue;
    }
    std::unique_ptr<Context> ctx(new Context());
    ctx->state_ = std::make_unique<State>();
    ctx->state_->display = opened->display;
    ctx->state_->context = opened->context;
    ctx->state_->max_messages = std::max(1, options.max_debug_messages);
    ctx->device_ = c.label;
    g_current = ctx->state_.get();
    // The engine's loader, when it gave one, stays; else EGL's (GLVND stubs: every context).
    if (!api::loaded()) {
      if (Status s = load_entry_points(eglGetProcAddress); !s.ok()) {
        if (first_error.empty()) first_error = c.label + ": " + s.message;
        continue;  // ~Context releases the EGL objects
      }
    }
    if (Status s = ctx->init_gl(options.debug); !s.ok()) {
      if (first_error.empty()) first_error = c.label + ": " + s.message;
      continue;
    }
    internal::set_context_error_source(&take_context_errors);
    return ctx;
  }
  return Status::error(ErrorCode::unsupported, first_error);
}

Status Context::init_gl(bool debug) {
  glGetIntegerv(GL_MAJOR_VERSION, &major_);
  glGetIntegerv(GL_MINOR_VERSION, &minor_);
  auto str = [](GLenum name) {
    const GLubyte* p = glGetString(name);
    return p != nullptr ? std::string(reinterpret_cast<const char*>(p)) : std::string();
  };
  renderer_ = str(GL_RENDERER);
  version_ = str(GL_VERSION);
  if (major_ * 10 + minor_ < 45) {
    return Status::error(ErrorCode::unsupported,
                         "OpenGL " + version_ + " is below 4.5 (" + renderer_ + ")");
  }
  GLint n_ext = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &n_ext);
  for (GLint i = 0; i < n_ext; ++i) {
    const GLubyte* e = glGetStringi(GL_EXTENSIONS, GLuint(i));
    if (e != nullptr) extensions_.emplace_back(reinterpret_cast<const char*>(e));
  }
  std::sort(extensions_.begin(), extensions_.end());
  if (debug) {  // tessera's own context only: an engine's callback is never touched
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(debug_callback, state_.get());
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
  }
  Limits& l = limits_;
  glGetIntegerv(GL_MAX_SAMPLES, &l.max_samples);
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &l.max_array_layers);
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &l.max_texture_size);
  glGetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &l.max_texture_units);
  GLint64 ssbo = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &ssbo);
  l.max_ssbo_bytes = ssbo;
  if (major_ * 10 + minor_ >= 46 || has_extension("GL_ARB_texture_filter_anisotropic") ||
      has_extension("GL_EXT_texture_filter_anisotropic")) {
    glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY, &l.max_anisotropy);
  }
  l.bindless_textures = has_extension("GL_ARB_bindless_texture");
  discard_first_timer_query();
  while (glGetError() != GL_NO_ERROR) {
  }
  return Status::success();
}

// Mesa 22.3 llvmpipe answers the first GL_TIME_ELAPSED query of a context that encloses
// rendering work with an absolute timestamp (about the system uptime); one discarded query
// around a 1x1 clear keeps GpuTimer honest.
void Context::discard_first_timer_query() {
  GLuint q = 0, fb = 0, rb = 0;
  GLuint64 ns = 0;
  const GLfloat black[4] = {0, 0, 0, 0};
  glCreateFramebuffers(1, &fb);
  glCreateRenderbuffers(1, &rb);
  glNamedRenderbufferStorage(rb, GL_RGBA8, 1, 1);
  glNamedFramebufferRenderbuffer(fb, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
  glCreateQueries(GL_TIME_ELAPSED, 1, &q);
  glBeginQuery(GL_TIME_ELAPSED, q);
  glClearNamedFramebufferfv(fb, GL_COLOR, 0, black);
  glEndQuery(GL_TIME_ELAPSED);
  glGetQueryObjectui64v(q, GL_QUERY_RESULT, &ns);
  glDeleteQueries(1, &q);
  glDeleteFramebuffers(1, &fb);
  glDeleteRenderbuffers(1, &rb);
}

Context::~Context() {
  if (!state_) return;
  if (eglGetCurrentContext() == state_->context) {
    eglMakeCurrent(state_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
  if (g_current == state_.get()) g_current = nullptr;
  eglDestroyContext(state_->display, state_->context);
  release_display(state_->display);
}

Status Context::make_current() {
  if (!eglMakeCurrent(state_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, state_->context)) {
    return Status::error(ErrorCode::invalid_argument,
                         device_ + ": eglMakeCurrent failed (" + egl_error_text() + ")");
  }
  g_current = state_.get();
  return Status::success();
}

bool Context::has_extension(std::string_view extension) const {
  return std::binary_search(extensions_.begin(), extensions_.end(), extension,
                            [](std::string_view a, std::string_view b) { return a < b; });
}

std::vector<DebugMessage> Context::take_debug_messages() {
  std::lock_guard<std::mutex> lock(state_->mutex);
  std::vector<DebugMessage> out(state_->messages.begin(), state_->messages.end());
  state_->messages.clear();
  return out;
}

int Context::debug_error_count() const {
  std::lock_guard<std::mutex> lock(state_->mutex);
  return state_->error_count;
}

}  // namespace tessera::gl
