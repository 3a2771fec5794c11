// tessera/experiments/aa.h — the experiment of Holländer, Boubekeur & Eisemann 2013 (Table 1
// and Figures 6a, 7, 8) as one library call: `run_aa` shades an enlarged m x m G-buffer four
// ways (1 sample per pixel, the same plus FXAA 3.11, every sample = the reference, adaptive)
// plus the engine baseline (edge pixels at every sample), alternated per frame, and the two
// one-metric ablations. The frames come from an `AaBackend` (aa_backend.h): the CPU, OpenGL, or
// both side by side (`AaConfig::backend`).
//
// It returns a plain result struct (timings with every per-frame sample, qualities, images) and
// prints nothing: progress goes to the optional callback. Every number and image except the
// timings is identical for any thread count and from run to run. Errors come back as a
// `Status`; a GL backend without a factory is `ErrorCode::unsupported`.
// Tests: tests/unit/experiments_aa_test.cpp; tests/cli/aa_cli_test.py.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tessera/core.h"
#include "tessera/deferred.h"
#include "tessera/experiments/aa_backend.h"
#include "tessera/experiments/common.h"
#include "tessera/scene.h"

namespace tessera::experiments {

/// 8-bit sRGB quality against the same rate's reference (`metrics::compare_images`).
struct AaQuality {
  double mse = 0.0;      ///< Over RGB, 8-bit units squared.
  double psnr_db = 0.0;  ///< +infinity when identical.
  double ssim = 1.0;     ///< Mean SSIM on Rec.709 luma.
  bool identical() const;
};

struct AaConfig {
  /// The scene; nullptr = `scene::builtin_scene()`.
  std::shared_ptr<const scene::Scene> scene;
  /// The camera; unset = `scene::orbit_camera(scene, 1, 8)`.
  std::optional<scene::Camera> camera;
  std::vector<int> ssaa = {2, 3, 4};  ///< Window sizes m, each in [1, 8].
  int width = 1024, height = 768;     ///< Output pixels, each at least 1.
  int frames = 3;                     ///< Timed frames per method (medians reported).
  int lights = 8;                     ///< Extra point lights (`deferred::scene_shading`).
  bool heavy = false;                 ///< Also time the heavy per-sample shader.
  int heavy_terms = -1;               ///< Heavy sinusoids per sample; < 0 = the default.
  int fxaa_preset = 39;               ///< FXAA 3.11 quality preset.
  AdaptiveThresholds adaptive;
  deferred::EdgePerSampleOptions edge;  ///< The engine baseline's classification.
  int threads = 0;                      ///< Worker threads (0 = all); results do not depend on it.
  /// Who renders: the CPU; OpenGL through `gl_factory` or Vulkan through `vk_factory` (its own
  /// G-buffer and reference; times are host wall times to glFinish / the fence, the GPU timer
  /// beside them; every method is called once untimed per rate first, so shader compilation
  /// is not timed); or both: the CPU result plus
  /// the whole experiment on GL (`AaResult::gl`), GL's adaptive image and k map compared with
  /// the CPU's per rate (`AaRateResult::gl_vs_cpu`).
  Backend backend = Backend::cpu;
  /// Makes the GL backend (gl and both); unset: those fail with unsupported ("not built with
  /// the OpenGL runtime"). Called, and every G-buffer size checked, before `on_ready`.
  std::shared_ptr<const GpuBackendFactory> gl_factory;
  /// Makes the Vulkan backend (vk), as `gl_factory` does for GL (times: GPU timestamps, and
  /// host time from submission to the fence). Its `device_status()` is checked at the end.
  std::shared_ptr<const GpuBackendFactory> vk_factory;
  ProgressFn progress;  ///< Optional: one line per rate.
  ReadyFn on_ready;     ///< Optional.
};

/// Timings of one method (shading pass, plus FXAA where it applies; ms per frame).
struct AaTiming {
  FrameTimes normal;
  FrameTimes heavy;  ///< Empty unless `AaConfig::heavy`.
  /// GL: GL_TIME_ELAPSED sums of the same frames (`normal`, `heavy` are then wall times to
  /// glFinish); empty on the CPU.
  FrameTimes gpu, gpu_heavy;
};

/// Per-pass times of one method over the frames (normal shading).
struct AaPassFrames {
  std::string pass;
  FrameTimes wall, gpu;  ///< `gpu` empty on the CPU.
};

struct AaMethodResult {
  AaMethod method = AaMethod::default_1spp;
  AaTiming timing;
  ImageRGBA8 image;                  ///< Last frame, 8-bit sRGB.
  ImageRGBA8 image_heavy;            ///< Heavy mode only.
  AaQuality quality;                 ///< vs the reference (the reference: vs itself).
  double samples_pct = 0;            ///< Shaded samples, percent of the reference's.
  std::vector<AaPassFrames> passes;  ///< The backend's passes, in order.
};

/// `Backend::both`, per rate: GL's adaptive result against the CPU's (last frame).
struct AaGlVsCpu {
  double psnr_db = 0.0;              ///< 8-bit sRGB RGB PSNR; +infinity when identical.
  double k_mismatch_fraction = 0.0;  ///< Pixels whose shaded-sample count differs.
};

/// One metric only (Figure 8): the adaptive method with the other metric switched off.
struct AaAblation {
  ImageRGBA8 image;
  std::vector<std::uint8_t> samples;  ///< Samples shaded per pixel.
  double samples_pct = 0;
  AaQuality quality;
};

struct AaRateResult {
  int m = 1;
  FrameTimes gbuffer;      ///< The shared G-buffer pass (GL: wall time to glFinish).
  FrameTimes gbuffer_gpu;  ///< GL: its GL_TIME_ELAPSED; empty on the CPU.
  std::array<AaMethodResult, kAaMethods.size()> methods;  ///< Indexed by `AaMethod`.
  std::vector<std::uint8_t> adaptive_samples;  ///< Samples shaded per pixel (last frame).
  std::vector<std::uint8_t> edge_samples;      ///< edge_per_sample: 1 or m^2 per pixel.
  std::optional<AaGlVsCpu> gl_vs_cpu;          ///< `Backend::both` only.
  FrameTimes adaptive_first, adaptive_metric, adaptive_rest;  ///< The adaptive passes.
  double adaptive_extra_albedo_lookups_pct = 0;               ///< Per pixel.
  AaQuality adaptive_heavy_quality;  ///< Heavy adaptive vs heavy reference.
  double adaptive_heavy_samples_pct = 0;
  AaAblation ablation_geometry, ablation_shading;

  AaMethodResult& method(AaMethod k) { return methods[std::size_t(k)]; }
  const AaMethodResult& method(AaMethod k) const { return methods[std::size_t(k)]; }
};

struct AaResult {
  Backend backend = Backend::cpu;         ///< Who rendered `rates`; both: the CPU, `gl` beside.
  std::string gpu_renderer, gpu_version;  ///< The GPU device where one was used.
  /// `Backend::both`: the whole experiment on GL (its own G-buffers and reference); else null.
  std::shared_ptr<const AaResult> gl;
  int threads = 0;         ///< Worker threads used (0 resolved).
  int heavy_terms = 0;     ///< Resolved.
  std::size_t lights = 0;  ///< Point lights in total.
  /// The paper's 1x1 rows: a w x h G-buffer, one sample per pixel, and FXAA on it.
  FrameTimes gbuffer_1x1;
  FrameTimes gbuffer_1x1_gpu;  ///< GL only.
  AaTiming default_1x1, fxaa_1x1;
  std::vector<AaRateResult> rates;  ///< In the order of `AaConfig::ssaa`.
};

/// Runs the adaptive-supersampling experiment. Fails with invalid_argument on a bad
/// configuration, unsupported for GL without a factory, the factory's error (no EGL device,
/// missing shaders) or too_large for a G-buffer beyond the GL device's limits; all of these
/// before `on_ready`.
Result<AaResult> run_aa(const AaConfig& config);

// ---------------------------------------------------------------------------------------------
// Results as files (aa.json, aa.md and the images beside them)
// ---------------------------------------------------------------------------------------------

struct AaReportOptions {
  std::string scene_label = "builtin";  ///< Names the scene in both reports (or its path).
};

/// One image of a rate's figures as `tessera aa` writes it: `name` is the file stem without
/// the backend prefix ("gl-" for Backend::both's GL side) and ".png", e.g. "adaptive-2x2".
struct AaRateImage {
  std::string name;
  bool edge_per_sample = false;  ///< Listed under the engine baseline in the JSON.
  ImageRGBA8 image;              ///< Empty when only the names were asked for.
};

/// The images of one rate: reference, adaptive, 1 spp, FXAA, samples maps (inferno, 0..m²),
/// difference heatmaps against the reference and 1 spp (32 levels saturate), the ablations and
/// the engine baseline. `pixels` false: the names only. Besides these, the reports name two
/// colour bars, "samples-colourbar-MxM.svg" (prefixed) and "diff-colourbar.svg".
Result<std::vector<AaRateImage>> aa_rate_images(const AaConfig& config, const AaRateResult& rate,
                                                bool pixels = true);

/// aa.json of `result`, the outcome of `config` (two-space indentation, no final newline): the
/// configuration, the 1x1 rows, and per rate every method's times, quality and samples, the
/// ablations and the images; with Backend::gl / vk the device ("backend", "gpu_renderer",
/// "gpu_version") and GPU-timer and per-pass times, with both GL's side under "gl" and
/// "gl_vs_cpu". Deterministic except for the times.
Result<std::string> to_json(const AaConfig& config, const AaResult& result,
                            const AaReportOptions& options = {});
/// aa.md of `result`: Table 1 with our columns and the Figure 6a/7/8 blocks, which show the
/// images of `aa_rate_images` from the same folder.
Result<std::string> to_markdown(const AaConfig& config, const AaResult& result,
                                const AaReportOptions& options = {});

}  // namespace tessera::experiments
