// tessera/raster.h — the software rasteriser of the rendering core.
//
// A tile-binned, multithreaded triangle rasteriser that behaves like a GPU where it matters for
// anti-aliasing and texture-filtering studies:
//  * clip-space triangles, homogeneous near/far clipping, guard-band clipping for x/y;
//  * 8 sub-pixel bits of fixed-point vertex snapping and exact integer edge functions with the
//    Direct3D top-left fill rule (watertight: adjacent triangles never crack or double-cover);
//  * MSAA 1/2/4/8/16 with the Direct3D 11 standard sample positions and a per-sample coverage
//    mask; shading once per pixel per triangle (at the pixel centre, or the centroid); or any
//    explicit pattern of 1..16 positions on the 1/16-pixel grid (`FrameBufferDesc::
//    sample_pattern`: a GPU driver's own positions, to compare with its frames like for like);
//  * supersampling m x m: the frame buffer is a (m*w) x (m*h) grid ("G-buffer view") in which
//    every grid pixel is shaded, box-resolved to w x h; MSAA and supersampling may combine;
//  * shading in 2x2 quads: every varying is interpolated (perspective-correct) at all four quad
//    pixels, including helper pixels outside the triangle, and ddx/ddy are the finite
//    differences inside the quad, as on a GPU (fine derivatives by default, coarse on request).
//    Helper lanes are not passed to the shader unless `RasterOptions::shade_helpers` is set;
//    their varyings still feed the derivatives, and every lane's varyings are visible to the
//    shader (`ShadeInput::quad_varyings`) for derivatives of shader-computed values;
//  * depth per sample (interpolated at each sample position), early depth test, depth write;
//  * a generic per-sample payload of 1..16 float channels, so the same machinery renders colour
//    (4 channels, linear RGBA) or a G-buffer (depth, normal, material, UV, UV derivatives, ...).
//
// Coordinate conventions
//  * Clip space: right-handed OpenGL style by default (-w <= z <= w, see `ClipDepth`); NDC y
//    points up. Window ("grid") coordinates have the origin at the top-left corner of the
//    top-left grid pixel, x right, y down, one unit per grid pixel; pixel (x, y) has its centre at
//    (x + 0.5, y + 0.5). The stored depth is the window depth in [0, 1] (0 = near plane).
//  * Sample positions are offsets from the pixel centre in 1/16 pixel, x right, y down (the
//    Direct3D convention), see `sample_positions` and `FrameBuffer::sample_offsets`.
//  * Front faces are counter-clockwise in NDC (y up) unless `DrawCall::front_ccw` is false.
//
// Pipeline (geometry stage, then raster stage over tiles): src/raster/rasterizer.cpp.
//
// Determinism and threads: triangles are binned into 64x64 grid-pixel tiles; every tile is
// rasterised by exactly one task, visiting its triangles in submission order (draw order, then
// index order). Frame buffers are therefore bit-identical for any `RasterOptions::threads`.
// A `Rasteriser` is not thread-safe (it owns scratch memory); use one per thread. Shaders are
// called concurrently from several threads and must be thread-safe (pure functions of their
// input plus read-only state).
// Tests: tests/unit/raster_test.cpp, raster_output_test.cpp, raster_sample_pattern_test.cpp.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "tessera/core.h"

namespace tessera::raster {

/// Largest number of float varyings per vertex.
inline constexpr int kMaxVaryings = 16;
/// Largest number of float channels per frame-buffer sample (the shader output size).
inline constexpr int kMaxChannels = 16;
/// Sub-pixel precision of vertex snapping: positions are rounded to 1/256 grid pixel.
inline constexpr int kSubpixelBits = 8;
/// Side of the square screen tiles (in grid pixels) that triangles are binned into.
inline constexpr int kTileSize = 64;
/// Value of a cleared per-sample primitive id ("no primitive").
inline constexpr std::uint32_t kNoPrimitive = 0xFFFFFFFFu;

/// One MSAA sample position: offset from the pixel centre in 1/16 pixel units (x right, y
/// down), each in [-8, 7].
struct SampleOffset {
  int x = 0;
  int y = 0;
  bool operator==(const SampleOffset&) const = default;
};

/// The Direct3D 11 standard multisample pattern (D3D11_STANDARD_MULTISAMPLE_PATTERN) for
/// `count` = 1, 2, 4, 8 or 16 samples, in sample-index order; an empty span for any other count.
/// Sample `s` of a pixel is bit `s` of every coverage mask.
std::span<const SampleOffset> sample_positions(int count);

/// True for the supported MSAA rates 1, 2, 4, 8 and 16 (the rates with a standard pattern).
bool valid_msaa(int count);

/// Most samples per pixel (coverage masks have 16 bits); an explicit pattern has 1..16.
inline constexpr int kMaxSamples = 16;

// ---------------------------------------------------------------------------------------------
// Frame buffer
// ---------------------------------------------------------------------------------------------

/// What a clear writes: `FrameBuffer::clear`, and the optional clear done by each tile task of
/// `Rasteriser::render` before it rasterises (cache-friendly, parallel).
struct ClearValues {
  std::array<float, kMaxChannels> value{};  ///< First `channels` entries are used.
  float depth = 1.0f;
};

/// Shape of a frame buffer. Output size `width` x `height`; the rasterised grid is
/// (`ssaa`*width) x (`ssaa`*height) grid pixels with `msaa` samples each.
struct FrameBufferDesc {
  int width = 0;   ///< Output (resolved) width in pixels, >= 1.
  int height = 0;  ///< Output (resolved) height in pixels, >= 1.
  /// Samples per grid pixel: 1, 2, 4, 8 or 16 at the D3D standard positions; with an explicit
  /// `sample_pattern`, 1..kMaxSamples at those positions.
  int msaa = 1;
  int ssaa = 1;      ///< Supersampling factor m in [1, 8]: m x m grid pixels per output pixel.
  int channels = 4;  ///< Float channels per sample, 1..kMaxChannels (4 = linear RGBA colour).
  bool primitive_ids = false;    ///< Keep a per-sample primitive id (`kNoPrimitive` if none).
  bool coverage_counts = false;  ///< Count, per sample, every triangle that covered it (any
                                 ///< depth): a watertightness diagnostic.
  /// Explicit sample positions, in sample-index order (sample s is bit s of the coverage
  /// masks). Empty (the default): the standard pattern `sample_positions(msaa)`, bit-identical
  /// to a buffer without this field. Otherwise exactly `msaa` offsets, each coordinate in
  /// [-8, 7] (inside the pixel: the rasteriser's conservative 8x8-block bounds rely on it);
  /// duplicates are allowed. For drawing at another renderer's positions, e.g. a GPU driver's
  /// that match no standard pattern. Coverage, per-sample depth and centroid shading use these
  /// positions; the resolve is the plain mean of the samples, whatever their positions.
  std::vector<SampleOffset> sample_pattern;
};

/// Per-sample render target: `channels` floats, a depth and optionally a primitive id and a
/// coverage count per sample. Storage is row-major over the grid, samples of one grid pixel
/// adjacent: sample s of grid pixel (x, y) has index ((y * grid_width + x) * msaa + s).
/// Movable, not copyable (use `clone`). Not thread-safe for concurrent writes.
class FrameBuffer {
 public:
  FrameBuffer() = default;
  /// Validates `desc` (sizes against the image limits, including the grid; the rate, or the
  /// explicit pattern's size and offsets) and allocates. Fails with invalid_argument naming the
  /// problem.
  static Result<FrameBuffer> create(const FrameBufferDesc& desc);

  const FrameBufferDesc& desc() const { return desc_; }
  int width() const { return desc_.width; }
  int height() const { return desc_.height; }
  int grid_width() const { return desc_.width * desc_.ssaa; }
  int grid_height() const { return desc_.height * desc_.ssaa; }
  int msaa() const { return desc_.msaa; }
  int ssaa() const { return desc_.ssaa; }
  int channels() const { return desc_.channels; }
  /// The sample positions in effect, `msaa` of them in sample-index order: the description's
  /// explicit `sample_pattern`, or the standard pattern for `msaa` when that is empty. Valid
  /// while the frame buffer lives (it moves with the buffer).
  std::span<const SampleOffset> sample_offsets() const {
    return desc_.sample_pattern.empty() ? sample_positions(desc_.msaa)
                                        : std::span<const SampleOffset>(desc_.sample_pattern);
  }
  /// Total samples: grid_width * grid_height * msaa.
  std::size_t sample_count() const { return depth_.size(); }
  std::size_t sample_index(int gx, int gy, int s) const {
    return (std::size_t(gy) * std::size_t(grid_width()) + std::size_t(gx)) *
               std::size_t(desc_.msaa) +
           std::size_t(s);
  }

  /// The `channels` floats of one sample.
  float* data(int gx, int gy, int s) { return &data_[sample_index(gx, gy, s) * desc_.channels]; }
  const float* data(int gx, int gy, int s) const {
    return &data_[sample_index(gx, gy, s) * desc_.channels];
  }
  float depth(int gx, int gy, int s) const { return depth_[sample_index(gx, gy, s)]; }
  /// Primitive id of the sample (`kNoPrimitive` when cleared); requires `primitive_ids`.
  std::uint32_t primitive_id(int gx, int gy, int s) const { return ids_[sample_index(gx, gy, s)]; }
  /// Number of triangles that covered the sample since the last clear; requires
  /// `coverage_counts`.
  std::uint32_t coverage_count(int gx, int gy, int s) const {
    return counts_[sample_index(gx, gy, s)];
  }

  /// Raw arrays (indexed by `sample_index`; `data` additionally by channel).
  std::span<float> data() { return data_; }
  std::span<const float> data() const { return data_; }
  std::span<float> depth_data() { return depth_; }
  std::span<const float> depth_data() const { return depth_; }
  /// Per-sample ids / counts; empty unless enabled in the description.
  std::span<std::uint32_t> primitive_id_data() { return ids_; }
  std::span<const std::uint32_t> primitive_id_data() const { return ids_; }
  std::span<std::uint32_t> coverage_count_data() { return counts_; }
  std::span<const std::uint32_t> coverage_count_data() const { return counts_; }

  /// Sets every sample to `values.value` (its first `channels` floats), depth to
  /// `values.depth`, ids to `kNoPrimitive` and coverage counts to 0.
  void clear(const ClearValues& values = {}, const Parallel& parallel = {});
  /// Clears the grid rectangle [x0, x1) x [y0, y1) (used per tile by the rasteriser).
  void clear_rect(int x0, int y0, int x1, int y1, const float* value, float depth);

  /// A deep copy (copying is explicit because frame buffers are large).
  FrameBuffer clone() const { return FrameBuffer(*this); }

  FrameBuffer(FrameBuffer&&) noexcept = default;
  FrameBuffer& operator=(FrameBuffer&&) noexcept = default;

 private:
  FrameBuffer(const FrameBuffer&) = default;
  FrameBuffer& operator=(const FrameBuffer&) = default;

  FrameBufferDesc desc_;
  std::vector<float> data_;
  std::vector<float> depth_;
  std::vector<std::uint32_t> ids_;
  std::vector<std::uint32_t> counts_;
};

/// Box resolve: every output pixel is the mean of its ssaa x ssaa grid pixels' msaa samples.
/// Channels 0..3 become RGBA; with fewer than 4 channels the missing colour channels are 0 and
/// alpha is 1. Deterministic for any `parallel.threads`.
ImageRGBAF resolve(const FrameBuffer& fb, const Parallel& parallel = {});
/// Box resolve to 8-bit sRGB: bit-identical to `to_srgb8(resolve(fb))` (a table-driven exact
/// encoder avoids the per-channel pow). Channels 0..2 are linear RGB, channel 3 linear alpha.
ImageRGBA8 resolve_srgb8(const FrameBuffer& fb, const Parallel& parallel = {});
/// Box resolve of all channels: `channels` floats per output pixel, row-major.
std::vector<float> resolve_channels(const FrameBuffer& fb, const Parallel& parallel = {});

// ---------------------------------------------------------------------------------------------
// Shading
// ---------------------------------------------------------------------------------------------

/// What a shader sees for one pixel (one lane of a 2x2 quad). Pointers are valid only during
/// the call. Lanes are numbered 2 * row + column inside the quad (0 = top-left).
struct ShadeInput {
  /// Perspective-correct varyings at the shading position (`varying_count` floats).
  const float* varyings = nullptr;
  /// Screen-space derivatives per grid pixel: d(varying)/dx and d(varying)/dy, the finite
  /// differences of the pixel-centre values across the quad (fine or coarse, see
  /// `RasterOptions::derivatives`). Helper lanes take part, so derivatives are defined on
  /// triangle edges exactly like a GPU's.
  const float* ddx = nullptr;
  const float* ddy = nullptr;
  /// Pixel-centre varyings of all four quad lanes, for derivatives of values the shader
  /// computes itself (f(quad_varyings[1]) - f(quad_varyings[0]) is ddx_coarse of f).
  std::array<const float*, 4> quad_varyings{};
  int varying_count = 0;
  float x = 0, y = 0;  ///< Shading position in grid coordinates (pixel centre, or centroid).
  float depth = 0;     ///< Window depth in [0, 1] at the shading position.
  float inv_w = 0;     ///< 1 / w_clip at the shading position.
  int px = 0, py = 0;  ///< Grid pixel.
  int lane = 0;        ///< Quad lane 0..3.
  std::uint32_t primitive_id = 0;  ///< DrawCall::primitive_id_base + triangle index.
  std::uint32_t coverage = 0;      ///< Raster coverage mask of this pixel (bit s = sample s).
  std::uint32_t visible = 0;       ///< Samples of `coverage` that passed the depth test.
  bool helper = false;             ///< No visible sample: outputs are discarded.
  bool front_facing = true;
};

/// A material: writes `channels` floats (pre-filled with zeros) for one pixel. For colour, the
/// first four are linear RGBA. Called concurrently from worker threads; must be thread-safe.
using ShadeFn = std::function<void(const ShadeInput& in, float* out)>;

/// A material that shades a whole 2x2 quad per call: one indirect call per quad instead of
/// one per pixel, and room for quad-wide work (shared texture set-up, SIMD across lanes).
/// `lanes[i]` is exactly what a `ShadeFn` would see for lane i; the shader must write the
/// `channels` floats of every lane whose bit is set in `active`, at `out + i * kMaxChannels`
/// (pre-filled with zeros); other lanes' inputs are unspecified and their outputs are ignored.
/// Results must be the same as shading each active lane alone (the rasteriser may call either
/// form). Called concurrently from worker threads; must be thread-safe.
using QuadShadeFn = std::function<void(const ShadeInput* lanes, std::uint32_t active, float* out)>;

// ---------------------------------------------------------------------------------------------
// Draw calls
// ---------------------------------------------------------------------------------------------

enum class CullMode { none, back, front };
enum class DepthTest { less, less_equal, equal, always };
/// Depth range of clip space: OpenGL (-w <= z <= w, near at z = -w) or Direct3D/Vulkan
/// (0 <= z <= w, near at z = 0). Window depth is (z/w + 1)/2 or z/w respectively.
enum class ClipDepth { negative_one_to_one, zero_to_one };

/// One draw: triangles from vertex arrays, rendered with one shader and pipeline state.
/// Arrays are borrowed: they must stay valid until `Rasteriser::render` returns.
struct DrawCall {
  const float* positions = nullptr;  ///< Clip-space x, y, z, w per vertex (4 floats each).
  const float* varyings = nullptr;   ///< `varying_count` floats per vertex (may be null if 0).
  int varying_count = 0;             ///< 0..kMaxVaryings.
  std::size_t vertex_count = 0;
  /// Three indices per triangle; null = non-indexed (vertex_count / 3 triangles).
  const std::uint32_t* indices = nullptr;
  std::size_t index_count = 0;
  ShadeFn shader;  ///< Null = output zeros (depth-only pass).
  /// Per-quad form of the material; when set it is used instead of `shader`.
  QuadShadeFn quad_shader;
  std::uint32_t primitive_id_base = 0;
  CullMode cull = CullMode::back;
  bool front_ccw = true;  ///< Counter-clockwise in NDC is front.
  DepthTest depth_test = DepthTest::less;
  bool depth_write = true;
  /// Centroid interpolation: partially covered pixels shade at the covered sample nearest the
  /// pixel centre (lowest index on ties) instead of the centre. Derivatives still come from the
  /// pixel centres.
  bool centroid = false;
};

/// Derivative flavour (GLSL dFdxFine/dFdxCoarse, HLSL ddx_fine/ddx_coarse).
enum class Derivatives {
  fine,    ///< ddx from the lane's own quad row, ddy from its own quad column.
  coarse,  ///< ddx from the top row, ddy from the left column, shared by the whole quad.
};

/// Rasteriser behaviour that is not per draw.
struct RasterOptions {
  int threads = 0;  ///< Worker threads (0 = all hardware threads). Output is identical for any.
  ClipDepth clip_depth = ClipDepth::negative_one_to_one;
  Derivatives derivatives = Derivatives::fine;
  /// Also call the shader for helper lanes (outputs discarded). Derivatives of varyings do not
  /// need it (they come from interpolation at helper pixels); enable it to observe helper
  /// invocations as a GPU would run them.
  bool shade_helpers = false;
};

/// Counters of one `render` call (independent of the thread count).
struct RasterStats {
  std::uint64_t triangles_in = 0;       ///< Triangles submitted.
  std::uint64_t triangles_culled = 0;   ///< Rejected: outside, back-facing or degenerate.
  std::uint64_t triangles_clipped = 0;  ///< Input triangles that needed polygon clipping.
  std::uint64_t triangles_setup = 0;    ///< Triangles after clipping that were rasterised.
  std::uint64_t quads = 0;              ///< 2x2 quads with at least one visible sample.
  std::uint64_t lanes_shaded = 0;       ///< Shader invocations (helpers included if shaded).
  std::uint64_t helper_lanes = 0;       ///< Lanes of those quads with no visible sample.
  std::uint64_t samples_written = 0;
};

/// A reusable rasteriser. It owns the scratch memory (transformed triangles, tile bins), which
/// is kept between calls, so steady-state rendering does not allocate.
class Rasteriser {
 public:
  explicit Rasteriser(const RasterOptions& options = {});
  ~Rasteriser();
  Rasteriser(Rasteriser&&) noexcept;
  Rasteriser& operator=(Rasteriser&&) noexcept;

  const RasterOptions& options() const { return options_; }
  void set_options(const RasterOptions& options) { options_ = options; }

  /// Renders `draws` into `fb` in order. With `clear`, every tile is cleared first (the whole
  /// frame buffer is covered by tiles, so this equals `fb.clear`). Fails with invalid_argument
  /// on out-of-range indices, a bad varying count or an empty frame buffer; nothing is drawn
  /// then.
  Result<RasterStats> render(FrameBuffer& fb, std::span<const DrawCall> draws,
                             const ClearValues* clear = nullptr);
  Result<RasterStats> render(FrameBuffer& fb, const DrawCall& draw,
                             const ClearValues* clear = nullptr) {
    return render(fb, std::span<const DrawCall>(&draw, 1), clear);
  }

 private:
  struct Impl;
  RasterOptions options_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tessera::raster
