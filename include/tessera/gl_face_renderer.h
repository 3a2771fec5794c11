// tessera/gl_face_renderer.h — the seams experiment (Toth 2013) drawn on the GPU: a
// per-face-textured quad mesh rendered with OpenGL 4.5 through
// share/tessera/glsl/seams_render.{vert,frag}, which
// `#include "seams.glsl"` (Clamp / Discard / Traverse / Traverse+corners), into a multisampled
// RGBA32F target, box-resolved in linear light and read back. Part of `tessera::gl` (built only
// where EGL/GL are found); every call needs the tessera GL context current on the calling
// thread (gl.h).
//
// The GL twin of `faces::FaceRenderer` (faces.h): the same frame, pixel for pixel where the
// drivers agree —
//  * the same clip-space vertices (computed on the CPU with the CPU renderer's arithmetic,
//    including its sub-rectangle remapping for tiled references), four unshared vertices per
//    face, triangles (0,1,2) and (0,2,3), back faces culled, depth test `less`;
//  * the same per-face UVs ((0,0), (1,0), (1,1), (0,1) at the face's vertices, interpolated
//    perspective-correctly per triangle) and smooth area-weighted vertex normals;
//  * shading once per pixel at the pixel centre (no centroid: a partially covered pixel may
//    look up a UV outside its face, which is what Discard's coverage channel is for), UV
//    gradients from fine 2x2-quad derivatives (dFdxFine/dFdyFine) including helper pixels,
//    the sampled colour times 0.35 + 0.65 max(N·L, 0) with L = (0.42, 0.82, 0.39), alpha 1,
//    background `faces::kFaceBackground` with alpha 0;
//  * image rows top-down with the CPU rasteriser's orientation: clip y is negated so GL's
//    framebuffer row 0 is the image's top row, which makes the driver's sample positions (Mesa
//    uses the Direct3D standard patterns in memory order) the CPU rasteriser's.
// Sample counts: GL allocates at least the samples asked for, and a driver may round a rate up
// to one it has (glRenderbufferStorageMultisample): Mesa 22.3 llvmpipe has only 4x, so a 2x
// frame is drawn with 4 samples at the 4x positions. `sample_pattern` reports what the driver
// gives (GL_SAMPLES, GL_SAMPLE_POSITION) and which CPU rate has the same positions; a
// like-for-like comparison renders the CPU frame at that rate (`SamplePattern::cpu_msaa`), or,
// where no standard pattern has them (possible on hardware GPUs), at the driver's own positions
// (`cpu_sample_offsets`, raster::FrameBufferDesc::sample_pattern); positions off the CPU's
// 1/16-pixel grid cannot be reproduced, and such a rate is not compared.
// Draw calls are grouped by face class (one GL_TEXTURE_2D_ARRAY per face resolution): the own
// face's lookup indexes the sampler array with a per-draw uniform (dynamically uniform, so it
// works without bindless or non-uniform indexing, e.g. on llvmpipe); neighbour lookups of
// Traverse go through seams.glsl's switch over the classes. Each (method, fallback, output)
// combination is its own compiled program, so a software rasteriser that executes both sides
// of every branch (llvmpipe) runs only the chosen method's code.
//
// Agreement with the CPU frame of the same sample positions: under trilinear filtering only
// rasterisation ties and the draw order (class-grouped here, face order on the CPU) differ;
// tests/gl/gl_face_renderer_test.cpp holds the bounds and docs/benchmarks/seams_gl.md the measured
// agreement. Hardware anisotropic filtering is implementation-defined (llvmpipe's is much
// blurrier than tessera's exact filter), so under it the frames agree far less.
//
// Timing: `gpu_ms_*` are GL_TIME_ELAPSED queries. On llvmpipe they do not cover the frame (the
// query commands are executed per screen tile by the rasteriser threads, so the timer grows
// more slowly with the pixel count than the wall time does; docs/benchmarks/seams_gl.md), so
// use `wall_ms` (ended by glFinish) there; on hardware GPUs the timer is the pass time.
// Tests: tests/gl/gl_face_renderer_test.cpp (against faces::FaceRenderer).
#pragma once

#include <filesystem>
#include <memory>
#include <vector>

#include "tessera/core.h"
#include "tessera/faces.h"
#include "tessera/gl.h"
#include "tessera/gl_faces.h"
#include "tessera/scene.h"

namespace tessera::gl {

/// One sample position of a GL framebuffer: the offset from the pixel centre in pixels, x right,
/// y down in the image (GL_SAMPLE_POSITION minus 0.5; the renderer's y flip makes GL's window y
/// the image's row order) — raster::SampleOffset / 16.
struct SamplePosition {
  float x = 0;
  float y = 0;
};

/// The samples a driver allocates for a requested MSAA rate.
struct SamplePattern {
  int requested = 1;  ///< The rate asked for.
  int samples = 1;    ///< GL_SAMPLES of the framebuffer, >= requested (llvmpipe: 4 for 2).
  /// GL_SAMPLE_POSITION of every sample in sample-index order; one {0, 0} single-sampled.
  std::vector<SamplePosition> positions;
  /// The CPU rasteriser's rate whose standard pattern (raster::sample_positions) is this set
  /// of positions (`matching_cpu_msaa`); 0 when none is.
  int cpu_msaa = 0;
};

/// The rate n in 1, 2, 4, 8, 16 whose raster::sample_positions(n), divided by 16, equals
/// `positions` as a set (order aside: the box resolve does not depend on it; within 1e-4
/// pixel); 0 when there is none. An empty list matches nothing.
int matching_cpu_msaa(const std::vector<SamplePosition>& positions);

/// `positions` on the CPU rasteriser's grid, in the same order: each offset times 16 rounded
/// to a raster::SampleOffset, so that the CPU can draw a frame at a driver's own positions
/// (raster::FrameBufferDesc::sample_pattern) when no standard pattern has them. Empty when the
/// pattern cannot be reproduced: no positions, more than raster::kMaxSamples (16), a coordinate
/// more than 1e-3 pixel from a multiple of 1/16 pixel, or one outside [-8, 7] sixteenths.
std::vector<raster::SampleOffset> cpu_sample_offsets(const std::vector<SamplePosition>& positions);

/// What the fragment shader writes.
enum class SeamsOutput {
  colour,         ///< Shaded linear RGB, alpha 1 (the frame).
  zero_coverage,  ///< 1 where the method's coverage Σw was 0 (Discard's fallback or NaN
                  ///< pixels), else 0; alpha 1; background (0,0,0,0). Resolved: the
                  ///< fraction of the pixel's samples that such fragments cover.
};

/// One frame's settings (the GL counterpart of faces::FaceRenderOptions).
struct FaceFrameOptions {
  int width = 480;  ///< The paper's frame size.
  int height = 540;
  int msaa = 1;  ///< 1, 2, 4 or 8 samples (8 is refused where GL_MAX_SAMPLES < 8); the
                 ///< driver may draw with more (FaceFrame::samples, sample_pattern).
  faces::SeamMethod method = faces::SeamMethod::discard;
  /// trilinear, or anisotropic (GL_TEXTURE_MAX_ANISOTROPY = max_aniso on both samplers).
  texture::TextureFilter filter = texture::TextureFilter::anisotropic;
  int max_aniso = 16;  ///< 1..16, clamped to the implementation's maximum.
  /// Discard's zero-coverage fallback (Listing 1, lines 13-15). Off: NaN where Σw = 0.
  bool clamp_fallback = true;
  SeamsOutput output = SeamsOutput::colour;
  /// Read the resolved frame back into `FaceFrame::image` (off: timing only).
  bool read_back = true;
  /// Sub-rectangle [x0, x0 + width) x [y0, y0 + height) of a virtual full_width x full_height
  /// image (as FaceRenderOptions: tiled references); 0 = the whole image.
  int full_width = 0, full_height = 0, x0 = 0, y0 = 0;
};

/// A rendered frame.
struct FaceFrame {
  /// Resolved linear RGB, alpha = geometry coverage (0 background .. 1 covered); top-down.
  /// Empty when `read_back` was off.
  ImageRGBAF image;
  double gpu_ms_draw = 0;     ///< GL_TIME_ELAPSED of the clear + class-grouped draws.
  double gpu_ms_resolve = 0;  ///< GL_TIME_ELAPSED of the MSAA box resolve (0 at 1x).
  double gpu_ms() const { return gpu_ms_draw + gpu_ms_resolve; }
  /// Wall time from the first GL call of the frame to glFinish after the resolve (vertex
  /// upload included, read-back excluded).
  double wall_ms = 0;
  int draw_calls = 0;  ///< One per face class with faces.
  /// Samples per pixel the frame was drawn with (`SamplePattern::samples` of the rate: more
  /// than `FaceFrameOptions::msaa` where the driver rounds the rate up).
  int samples = 1;
};

struct FaceRendererOptions {
  /// Development override: a folder read instead of the GLSL embedded in the library (see
  /// tessera/glsl.h). Empty (the default): $TESSERA_GLSL_DIR when set, else the embedded copy;
  /// no file is read.
  std::filesystem::path glsl_dir;
  faces::TexelFormat texels = faces::TexelFormat::rgba32f;
};

/// Draws a per-face-textured quad mesh with OpenGL. Owns the uploaded textures, the vertex
/// buffers, render targets (re-created when size or samples change) and one program per
/// shader variant (compiled on first use). Not thread-safe; one context.
class FaceRenderer {
 public:
  /// Uploads `textures` (FaceTextureSet::upload) and the mesh. `scene` and `textures` must
  /// outlive the renderer; face counts must match (size_mismatch). Fails (unsupported) when the
  /// face classes need more texture units than the fragment stage has (2 per class).
  static Result<std::unique_ptr<FaceRenderer>> create(const faces::FaceScene& scene,
                                                      const faces::FaceTextureSet& textures,
                                                      const FaceRendererOptions& options = {});
  ~FaceRenderer();
  FaceRenderer(const FaceRenderer&) = delete;
  FaceRenderer& operator=(const FaceRenderer&) = delete;

  /// Renders one frame. An MSAA rate the driver refuses fails with unsupported (see
  /// `msaa_supported`); a bad size or rate with invalid_argument.
  Result<FaceFrame> render(const scene::Camera& camera, const FaceFrameOptions& options);

  /// Whether an RGBA32F + depth framebuffer with `samples` samples is complete here (cached).
  bool msaa_supported(int samples);
  /// The rates of `rates` that the driver refuses (llvmpipe: 8 and above), in order.
  std::vector<int> refused_msaa(const std::vector<int>& rates);
  /// The sample count and positions the driver gives a target of `msaa` samples (RGBA32F +
  /// depth, as `render` draws into), queried once per rate on a small probe framebuffer.
  /// Fails with unsupported where the rate is refused, invalid_argument below 1.
  Result<SamplePattern> sample_pattern(int msaa);

  /// The paper's reference on the GPU: Traverse at `options.factor` x `options.factor` the
  /// resolution with `options.filter`, single-sampled, rendered in tiles of `options.tile`
  /// output pixels (plus a 2-pixel margin) and down-sampled on the CPU by
  /// faces::downsample_mitchell (B = C = 1/3, radius 2 output pixels, `options.threads`
  /// workers) — faces::FaceRenderer::render_reference's tiles and filter
  /// (faces::render_reference_tiles), with the same options.
  Result<ImageRGBAF> render_reference(const scene::Camera& camera, int width, int height,
                                      const faces::ReferenceOptions& options = {});

  const FaceTextureSet& textures() const;
  const std::filesystem::path& glsl_dir() const;

  struct State;  ///< Internal.

 private:
  FaceRenderer() = default;
  std::unique_ptr<State> state_;
};

}  // namespace tessera::gl
