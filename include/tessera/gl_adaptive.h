// tessera/gl_adaptive.h — adaptive supersampling for deferred shading (Hollander, Boubekeur &
// Eisemann 2013) as an engine component on OpenGL 4.5: the engine's enlarged G-buffer textures
// and its GLSL shading hook in, the anti-aliased image out. Contract: create, dispatch and
// destroy on the thread where the engine's OpenGL 4.5 core context is current (any context, no
// tessera `Context` needed; entry points as tessera/gl.h says: `load_entry_points` or first-use
// resolution); destroy it before that context. A dispatch puts back every piece of GL state it
// changes (the list is in docs/engine_integration.md) and never touches framebuffers, viewport,
// pixel-store, vertex state or the debug callback; it reads no file (the GLSL is embedded) unless
// `glsl_dir` asks. Without a current context every call fails with one line. The walkthrough
// (G-buffer layout, hook contract, passes, resources) is docs/engine_integration.md; Tests:
// tests/gl/gl_adaptive_test.cpp (state), gl_engine_context* (engine contexts). Not thread-safe.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tessera/adaptive_supersampler.h"
#include "tessera/core.h"
#include "tessera/gl.h"

namespace tessera::gl {

/// The GL component's options: the shared ones (tessera/adaptive_supersampler.h) and GL's.
struct AdaptiveSupersamplerOptions : AdaptiveCommonOptions {
  /// Development override: a folder read instead of the GLSL embedded in the library (see
  /// tessera/glsl.h). Empty (the default): $TESSERA_GLSL_DIR when set, else the embedded copy;
  /// no file is read.
  std::filesystem::path glsl_dir;
  /// Binding points the component uses during a dispatch (-1 = the top of the driver's range).
  int first_texture_unit = -1;     ///< 4 units.
  int uniform_binding = -1;        ///< 1 uniform-buffer binding.
  int first_storage_binding = -1;  ///< 2 storage-buffer bindings.
  int first_image_unit = -1;       ///< 2 image units.
  // `profile` on GL: GL_TIME_ELAPSED queries plus the host time to a glFinish after each pass
  // (llvmpipe's queries read 0 for compute), and a read-back of the extra-sample count.
};

/// One frame's inputs.
struct AdaptiveFrame {
  /// The G-buffer textures (GL_TEXTURE_2D names, at least (m*w) x (m*h) for the render size
  /// w x h, owned by the engine; the top-left m*w x m*h texels are read) by slot; 0 for slots
  /// the layout does not use.
  std::array<std::uint32_t, 4> gbuffer{};
  /// This frame's output size (dynamic resolution), at most options.width x options.height;
  /// {0, 0} = that largest size. Any size, any order, no re-create: the same bytes as a
  /// component created for that size.
  AdaptiveExtent render_size{};
  /// At most this many extra samples (samples beyond S) in this frame. When the metrics ask
  /// for more, pixels are ranked by metric strength (the unrounded max(k_d, k_n, k_s)), ties
  /// by pixel index (row-major y*w + x, lower first); whole pixels keep their k in rank order
  /// while it fits, the first pixel that does not fit keeps the remainder (its first samples
  /// in the sample order), all later pixels 0. So exactly min(budget, asked) extra samples
  /// are shaded, the same for every run. Empty = no budget; negative = an error.
  std::optional<std::int64_t> budget;
};

/// What a dispatch leaves (vk::AdaptiveOutput's twin; GL runs the passes within the call, so
/// the profile's figures come with it, where Vulkan's come from read_profile).
struct AdaptiveOutput {
  /// The output texture (owned by the component, options.width x options.height): its
  /// top-left `render_size` texels hold the image.
  std::uint32_t colour = 0;
  std::uint32_t sample_counts = 0;  ///< GL_R8UI k + 1 per pixel (0 unless requested).
  AdaptiveExtent render_size{};     ///< The texels written, from (0, 0).
  /// With `profile`: the extra samples shaded (sum of k) and, per pass in order, the
  /// GL_TIME_ELAPSED time (gpu_ms, NaN when the driver's is impossible) and the host time
  /// (wall_ms).
  std::uint64_t extra_samples = 0;
  std::vector<PassTime> passes;
  double total_gpu_ms() const;
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

  /// The adaptive image. Fails (invalid_argument / size_mismatch / too_large, nothing
  /// dispatched) when a texture the layout needs is 0, not a GL_TEXTURE_2D, smaller than
  /// (m*w) x (m*h), of an integer/sRGB/unknown format or lacks a channel the layout reads, the
  /// render size exceeds the options' size, or the budget is negative. The message names the
  /// slot or the size.
  Result<AdaptiveOutput> dispatch(const AdaptiveFrame& frame);
  /// Full supersampling: all m*m samples, footprint 1 (same checks).
  Result<AdaptiveOutput> dispatch_reference(const AdaptiveFrame& frame);
  /// S alone: one sample per pixel (sample 0 of the order), footprint m.
  Result<AdaptiveOutput> dispatch_first_sample(const AdaptiveFrame& frame);

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
