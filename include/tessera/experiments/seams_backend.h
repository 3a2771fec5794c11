// tessera/experiments/seams_backend.h — the backend interface of the seam experiment (Toth
// 2013): one frame, the reference and the sample positions of an MSAA rate, rendered by the CPU
// (`create_cpu_seams_backend`, faces::FaceRenderer) or by OpenGL (gl::FaceRenderer, made by a
// `GpuBackendFactory`, experiments/common.h), and the rule by which `run_seams` compares a GL
// frame with a CPU frame.
// Tests: tests/unit/experiments_seams_backend_test.cpp, tests/vk/vk_seams_backend_test.cpp.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "tessera/core.h"
#include "tessera/experiments/common.h"
#include "tessera/faces.h"
#include "tessera/scene.h"

namespace tessera::experiments {

/// One frame as a seam-experiment backend renders it (the options `run_seams` varies).
struct FaceFrameOptions {
  int width = 480, height = 540;
  int msaa = 1;
  faces::SeamMethod method = faces::SeamMethod::discard;
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
  int msaa = 1;     ///< The rate asked for.
  int samples = 1;  ///< Samples per pixel drawn (GL: GL_SAMPLES; a driver may round up).
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

/// What `run_seams` compares a GL rate's frames with (`Backend::both`).
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

/// The rule of `run_seams`: `cpu_rate` where `cpu_msaa` > 0, else `driver_positions` where
/// `positions` holds `samples` (1..16) offsets in [-8, 7], else `none`.
SeamsGlComparison seams_gl_comparison(const SeamsSamplePattern& pattern);

/// A renderer of the seam experiment's frames: the CPU (`create_cpu_seams_backend`, wrapping
/// faces::FaceRenderer) or OpenGL (`GpuBackendFactory::create_seams`, wrapping
/// gl::FaceRenderer). Used on the calling thread only.
class SeamsBackend : public BackendDevice {
 public:
  /// Whether frames with `samples` MSAA samples can be rendered (a GL driver may refuse some).
  virtual bool msaa_supported(int samples) = 0;
  /// Whether `FaceFrameOptions::shading_only` is implemented.
  virtual bool has_shading_only() const = 0;
  /// What frames at `msaa` are drawn with (the CPU: exactly `msaa`, at the standard positions;
  /// GL: what the driver allocates, e.g. Mesa llvmpipe draws 2x with its 4x samples). Only for
  /// supported rates.
  virtual SeamsSamplePattern sample_pattern(int msaa) {
    const std::span<const raster::SampleOffset> standard = raster::sample_positions(msaa);
    return {msaa, msaa, msaa, {standard.begin(), standard.end()}};
  }
  virtual Result<SeamsBackendFrame> render(const scene::Camera& camera,
                                           const FaceFrameOptions& options) = 0;
  /// The paper's reference: Traverse (16x anisotropic by default) at factor x factor the
  /// resolution, Mitchell-Netravali downsampled (faces::FaceRenderer::render_reference and its
  /// GL twin, which take the same options).
  virtual Result<ImageRGBAF> render_reference(const scene::Camera& camera, int width, int height,
                                              const faces::ReferenceOptions& options) = 0;
};

/// The CPU backend (faces::FaceRenderer). `scene` and `textures` must outlive it.
Result<std::unique_ptr<SeamsBackend>> create_cpu_seams_backend(
    const faces::FaceScene& scene, const faces::FaceTextureSet& textures);

}  // namespace tessera::experiments
