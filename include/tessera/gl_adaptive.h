// tessera/gl_adaptive.h — adaptive supersampling for deferred shading (Hollander, Boubekeur &
// Eisemann 2013) as an engine component on OpenGL 4.5: the engine's enlarged G-buffer textures
// and its GLSL shading hook in, the anti-aliased image out. Contract: create, dispatch and
// destroy on the thread where the engine's OpenGL 4.5 core context is current (any context, no
// tessera `Context` needed; entry points as tessera/gl.h says: `load_entry_points` or first-use
// resolution); destroy it before that context. A dispatch puts back every piece of GL state it
// changes (the list is in docs/engine_integration.md) and never touches framebuffers, viewport,
// pixel-store, vertex state or the debug callback; it reads no file (the GLSL is embedded) unless
// `glsl_dir` asks. Without a current context every call fails with one line. The walkthrough
// (G-buffer layout, hook contract, passes, resources) is docs/engine_integration.md; tests:
// tests/gl/gl_adaptive_test.cpp (state), gl_engine_context* (engine contexts). Not thread-safe.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tessera/core.h"
#include "tessera/gl.h"

namespace tessera::gl {

/// Where one G-buffer quantity lives: texture slot (index into `AdaptiveFrame::gbuffer`) and
/// channels. Decoded value = stored * scale + bias (per channel).
struct AdaptiveChannel {
  int texture = -1;      ///< 0..3; -1 = absent (only uv and uv_derivatives may be absent).
  std::string channels;  ///< Swizzle of exactly the quantity's width: "r", "xyz", "wzy", ...
                         ///< (letters of one set: rgba or xyzw).
  float scale = 1.0f;
  float bias = 0.0f;
};

/// Which texture and channels hold each quantity (fixed at creation; see the header comment).
struct AdaptiveGBufferLayout {
  AdaptiveChannel depth;           ///< 1 channel, linear view depth (> 0 where not empty).
  AdaptiveChannel normal;          ///< 3 channels.
  AdaptiveChannel id;              ///< 1 channel, material/object id; < 0 = empty texel.
  AdaptiveChannel uv;              ///< 2 channels, optional (with uv_derivatives).
  AdaptiveChannel uv_derivatives;  ///< 4 channels du/dx, dv/dx, du/dy, dv/dy, optional.
};

/// The engine's shading (see the header comment for the contract).
struct AdaptiveShadingHook {
  std::string source;                 ///< GLSL defining vec4 tessera_shade_sample(ivec2, float).
  std::string name = "shading hook";  ///< Used in compile errors ("name:line: ...").
  std::vector<std::filesystem::path> include_paths;  ///< Searched before the shipped GLSL.
};

/// The paper's thresholds (§3.1; the same formulas and defaults as deferred::AdaptiveOptions).
/// With K = m*m - 1: k = clamp(round(max(k_d, k_n, k_s)), 0, K), k_d = c_depth*K*Var(d/mean d),
/// k_n = c_normal*K*sqrt(1 - min |nbar.n_i|), k_s = c_shade*K*r when the luma range r around
/// the pixel is >= max(t_min, l_max*t_edge), else 0. A window mixing empty and non-empty texels
/// gets K. The unrounded max is the pixel's metric strength (what the budget ranks).
struct AdaptiveThresholds {
  float c_depth = 200.0f;
  float c_normal = 2.0f;
  float c_shade = 8.0f;
  float t_min = 0.0312f;
  float t_edge = 0.0625f;
  bool use_geometry = true;  ///< k_d and k_n.
  bool use_shading = true;   ///< k_s.
  float seam_factor = 4.0f;  ///< UV-seam rule of the footprint (adaptive_samples.glsl).
  int force_k = -1;          ///< >= 0: every pixel asks for min(force_k, K) (strength force_k).
};

/// How the extra samples are scheduled on the GPU; all give the same image, bit for bit.
enum class AdaptiveSchedule {
  /// One dense list of (pixel, sample) over the frame, one invocation per sample, then a
  /// per-pixel resolve; sized by `list_capacity` (a pixel whose samples do not fit shades them
  /// itself in the resolve pass: same image). No read-back (indirect dispatch).
  frame_list,
  tile_list,  ///< Per 8x8 tile, in shared memory (m <= 4; larger m runs `loop`).
  loop,       ///< The paper's §4.2: each pixel's invocation shades its own samples.
};

/// How a pixel's shaded samples are averaged.
enum class AdaptiveResolve {
  box,  ///< Plain mean (sum of the samples in sample order, / (k + 1)).
  /// Tonemap-weighted mean for HDR (bright samples do not dominate the edge): sample c with
  /// luminance Y = dot(max(c.rgb, 0), (0.2126, 0.7152, 0.0722)) gets weight
  /// w = 1 / (1 + e*Y), e = `hdr_exposure`; the pixel is sum(w*c) / sum(w) (all four
  /// channels). The shading metric then uses the luma of T(c) = c * e / (1 + e*Y) (Reinhard
  /// on luminance). The reference pass resolves the same way.
  tonemap_weighted,
};

enum class AdaptiveOutputFormat { rgba16f, rgba32f };

struct AdaptiveSupersamplerOptions {
  int width = 0, height = 0;  ///< Output pixels (> 0); the G-buffer is (m*width) x (m*height).
  int m = 4;                  ///< Window side, 2..8.
  AdaptiveThresholds thresholds;
  /// Sample order: entry p = the row-major window cell of sample p (p = 0 is S's sample); a
  /// permutation of 0..m*m-1. Empty = tessera's (deferred::sample_order: the paper's Figure 3
  /// index matrices for m = 2..4, ordered-dither matrices beyond).
  std::vector<std::uint8_t> sample_order;
  AdaptiveSchedule schedule = AdaptiveSchedule::frame_list;
  /// frame_list items (shaded samples of pixels with k > 0, sample 0 counted), 24 bytes each;
  /// 0 = w*h*(m*m/2), half of full supersampling (m = 4: 192 bytes per output pixel, 398 MB at
  /// 1920x1080; with a budget B, B + w*h items always suffice). Clamped to what
  /// GL_MAX_SHADER_STORAGE_BLOCK_SIZE allows. Pixels beyond it are still shaded (see above).
  std::size_t list_capacity = 0;
  AdaptiveResolve resolve = AdaptiveResolve::box;
  float hdr_exposure = 1.0f;  ///< e of `tonemap_weighted` (> 0).
  AdaptiveOutputFormat output = AdaptiveOutputFormat::rgba16f;
  bool sample_count_texture = false;  ///< Also write k + 1 per pixel to a GL_R8UI texture.
  AdaptiveGBufferLayout layout;
  AdaptiveShadingHook hook;
  /// Development override: a folder read instead of the GLSL embedded in the library (see
  /// tessera/glsl.h). Empty (the default): $TESSERA_GLSL_DIR when set, else the embedded copy;
  /// no file is read.
  std::filesystem::path glsl_dir;
  /// Binding points the component uses during a dispatch (-1 = the top of the driver's range).
  int first_texture_unit = -1;     ///< 4 units.
  int uniform_binding = -1;        ///< 1 uniform-buffer binding.
  int first_storage_binding = -1;  ///< 2 storage-buffer bindings.
  int first_image_unit = -1;       ///< 2 image units.
  /// Measure every pass: GL_TIME_ELAPSED queries plus the host time to a glFinish after each
  /// pass (llvmpipe's queries read 0 for compute), and read back the extra-sample count. Costs
  /// a GPU stall per pass: for benchmarks, not for frames.
  bool profile = false;
};

/// One frame's inputs.
struct AdaptiveFrame {
  /// The G-buffer textures (GL_TEXTURE_2D names, (m*w) x (m*h), owned by the engine) by slot;
  /// 0 for slots the layout does not use.
  std::array<std::uint32_t, 4> gbuffer{};
  /// At most this many extra samples (samples beyond S) in this frame. When the metrics ask
  /// for more, pixels are ranked by metric strength (the unrounded max(k_d, k_n, k_s)), ties
  /// by pixel index (row-major y*w + x, lower first); whole pixels keep their k in rank order
  /// while it fits, the first pixel that does not fit keeps the remainder (its first samples
  /// in the sample order), all later pixels 0. So exactly min(budget, asked) extra samples
  /// are shaded, the same for every run. Empty = no budget; negative = an error.
  std::optional<std::int64_t> budget;
};

/// What a dispatch returns.
struct AdaptiveFrameResult {
  std::uint32_t colour = 0;         ///< The output texture (owned by the component).
  std::uint32_t sample_counts = 0;  ///< GL_R8UI k + 1 per pixel (0 unless requested).
  /// With `profile`: the extra samples shaded (sum of k) and, per pass in order, the
  /// GL_TIME_ELAPSED time (NaN when the driver's is impossible) and the host time.
  std::uint64_t extra_samples = 0;
  std::vector<PassTime> passes;
  std::vector<PassTime> wall_passes;
  double total_wall_ms() const;
};

/// The component. Works on whatever OpenGL 4.5 core context is current (see the header comment).
class AdaptiveSupersampler {
 public:
  /// Checks the options (invalid_argument naming the field: m outside 2..8, size <= 0, a
  /// layout channel of the wrong width or an unknown letter, a bad sample order, bindings
  /// beyond the driver's range; too_large when the G-buffer exceeds GL_MAX_TEXTURE_SIZE or the
  /// work buffer GL_MAX_SHADER_STORAGE_BLOCK_SIZE) before creating any GL object, then compiles
  /// every pass with the hook (a compile error names the hook's file and line).
  static Result<std::unique_ptr<AdaptiveSupersampler>> create(
      const AdaptiveSupersamplerOptions& options);
  ~AdaptiveSupersampler();
  AdaptiveSupersampler(const AdaptiveSupersampler&) = delete;
  AdaptiveSupersampler& operator=(const AdaptiveSupersampler&) = delete;

  /// The adaptive image. Fails (invalid_argument, nothing dispatched) when a texture the layout
  /// needs is 0, not a GL_TEXTURE_2D, not (m*w) x (m*h), of an integer/sRGB/unknown format or
  /// lacks a channel the layout reads, or the budget is negative. The message names the slot.
  Result<AdaptiveFrameResult> dispatch(const AdaptiveFrame& frame);
  /// Full supersampling: all m*m samples, footprint 1 (same checks).
  Result<AdaptiveFrameResult> dispatch_reference(const AdaptiveFrame& frame);
  /// S alone: one sample per pixel (sample 0 of the order), footprint m.
  Result<AdaptiveFrameResult> dispatch_first_sample(const AdaptiveFrame& frame);

  /// Replaces the thresholds for the following dispatches (an upload of the parameter block;
  /// no recompilation), e.g. for tuning per scene.
  void set_thresholds(const AdaptiveThresholds& thresholds);

  const AdaptiveSupersamplerOptions& options() const;
  /// The binding points actually used (the defaults resolved).
  int texture_unit() const;
  int uniform_binding() const;
  int storage_binding() const;
  int image_unit() const;

  struct State;

 private:
  AdaptiveSupersampler() = default;
  std::unique_ptr<State> state_;
};

}  // namespace tessera::gl
