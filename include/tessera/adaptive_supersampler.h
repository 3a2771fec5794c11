// tessera/adaptive_supersampler.h — the backend-neutral options of the adaptive supersampler
// (Hollander, Boubekeur & Eisemann 2013, §3-4) as an engine component: the G-buffer layout
// descriptor, the shading hook, the paper's thresholds, the schedules, the resolve and the output
// format, shared by gl::AdaptiveSupersampler (tessera/gl_adaptive.h) and vk::AdaptiveSupersampler
// (tessera/vk_adaptive.h), whose option structs extend `AdaptiveCommonOptions` with their
// backend's bindings. Part of the core `tessera` library: plain structs, no OpenGL, no Vulkan.
// The thresholds are AdaptiveThresholds (tessera/adaptive_thresholds.h), as on the CPU. The hook
// contract, the G-buffer layout and the passes: docs/engine_integration.md. Checked by each
// backend's `create` (one-line errors naming the field); Tests: tests/gl/gl_adaptive_test.cpp,
// tests/vk/vk_adaptive_test.cpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "tessera/adaptive_thresholds.h"

namespace tessera {

/// Where one G-buffer quantity lives: texture slot (index into `AdaptiveFrame::gbuffer`) and
/// channels. Decoded value = stored * scale + bias (per channel).
struct AdaptiveChannel {
  int texture = -1;      ///< 0..3; -1 = absent (only uv and uv_derivatives may be absent).
  std::string channels;  ///< Swizzle of exactly the quantity's width: "r", "xyz", "wzy", ...
                         ///< (letters of one set: rgba or xyzw).
  float scale = 1.0f;
  float bias = 0.0f;
};

/// Which texture and channels hold each quantity (fixed at creation; docs/engine_integration.md).
struct AdaptiveGBufferLayout {
  AdaptiveChannel depth;           ///< 1 channel, linear view depth (> 0 where not empty).
  AdaptiveChannel normal;          ///< 3 channels.
  AdaptiveChannel id;              ///< 1 channel, material/object id; < 0 = empty texel.
  AdaptiveChannel uv;              ///< 2 channels, optional (with uv_derivatives).
  AdaptiveChannel uv_derivatives;  ///< 4 channels du/dx, dv/dx, du/dy, dv/dy, optional.
};

/// The engine's shading (the contract: docs/engine_integration.md).
struct AdaptiveShadingHook {
  std::string source;                 ///< GLSL defining vec4 tessera_shade_sample(ivec2, float).
  std::string name = "shading hook";  ///< Used in compile errors ("name:line: ...").
  std::vector<std::filesystem::path> include_paths;  ///< Searched before the shipped GLSL.
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

/// The colour output's format (GL_RGBA16F / GL_RGBA32F; R16G16B16A16 / R32G32B32A32_SFLOAT).
enum class AdaptiveOutputFormat { rgba16f, rgba32f };

/// A size in output pixels (the render size of one frame on GL; Vulkan's is a VkExtent2D).
struct AdaptiveExtent {
  int width = 0, height = 0;
};

/// What both components are asked for, fixed at `create` but `thresholds` (`set_thresholds`);
/// gl:: and vk::AdaptiveSupersamplerOptions add their backend's bindings.
struct AdaptiveCommonOptions {
  /// Output pixels (> 0): the largest output a frame renders. Each frame may name a smaller
  /// render size (dynamic resolution; AdaptiveFrame::render_size on GL and Vulkan), its
  /// G-buffer m times it; buffers are sized for this largest size.
  int width = 0, height = 0;
  int m = 4;  ///< Window side, 2..8.
  AdaptiveThresholds thresholds;
  /// Sample order: entry p = the row-major window cell of sample p (p = 0 is S's sample); a
  /// permutation of 0..m*m-1. Empty = tessera's (deferred::sample_order: the paper's Figure 3
  /// index matrices for m = 2..4, ordered-dither matrices beyond).
  std::vector<std::uint8_t> sample_order;
  AdaptiveSchedule schedule = AdaptiveSchedule::frame_list;
  /// frame_list items (shaded samples of pixels with k > 0, sample 0 counted), 24 bytes each;
  /// 0 = w*h*(m*m/2), half of full supersampling (m = 4: 192 bytes per output pixel, 398 MB at
  /// 1920x1080; with a budget B, B + w*h items always suffice). Clamped to what the device's
  /// largest storage buffer allows (GL_MAX_SHADER_STORAGE_BLOCK_SIZE, maxStorageBufferRange).
  /// Pixels beyond it are still shaded (see above).
  std::size_t list_capacity = 0;
  AdaptiveResolve resolve = AdaptiveResolve::box;
  float hdr_exposure = 1.0f;                                    ///< e of `tonemap_weighted` (> 0).
  AdaptiveOutputFormat output = AdaptiveOutputFormat::rgba16f;  ///< The colour output.
  bool sample_count_texture = false;  ///< Also write k + 1 per pixel (GL_R8UI / R8_UINT).
  AdaptiveGBufferLayout layout;
  AdaptiveShadingHook hook;
  /// Measure every pass (the backend says how: tessera/gl_adaptive.h, tessera/vk_adaptive.h).
  /// Costs a stall or a read-back: for benchmarks, not for frames.
  bool profile = false;
};

/// The layout of tessera's own G-buffer packing (deferred_shading.glsl; gl::DeferredRenderer):
/// slot 0 = depth "r", normal "gba"; slot 1 = id "r", uv "gb"; slot 2 = uv_derivatives "rgba".
AdaptiveGBufferLayout deferred_gbuffer_layout();

}  // namespace tessera
