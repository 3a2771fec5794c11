// tessera/deferred.h — deferred shading with adaptive supersampling, and FXAA 3.11.
//
// What: `DeferredRenderer` rasterises a scene into an enlarged m x m G-buffer and shades each
//   pixel with 1 + k of its m^2 samples, k from the window's depth, normal and shading
//   variation (`AdaptiveThresholds`); baselines: the reference (all samples), 1 spp, FXAA 3.11,
//   edge-per-sample.
// Paper: Holländer, Boubekeur & Eisemann 2013, "Adaptive Supersampling for Deferred
//   Anti-Aliasing", JCGT 2(1): Listing 1, §3.1 (metrics), §4.1 (texture footprints).
// Where: src/deferred/; GPU twin gl::DeferredRenderer (tessera/gl_deferred.h); engine
//   component gl::AdaptiveSupersampler; the steps and footprint rules: docs/architecture.md,
//   "Adaptive supersampling, pass by pass".
// Threads: results are bit-identical for any thread count; a `DeferredRenderer` is not
//   thread-safe (it owns the rasteriser), its const shading methods may run concurrently.
// Tests: tests/unit/deferred_test.cpp (kernels, metrics, the renderer), deferred_edge_test.cpp
// (edge-per-sample), tests/gl/gl_deferred_renderer_test.cpp (GPU = CPU).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "tessera/adaptive_thresholds.h"
#include "tessera/core.h"
#include "tessera/math.h"
#include "tessera/raster.h"
#include "tessera/scene.h"
#include "tessera/texture.h"

namespace tessera::deferred {

// ---------------------------------------------------------------------------------------------
// G-buffer layout
// ---------------------------------------------------------------------------------------------

/// Channel offsets of one G-buffer sample (11 floats).
inline constexpr int kChDepth = 0;     ///< Linear view depth (distance along the view axis,
                                       ///< world units, > 0); the camera's far plane if empty.
inline constexpr int kChNormal = 1;    ///< World-space normal, 3 floats (interpolated vertex
                                       ///< normals, not renormalised); 0 if empty.
inline constexpr int kChMaterial = 4;  ///< Material index as a float; -1 if empty (background).
inline constexpr int kChUv = 5;        ///< Texture coordinates u, v.
inline constexpr int kChDuvDx = 7;     ///< d(u, v)/dx per grid pixel.
inline constexpr int kChDuvDy = 9;     ///< d(u, v)/dy per grid pixel.
inline constexpr int kGBufferChannels = 11;

/// Linear RGB of pixels with no geometry.
inline constexpr std::array<float, 3> kBackground = {0.05f, 0.05f, 0.08f};

/// The camera set-up of a G-buffer pass, shared by `DeferredRenderer` and its GL twin
/// (gl::DeferredRenderer) so that both rasterise the same clip positions and reconstruct
/// positions with the same constants.
struct GBufferCamera {
  Mat4 view;                    ///< World to camera.
  Mat4 inv_view;                ///< Camera to world.
  Mat4 view_projection;         ///< projection(aspect) * view.
  Vec3 eye;                     ///< Camera position (world).
  float tan_half_fov_y = 0.5f;  ///< tan(fov_y / 2).
  float aspect = 1.0f;          ///< width / height.
};

/// The set-up of `camera` for a width x height output (pixels, each >= 1).
GBufferCamera gbuffer_camera(const scene::Camera& camera, int width, int height);

/// Per vertex i of `positions`: its clip position (x, y, z, w) at clip[i * clip_stride ..] and
/// its linear view depth at depth[i * depth_stride] (floats; the arrays may interleave).
/// Identical for any thread count.
void transform_gbuffer_vertices(const GBufferCamera& camera, std::span<const Vec3> positions,
                                float* clip, std::size_t clip_stride, float* depth,
                                std::size_t depth_stride, const Parallel& parallel = {});

/// An enlarged G-buffer and what the shading pass needs to reconstruct positions.
struct GBuffer {
  raster::FrameBuffer fb;       ///< ssaa = m, msaa = 1, kGBufferChannels channels.
  int m = 1;                    ///< Window size (supersampling factor).
  Mat4 inv_view;                ///< Camera to world.
  Vec3 eye;                     ///< Camera position (world).
  float tan_half_fov_y = 0.5f;  ///< tan(fov_y / 2).
  float aspect = 1.0f;          ///< width / height.

  int width() const { return fb.width(); }
  int height() const { return fb.height(); }
  /// The 11 channels of grid pixel (gx, gy).
  const float* sample(int gx, int gy) const { return fb.data(gx, gy, 0); }
  /// World position of grid pixel (gx, gy), reconstructed from its linear depth.
  Vec3 position(int gx, int gy) const;
};

// ---------------------------------------------------------------------------------------------
// Index matrices (Figure 3)
// ---------------------------------------------------------------------------------------------

/// The index matrix of an m x m window, row-major: entry (row j, column i) is the position in
/// the sampling order of grid pixel (i, j) of the window. m = 2, 3, 4 are the paper's Figure 3;
/// other m in [1, 8] are generated greedily by farthest-point insertion (the first sample nearest
/// the centre; each next one maximises its distance to those already chosen, ties to the one
/// nearest the centre, then to the lowest row-major index). Empty for m outside [1, 8].
std::span<const std::uint8_t> index_matrix(int m);
/// The inverse permutation: entry p is the row-major window index (j * m + i) of the p-th sample.
std::span<const std::uint8_t> sample_order(int m);

// ---------------------------------------------------------------------------------------------
// Shading
// ---------------------------------------------------------------------------------------------

/// A point light (world space), attenuated as KHR_lights_punctual: intensity / d^2 times the
/// range window clamp(1 - (d / range)^4, 0, 1)^2 when range > 0.
struct Light {
  Vec3 position;
  std::array<float, 3> color = {1, 1, 1};  ///< Linear RGB (KHR_lights_punctual's name, kept).
  float intensity = 1.0f;
  float range = 0.0f;
};

/// The deferred shader: Blinn-Phong, many point lights, optional heavy per-sample term.
struct ShadingOptions {
  std::vector<Light> lights;
  std::array<float, 3> ambient = {0.06f, 0.06f, 0.07f};  ///< Linear RGB ambient light.
  float specular = 0.3f;    ///< Specular colour (grey) of every material.
  float shininess = 48.0f;  ///< Blinn-Phong exponent.
  float exposure = 1.0f;    ///< Multiplies all light (D and P).
  /// Texture filtering of the albedo lookup. Anisotropic with `max_aniso` probes by default.
  texture::TextureFilter filter = texture::TextureFilter::anisotropic;
  int max_aniso = 16;
  /// The paper's "stalled" column: adds a genuinely expensive per-sample computation whose
  /// result modulates the diffuse light — a sum of `heavy_terms` smooth sinusoids of the world
  /// position (wavelengths between 1/8 and 1/2 of `heavy_wavelength`), i.e. heavy_terms cos and
  /// sin evaluations per shaded sample. No sleeping: the cost is real arithmetic.
  bool heavy = false;
  int heavy_terms = 256;
  float heavy_wavelength = 4.0f;  ///< World units; `scene_shading` sets it from the bounds.
  int threads = 0;  ///< Worker threads (0 = all). Results are identical for any value.
};

/// Shading options for a scene: its point lights plus `extra_lights` generated ones on a
/// horizontal ring (deterministic colours; together they give an irradiance of about 0.8 at the
/// ring's centre). With `camera`, the ring is centred on the camera's target with a radius of
/// half the eye-target distance, 0.35 of that distance above the target; otherwise on the
/// bounds' centre, radius 0.35 of the extent, a quarter of the height above the centre. The
/// heavy wavelength is a quarter of the bounds' half diagonal. With no lights at all, 4 extra
/// ones are added.
ShadingOptions scene_shading(const scene::Scene& scene, int extra_lights = 0,
                             const scene::Camera* camera = nullptr);

// ---------------------------------------------------------------------------------------------
// Adaptive sampling
// ---------------------------------------------------------------------------------------------

// The thresholds: AdaptiveThresholds (tessera/adaptive_thresholds.h), shared with the GPU.

/// Depth term k_d of a window of `n` linear depths (kernel; K = n - 1).
float metric_depth(std::span<const float> depths, float c_depth);
/// Normal term k_n of a window: `normals` holds 3 floats per sample; zero normals (background)
/// are skipped. 0 with fewer than two valid normals; K when the valid normals cancel out.
float metric_normal(std::span<const float> normals, float c_normal, int n);
/// Shading term k_s from the luma of the pixel and its four direct neighbours (kernel).
float metric_shading(float luma_m, float luma_n, float luma_s, float luma_w, float luma_e,
                     float t_min, float t_edge, float c_shade, int n);

/// Output of the adaptive pass.
struct AdaptiveResult {
  ImageRGBAF image;                   ///< Linear RGB, alpha 1.
  std::vector<std::uint8_t> samples;  ///< Shaded samples per pixel (k + 1), row-major.
  std::uint64_t samples_shaded = 0;   ///< Sum of `samples`.
  std::uint64_t extra_lookups = 0;    ///< Albedo re-lookups of first samples (k > 0, textured).
  double ms_first = 0;                ///< Shading S.
  double ms_metric = 0;               ///< Evaluating k.
  double ms_rest = 0;                 ///< Shading the k extra samples and averaging.
};

/// What the experiment's GPU renderers (gl::DeferredRenderer; the Vulkan twin inside
/// `tessera aa --backend vk`) return from one shading call: the image, the pass times and, for
/// adaptive and edge-per-sample, the per-pixel sample counts.
struct ShadeResult {
  ImageRGBAF image;                   ///< Linear RGB, alpha 1 (w x h).
  std::vector<std::uint8_t> samples;  ///< Shaded samples per pixel (k + 1); empty for others.
  std::uint64_t samples_shaded = 0;   ///< Sum of `samples` (or w*h*n for the reference, w*h
                                      ///< for 1 spp).
  /// Per pass, in order. GL: gpu_ms = GL_TIME_ELAPSED (NaN when the driver's result is
  /// impossible; Mesa 22.3 llvmpipe reports 0 for compute dispatches), wall_ms = host time
  /// from its dispatch to the end of glFinish (every pass ends with glFinish): what llvmpipe's
  /// compute work costs. Vulkan: gpu_ms from timestamps, wall_ms the submission's submit-to-
  /// fence time shared out by the GPU times.
  std::vector<PassTime> passes;
  double total_gpu_ms() const;   ///< Sum of the passes' gpu_ms.
  double total_wall_ms() const;  ///< Sum of the passes' wall_ms.
};

/// FXAA's 8-bit result, from the same renderers.
struct FxaaResult {
  ImageRGBA8 image;
  std::vector<PassTime> passes;  ///< As ShadeResult::passes.
  double total_gpu_ms() const;
  double total_wall_ms() const;
};

// ---------------------------------------------------------------------------------------------
// FXAA 3.11
// ---------------------------------------------------------------------------------------------

/// FXAA 3.11 "quality" (PC) settings. Presets: 10..15, 20..29 and 39 (the search step tables
/// of Fxaa3_11.h); the paper compares against "high quality settings".
struct FxaaOptions {
  int preset = 39;                     ///< 39 = "extreme quality": 12 search steps.
  float subpix = 0.75f;                ///< fxaaQualitySubpix (0 = off, 1 = softest).
  float edge_threshold = 0.125f;       ///< fxaaQualityEdgeThreshold ("high quality").
  float edge_threshold_min = 0.0312f;  ///< fxaaQualityEdgeThresholdMin ("visible limit").
  int threads = 0;
};

/// True for a preset number FXAA 3.11 defines.
bool valid_fxaa_preset(int preset);

/// A preset's edge-search steps: FXAA_QUALITY__PS and FXAA_QUALITY__P0..P11 of Fxaa3_11.h
/// (the CPU filter and share/tessera/glsl/fxaa.glsl use the same table).
struct FxaaPresetSteps {
  int steps = 0;
  std::array<float, 12> p{};
};

/// The steps of `preset`, or nullptr for an unknown preset.
const FxaaPresetSteps* fxaa_preset_steps(int preset);

/// FXAA 3.11 on an 8-bit sRGB image (the LDR back buffer FXAA is designed for): luma =
/// Rec.601 weights on the sRGB values, local contrast early exit, edge orientation, end-of-edge
/// search with the preset's steps, sub-pixel blend, then one bilinear fetch at the offset
/// position (clamp to edge). Alpha is copied. Fails on an empty image or a bad preset.
Result<ImageRGBA8> fxaa(const ImageRGBA8& image, const FxaaOptions& options = {});

// ---------------------------------------------------------------------------------------------
// The renderer
// ---------------------------------------------------------------------------------------------

/// Deferred renderer of one scene: owns the textures (mipmapped, linear) and the rasteriser.
class DeferredRenderer {
 public:
  /// Builds textures; fails if one cannot be built. `scene` must outlive the renderer.
  /// `parallel.threads` also drives the geometry pass (the shading passes take
  /// `ShadingOptions::threads`).
  static Result<std::unique_ptr<DeferredRenderer>> create(const scene::Scene& scene,
                                                          const Parallel& parallel = {});
  ~DeferredRenderer();

  /// Rasterises the G-buffer of `width` x `height` pixels with window m in [1, 8] into `out`
  /// (reallocated only when the size changes). Optional raster counters in `stats`.
  Status render_gbuffer(const scene::Camera& camera, int width, int height, int m, GBuffer& out,
                        raster::RasterStats* stats = nullptr);

  /// Full supersampling: all m^2 samples per pixel, footprint scale 1, mean in index order.
  ImageRGBAF shade_reference(const GBuffer& gb, const ShadingOptions& shading) const;
  /// Plain 1x deferred shading: the window's first sample (index order), footprint scale m.
  ImageRGBAF shade_default(const GBuffer& gb, const ShadingOptions& shading) const;
  /// The adaptive method (Listing 1).
  AdaptiveResult shade_adaptive(const GBuffer& gb, const ShadingOptions& shading,
                                const AdaptiveThresholds& adaptive) const;

 private:
  DeferredRenderer() = default;
  struct MaterialInfo {
    std::array<float, 3> base{1, 1, 1};
    const texture::Texture* texture = nullptr;
  };
  const scene::Scene* scene_ = nullptr;
  std::vector<texture::Texture> textures_;
  std::vector<MaterialInfo> materials_;
  std::vector<std::vector<float>> clip_;      // per mesh: 4 floats per vertex
  std::vector<std::vector<float>> varyings_;  // per mesh: depth, normal, uv per vertex
  raster::Rasteriser rasteriser_;
  int threads_ = 0;
  friend struct ShadeContext;
};

}  // namespace tessera::deferred

// ---------------------------------------------------------------------------------------------
// Engine baseline: per-sample shading on edges only (Lauritzen 2010)
// ---------------------------------------------------------------------------------------------

namespace tessera::deferred {

/// Deferred MSAA-style shading as engines do it (Lauritzen 2010, "Deferred Rendering for
/// Current and Future Rendering Pipelines"): a pixel whose samples may come from different
/// surfaces is shaded at every sample, any other pixel once. Here the m x m window of the
/// enlarged G-buffer is the pixel's sample set. A pixel is "complex" when its window mixes
/// background and geometry, or some sample's linear depth differs from sample 0's (the first in
/// index order) by more than one output pixel's depth change along sample 0's plane (its
/// position and normal; Lauritzen's maxZDelta = |ddx| + |ddy|):
/// |d_i - d_0| > depth_slack * m * (|dd/dx| + |dd/dy|) + 1e-4 d_0 with dd/dx, dd/dy per grid
/// pixel, or a normal deviates, dot(n_i, n_0) < min_normal_dot (both normalised).
/// share/tessera/glsl/edge_classify.glsl is the GPU twin.
struct EdgePerSampleOptions {
  float min_normal_dot = 0.99f;  ///< Lauritzen's value (about 8 degrees).
  float depth_slack = 1.0f;      ///< Multiplies the depth tolerance (0: 1e-4 relative only).
  int threads = 0;
};

/// 1 for complex pixels, 0 otherwise, row-major (w x h of the G-buffer's output).
std::vector<std::uint8_t> classify_edge_per_sample(const GBuffer& gb,
                                                   const EdgePerSampleOptions& options = {});

/// The baseline's image: simple pixels are the 1x pixel (`shade_default`'s value), complex
/// pixels the mean of all m^2 samples at footprint scale 1 (`shade_reference`'s value).
/// `samples` holds 1 or m^2 per pixel; the timings are `ms_metric` (classification) and
/// `ms_rest` (shading); `ms_first` stays 0.
AdaptiveResult shade_edge_per_sample(const DeferredRenderer& renderer, const GBuffer& gb,
                                     const ShadingOptions& shading,
                                     const EdgePerSampleOptions& options = {});

}  // namespace tessera::deferred
