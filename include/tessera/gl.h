// tessera/gl.h — tessera's OpenGL 4.5 runtime (optional `tessera::gl` library). Contract: every
// GL-touching call works on the OpenGL 4.5 core context CURRENT ON THE CALLING THREAD, whoever
// made it (GLFW, SDL, Qt, EGL, GLX; or tessera's headless `Context`), and reads errors from it
// with glGetError. Entry points: pass the host's GetProcAddress once to `load_entry_points`
// (glfwGetProcAddress, SDL_GL_GetProcAddress, eglGetProcAddress, no cast); without it they are
// resolved at the first call from libOpenGL.so.0 (Linux/GLVND), or by `Context::create`. The
// table is process-wide: on GLVND and Mesa (EGL, GLX) its pointers serve every context; on WGL
// (untested) they are only guaranteed for the context current when loaded. No current context:
// a one-line error, not a crash. tessera never installs, replaces or leaves changed an engine's
// glDebugMessageCallback; only its own `Context` collects debug output. EGL is used by
// `Context` alone. Guide: docs/engine_integration.md; Tests: tests/gl (gl_entry_points_test,
// gl_engine_context*).
//
// Also here: `Context` (headless EGL: device by `ContextOptions::device` / TESSERA_EGL_DEVICE:
// an index, `hardware`, `software` (llvmpipe), `surfaceless` or `auto`), RAII objects
// (`Object`), programs from tessera/glsl.h sources (`link_program`), GPU timers (`GpuTimer`),
// render targets and read-back. Every fallible call returns `Status` / `Result` with one line;
// nothing throws or aborts. Threads: a context is current on one thread at a time; destroy GL
// objects while the context that made them is current. Row order: textures keep tessera's
// (image row y = texel row y); framebuffer read-back flips GL's bottom-up rows to top-down.
#pragma once

#include <bit>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "tessera/core.h"
#include "tessera/glsl.h"

namespace tessera::gl {

// ---------------------------------------------------------------------------------------------
// Entry points and the current context
// ---------------------------------------------------------------------------------------------

/// A GL function pointer of unknown type (what GetProcAddress functions return).
using ProcAddress = void (*)();

namespace detail {
using ErasedLoader = ProcAddress (*)(const void* context, const char* name);
Status load_entry_points(ErasedLoader loader, const void* context);
}  // namespace detail

/// Loads tessera's OpenGL entry points with the host's GetProcAddress: glfwGetProcAddress,
/// SDL_GL_GetProcAddress (returns void*), eglGetProcAddress, glXGetProcAddressARB (takes
/// const GLubyte*), or any `R (*)(NAME)` with R a pointer and NAME const char* or const
/// unsigned char*; no cast needed. Call it once, with the engine's context current (some
/// loaders need one), before tessera's first GL call and never while tessera GL calls run on
/// other threads. All or nothing: fails (unsupported) naming the first function the loader
/// does not know, leaving the previous table. A later call replaces the table.
template <class R, class Name>
Status load_entry_points(R (*get_proc_address)(Name)) {
  static_assert(std::is_pointer_v<R>, "GetProcAddress must return a pointer");
  using Get = R (*)(Name);
  return detail::load_entry_points(
      [](const void* context, const char* name) -> ProcAddress {
        const R r = (*static_cast<const Get*>(context))(reinterpret_cast<Name>(name));
        if constexpr (std::is_function_v<std::remove_pointer_t<R>>) {
          return reinterpret_cast<ProcAddress>(r);
        } else {
          static_assert(sizeof(R) == sizeof(ProcAddress), "object and function pointers differ");
          return std::bit_cast<ProcAddress>(r);
        }
      },
      &get_proc_address);
}

/// As above with a loader that needs state (e.g. a wrapper around
/// QOpenGLContext::getProcAddress): `loader(user, name)` for every name.
Status load_entry_points(ProcAddress (*loader)(void* user, const char* name), void* user);

/// True when tessera's entry points are loaded (by `load_entry_points`, `Context::create` or
/// the first GL-touching call; see the header comment).
bool entry_points_loaded();

/// Succeeds when tessera's entry points are loaded (loading them first if needed) and an
/// OpenGL 4.5 or later context is current on the calling thread; else fails with one line
/// "WHAT: no OpenGL context is current on this thread" (invalid_argument), "WHAT: OpenGL 3.3
/// is below 4.5" or "WHAT: no OpenGL entry points: ..." (unsupported). Every GL-touching call of
/// tessera starts with this check.
Status check_current_context(std::string_view what);

// ---------------------------------------------------------------------------------------------
// Context and device selection
// ---------------------------------------------------------------------------------------------

/// How the EGL device is chosen.
enum class DeviceChoice {
  automatic,    ///< A hardware device, else a software one, else the surfaceless platform.
  hardware,     ///< The first device whose extensions lack EGL_MESA_device_software.
  software,     ///< The first device with EGL_MESA_device_software (llvmpipe).
  surfaceless,  ///< EGL_PLATFORM_SURFACELESS_MESA (no device enumeration).
  index,        ///< The device with a given index in eglQueryDevicesEXT order.
};

/// A parsed device selection.
struct DeviceSelection {
  DeviceChoice choice = DeviceChoice::automatic;
  int index = -1;  ///< For DeviceChoice::index.
};

/// Parses "auto" (or ""), "hardware", "software", "surfaceless" or a decimal index. Fails with
/// invalid_argument naming the text. Pure.
Result<DeviceSelection> parse_device_selection(std::string_view text);

struct ContextOptions {
  /// Device selection text as for `parse_device_selection`; "" defers to TESSERA_EGL_DEVICE
  /// (when `use_environment`) and then to "auto".
  std::string device;
  /// Read TESSERA_EGL_DEVICE when `device` is empty.
  bool use_environment = true;
  /// Ask for a debug context and install the GL_KHR_debug callback (synchronous output).
  bool debug = true;
  /// Debug messages kept at most (older ones are dropped first; errors are always counted).
  int max_debug_messages = 256;
};

/// One EGL device as enumerated.
struct DeviceInfo {
  int index = 0;
  bool software = false;   ///< Its extension string has EGL_MESA_device_software.
  std::string drm_file;    ///< EGL_DRM_DEVICE_FILE_EXT, "" when not reported.
  std::string extensions;  ///< The device extension string.
};

/// The EGL devices (empty when EGL lacks EGL_EXT_device_enumeration). Fails with unsupported
/// when EGL itself is unusable.
Result<std::vector<DeviceInfo>> list_devices();

/// Implementation limits of the current context.
struct Limits {
  int max_samples = 0;              ///< GL_MAX_SAMPLES (colour and depth renderbuffers).
  int max_array_layers = 0;         ///< GL_MAX_ARRAY_TEXTURE_LAYERS.
  int max_texture_size = 0;         ///< GL_MAX_TEXTURE_SIZE (texels per side).
  int max_texture_units = 0;        ///< GL_MAX_TEXTURE_IMAGE_UNITS (fragment stage).
  std::int64_t max_ssbo_bytes = 0;  ///< GL_MAX_SHADER_STORAGE_BLOCK_SIZE.
  float max_anisotropy = 1.0f;      ///< GL_MAX_TEXTURE_MAX_ANISOTROPY (1 when unsupported).
  bool bindless_textures = false;   ///< GL_ARB_bindless_texture is exposed.
};

/// A message from the GL_KHR_debug callback.
struct DebugMessage {
  std::uint32_t source = 0;  ///< GL_DEBUG_SOURCE_*.
  std::uint32_t type = 0;    ///< GL_DEBUG_TYPE_*.
  std::uint32_t id = 0;
  std::uint32_t severity = 0;  ///< GL_DEBUG_SEVERITY_*.
  std::string text;
  bool is_error() const;  ///< type == GL_DEBUG_TYPE_ERROR.
};

/// A headless OpenGL 4.5 core context. Owns its EGL context (and a reference on its display).
class Context {
 public:
  /// Creates the context and makes it current on the calling thread. Errors (unsupported: no
  /// EGL, no such device, GL below 4.5, missing entry points) are one line naming the device.
  static Result<std::unique_ptr<Context>> create(const ContextOptions& options = {});
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  /// Makes this context current on the calling thread (it must not be current elsewhere).
  Status make_current();

  const std::string& renderer() const { return renderer_; }  ///< GL_RENDERER.
  const std::string& version() const { return version_; }    ///< GL_VERSION.
  int version_major() const { return major_; }
  int version_minor() const { return minor_; }
  /// "EGL device 0 (software)", "EGL device 1 (/dev/dri/card0)" or "EGL surfaceless platform".
  const std::string& device_description() const { return device_; }
  const Limits& limits() const { return limits_; }
  /// True when the context exposes `extension` (e.g. "GL_ARB_bindless_texture").
  bool has_extension(std::string_view extension) const;

  /// Debug messages received since the last `take_debug_messages` (oldest first).
  std::vector<DebugMessage> take_debug_messages();
  /// Error-type debug messages received since creation.
  int debug_error_count() const;

  struct State;  ///< Internal (EGL handles, message store).

 private:
  Context() = default;
  Status init_gl(bool debug);  // strings, extensions, limits, debug output, timer work-around
  void discard_first_timer_query();
  std::unique_ptr<State> state_;
  std::string renderer_, version_, device_;
  int major_ = 0, minor_ = 0;
  Limits limits_;
  std::vector<std::string> extensions_;
};

/// Drains glGetError of the current context (any context) and, when that is a tessera `Context`,
/// its error-type debug messages received since the last check; fails (invalid_argument) with
/// "WHAT: GL_INVALID_OPERATION: <debug text>" when there was any. Also fails as
/// `check_current_context` does when no OpenGL 4.5 context is current.
Status check_errors(std::string_view what);

// ---------------------------------------------------------------------------------------------
// Objects
// ---------------------------------------------------------------------------------------------

enum class ObjectType {
  buffer,
  texture,
  framebuffer,
  renderbuffer,
  vertex_array,
  query,
  sampler,
  program,
  shader
};

/// Owns one GL object name; deletes it on destruction (move-only). Name 0 = none.
class Object {
 public:
  Object() = default;
  Object(ObjectType type, std::uint32_t name) : type_(type), name_(name) {}
  ~Object() { reset(); }
  Object(Object&& o) noexcept : type_(o.type_), name_(o.name_) { o.name_ = 0; }
  Object& operator=(Object&& o) noexcept;
  Object(const Object&) = delete;
  Object& operator=(const Object&) = delete;

  std::uint32_t get() const { return name_; }
  explicit operator bool() const { return name_ != 0; }
  ObjectType type() const { return type_; }
  /// Deletes the object now.
  void reset();

 private:
  ObjectType type_ = ObjectType::buffer;
  std::uint32_t name_ = 0;
};

/// Creates (glCreate*) an object of `type`; for `texture` and `query` the target is required
/// (GL_TEXTURE_2D_ARRAY, GL_TIME_ELAPSED, ...), for `shader` the shader type.
Object create_object(ObjectType type, std::uint32_t target = 0);

// ---------------------------------------------------------------------------------------------
// Shaders
// ---------------------------------------------------------------------------------------------

// Sources, `#include` expansion and the shipped GLSL are GL-free: tessera/glsl.h.

/// A linked program (owns the GL program object).
class Program {
 public:
  Program() = default;
  explicit Program(Object program) : object_(std::move(program)) {}
  std::uint32_t get() const { return object_.get(); }
  /// glGetUniformLocation (-1 when absent or optimised away).
  int uniform(const char* name) const;

 private:
  Object object_;
};

/// Compiles every stage (after `glsl::expand_includes`, so `#include "seams.glsl"` resolves to
/// the shipped GLSL) and links them. A compile error is invalid_argument with
/// `glsl::format_log`'s one line ("seams.glsl:41: error: ..."); a link error names the stages.
Result<Program> link_program(const std::vector<glsl::Source>& stages,
                             const glsl::ExpandOptions& options = {});

// ---------------------------------------------------------------------------------------------
// Timers, render targets, read-back
// ---------------------------------------------------------------------------------------------

/// GL_TIME_ELAPSED queries around named passes. Passes must not nest (GL allows one elapsed
/// query at a time); each begin/end pair is one query, read back by `collect`.
class GpuTimer {
 public:
  /// Starts timing `pass`. Fails if another pass is open.
  Status begin(std::string pass);
  /// Ends the open pass. Fails if none is open.
  Status end();
  /// Waits for every ended pass and returns them in begin order (clears them; PassTime::gpu_ms
  /// set, wall_ms NaN). Fails if a pass
  /// is still open, or (unsupported) if the driver reports a pass longer than the wall time
  /// from its `begin` to its result (a driver bug; Mesa 22.3 llvmpipe's first query in a
  /// context does this, which `Context::create` works around with one discarded query).
  Result<std::vector<PassTime>> collect();

 private:
  struct Pending {
    std::string pass;
    Object query;
    std::chrono::steady_clock::time_point begun;
  };
  std::vector<Pending> pending_;
  bool open_ = false;
};

enum class ColourFormat { rgba8, rgba32f };

struct RenderTargetOptions {
  int width = 256, height = 256;  ///< Pixels, 1..GL_MAX_RENDERBUFFER_SIZE.
  int samples = 1;                ///< 1 = single-sampled; else <= GL_MAX_SAMPLES.
  ColourFormat colour = ColourFormat::rgba32f;
  bool depth = true;  ///< A GL_DEPTH_COMPONENT32F renderbuffer.
};

/// A framebuffer with one colour renderbuffer and optionally depth.
struct RenderTarget {
  Object framebuffer, colour, depth;
  int width = 0, height = 0, samples = 1;
};

/// Creates a complete render target; fails with one line naming the size, format and samples
/// when the framebuffer is incomplete (e.g. 8 samples where GL_MAX_SAMPLES is 4).
Result<RenderTarget> create_render_target(const RenderTargetOptions& options);

/// Reads colour attachment `attachment` (0..7) of `framebuffer` (0 = none is invalid), the
/// rectangle [0, width) x [0, height), into a top-down image (rows flipped). Single-sampled
/// framebuffers only (resolve with glBlitFramebuffer first).
Result<ImageRGBAF> read_framebuffer_rgbaf(std::uint32_t framebuffer, int attachment, int width,
                                          int height);
/// As `read_framebuffer_rgbaf`, 8 bits per channel (GL's float->unorm conversion).
Result<ImageRGBA8> read_framebuffer_rgba8(std::uint32_t framebuffer, int attachment, int width,
                                          int height);

/// Reads `level` of a GL_TEXTURE_2D (layer 0) or one `layer` of a GL_TEXTURE_2D_ARRAY, rows in
/// texel order (row 0 = GL row 0 = v = 0, tessera's texture convention).
Result<ImageRGBAF> read_texture_rgbaf(std::uint32_t texture, int level = 0, int layer = 0);
Result<ImageRGBA8> read_texture_rgba8(std::uint32_t texture, int level = 0, int layer = 0);

}  // namespace tessera::gl
