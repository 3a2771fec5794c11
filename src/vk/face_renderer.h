// Internal to src/vk: the seam experiment (Toth 2013) drawn with Vulkan on a HeadlessDevice —
// the twin of gl::FaceRenderer (tessera/gl_face_renderer.h) and faces::FaceRenderer, behind
// the seam backend (seams_backend.cpp). The same frame as theirs:
//  * the clip-space vertices computed on the CPU with the CPU renderer's arithmetic
//    (faces::face_clip_positions, sub-rectangles of tiled references included), z remapped
//    from OpenGL's [-w, w] to Vulkan's [0, w]; four unshared vertices per face, the CPU's
//    triangles (0,1,2), (0,2,3) (faces::class_grouped_indices, not reversed: seams_render.vert
//    negates clip y and Vulkan's framebuffer y runs down, so front faces stay counter-clockwise
//    on screen), back faces culled, depth test `less` on D32_SFLOAT cleared to 1;
//  * share/tessera/glsl/seams_render.vert/.frag with VULKAN defined, one pipeline per (method,
//    fallback, output, samples), one draw per face class with the class in the push constant —
//    or, where the device lacks shaderSampledImageArrayDynamicIndexing (lavapipe), as
//    specialization constant 0 of one pipeline per class (TESSERA_RENDER_CLASS_CONSTANT), so
//    that the own face's sampler array is indexed by a constant; the textures as
//    vk::FaceTextureSet (set 0, its default bindings);
//  * an R32G32B32A32_SFLOAT target (GL's RGBA32F) with `msaa` samples, cleared to
//    faces::kFaceBackground with alpha 0, resolved to one sample with vkCmdResolveImage;
//    row 0 is the image's top row (the shader's y flip), so the standard sample locations are
//    the CPU rasteriser's raster::sample_positions.
// Anisotropic frames use samplers with maxAnisotropy = the frame's max_aniso (clamped to the
// device's), trilinear ones samplers without: a sampler's anisotropy is fixed at creation, so
// there is one vk::FaceTextureSet per anisotropy in use (16x made with the renderer, trilinear's
// on the first trilinear frame).
// Timing: timestamps before the render pass, after it and after the resolve; the wall time runs
// from vkQueueSubmit to the fence. The read-back is a second submission, outside both times.
#pragma once

#include <map>
#include <memory>
#include <vector>

#include "tessera/core.h"
#include "tessera/experiments/seams_backend.h"
#include "tessera/faces.h"
#include "tessera/scene.h"
#include "tessera/vk_faces.h"
#include "vk/headless_device.h"

namespace tessera::vk {

/// What the fragment shader writes (seams_render.frag's TESSERA_RENDER_OUTPUT).
enum class SeamsOutput {
  colour,         ///< Shaded linear RGB, alpha 1.
  zero_coverage,  ///< 1 where the method's coverage was 0, else 0; background (0,0,0,0).
};

/// One frame's settings: the seam backend's (size, rate, method, filter, fallback; keep_image
/// off: times only, an empty image), what the fragment shader writes, and the frame as a
/// sub-rectangle of a full_width x full_height image (0 = the whole image: tiled references).
/// shading_only and an explicit sample_pattern are refused (unsupported); threads is unused.
struct FaceFrameOptions : experiments::FaceFrameOptions {
  SeamsOutput output = SeamsOutput::colour;
  int full_width = 0, full_height = 0, x0 = 0, y0 = 0;
};

/// A rendered frame: the backend's (image: resolved linear RGB, alpha = coverage, top-down,
/// empty without keep_image; ms = gpu_ms_draw + gpu_ms_resolve; wall_ms: vkQueueSubmit to the
/// fence, read-back excluded) and its parts.
struct FaceFrame : experiments::SeamsBackendFrame {
  double gpu_ms_draw = 0;     ///< Timestamps around the render pass (clear and draws).
  double gpu_ms_resolve = 0;  ///< Timestamps around vkCmdResolveImage (0 at 1x).
  int draw_calls = 0;         ///< One per face class with faces.
};

class FaceRenderer {
 public:
  /// Uploads `set` (vk::FaceTextureSet) and the mesh on `device`. `device`, `scene` and `set`
  /// must outlive the renderer. Fails with size_mismatch when the face counts differ,
  /// unsupported when the device lacks timestamps on its queue or R32G32B32A32_SFLOAT /
  /// D32_SFLOAT attachments.
  static Result<std::unique_ptr<FaceRenderer>> create(HeadlessDevice& device,
                                                      const faces::FaceScene& scene,
                                                      const faces::FaceTextureSet& set);
  ~FaceRenderer();
  FaceRenderer(const FaceRenderer&) = delete;
  FaceRenderer& operator=(const FaceRenderer&) = delete;

  /// Renders one frame; invalid_argument for a bad size, rate or filter, unsupported for a rate
  /// the device lacks, shading_only or an explicit sample pattern.
  Result<FaceFrame> render(const scene::Camera& camera, const FaceFrameOptions& options);
  /// Whether `samples` (1, 2, 4, 8, 16) is in the device's framebufferColorSampleCounts,
  /// framebufferDepthSampleCounts and the formats' sample counts.
  bool msaa_supported(int samples) const;
  /// VkPhysicalDeviceLimits::standardSampleLocations.
  bool standard_sample_locations() const;
  /// The paper's reference: Traverse at factor x factor the resolution in tiles, down-sampled
  /// by faces::downsample_mitchell (faces::render_reference_tiles, as the CPU and GL do).
  Result<ImageRGBAF> render_reference(const scene::Camera& camera, int width, int height,
                                      const faces::ReferenceOptions& options);
  int class_count() const;

  struct State;  ///< Internal (face_renderer.cpp, face_renderer_targets.cpp).

 private:
  FaceRenderer() = default;
  std::unique_ptr<State> s_;
};

}  // namespace tessera::vk
