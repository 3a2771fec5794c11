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
#include <span>
#include <string>
#include <vector>

#include "tessera/core.h"
#include "tessera/deferred.h"
#include "tessera/faces.h"
#include "tessera/scene.h"

namespace tessera::experiments {

/// Where the frames are rendered: the CPU renderers, or the OpenGL runtime through the config's
/// GL factory (set by callers linked with tessera::gl; without one, `gl` is an `unsupported`
/// error). `compare_gl` in the configs runs both and compares them.
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

/// One frame as a seam-experiment backend renders it (the options `run_seams` varies).
struct SeamsFrameOptions {
  int width = 480, height = 540;
  int msaa = 1;
  faces::Method method = faces::Method::discard;
  texture::TextureFilter filter = texture::TextureFilter::anisotropic;
  int max_aniso = 16;
  bool clamp_fallback = true;  ///< Discard's zero-coverage fallback (off: NaN where Σw = 0).
  /// The same pass without the texture lookup (only where `has_shading_only()`).
  bool shading_only = false;
  /// false: the caller needs only the times (a GPU backend may skip the read-back and return
  /// an empty image).
  bool keep_image = true;
  int threads = 0;  ///< CPU worker threads (0 = all).
  /// Explicit sample positions (faces::FaceRenderOptions::sample_pattern: `msaa` offsets in
  /// 1/16 pixel, each in [-8, 7]); empty = the standard pattern of `msaa`. Only the CPU draws
  /// them: `run_seams` asks for them for the CPU frame that a GL frame is compared with when the
  /// driver's positions are no standard pattern. A GL backend refuses them (unsupported): its
  /// positions are the driver's.
  std::vector<raster::SampleOffset> sample_pattern;
};

/// A rendered frame of a seam-experiment backend.
struct SeamsBackendFrame {
  ImageRGBAF image;  ///< Resolved linear RGB, alpha = coverage; top-down.
  /// The frame time of Table 1: CPU raster + shading + resolve; GL: GL_TIME_ELAPSED of the
  /// draws and the resolve.
  double ms = 0;
  /// Wall time of the frame (GL: first call to glFinish, read-back excluded; CPU: = ms).
  double wall_ms = 0;
};

/// The samples a backend draws for an MSAA rate.
struct SeamsSamplePattern {
  int msaa = 1;      ///< The rate asked for.
  int samples = 1;   ///< Samples per pixel drawn (GL: GL_SAMPLES; a driver may round up).
  /// The CPU rasteriser's rate with the same sample positions (raster::sample_positions), 0
  /// when none has them. Like-for-like GL-vs-CPU comparisons render the CPU at this rate.
  int cpu_msaa = 1;
  /// Where the `samples` samples are, in sample-index order: offsets from the pixel centre in
  /// 1/16 pixel, x right, y down in the image (raster::SampleOffset). Empty when not known or
  /// not on that grid (a GL driver's positions more than 1e-3 pixel off it, or more than 16
  /// samples: gl::cpu_sample_offsets): then no CPU frame can be drawn at them. Where
  /// `cpu_msaa` is 0, a comparison draws the CPU frame at these positions
  /// (`seams_gl_comparison`).
  std::vector<raster::SampleOffset> positions;
};

/// What `run_seams` compares a GL rate's frames with (`SeamsConfig::compare_gl`).
enum class SeamsGlComparison {
  /// The CPU frame at `SeamsSamplePattern::cpu_msaa`, whose standard pattern has the driver's
  /// positions (another, untimed CPU render where that is not the rate itself).
  cpu_rate,
  /// A CPU frame (untimed) drawn at the driver's own positions (`SeamsSamplePattern::
  /// positions`, as many samples as it has): no standard pattern has them.
  driver_positions,
  /// Not compared: no standard pattern has the driver's positions and they are not known on
  /// the CPU's 1/16-pixel grid, so no CPU frame would be like for like.
  none,
};

/// The rule of `run_seams` (and bench/seams_gl_table1): `cpu_rate` where `cpu_msaa` > 0, else
/// `driver_positions` where `positions` holds `samples` (1..16) offsets in [-8, 7], else `none`.
SeamsGlComparison seams_gl_comparison(const SeamsSamplePattern& pattern);

/// A renderer of the seam experiment's frames: the CPU (`create_cpu_seams_renderer`, wrapping
/// faces::FaceRenderer) or OpenGL (`create_gl_seams_renderer`, wrapping gl::SeamsRenderer).
/// Used on the calling thread only.
class SeamsFrameRenderer {
 public:
  virtual ~SeamsFrameRenderer() = default;
  virtual Backend backend() const = 0;
  /// GL_RENDERER and GL_VERSION of a GL backend; "" for the CPU.
  virtual std::string device_name() const = 0;
  virtual std::string device_version() const = 0;
  /// Whether frames with `samples` MSAA samples can be rendered (a GL driver may refuse some).
  virtual bool msaa_supported(int samples) = 0;
  /// Whether `SeamsFrameOptions::shading_only` is implemented.
  virtual bool has_shading_only() const = 0;
  /// What frames at `msaa` are drawn with (the CPU: exactly `msaa`, at the standard positions;
  /// GL: what the driver allocates, e.g. Mesa llvmpipe draws 2x with its 4x samples). Only for
  /// supported rates.
  virtual SeamsSamplePattern sample_pattern(int msaa) {
    const std::span<const raster::SampleOffset> standard = raster::sample_positions(msaa);
    return {msaa, msaa, msaa, {standard.begin(), standard.end()}};
  }
  virtual Result<SeamsBackendFrame> render(const scene::Camera& camera,
                                           const SeamsFrameOptions& options) = 0;
  /// The paper's reference: Traverse (16x anisotropic by default) at factor x factor the
  /// resolution, Mitchell-Netravali downsampled (faces::FaceRenderer::render_reference and its
  /// GL twin, which take the same options).
  virtual Result<ImageRGBAF> render_reference(const scene::Camera& camera, int width, int height,
                                              const faces::ReferenceOptions& options) = 0;
};

/// The CPU backend (faces::FaceRenderer). `scene` and `textures` must outlive it.
Result<std::unique_ptr<SeamsFrameRenderer>> create_cpu_seams_renderer(
    const faces::FaceScene& scene, const faces::FaceTextureSet& textures);

/// The OpenGL backend (gl::SeamsRenderer on a headless context of its own, created on the
/// calling thread with the device TESSERA_EGL_DEVICE names). Defined in the `tessera_gl` library
/// (src/gl/seams_backend.cpp), not in `tessera`: only programs linking tessera_gl may call it.
/// `glsl_dir`: the folder of seams_render.vert/.frag (empty: gl::SeamsRendererOptions' search).
/// Fails (unsupported) with one line when there is no usable OpenGL 4.5 device.
Result<std::unique_ptr<SeamsFrameRenderer>> create_gl_seams_renderer(
    const faces::FaceScene& scene, const faces::FaceTextureSet& textures,
    const std::string& glsl_dir);

/// Makes the GL backend for a scene (`SeamsConfig::gl_renderer_factory`).
using SeamsRendererFactory = std::function<Result<std::unique_ptr<SeamsFrameRenderer>>(
    const faces::FaceScene&, const faces::FaceTextureSet&)>;

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
  /// Who renders the frames of `rates`: the CPU, or OpenGL through `gl_renderer_factory` (then
  /// MSAA rates the driver refuses are skipped and listed in `SeamsResult::msaa_unsupported`;
  /// the reference is the GL one; face ids and the character mask come from the CPU renderer,
  /// the geometry being the same).
  Backend backend = Backend::cpu;
  /// With backend cpu: also render every frame, rate and method with the GL backend
  /// (`SeamsResult::gl_rates`: GL times and GL-vs-CPU agreement; `tessera seams --backend both`).
  bool compare_gl = false;
  /// Makes the GL backend; unset: `Backend::gl` and `compare_gl` fail with unsupported ("not
  /// built with the OpenGL runtime"). Called before `on_ready`.
  SeamsRendererFactory gl_renderer_factory;
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
  std::array<SeamsMethodResult, 4> methods;  ///< Indexed by `faces::Method`; use `method()`.
  /// The same pass without the texture lookup (empty where the backend has none: GL).
  FrameTimes shading_only;
  ErrorStats traverse_vs_discard;            ///< Figure 5 left.
  /// Discard without the zero-coverage clamp fallback, frame 0: pixels with a NaN colour.
  std::uint64_t nan_pixels_without_fallback = 0;

  SeamsMethodResult& method(faces::Method m) { return methods[std::size_t(m)]; }
  const SeamsMethodResult& method(faces::Method m) const { return methods[std::size_t(m)]; }
};

/// One method at one rate rendered by GL beside the CPU (`SeamsConfig::compare_gl`).
struct SeamsGlMethodResult {
  faces::Method method = faces::Method::clamp;
  FrameTimes gpu;   ///< GL_TIME_ELAPSED per frame (draws + resolve).
  FrameTimes wall;  ///< Wall time per frame to glFinish.
  /// GL against the CPU frame, pooled over the quality frames: PSNR of the 8-bit sRGB outputs
  /// (from the mean MSE; +infinity when identical) and the fraction of pixels whose linear-RGB
  /// 2-norm difference is >= 0.01 (NaN counts as different); all pixels of the frame.
  double psnr_db = 0;
  double fraction_ge_001 = 0;
};

struct SeamsGlRateResult {
  int msaa = 1;
  /// What the GL frames were compared with (`seams_gl_comparison` of the rate's pattern). With
  /// `none` the GL frames are still drawn and timed, and every method's `psnr_db` and
  /// `fraction_ge_001` are NaN (not measured).
  SeamsGlComparison compared_with = SeamsGlComparison::cpu_rate;
  std::array<SeamsGlMethodResult, 4> methods;  ///< Indexed by `faces::Method`.
  const SeamsGlMethodResult& method(faces::Method m) const { return methods[std::size_t(m)]; }
};

struct SeamsResult {
  // The backend.
  Backend backend = Backend::cpu;  ///< Who rendered `rates`.
  bool compared_gl = false;        ///< `gl_rates` filled (SeamsConfig::compare_gl).
  /// GL_RENDERER and GL_VERSION where GL was used.
  std::string gl_renderer, gl_version;
  /// Requested MSAA rates the GL driver refuses: skipped (not in `rates` for backend gl, not
  /// in `gl_rates` with compare_gl).
  std::vector<int> msaa_unsupported;
  std::vector<SeamsGlRateResult> gl_rates;  ///< compare_gl: the GL side, per rate GL renders.
  /// Where GL was used: per rate GL renders (in `SeamsConfig::msaa` order), the samples it
  /// draws. With compare_gl, a GL frame is compared with the CPU frame at `cpu_msaa` (another
  /// CPU render, untimed, where that is not the rate itself); where `cpu_msaa` is 0 (no CPU
  /// pattern has the driver's positions), with a CPU frame drawn at the driver's `positions`,
  /// or not at all when those are unknown (`SeamsGlRateResult::compared_with`).
  std::vector<SeamsSamplePattern> gl_sample_patterns;
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
// Adaptive supersampling (Holländer et al. 2013)
// ---------------------------------------------------------------------------------------------

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

/// Times of one pass of an AA backend (ms).
struct AaPassTime {
  std::string pass;
  double wall_ms = 0.0;  ///< Host time (GL: from the dispatch to the end of a closing glFinish).
  double gpu_ms = 0.0;   ///< GL_TIME_ELAPSED (GL only; NaN on the CPU and where the driver's
                         ///< result is impossible; Mesa 22.3 llvmpipe reads 0 for compute).
};

/// One shading call of an AA backend.
struct AaShadeOutput {
  ImageRGBA8 image;                   ///< 8-bit sRGB, w x h.
  std::vector<std::uint8_t> samples;  ///< adaptive, edge_per_sample: shaded samples per pixel.
  std::uint64_t samples_shaded = 0;   ///< Sum of `samples` (adaptive, edge_per_sample).
  std::uint64_t extra_lookups = 0;    ///< CPU adaptive: albedo re-lookups of first samples.
  /// The method's time: CPU = the whole call (shading, sRGB encoding, FXAA); GL = the sum of
  /// the passes' wall times (read-back excluded).
  double wall_ms = 0.0;
  double gpu_ms = 0.0;             ///< GL: sum of the passes' GL_TIME_ELAPSED; CPU: NaN.
  std::vector<AaPassTime> passes;  ///< In order; adaptive: "first", "metrics", "extra".
};

/// What an AA backend shades with besides the method.
struct AaShadeOptions {
  deferred::AdaptiveOptions adaptive;
  deferred::FxaaOptions fxaa;
  deferred::EdgePerSampleOptions edge;
};

/// A renderer of the AA experiment at one scene: the CPU (`create_cpu_aa_backend`, wrapping
/// deferred::DeferredRenderer) or OpenGL (`create_gl_aa_backend`, wrapping
/// gl::DeferredGlRenderer). It keeps the last G-buffer; `shade` works on it. Used on the
/// calling thread only.
class AaBackend {
 public:
  virtual ~AaBackend() = default;
  virtual Backend backend() const = 0;
  /// GL_RENDERER and GL_VERSION of a GL backend; "" for the CPU.
  virtual std::string device_name() const = 0;
  virtual std::string device_version() const = 0;
  /// Whether a (m*width) x (m*height) G-buffer fits the device, checked without allocating
  /// (GL: the framebuffer and texture limits; too_large naming the limit).
  virtual Status check_size(int width, int height, int m) const = 0;
  /// The geometry pass into the enlarged G-buffer; its time (pass "gbuffer").
  virtual Result<AaPassTime> render_gbuffer(const scene::Camera& camera, int width, int height,
                                            int m) = 0;
  /// Shades the last G-buffer with `method`.
  virtual Result<AaShadeOutput> shade(AaMethod method, const deferred::ShadingOptions& shading,
                                      const AaShadeOptions& options) = 0;
};

/// The CPU backend (deferred::DeferredRenderer with `parallel.threads` workers, 0 = all).
/// `scene` must outlive it.
Result<std::unique_ptr<AaBackend>> create_cpu_aa_backend(const scene::Scene& scene,
                                                         const Parallel& parallel = {});

/// The OpenGL backend (gl::DeferredGlRenderer on a headless context of its own, created on the
/// calling thread with the device TESSERA_EGL_DEVICE names). Defined in the `tessera_gl` library
/// (src/gl/aa_backend.cpp), not in `tessera`: only programs linking tessera_gl may call it.
/// `glsl_dir`: share/tessera/glsl (empty: gl::DeferredGlOptions' search). Fails with one line
/// when there is no usable OpenGL 4.5 device or the shaders are missing.
Result<std::unique_ptr<AaBackend>> create_gl_aa_backend(const scene::Scene& scene,
                                                        const std::string& glsl_dir);

/// Makes the GL backend for a scene (`AaConfig::gl_backend_factory`).
using AaBackendFactory =
    std::function<Result<std::unique_ptr<AaBackend>>(const scene::Scene& scene)>;

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
  deferred::AdaptiveOptions adaptive;
  deferred::EdgePerSampleOptions edge;  ///< The engine baseline's classification.
  int threads = 0;  ///< Worker threads (0 = all); results do not depend on it.
  /// Who renders: the CPU, or OpenGL through `gl_backend_factory` (its own G-buffer and
  /// reference; times are wall times to glFinish, GL_TIME_ELAPSED beside them; every method is
  /// called once untimed per rate first, so shader compilation is not timed).
  Backend backend = Backend::cpu;
  /// With backend cpu: also run the whole experiment on GL (`AaResult::gl`) and compare GL's
  /// adaptive image and k map with the CPU's per rate (`AaRateResult::gl_vs_cpu`).
  bool compare_gl = false;
  /// Makes the GL backend; unset: `Backend::gl` and `compare_gl` fail with unsupported ("not
  /// built with the OpenGL runtime"). Called, and every G-buffer size checked, before `on_ready`.
  AaBackendFactory gl_backend_factory;
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
  ImageRGBA8 image;        ///< Last frame, 8-bit sRGB.
  ImageRGBA8 image_heavy;  ///< Heavy mode only.
  AaQuality quality;       ///< vs the reference (the reference: vs itself).
  double samples_pct = 0;  ///< Shaded samples, percent of the reference's.
  std::vector<AaPassFrames> passes;  ///< The backend's passes, in order.
};

/// `compare_gl`, per rate: GL's adaptive result against the CPU's (last frame).
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
  std::optional<AaGlVsCpu> gl_vs_cpu;          ///< `compare_gl` only.
  FrameTimes adaptive_first, adaptive_metric, adaptive_rest;  ///< The adaptive passes.
  double adaptive_extra_albedo_lookups_pct = 0;               ///< Per pixel.
  AaQuality adaptive_heavy_quality;  ///< Heavy adaptive vs heavy reference.
  double adaptive_heavy_samples_pct = 0;
  AaAblation ablation_geometry, ablation_shading;

  AaMethodResult& method(AaMethod k) { return methods[std::size_t(k)]; }
  const AaMethodResult& method(AaMethod k) const { return methods[std::size_t(k)]; }
};

struct AaResult {
  Backend backend = Backend::cpu;       ///< Who rendered `rates`.
  std::string gl_renderer, gl_version;  ///< GL_RENDERER, GL_VERSION where GL was used.
  /// `compare_gl`: the whole experiment on GL (its own G-buffers and reference); else null.
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

}  // namespace tessera::experiments
