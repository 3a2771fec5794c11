// tessera/experiments/aa_backend.h — the backend interface of the adaptive-supersampling
// experiment (Holländer, Boubekeur & Eisemann 2013): an enlarged G-buffer and the shading
// methods on it, rendered by the CPU (`create_cpu_aa_backend`, deferred::DeferredRenderer) or by
// OpenGL (gl::DeferredRenderer, made by a `GpuBackendFactory`, experiments/common.h).
// Tests: tests/unit/experiments_aa_test.cpp, tests/vk/vk_aa_backend_test.cpp.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tessera/core.h"
#include "tessera/deferred.h"
#include "tessera/experiments/common.h"
#include "tessera/scene.h"

namespace tessera::experiments {

/// The shading methods of a rate.
enum class AaMethod {
  default_1spp,     ///< One sample per pixel (plain deferred shading), "default".
  fxaa,             ///< The same plus FXAA 3.11.
  reference,        ///< Every sample of the m x m window.
  adaptive,         ///< The paper's method.
  edge_per_sample,  ///< The engine baseline: edge pixels at every sample (Lauritzen 2010).
};
inline constexpr std::array<AaMethod, 5> kAaMethods = {AaMethod::default_1spp, AaMethod::fxaa,
                                                       AaMethod::reference, AaMethod::adaptive,
                                                       AaMethod::edge_per_sample};
/// "default", "fxaa", "reference", "adaptive", "edge_per_sample" (the JSON keys of `tessera aa`).
const char* aa_method_name(AaMethod method);

/// One shading call of an AA backend.
struct AaShadeOutput {
  ImageRGBA8 image;                   ///< 8-bit sRGB, w x h.
  std::vector<std::uint8_t> samples;  ///< adaptive, edge_per_sample: shaded samples per pixel.
  std::uint64_t samples_shaded = 0;   ///< Sum of `samples` (adaptive, edge_per_sample).
  std::uint64_t extra_lookups = 0;    ///< CPU adaptive: albedo re-lookups of first samples.
  /// The method's time: CPU = the whole call (shading, sRGB encoding, FXAA); GL = the sum of
  /// the passes' wall times (read-back excluded).
  double wall_ms = 0.0;
  double gpu_ms = 0.0;           ///< GL: sum of the passes' GL_TIME_ELAPSED; CPU: NaN.
  std::vector<PassTime> passes;  ///< In order; adaptive: "first", "metrics", "extra".
};

/// What an AA backend shades with besides the method.
struct AaShadeOptions {
  AdaptiveThresholds adaptive;
  deferred::FxaaOptions fxaa;
  deferred::EdgePerSampleOptions edge;
};

/// A GPU renderer's shading call as an AA backend's output (the GL and Vulkan backends'): the
/// image as 8-bit sRGB (`threads` for the encoding), the sample counts of adaptive and
/// edge-per-sample, the passes and their sums.
AaShadeOutput aa_shade_output(AaMethod method, deferred::ShadeResult result, int threads);
/// The same for FXAA's 8-bit result.
AaShadeOutput aa_shade_output(deferred::FxaaResult result);

/// A renderer of the AA experiment at one scene: the CPU (`create_cpu_aa_backend`, wrapping
/// deferred::DeferredRenderer) or OpenGL (`GpuBackendFactory::create_aa`, wrapping
/// gl::DeferredRenderer). It keeps the last G-buffer; `shade` works on it. Used on the
/// calling thread only.
class AaBackend : public BackendDevice {
 public:
  /// Whether a (m*width) x (m*height) G-buffer fits the device, checked without allocating
  /// (GL: the framebuffer and texture limits; too_large naming the limit).
  virtual Status check_size(int width, int height, int m) const = 0;
  /// The geometry pass into the enlarged G-buffer; its time (pass "gbuffer").
  virtual Result<PassTime> render_gbuffer(const scene::Camera& camera, int width, int height,
                                          int m) = 0;
  /// Shades the last G-buffer with `method`.
  virtual Result<AaShadeOutput> shade(AaMethod method, const deferred::ShadingOptions& shading,
                                      const AaShadeOptions& options) = 0;
};

/// The CPU backend (deferred::DeferredRenderer with `parallel.threads` workers, 0 = all).
/// `scene` must outlive it.
Result<std::unique_ptr<AaBackend>> create_cpu_aa_backend(const scene::Scene& scene,
                                                         const Parallel& parallel = {});

}  // namespace tessera::experiments
