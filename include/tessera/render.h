// tessera/render.h — drawing scenes with the software rasteriser.
//
// `SceneRenderer` is the forward-rendering driver of the rendering core: it owns the scene's
// textures as mipmapped linear-light `texture::Texture`s (built once), transforms every mesh to
// clip space per frame, and rasterises it with an unlit material — the base-colour factor times
// the base-colour texture, sampled trilinear or anisotropically with the UV derivatives of the
// 2x2 quad (`textureGrad`), wrap addressing. It is the reference workload of the llvmpipe
// comparison: tools/glpeer renders the same frame with the same conventions through OpenGL.
//
// Conventions shared with tools/glpeer: OpenGL clip space, counter-clockwise front faces, no
// culling (glTF materials are double-sided in the test scenes), depth test less, background
// `kBackground` (linear), colour resolved with a box filter in linear light, encoded to sRGB.
// Tests: tests/unit/raster_output_test.cpp, scene_test.cpp; tests/cli/cli_test.py (tessera render).
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "tessera/raster.h"
#include "tessera/scene.h"
#include "tessera/texture.h"

namespace tessera::render {

/// Linear RGB clear colour of every rendered frame (also used by tools/glpeer).
inline constexpr std::array<float, 4> kBackground = {0.05f, 0.05f, 0.08f, 1.0f};

/// A draw call for one scene mesh: clip-space positions `clip` (4 floats per vertex),
/// `varying_count` floats per vertex in `varyings`, the mesh's indices, no culling (the test
/// scenes' materials are double-sided), primitive ids from `primitive_id_base`. The shader is
/// left empty for the caller. Arrays are borrowed (see raster::DrawCall).
raster::DrawCall mesh_draw(const scene::Mesh& mesh, const float* clip, const float* varyings,
                           int varying_count, std::uint32_t primitive_id_base);

/// Builds the mipmapped linear-light textures of every scene texture (sRGB ones decoded before
/// filtering), in scene order. Fails on the first texture that cannot be built.
Result<std::vector<texture::Texture>> build_scene_textures(const scene::Scene& scene,
                                                           const Parallel& parallel = {});

/// Texture filtering of the unlit material.
enum class Filter { trilinear, aniso16 };

/// What the unlit material outputs.
enum class Shading {
  textured,  ///< base colour factor x base-colour texture.
  flat,      ///< constant white: isolates coverage (for rasteriser comparisons).
};

/// Per-frame settings.
struct FrameOptions {
  int width = 1024;
  int height = 768;
  int msaa = 1;  ///< 1, 2, 4, 8 or 16 samples per pixel (D3D standard positions).
  int ssaa = 1;  ///< m: m x m shaded samples per pixel (combinable with msaa).
  Filter filter = Filter::trilinear;
  Shading shading = Shading::textured;
  int threads = 0;  ///< 0 = all hardware threads; output identical for any value.
};

/// Result of one frame.
struct Frame {
  ImageRGBA8 image;  ///< Resolved, sRGB-encoded.
  raster::RasterStats stats;
  double ms_transform = 0;  ///< Vertex transform time.
  double ms_raster = 0;     ///< Rasterisation + shading time.
  double ms_resolve = 0;    ///< Box resolve + sRGB encode time.
  double ms_total() const { return ms_transform + ms_raster + ms_resolve; }
};

/// Renders frames of one scene. Construction builds textures (the expensive part); `render`
/// reuses them and the rasteriser's scratch memory. Not thread-safe: one renderer per thread
/// (each frame is itself parallel).
class SceneRenderer {
 public:
  /// Builds the renderer (its textures on `parallel.threads` threads); fails if a texture
  /// cannot be built. `scene` must outlive it.
  static Result<std::unique_ptr<SceneRenderer>> create(const scene::Scene& scene,
                                                       const Parallel& parallel = {});
  ~SceneRenderer();

  /// Renders one frame from `camera`.
  Result<Frame> render(const scene::Camera& camera, const FrameOptions& options);

 private:
  SceneRenderer() = default;
  const scene::Scene* scene_ = nullptr;
  std::vector<texture::Texture> textures_;
  std::vector<std::vector<float>> clip_;      // per mesh: 4 floats per vertex
  std::vector<std::vector<float>> varyings_;  // per mesh: u, v per vertex
  raster::Rasteriser rasteriser_;
  raster::FrameBuffer fb_;
};

}  // namespace tessera::render
