// tessera/faces.h — per-face textures without seams: Clamp, Discard (Toth 2013), Traverse
// (McDonald 2013) and Traverse+corners, on quad meshes with one texture per face (Ptex style).
//
// What: `FaceTextureSet` (one mipmapped texture per face + adjacency), the seam methods
//   (`sample_face` and `sample_clamp` / `_discard` / `_traverse` / `_traverse_corners`), the
//   experiment's renderer `FaceRenderer` and its supersampled reference `render_reference`.
// Paper: Toth 2013, "Avoiding Texture Seams by Discarding Filter Taps", JCGT 2(2): Equation 6,
//   Listing 1, Figure 1. The layers (kernel, data, drivers) and the methods in full:
//   docs/architecture.md, "Per-face texturing: layers and methods".
// Where: src/faces/; GLSL twin share/tessera/glsl/seams.glsl; GL twin gl::FaceRenderer.
// Faces (Ptex's convention): vertices 0..3 at (u, v) = (0,0), (1,0), (1,1), (0,1); edge e joins
//   vertex e to e+1 (0: v = 0, 1: u = 1, 2: v = 1, 3: u = 0); texel row 0 is v = 0;
//   neighbours share an edge in opposite directions.
// Threads: all types are immutable after construction; sampling and rendering are const and
//   may run concurrently (a `FaceRenderer` owns a rasteriser: one per thread).
// Tests: tests/unit/faces_test.cpp (sampling, adjacency, the renderer),
// tests/gl/gl_face_renderer_test.cpp.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "tessera/core.h"
#include "tessera/math.h"
#include "tessera/raster.h"
#include "tessera/scene.h"
#include "tessera/texture.h"

namespace tessera::ptex {
struct PtexFile;
}

namespace tessera::faces {

// ---------------------------------------------------------------------------------------------
// Kernel: edge transforms
// ---------------------------------------------------------------------------------------------

/// 2x3 affine map of face UVs: u' = a u + b v + c, v' = d u + e v + f.
struct UvTransform {
  float a = 1, b = 0, c = 0;
  float d = 0, e = 1, f = 0;

  texture::Uv apply(texture::Uv p) const { return {a * p.u + b * p.v + c, d * p.u + e * p.v + f}; }
  /// The linear part applied to both gradient vectors (d/dx and d/dy).
  texture::UvGradients apply(const texture::UvGradients& g) const {
    return {a * g.dudx + b * g.dvdx, d * g.dudx + e * g.dvdx, a * g.dudy + b * g.dvdy,
            d * g.dudy + e * g.dvdy};
  }
  /// `next` after this: p -> next(this(p)).
  UvTransform then(const UvTransform& next) const;
};

/// The map from my face's UV space to the UV space of the neighbour across my edge `my_edge`,
/// whose shared edge is `neighbour_edge` (both 0..3). Points on the shared edge map to the same
/// surface point; points outside my edge map inside the neighbour (a rigid unfolding in
/// normalised units, rotations by multiples of 90 degrees plus reflections of the edge
/// parameter).
UvTransform edge_transform(int my_edge, int neighbour_edge);

/// All 16 transforms, indexed my_edge * 4 + neighbour_edge (the shader's constant table).
const std::array<UvTransform, 16>& edge_transform_table();

// ---------------------------------------------------------------------------------------------
// Data: meshes and adjacency
// ---------------------------------------------------------------------------------------------

/// Neighbours of one quad face.
struct FaceAdjacency {
  std::array<int, 4> face{-1, -1, -1, -1};  ///< Neighbour across edge e, -1 on a boundary.
  std::array<int, 4> edge{0, 0, 0, 0};      ///< The neighbour's shared edge (0..3).
};

/// The diagonal neighbour at a corner: the face across the vertex (valence 4 only).
struct CornerLink {
  int face = -1;          ///< -1 when the vertex is not an interior valence-4 vertex.
  UvTransform transform;  ///< My UV space -> the diagonal face's UV space.
};

/// A polygon mesh as read from OBJ: positions and faces of any vertex count.
struct PolygonMesh {
  std::vector<Vec3> positions;
  std::vector<std::vector<int>> faces;  ///< 0-based position indices.
};

/// An all-quad mesh.
struct QuadMesh {
  std::vector<Vec3> positions;
  std::vector<std::array<int, 4>> quads;  ///< Vertex indices in order 0..3 (see conventions).

  int face_count() const { return int(quads.size()); }
  /// Surface point of the bilinear patch of `face` at (u, v).
  Vec3 point(int face, texture::Uv uv) const;
};

/// Reads the `v` and `f` records of an OBJ file (other records ignored; negative indices
/// resolved). Fails with corrupt_data on malformed or out-of-range indices.
Result<PolygonMesh> load_obj_polygons(const std::string& path);

/// The quad mesh of `mesh`, or unsupported naming the first non-quad face ("face 12 has 3
/// vertices: only all-quad meshes are supported; split it into quads, e.g. one Catmull-Clark
/// step"). `name` prefixes the message.
Result<QuadMesh> to_quad_mesh(const PolygonMesh& mesh, const std::string& name);

/// The Ptex face layout of a polygon mesh: quads stay one face; an n-gon (n = 3 or n >= 5)
/// becomes n subfaces, subface i being the quad (corner i, midpoint of edge i, face centre,
/// midpoint of edge i-1) in face order — the layout of the Ptex samples' split faces (tests
/// check it against nonquad.ptx and pentagon.ptx). `subface` (optional) receives a flag per
/// output face.
QuadMesh ptex_face_layout(const PolygonMesh& mesh, std::vector<bool>* subface = nullptr);

/// Adjacency from a directed-edge map: my edge (a -> b) pairs with the neighbour's (b -> a).
/// Fails with invalid_argument on a degenerate quad, an edge used twice in the same direction
/// (inconsistent orientation or non-manifold) or an edge shared by more than two faces.
Result<std::vector<FaceAdjacency>> build_adjacency(const QuadMesh& mesh);

/// Diagonal links of every corner (4 per face, corner c = vertex c), found by walking around
/// each vertex through the adjacency: a vertex is valence 4 when four edge steps return to the
/// start face.
std::vector<std::array<CornerLink, 4>> corner_links(const std::vector<FaceAdjacency>& adjacency);

/// Counts of the 16 (my edge, neighbour edge) pairings over all interior edges, index
/// my_edge * 4 + neighbour_edge.
std::array<int, 16> edge_pairing_histogram(const std::vector<FaceAdjacency>& adjacency);

/// One linear subdivision step: every quad becomes 4 (edge midpoints and the face centre as new
/// vertices, shared between neighbours), orientation kept. Positions are not smoothed.
QuadMesh subdivide(const QuadMesh& mesh);

/// Rotates the vertex order of every quad by a pseudo-random 0..3 steps (winding unchanged),
/// so that all 16 edge pairings occur. Deterministic for a given seed.
void randomise_orientation(QuadMesh& mesh, std::uint32_t seed);

// ---------------------------------------------------------------------------------------------
// Data: per-face textures
// ---------------------------------------------------------------------------------------------

/// One mipmapped texture per face, the adjacency and the corner links.
class FaceTextureSet {
 public:
  FaceTextureSet() = default;

  /// Builds the set from linear RGB face images (alpha is replaced by the coverage channel 1)
  /// and the adjacency (sizes must match; neighbour indices in range). Mip chains are built
  /// on `parallel.threads` threads; the result does not depend on it.
  static Result<FaceTextureSet> create(const std::vector<ImageRGBAF>& images,
                                       std::vector<FaceAdjacency> adjacency,
                                       const Parallel& parallel = {});
  /// Builds the set from a decoded .ptx file: level-0 texels (1 channel -> grey, 2 -> grey
  /// and alpha ignored, 3+ -> RGB; u8/u16 data decoded from sRGB, half/float taken as linear)
  /// and the file's adjacency. Triangle meshes are refused (unsupported); subfaces of split
  /// non-quad faces are accepted as ordinary quads, except that an edge between a subface and
  /// a regular quad (a T-junction: one quad edge against two subface half-edges) becomes a
  /// border, since the full-edge transforms do not apply there.
  static Result<FaceTextureSet> from_ptex(const ptex::PtexFile& file, const std::string& name,
                                          const Parallel& parallel = {});

  int face_count() const { return int(textures_.size()); }
  const texture::Texture& texture(int face) const { return textures_[std::size_t(face)]; }
  const FaceAdjacency& adjacency(int face) const { return adjacency_[std::size_t(face)]; }
  const std::vector<FaceAdjacency>& adjacency() const { return adjacency_; }
  const CornerLink& corner(int face, int c) const {
    return corners_[std::size_t(face)][std::size_t(c)];
  }
  /// Corners (over all faces) with a valence-4 diagonal link.
  int linked_corner_count() const;
  /// Total texels of level 0 over all faces.
  std::uint64_t texel_count() const;

 private:
  std::vector<texture::Texture> textures_;
  std::vector<FaceAdjacency> adjacency_;
  std::vector<std::array<CornerLink, 4>> corners_;
};

// ---------------------------------------------------------------------------------------------
// Sampling methods
// ---------------------------------------------------------------------------------------------

enum class SeamMethod { clamp, discard, traverse, traverse_corners };

/// All methods in a fixed order.
const std::vector<SeamMethod>& all_methods();
/// "clamp", "discard", "traverse", "traverse_corners".
const char* method_name(SeamMethod m);
/// Parses a method name; false if unknown.
bool parse_method(const std::string& text, SeamMethod& out);

struct SampleOptions {
  SeamMethod method = SeamMethod::discard;
  texture::TextureFilter filter =
      texture::TextureFilter::anisotropic;  ///< trilinear or anisotropic.
  int max_aniso = 16;                       ///< 1..16.
  /// The paper's zero-coverage fallback (clamp lookup). Off: 0/0 gives NaN.
  bool clamp_fallback = true;
};

/// Filtered colour of face `face` at `uv` by `options.method` (one of the four functions
/// below), with UV gradients per pixel in normalised units of that face. Returns linear RGB
/// and, in [3], the coverage Σw that was divided out (1 for clamp; after a fallback, 0).
std::array<float, 4> sample_face(const FaceTextureSet& set, int face, texture::Uv uv,
                                 const texture::UvGradients& gradients,
                                 const SampleOptions& options);

// The four methods, named as their GLSL twins in share/tessera/glsl/seams.glsl
// (tessera_seams_sample_clamp / _discard / _traverse / _traverse_corners); `options.method` is
// not read. Arguments and result as `sample_face`'s.

/// Clamp: the face alone with clamp-to-edge addressing (the seam-artefact baseline).
std::array<float, 4> sample_clamp(const FaceTextureSet& set, int face, texture::Uv uv,
                                  const texture::UvGradients& gradients,
                                  const SampleOptions& options);
/// Discard (Toth 2013): the face's taps with a zero border, the taps outside the face divided
/// out; no covered tap: the clamp fallback (or NaN without `clamp_fallback`).
std::array<float, 4> sample_discard(const FaceTextureSet& set, int face, texture::Uv uv,
                                    const texture::UvGradients& gradients,
                                    const SampleOptions& options);
/// Traverse (McDonald 2013, Listing 1): the face and its four edge neighbours, normalised.
std::array<float, 4> sample_traverse(const FaceTextureSet& set, int face, texture::Uv uv,
                                     const texture::UvGradients& gradients,
                                     const SampleOptions& options);
/// Traverse plus the diagonal face at each valence-4 corner.
std::array<float, 4> sample_traverse_corners(const FaceTextureSet& set, int face, texture::Uv uv,
                                             const texture::UvGradients& gradients,
                                             const SampleOptions& options);

// ---------------------------------------------------------------------------------------------
// Scenes
// ---------------------------------------------------------------------------------------------

/// The continuous procedural 3D colour function the Figure-1 textures are baked from (linear
/// RGB in [0, 1]): coloured value noise with stripes, band-limited at about `1 / scale`.
std::array<float, 3> procedural_colour(const Vec3& p, float scale = 1.0f);

/// A quad mesh with per-face texture resolutions (log2 per side).
struct FaceScene {
  std::string name;
  QuadMesh mesh;
  std::vector<int> ulog2, vlog2;
  int ground_faces = 0;  ///< Faces of the ground plane (the first ones), 0 if none.
};

struct Figure1Options {
  int ground = 32;     ///< Ground plane of ground x ground quads.
  int character = 16;  ///< Character: a deformed cube-sphere of 6 x n x n quads.
  /// Optional character mesh used instead of the cube-sphere (e.g. the Ptex teapot after one
  /// `subdivide` step); it is scaled to stand 2 units tall at the centre of the ground.
  QuadMesh character_mesh;
  float texels_per_unit = 48.0f;   ///< Texel density setting the face resolutions.
  int min_log2 = 2, max_log2 = 7;  ///< Face side between 2^min and 2^max texels.
  std::uint32_t seed = 1;          ///< Face orientations.
};

/// The Figure-1-like scene: a ground plane and a blobby character made of quads, every face's
/// vertex order randomly rotated, per-side resolutions from the face's edge lengths.
FaceScene figure1_scene(const Figure1Options& options = {});

/// Per-side resolutions for an arbitrary quad mesh: 2^round(log2(edge length x density)),
/// clamped, so neighbouring faces may differ and faces may be non-square.
void assign_resolutions(FaceScene& scene, float texels_per_unit, int min_log2, int max_log2);

/// Options of `bake_faces`.
struct BakeOptions {
  float scale = 1.0f;  ///< `procedural_colour`'s scale (detail at about 1 / scale world units).
  int threads = 0;     ///< 0 = all hardware threads; results do not depend on it.
};

/// Bakes each face's texture: texel (x, y) = procedural_colour(p, options.scale) of the surface
/// point p at the texel centre (so the seamless truth is known). Linear RGBA, alpha 1.
std::vector<ImageRGBAF> bake_faces(const FaceScene& scene, const BakeOptions& options = {});

// ---------------------------------------------------------------------------------------------
// Rendering
// ---------------------------------------------------------------------------------------------

struct FaceRenderOptions {
  int width = 480;
  int height = 540;
  int msaa = 1;  ///< 1, 2, 4, 8, 16 (with `sample_pattern`: its size, 1..16).
  /// Explicit sample positions (raster::FrameBufferDesc::sample_pattern: `msaa` offsets in
  /// 1/16 pixel, each in [-8, 7]); empty = the standard pattern of `msaa`. Used to draw at a
  /// GPU driver's own positions when they are none of the standard patterns.
  std::vector<raster::SampleOffset> sample_pattern;
  SampleOptions sampling;
  bool shading_only = false;  ///< Lighting without the texture lookup (the shading cost).
  /// With `shading_only`: output unlit white for faces >= this index and black below (a
  /// coverage mask of e.g. the character); -1 = off.
  int mask_faces_from = -1;
  /// Output the covering face's index + 1 in R, G and B (exact in float up to 2^24 faces) and
  /// coverage in alpha, instead of a shaded colour: with `msaa` 1, a face-id image (where the
  /// seams are on screen; `experiments::run_seams` counts errors near them).
  bool face_ids = false;
  int threads = 0;
  /// Sub-rectangle [x0, x0 + w) x [y0, y0 + h) of a virtual full_width x full_height image
  /// that this frame shows (used to render the reference in tiles); 0 = the whole image.
  int full_width = 0, full_height = 0, x0 = 0, y0 = 0;
};

/// A resolved frame: linear RGB, alpha = geometry coverage (0 background .. 1 covered).
struct FaceFrame {
  ImageRGBAF image;
  raster::RasterStats stats;
  double ms_raster = 0;   ///< Rasterisation and shading.
  double ms_resolve = 0;  ///< MSAA box resolve.
  double ms() const { return ms_raster + ms_resolve; }
};

/// Linear RGB background of face renders.
inline constexpr std::array<float, 3> kFaceBackground = {0.45f, 0.55f, 0.7f};

/// Settings of the paper's reference frame: `FaceRenderer::render_reference`, its GL twin
/// `gl::FaceRenderer::render_reference` and `experiments::SeamsBackend::render_reference`.
struct ReferenceOptions {
  int factor = 8;  ///< Supersampling factor per axis, 1..16 (factor x factor the resolution).
  /// Texture filter of the Traverse lookups: anisotropic (16x, the paper's reference) or
  /// trilinear.
  texture::TextureFilter filter = texture::TextureFilter::anisotropic;
  int threads = 0;  ///< CPU worker threads (0 = all; GL: for the down-sampling); results do
                    ///< not depend on it.
  int tile = 96;    ///< Tile side in output pixels (>= 1): bounds the supersampled grid's memory.
};

/// Draws a textured quad mesh. Not thread-safe (owns a rasteriser and frame buffer).
class FaceRenderer {
 public:
  /// `scene` and `textures` must outlive the renderer; face counts must match.
  static Result<std::unique_ptr<FaceRenderer>> create(const FaceScene& scene,
                                                      const FaceTextureSet& textures);
  ~FaceRenderer();

  /// Renders one frame of the mesh from `camera` as `options` asks (method, filter, MSAA).
  Result<FaceFrame> render(const scene::Camera& camera, const FaceRenderOptions& options);

  /// The paper's reference: Traverse (16x anisotropic by default, `options.filter`) at
  /// `options.factor` x `options.factor` the resolution, downsampled with the
  /// Mitchell-Netravali filter (B = C = 1/3, radius 2 output pixels), rendered in tiles of
  /// `options.tile` output pixels so memory stays bounded. Fails with invalid_argument on a
  /// bad size, factor or tile.
  Result<ImageRGBAF> render_reference(const scene::Camera& camera, int width, int height,
                                      const ReferenceOptions& options = {});

 private:
  FaceRenderer() = default;
  const FaceScene* scene_ = nullptr;
  const FaceTextureSet* textures_ = nullptr;
  std::vector<float> clip_;      // 4 floats per face-vertex (4 vertices per face)
  std::vector<float> varyings_;  // u, v, nx, ny, nz per face-vertex
  std::vector<std::uint32_t> indices_;
  raster::Rasteriser rasteriser_;
  raster::FrameBuffer fb_;
};

// ---------------------------------------------------------------------------------------------
// Host set-up shared by the CPU renderer and its GPU twins (gl::FaceRenderer, the Vulkan one)
// ---------------------------------------------------------------------------------------------

/// Smooth vertex normals of a quad mesh, one per face vertex (4 per face, face-major): the
/// normalised sum of the area-weighted normals (cross product of the diagonals) of the faces at
/// the vertex's position.
std::vector<Vec3> smooth_face_normals(const QuadMesh& mesh);

/// The part of the image a frame shows: the sub-rectangle [x0, x0 + width) x [y0, y0 + height)
/// of a virtual full_width x full_height image (0 = the whole image); FaceRenderOptions' fields.
struct FrameWindow {
  int width = 0, height = 0;
  int full_width = 0, full_height = 0, x0 = 0, y0 = 0;
};

/// The window of a frame's options (FaceRenderOptions, gl::FaceFrameOptions: fields width,
/// height, full_width, full_height, x0, y0).
template <typename Options>
FrameWindow frame_window(const Options& o) {
  return {o.width, o.height, o.full_width, o.full_height, o.x0, o.y0};
}

/// Sets the window fields of a frame's options to `w`.
template <typename Options>
void set_frame_window(Options& o, const FrameWindow& w) {
  o.width = w.width;
  o.height = w.height;
  o.full_width = w.full_width;
  o.full_height = w.full_height;
  o.x0 = w.x0;
  o.y0 = w.y0;
}

/// Clip-space positions (x, y, z, w) of every face vertex, 4 vertices per face, for `camera`
/// and `window`: the full image's projection remapped to the window. `out` holds 16 floats per
/// face.
void face_clip_positions(const QuadMesh& mesh, const scene::Camera& camera,
                         const FrameWindow& window, std::span<float> out);

/// Renders one tile of a reference: the frame `window` (Traverse, single-sampled, the
/// supersampled grid), returning its image.
using ReferenceTileFn = std::function<Result<ImageRGBAF>(const FrameWindow& window)>;

/// The reference of `FaceRenderer::render_reference` and its GL twin, given the renderer: the
/// output in tiles of `options.tile` pixels, each rendered by `render_tile` at `options.factor`
/// times the resolution with a 2-pixel margin and reduced by `downsample_mitchell`. Fails with
/// invalid_argument on a bad size, factor or tile, or with `render_tile`'s error.
Result<ImageRGBAF> render_reference_tiles(int width, int height, const ReferenceOptions& options,
                                          const ReferenceTileFn& render_tile);

/// The reference of a GPU twin (gl::FaceRenderer, the Vulkan face renderer) through
/// `render_reference_tiles`: each tile is `renderer.render(camera, o)` of frame options
/// `Options` (fields method, filter, max_aniso, msaa and the FrameWindow fields) set to
/// Traverse, `options.filter` at 16x, single-sampled, and the tile's window; the frame's
/// `image` is the tile.
template <typename Options, typename Renderer>
Result<ImageRGBAF> render_reference_with(Renderer& renderer, const scene::Camera& camera, int width,
                                         int height, const ReferenceOptions& options) {
  Options o;
  o.method = SeamMethod::traverse;
  o.filter = options.filter;
  o.max_aniso = 16;
  o.msaa = 1;
  const ReferenceTileFn tile = [&](const FrameWindow& w) -> Result<ImageRGBAF> {
    set_frame_window(o, w);
    auto frame = renderer.render(camera, o);
    if (!frame) return frame.status();
    return std::move(frame->image);
  };
  return render_reference_tiles(width, height, options, tile);
}

/// Separable Mitchell-Netravali down-sampling (B = C = 1/3) of a supersampled grid by `factor`:
/// output pixel x reads grid columns [(x - margin) * factor, (x + margin) * factor) of a grid
/// that starts `margin` output pixels before the output's first pixel, with normalised weights.
/// `grid` must be ((width + 2 margin) factor) x ((height + 2 margin) factor); margin = 2
/// (`kReferenceMargin`). Fails with size_mismatch otherwise. Identical for any thread count.
Result<ImageRGBAF> downsample_mitchell(const ImageRGBAF& grid, int factor, int width, int height,
                                       const Parallel& parallel = {});

/// The margin of a reference tile, in output pixels: the Mitchell-Netravali support.
inline constexpr int kReferenceMargin = 2;

/// Mitchell-Netravali kernel with parameters B, C at distance x (support |x| < 2).
float mitchell_netravali(float x, float b = 1.0f / 3.0f, float c = 1.0f / 3.0f);

/// Camera on an orbit around a face scene (`scene::orbit_camera` on its bounds), frame
/// `frame` of `frames`, looking at the character's centre from a little above.
scene::Camera face_orbit_camera(const FaceScene& scene, int frame, int frames);

}  // namespace tessera::faces
