// tessera/gl_deferred.h — adaptive supersampling for deferred shading on the GPU (Hollander,
// Boubekeur & Eisemann 2013), with its baselines, through OpenGL 4.5 (tessera::gl runtime).
//
// The GPU twin of tessera/deferred.h's CPU path, checked against it
// (tests/gl/gl_deferred_renderer_test.cpp):
//  * Geometry pass: the scene rasterised by GL into an enlarged G-buffer of (m*w) x (m*h)
//    RGBA32F texels (three colour attachments + a 32-bit float depth buffer), with the CPU's
//    conventions: clip positions computed on the CPU exactly as DeferredRenderer does, linear
//    view depth, interpolated world normal (not renormalised), material id (-1 background), UV
//    and fine UV derivatives per grid pixel; row 0 = top grid row. The size is checked against
//    GL_MAX_FRAMEBUFFER_WIDTH/HEIGHT, GL_MAX_TEXTURE_SIZE and GL_MAX_RENDERBUFFER_SIZE before
//    anything is allocated (an invalid_argument / too_large error naming the limit).
//  * The adaptive, reference and 1 spp passes (m >= 2) are tessera's engine component,
//    gl::AdaptiveSupersampler (tessera/gl_adaptive.h, adaptive_component.glsl), run on this
//    G-buffer with the shading below (deferred_shading.glsl) as its hook: one implementation of
//    the technique. The engine baseline, sRGB8, FXAA and m = 1 run deferred_passes.comp.
//  * Compute passes (share/tessera/glsl/deferred_passes.comp): S = the first sample of every
//    window (footprint scale m), k per pixel from the depth/normal/shading metrics
//    (adaptive_metrics.glsl, AdaptiveThresholds' formulas and constants), the k extra samples
//    (Figure-3 order, footprints of adaptive_samples.glsl: scaled to the samples used, §4.1
//    material-boundary and UV-seam rules) and the resolve; the full-SSAA reference; 1 spp (S);
//    FXAA 3.11 (fxaa.glsl) on the sRGB8-encoded 1 spp image; and the engine baseline, deferred
//    per-sample shading of edge pixels only (Lauritzen 2010; edge_classify.glsl), classified
//    per 8x8 tile in the compute pass that also shades.
//    Compute rather than fragment passes, so that the extra samples can be regrouped: by default
//    (`ExtraSchedule::frame_list`) every pixel's extra samples go into one dense list over the
//    whole frame, shaded one invocation per sample and summed per pixel in index order, so busy
//    edge pixels do not leave their neighbours' lanes idle (the fastest of the three schedules
//    wherever docs/benchmarks/aa_gl.md timed them). `tile_list` does the same within 8x8 tiles
//    in shared memory (Lauritzen's redistribution) and `loop` is the paper's §4.2 per-pixel
//    loop; all three give the same image, bit for bit.
//  * Shading: Blinn-Phong over point lights and the `heavy` term with the CPU's waves; albedo
//    lookups use the CPU's anisotropic filter built from textureLod probes on the CPU's own mip
//    chains (uploaded as RGBA32F texture arrays, one per texture size), so GL and CPU filter the
//    same texels the same way (hardware anisotropic filtering is implementation-defined).
//  * Every pass is timed with GL_TIME_ELAPSED (`GpuTimer`) and, because Mesa 22.3 llvmpipe's
//    elapsed-time queries do not count compute dispatches (they read 0), also on the host from
//    dispatch to the end of a glFinish that closes every pass; images, the k map and the
//    G-buffer are read back as tessera images / vectors.
//
// Threads: as tessera/gl.h — all calls on the thread where the context is current; destroy the
// renderer before the context. Not thread-safe.
// Tests: tests/gl/gl_deferred_renderer_test.cpp (GPU = CPU), tests/gl/aa_gl_cli_test.py.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "tessera/core.h"
#include "tessera/deferred.h"
#include "tessera/gl.h"
#include "tessera/scene.h"

namespace tessera::gl {

/// How the extra samples of the adaptive (and edge-per-sample) pass are scheduled.
enum class ExtraSchedule {
  tile_list,  ///< Per 8x8 tile, a shared list of (pixel, sample) shaded round-robin (m <= 4;
              ///< larger m falls back to `loop`).
  loop,       ///< The paper's §4.2: each invocation loops over its pixel's k samples.
  /// One dense list of (pixel, sample) over the whole frame, one invocation per extra sample,
  /// then a per-pixel resolve (three passes; any m). Adaptive: AdaptiveSchedule::frame_list
  /// (a list of fixed capacity; pixels beyond it shade their own samples, same image). Engine
  /// baseline: GPU buffers of 24 bytes per extra sample that grow with the frame's count (read
  /// back once per frame); past GL_MAX_SHADER_STORAGE_BLOCK_SIZE it falls back to `loop`.
  frame_list,
};

struct DeferredRendererOptions {
  /// Development override: a folder read instead of the GLSL embedded in the library (see
  /// tessera/glsl.h). Empty (the default): $TESSERA_GLSL_DIR when set, else the embedded copy;
  /// no file is read.
  std::filesystem::path glsl_dir;
  ExtraSchedule schedule = ExtraSchedule::frame_list;
  int threads = 0;  ///< CPU threads for the texture chains and vertex transforms.
};

/// The GPU deferred renderer of one scene. Needs a current `Context` for every call.
class DeferredRenderer {
 public:
  /// Builds the CPU texture chains (as DeferredRenderer does), uploads them and the meshes,
  /// and compiles the geometry pass. Fails (io_error) when the GLSL folder is missing,
  /// (too_large) when the textures need more than 8 size classes, or on GL errors.
  static Result<std::unique_ptr<DeferredRenderer>> create(
      const scene::Scene& scene, const DeferredRendererOptions& options = {});
  ~DeferredRenderer();
  DeferredRenderer(const DeferredRenderer&) = delete;
  DeferredRenderer& operator=(const DeferredRenderer&) = delete;

  /// Checks a G-buffer of (m*width) x (m*height) against the context's limits
  /// (GL_MAX_FRAMEBUFFER_WIDTH/HEIGHT, GL_MAX_TEXTURE_SIZE, GL_MAX_RENDERBUFFER_SIZE) without
  /// allocating: invalid_argument for m outside [1, 8] or a non-positive size, too_large with
  /// "deferred GL: G-buffer 40000x30000 (m = 4) exceeds GL_MAX_FRAMEBUFFER_WIDTH = 16384".
  Status check_size(int width, int height, int m) const;

  /// The geometry pass into the enlarged G-buffer (reallocated when the size changes). Its
  /// GPU time is `last_gbuffer_ms()` (NaN when the driver's query result is impossible), its
  /// host time to the end of glFinish `last_gbuffer_wall_ms()`.
  Status render_gbuffer(const scene::Camera& camera, int width, int height, int m);
  double last_gbuffer_ms() const;
  double last_gbuffer_wall_ms() const;
  int width() const;
  int height() const;
  int m() const;

  /// The G-buffer read back into the CPU layout (ssaa = m, kGBufferChannels channels) with
  /// the camera data of the last `render_gbuffer`, so the CPU shaders can run on it.
  Result<deferred::GBuffer> read_gbuffer() const;

  /// Full SSAA: all m^2 samples, footprint scale 1 (passes: "reference").
  Result<deferred::ShadeResult> shade_reference(const deferred::ShadingOptions& shading);
  /// 1 spp: the first sample, footprint scale m (passes: "first").
  Result<deferred::ShadeResult> shade_default(const deferred::ShadingOptions& shading);
  /// Adaptive (passes: "first", "metrics", "extra").
  Result<deferred::ShadeResult> shade_adaptive(const deferred::ShadingOptions& shading,
                                               const AdaptiveThresholds& adaptive);
  /// Engine baseline (passes: "first", "edge_extra": classification + shading per tile).
  Result<deferred::ShadeResult> shade_edge_per_sample(
      const deferred::ShadingOptions& shading, const deferred::EdgePerSampleOptions& edge = {});
  /// 1 spp, sRGB8 encoding and FXAA 3.11, all on the GPU (passes: "first", "srgb8", "fxaa").
  Result<deferred::FxaaResult> shade_default_fxaa(const deferred::ShadingOptions& shading,
                                                  const deferred::FxaaOptions& fxaa = {});
  /// FXAA 3.11 of an 8-bit image on the GPU (passes: "fxaa"); the CPU `deferred::fxaa`'s
  /// arithmetic. Independent of the G-buffer.
  Result<deferred::FxaaResult> fxaa(const ImageRGBA8& image,
                                    const deferred::FxaaOptions& fxaa = {});

  const std::filesystem::path& glsl_dir() const;

  struct State;

 private:
  DeferredRenderer() = default;
  std::unique_ptr<State> state_;
};

}  // namespace tessera::gl
