// tessera/experiments/common.h — what the two paper experiments share: the backend switch, the
// one factory interface of their GPU backends, progress callbacks and per-frame timings.
//
// The backend model: each experiment renders through an abstract backend of its own
// (experiments::SeamsBackend in seams_backend.h, experiments::AaBackend in aa_backend.h), with a
// CPU implementation in this library, an OpenGL one in the optional `tessera_gl` library and a
// Vulkan one in the optional `tessera_vk` library. `Backend` picks who renders: the CPU, OpenGL,
// Vulkan, or both (the CPU result, with the same run on GL beside it and compared with it). The
// main library links neither GPU API: a caller that wants one hands the config a
// `GpuBackendFactory`, implemented by `gl::experiment_backends()` (tessera/gl_experiments.h) and
// `vk::experiment_backends()` (tessera/vk_experiments.h).
// Tests: tests/unit/experiments_test.cpp.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/core.h"

namespace tessera::faces {
struct FaceScene;
class FaceTextureSet;
}  // namespace tessera::faces

namespace tessera::scene {
struct Scene;
}  // namespace tessera::scene

namespace tessera::experiments {

/// Who renders an experiment's frames.
enum class Backend {
  cpu,   ///< The CPU renderers (faces::FaceRenderer, deferred::DeferredRenderer).
  gl,    ///< OpenGL through the config's `gl_factory` (GL times, GL reference).
  vk,    ///< Vulkan through the config's `vk_factory` (GPU timestamps, Vulkan reference).
  both,  ///< The CPU result, plus the same frames on GL, timed and compared with the CPU's.
};

/// "cpu", "gl", "vk", "both" (the values of `--backend` and of the JSON key "backend").
const char* backend_name(Backend backend);

/// Parses "cpu", "gl", "vk" or "both"; anything else is invalid_argument naming the text.
Result<Backend> parse_backend(std::string_view text);

/// Whether `backend` renders on a GPU API (gl, vk, both).
inline bool uses_gpu(Backend backend) { return backend != Backend::cpu; }
/// Whether a GPU API renders the experiment's own results, with no CPU run (gl, vk).
inline bool gpu_primary(Backend backend) {
  return backend == Backend::gl || backend == Backend::vk;
}
/// Whether the CPU renderers run (cpu, both).
inline bool uses_cpu(Backend backend) { return !gpu_primary(backend); }

/// What every experiment backend (SeamsBackend, AaBackend) tells about itself.
class BackendDevice {
 public:
  virtual ~BackendDevice() = default;
  virtual Backend backend() const = 0;  ///< cpu, gl or vk.
  /// GL_RENDERER and GL_VERSION of a GL backend, VkPhysicalDeviceProperties' deviceName and
  /// "Vulkan 1.3.x, driver ..." of a Vulkan one; "" for the CPU.
  virtual std::string device_name() const = 0;
  virtual std::string device_version() const = 0;
};

class SeamsBackend;
class AaBackend;

/// Makes the GPU backends of both experiments: the one factory interface, of OpenGL
/// (`gl::experiment_backends`, tessera/gl_experiments.h, in `tessera_gl`) and of Vulkan
/// (`vk::experiment_backends`, tessera/vk_experiments.h, in `tessera_vk`); tests may implement
/// it with fakes. Each call makes a backend on a headless context / device of its own, created
/// on the calling thread; errors (no usable device, missing shaders) are one line.
class GpuBackendFactory {
 public:
  virtual ~GpuBackendFactory() = default;
  /// Backend::gl or Backend::vk.
  virtual Backend backend() const = 0;
  /// The seam experiment's backend for a face scene; `scene` and `textures` must outlive it.
  virtual Result<std::unique_ptr<SeamsBackend>> create_seams(
      const faces::FaceScene& scene, const faces::FaceTextureSet& textures) const = 0;
  /// The AA experiment's backend for a scene; `scene` must outlive it.
  virtual Result<std::unique_ptr<AaBackend>> create_aa(const scene::Scene& scene) const = 0;
  /// What the devices reported while they ran: `run_seams` and `run_aa` return it, once their
  /// backends are destroyed, in place of their result when it is not ok (Vulkan with
  /// validation on: any validation warning or error, the first one quoted).
  virtual Status device_status() const { return Status::success(); }
};

/// Progress report: one line of text (no trailing newline), e.g. "frame 2/8 done".
using ProgressFn = std::function<void(const std::string& line)>;

/// Called once the inputs are loaded and validated, before any frame is rendered; an error stops
/// the run and is returned. `tessera` creates its output folder here, so a bad input leaves no
/// folder and an unwritable folder fails before the expensive part.
using ReadyFn = std::function<Status()>;

/// Per-frame timings (milliseconds, in frame order) of one variant.
struct FrameTimes {
  std::vector<double> frame_ms;
  /// Median of `frame_ms` (mean of the middle two for an even count; 0 when empty).
  double median_ms() const;
};

}  // namespace tessera::experiments
