// tessera/experiments/seams.h — the seam experiment of Toth 2013 (Table 1 and Figure 5) as one
// library call: `run_seams` renders Clamp, Discard, Traverse and Traverse+corners per-face
// texturing at every MSAA rate along a camera orbit, timed side by side (the order of the
// variants rotates per frame and repetition), each compared against the reference (Traverse at
// f x f the resolution, Mitchell-Netravali downsampled) with the Figure-5 error CDF of metrics.h
// over the geometry pixels of the quality frames. The frames come from a `SeamsBackend`
// (seams_backend.h): the CPU, OpenGL, or both side by side (`SeamsConfig::backend`).
//
// It returns a plain result struct (timings with every per-frame sample, error statistics,
// images) and prints nothing: progress goes to the optional callback. Every number and image
// except the timings is identical for any thread count and from run to run. Errors come back as
// a `Status`; a GL backend without a factory is `ErrorCode::unsupported`.
// Tests: tests/unit/experiments_seams_options_test.cpp; tests/cli/seams_cli_test.py.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tessera/core.h"
#include "tessera/experiments/common.h"
#include "tessera/experiments/seams_backend.h"
#include "tessera/faces.h"

namespace tessera::experiments {

/// Figure-5 CDF thresholds: 0, 0.001, ..., 0.3 on the linear-RGB 2-norm.
inline constexpr int kSeamsCdfBins = 301;
inline constexpr double kSeamsCdfStep = 0.001;

/// Error statistics of one comparison over the counted pixels of every quality frame.
struct ErrorStats {
  std::vector<double> cdf;  ///< cdf[i]: fraction with error >= i * kSeamsCdfStep.
  double mean = 0.0;        ///< Mean linear-RGB 2-norm.
  std::uint64_t counted = 0;
  /// The CDF at threshold x (rounded to the nearest bin; x in [0, 0.3]).
  double at(double x) const;
};

struct SeamsConfig {
  std::string scene = "figure1";         ///< "figure1" (built in) or a quad (or polygon) .obj.
  std::string ptex;                      ///< Optional .ptx for the .obj (else procedural textures).
  std::string character;                 ///< figure1: an .obj replacing the cube-sphere character.
  int subdivide = 1;                     ///< Linear subdivision steps applied to `character`.
  std::vector<int> msaa = {1, 2, 4, 8};  ///< MSAA rates, each in 1, 2, 4, 8, 16.
  int frames = 8;                        ///< Orbit frames (timed; up to quality_frames compared).
  int quality_frames = 0;         ///< Frames with a reference, spread over the orbit (0 = all).
  int width = 480, height = 540;  ///< The paper's image size; each at least 8.
  int reference_factor = 8;       ///< Reference at factor x factor the resolution.
  faces::Figure1Options figure1;  ///< The built-in scene's parameters.
  int threads = 0;                ///< Worker threads (0 = all); results do not depend on it.
  /// Who renders: the CPU; OpenGL through `gl_factory` or Vulkan through `vk_factory` (then
  /// MSAA rates the driver refuses are skipped and listed in `SeamsResult::msaa_unsupported`;
  /// the reference is the GPU one; face ids and the character mask come from the CPU renderer,
  /// the geometry being the same); or both: the CPU result plus every frame, rate and method on
  /// GL (`SeamsResult::gl_rates`: GL times and GL-vs-CPU agreement).
  Backend backend = Backend::cpu;
  /// Makes the GL backend (gl and both); unset: those fail with unsupported ("not built with
  /// the OpenGL runtime"). Called before `on_ready`.
  std::shared_ptr<const GpuBackendFactory> gl_factory;
  /// Makes the Vulkan backend (vk); unset: vk fails with unsupported ("not built with the
  /// Vulkan runtime"). Its `device_status()` (validation messages) is checked at the end.
  std::shared_ptr<const GpuBackendFactory> vk_factory;
  /// The texture filter of the experiment's frames (every method, every backend; 16x
  /// anisotropic is the paper's). The reference stays the paper's: Traverse, 16x anisotropic.
  texture::TextureFilter filter = texture::TextureFilter::anisotropic;
  /// Timed renders of each frame, rate and method (>= 1): every one is a sample of the
  /// `FrameTimes`, and the order of the methods rotates with the repetition as with the frame.
  /// Images and statistics come from the first; they do not depend on the count.
  int repetitions = 1;
  /// Backend::both only: false = the CPU renders only the quality frames, untimed (its
  /// `FrameTimes` and `shading_only` stay empty), for what the statistics and the GL-vs-CPU
  /// agreement need; GL is timed on every frame as always. For GL timings without the cost of
  /// the CPU's (bench/seams_gl_table1.cpp).
  bool time_cpu = true;
  /// Backend::both only: also render the reference on GL on every quality frame and compare it
  /// with the CPU's (`SeamsResult::gl_reference_vs_cpu`).
  bool compare_references = false;
  bool keep_images = true;  ///< Fill the frame-0 images of the result (else left empty).
  /// Near-seam errors count the geometry pixels within this many pixels (Chebyshev distance)
  /// of a pixel showing another face: where the seam methods differ. 0 = off.
  int near_seam_pixels = 2;
  ProgressFn progress;  ///< Optional.
  ReadyFn on_ready;     ///< Optional.
};

/// One method at one rate.
struct SeamsMethodResult {
  faces::SeamMethod method = faces::SeamMethod::clamp;
  FrameTimes timing;  ///< Raster + shading + resolve per frame (GL: the GPU timer).
  FrameTimes wall;    ///< GL: wall time per frame to glFinish (empty on the CPU: = timing).
  ErrorStats vs_reference;
  /// The same counting only character pixels (Figure-1 scenes with a character; else empty):
  /// pixels with at least half of 8 MSAA samples on a character face.
  ErrorStats vs_reference_character;
  /// The same counting only pixels near a face edge (`SeamsConfig::near_seam_pixels`).
  ErrorStats vs_reference_near_seams;
  ImageRGBAF frame0;  ///< Frame 0, linear RGB with coverage alpha (when keep_images).
};

/// Everything measured at one MSAA rate.
struct SeamsRateResult {
  int msaa = 1;
  std::array<SeamsMethodResult, 4> methods;  ///< Indexed by `faces::SeamMethod`; use `method()`.
  /// The same pass without the texture lookup (empty where the backend has none: GL).
  FrameTimes shading_only;
  ErrorStats traverse_vs_discard;  ///< Figure 5 left.
  /// Discard without the zero-coverage clamp fallback, frame 0: pixels with a NaN colour.
  std::uint64_t nan_pixels_without_fallback = 0;

  SeamsMethodResult& method(faces::SeamMethod m) { return methods[std::size_t(m)]; }
  const SeamsMethodResult& method(faces::SeamMethod m) const { return methods[std::size_t(m)]; }
};

/// One method at one rate rendered by GL beside the CPU (`Backend::both`).
struct SeamsGlMethodResult {
  faces::SeamMethod method = faces::SeamMethod::clamp;
  FrameTimes gpu;   ///< GL_TIME_ELAPSED per frame (draws + resolve).
  FrameTimes wall;  ///< Wall time per frame to glFinish.
  /// GL against the CPU frame, pooled over the quality frames: PSNR of the 8-bit sRGB outputs
  /// (from the mean MSE; +infinity when identical) and the fraction of pixels whose linear-RGB
  /// 2-norm difference is >= 0.01 (NaN counts as different); all pixels of the frame.
  double psnr_db = 0;
  double fraction_ge_001 = 0;
  /// The same per quality frame, of the frame that agrees least: the lowest PSNR and the
  /// highest fraction (each over the frames on its own; NaN where not compared).
  double worst_psnr_db = 0;
  double worst_fraction_ge_001 = 0;
};

/// The GL reference against the CPU reference (`SeamsConfig::compare_references`), with the
/// measures of `SeamsGlMethodResult`: pooled over the quality frames, and of the worst frame.
struct SeamsReferenceAgreement {
  bool measured = false;  ///< Whether the references were compared.
  double psnr_db = 0;
  double fraction_ge_001 = 0;
  double worst_psnr_db = 0;
  double worst_fraction_ge_001 = 0;
};

struct SeamsGlRateResult {
  int msaa = 1;
  /// What the GL frames were compared with (`seams_gl_comparison` of the rate's pattern). With
  /// `none` the GL frames are still drawn and timed, and every method's `psnr_db` and
  /// `fraction_ge_001` are NaN (not measured).
  SeamsGlComparison compared_with = SeamsGlComparison::cpu_rate;
  std::array<SeamsGlMethodResult, 4> methods;  ///< Indexed by `faces::SeamMethod`.
  const SeamsGlMethodResult& method(faces::SeamMethod m) const { return methods[std::size_t(m)]; }
};

struct SeamsResult {
  // The backend.
  /// Who rendered `rates` (cpu, gl or vk); both: the CPU, with `gl_rates` filled beside it.
  Backend backend = Backend::cpu;
  /// The GPU device where one was used (BackendDevice::device_name / device_version).
  std::string gpu_renderer, gpu_version;
  /// Requested MSAA rates the GPU driver refuses: skipped (not in `rates` for backend gl / vk,
  /// not in `gl_rates` with both).
  std::vector<int> msaa_unsupported;
  std::vector<SeamsGlRateResult> gl_rates;  ///< both: the GL side, per rate GL renders.
  /// Where a GPU was used: per rate it renders (in `SeamsConfig::msaa` order), the samples it
  /// draws. With both, a GL frame is compared with the CPU frame at `cpu_msaa` (another
  /// CPU render, untimed, where that is not the rate itself); where `cpu_msaa` is 0 (no CPU
  /// pattern has the driver's positions), with a CPU frame drawn at the driver's `positions`,
  /// or not at all when those are unknown (`SeamsGlRateResult::compared_with`).
  std::vector<SeamsSamplePattern> gpu_sample_patterns;
  /// both with `compare_references`: the GL reference against the CPU's.
  SeamsReferenceAgreement gl_reference_vs_cpu;
  // The scene.
  std::string scene_description;
  int faces = 0;
  int ground_faces = 0;  ///< Figure-1 scenes: faces of the ground plane (0 for .obj scenes).
  std::uint64_t texels_level0 = 0;
  std::array<int, 16> edge_pairings{};  ///< `faces::edge_pairing_histogram`.
  int linked_corners = 0;               ///< Corners with a valence-4 diagonal face.
  bool has_character = false;           ///< Whether `vs_reference_character` is filled.
  int near_seam_pixels = 0;             ///< The distance used (0: near-seam stats not filled).
  // The run.
  int quality_frames = 0;              ///< Frames compared (quality_frames resolved).
  int threads = 0;                     ///< Worker threads used (0 resolved).
  std::vector<double> thresholds;      ///< The CDF thresholds (kSeamsCdfBins values).
  std::vector<SeamsRateResult> rates;  ///< In the order of `SeamsConfig::msaa`.
  double reference_ms_total = 0;       ///< Time spent rendering references.
  ImageRGBAF reference_frame0;         ///< Frame 0's reference (when keep_images).
};

/// Runs the seam experiment. Fails with invalid_argument on a bad configuration, unsupported
/// for GL without a factory (or the factory's error, e.g. no EGL device; also unsupported when
/// the driver refuses every rate asked for), or with the loader's error for a bad mesh or Ptex
/// file. All of these come before `on_ready`.
Result<SeamsResult> run_seams(const SeamsConfig& config);

// ---------------------------------------------------------------------------------------------
// Results as files (seams.json, seams.md)
// ---------------------------------------------------------------------------------------------

/// What the report says about the files written beside it.
struct SeamsReportOptions {
  /// The frame-0 images are written beside it (images/, `tessera seams`): the JSON gets
  /// `zoom_window`, the Markdown its Images section.
  bool images = true;
};

/// The window of frame 0 where Clamp and Traverse differ most at the first rate: 40 x 40 pixels
/// (at most the frame) on a 4-pixel grid, shown `scale` times enlarged in the zoom images. At
/// (0, 0) when the result has no frame-0 images.
struct SeamsZoomWindow {
  int x = 0, y = 0, w = 0, h = 0, scale = 4;
};
/// The zoom window of `result` (see `SeamsZoomWindow`).
SeamsZoomWindow seams_zoom_window(const SeamsConfig& config, const SeamsResult& result);

/// "4x" for MSAA rate 4: the key of a rate in the JSON (and in `tessera seams`' file names).
std::string seams_rate_key(int msaa);

/// seams.json of `result`, the outcome of `config` (one-space indentation, no final newline):
/// the configuration, the scene, Table 1's per-frame times and medians, Figure 5's CDFs and
/// summaries, and with Backend::gl / both the device, sample patterns, GL times and GL-vs-CPU
/// agreement. Deterministic except for the times. `result` must have at least one rate.
std::string to_json(const SeamsConfig& config, const SeamsResult& result,
                    const SeamsReportOptions& options = {});
/// seams.md of `result`: the same as Markdown tables with a few lines of reading.
std::string to_markdown(const SeamsConfig& config, const SeamsResult& result,
                        const SeamsReportOptions& options = {});

}  // namespace tessera::experiments
