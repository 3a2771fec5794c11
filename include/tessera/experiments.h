// tessera/experiments.h — the two paper experiments as library calls.
//
//  * `run_seams`: Toth 2013, Table 1 and Figure 5. Clamp, Discard, Traverse and Traverse+corners
//    per-face texturing at every MSAA rate along a camera orbit, timed side by side (the order
//    of the variants rotates per frame), each compared against the reference (Traverse at
//    f x f the resolution, Mitchell-Netravali downsampled) with the Figure-5 error CDF of
//    metrics.h over the geometry pixels of the quality frames.
//  * `run_aa`: Holländer, Boubekeur & Eisemann 2013, Table 1 and Figures 6a, 7, 8. An enlarged
//    m x m G-buffer shaded four ways (1 sample per pixel, the same plus FXAA 3.11, every sample
//    = the reference, adaptive), alternated per frame, plus the two one-metric ablations.
//
// Both return plain result structs (timings with every per-frame sample, error statistics,
// images) and print nothing: progress goes to the optional `progress` callback, and writing
// JSON, Markdown, plots and PNGs is the caller's business (`tessera seams` / `tessera aa`).
// Methods are named by enums, never by position.
//
// Determinism: every number and image except the timings is identical for any thread count
// and from run to run. Errors come back as a `Status` (no exceptions); a backend that is not
// available gives `ErrorCode::unsupported`. Each call is independent; the callbacks are called
// on the calling thread.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tessera/core.h"
#include "tessera/deferred.h"
#include "tessera/faces.h"
#include "tessera/scene.h"

namespace tessera::experiments {

/// Where the frames are rendered. Only `cpu` is implemented; `gl` (the OpenGL runtime) returns
/// an `unsupported` error until it is wired in.
enum class Backend { cpu, gl };

/// "cpu", "gl".
const char* backend_name(Backend backend);

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

/// Median of `values` (mean of the middle two for an even count; 0 when empty).
double median(std::vector<double> values);

// ---------------------------------------------------------------------------------------------
// Seams (Toth 2013)
// ---------------------------------------------------------------------------------------------

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
  Backend backend = Backend::cpu;
  bool keep_images = true;  ///< Fill the frame-0 images of the result (else left empty).
  /// Near-seam errors count the geometry pixels within this many pixels (Chebyshev distance)
  /// of a pixel showing another face: where the seam methods differ. 0 = off.
  int near_seam_pixels = 2;
  ProgressFn progress;      ///< Optional.
  ReadyFn on_ready;         ///< Optional.
};

/// One method at one rate.
struct SeamsMethodResult {
  faces::Method method = faces::Method::clamp;
  FrameTimes timing;  ///< Raster + shading + resolve per frame.
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
  std::array<SeamsMethodResult, 4> methods;  ///< Indexed by `faces::Method`; use `method()`.
  FrameTimes shading_only;                   ///< The same pass without the texture lookup.
  ErrorStats traverse_vs_discard;            ///< Figure 5 left.
  /// Discard without the zero-coverage clamp fallback, frame 0: pixels with a NaN colour.
  std::uint64_t nan_pixels_without_fallback = 0;

  SeamsMethodResult& method(faces::Method m) { return methods[std::size_t(m)]; }
  const SeamsMethodResult& method(faces::Method m) const { return methods[std::size_t(m)]; }
};

struct SeamsResult {
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
/// for a backend other than cpu, or with the loader's error for a bad mesh or Ptex file.
Result<SeamsResult> run_seams(const SeamsConfig& config);

// ---------------------------------------------------------------------------------------------
// Adaptive supersampling (Holländer et al. 2013)
// ---------------------------------------------------------------------------------------------

/// The four shading methods of a rate.
enum class AaMethod {
  default_1spp,  ///< One sample per pixel (plain deferred shading), "default".
  fxaa,          ///< The same plus FXAA 3.11.
  reference,     ///< Every sample of the m x m window.
  adaptive,      ///< The paper's method.
};
inline constexpr std::array<AaMethod, 4> kAaMethods = {AaMethod::default_1spp, AaMethod::fxaa,
                                                       AaMethod::reference, AaMethod::adaptive};
/// "default", "fxaa", "reference", "adaptive" (the JSON keys of `tessera aa`).
const char* aa_method_name(AaMethod method);

/// 8-bit sRGB quality against the same rate's reference (`compare_images`).
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
  deferred::AdaptiveOptions adaptive;
  int threads = 0;  ///< Worker threads (0 = all); results do not depend on it.
  Backend backend = Backend::cpu;
  ProgressFn progress;  ///< Optional: one line per rate.
  ReadyFn on_ready;     ///< Optional.
};

/// Timings of one method (shading pass, plus FXAA where it applies; ms per frame).
struct AaTiming {
  FrameTimes normal;
  FrameTimes heavy;  ///< Empty unless `AaConfig::heavy`.
};

struct AaMethodResult {
  AaMethod method = AaMethod::default_1spp;
  AaTiming timing;
  ImageRGBA8 image;        ///< Last frame, 8-bit sRGB.
  ImageRGBA8 image_heavy;  ///< Heavy mode only.
  AaQuality quality;       ///< vs the reference (the reference: vs itself).
  double samples_pct = 0;  ///< Shaded samples, percent of the reference's.
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
  FrameTimes gbuffer;                          ///< The shared G-buffer pass.
  std::array<AaMethodResult, 4> methods;       ///< Indexed by `AaMethod`; use `method()`.
  std::vector<std::uint8_t> adaptive_samples;  ///< Samples shaded per pixel (last frame).
  FrameTimes adaptive_first, adaptive_metric, adaptive_rest;  ///< The adaptive passes.
  double adaptive_extra_albedo_lookups_pct = 0;               ///< Per pixel.
  AaQuality adaptive_heavy_quality;  ///< Heavy adaptive vs heavy reference.
  double adaptive_heavy_samples_pct = 0;
  AaAblation ablation_geometry, ablation_shading;

  AaMethodResult& method(AaMethod k) { return methods[std::size_t(k)]; }
  const AaMethodResult& method(AaMethod k) const { return methods[std::size_t(k)]; }
};

struct AaResult {
  int threads = 0;         ///< Worker threads used (0 resolved).
  int heavy_terms = 0;     ///< Resolved.
  std::size_t lights = 0;  ///< Point lights in total.
  /// The paper's 1x1 rows: a w x h G-buffer, one sample per pixel, and FXAA on it.
  FrameTimes gbuffer_1x1;
  AaTiming default_1x1, fxaa_1x1;
  std::vector<AaRateResult> rates;  ///< In the order of `AaConfig::ssaa`.
};

/// Runs the adaptive-supersampling experiment. Fails with invalid_argument on a bad
/// configuration, unsupported for a backend other than cpu.
Result<AaResult> run_aa(const AaConfig& config);

}  // namespace tessera::experiments
