// Internal data shared by the rasteriser's drivers: the set-up triangle record, the per-chunk
// geometry output with its tile bins, and the per-frame context handed to tile tasks.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "tessera/raster.h"

namespace tessera::raster::detail {

/// Fixed-point scale of snapped positions: 1 unit = 1/256 grid pixel.
inline constexpr std::int64_t kSubpixel = std::int64_t{1} << kSubpixelBits;
/// Input triangles per geometry chunk (fixed, so chunking never depends on the thread count).
inline constexpr std::int64_t kChunkTriangles = 1024;
/// Side of the trivial-accept/reject blocks inside a tile, in grid pixels.
inline constexpr int kBlockSize = 8;
/// Guard band half-extent in grid pixels: snapped coordinates stay below 2^19 pixels, so edge
/// functions (products of two 28-bit values plus a 57-bit constant) fit in int64.
inline constexpr double kGuardBandPixels = double(1 << 18);

/// A triangle after clipping, projection, snapping and culling, ready for any tile.
///
/// Edge e is E_e(X, Y) = a[e] * X + b[e] * Y + c[e] with X, Y in 1/256 grid pixel; a sample is
/// inside when all three are >= 0 (the top-left bias is folded into c). Interpolation planes
/// are float, evaluated at grid position (x, y) as c + dx * (x - x0) + dy * (y - y0).
struct TriSetup {
  std::int64_t a[3];
  std::int64_t b[3];
  std::int64_t c[3];
  std::int32_t x0, y0, x1, y1;  ///< Inclusive grid-pixel bounding box, clamped to the grid.
  float z[3];                   ///< Window depth plane (c, dx, dy).
  float inv_w[3];               ///< 1/w plane.
  float l1[3];                  ///< lambda1 / w1 plane (perspective barycentric numerator).
  float l2[3];                  ///< lambda2 / w2 plane.
  std::uint32_t primitive_id;
  std::uint32_t varying_offset;  ///< Into Chunk::varyings: v0, v1-v0, v2-v0, each padded
                                 ///< to a multiple of 4 floats with zeros.
  std::uint32_t draw;
  bool front_facing;
};

/// Geometry-stage output of one chunk of kChunkTriangles input triangles, binned into tiles by
/// a counting sort: the triangles of tile t are items[tile_offsets[t] .. tile_offsets[t+1]).
struct Chunk {
  std::vector<TriSetup> tris;
  std::vector<float> varyings;
  std::vector<std::uint32_t> tile_offsets;
  std::vector<std::uint32_t> items;
  std::vector<std::uint32_t> cursor;  ///< Binning scratch.
  RasterStats stats;
  bool bad_index = false;
};

/// Everything a tile task reads.
struct FrameContext {
  FrameBuffer* fb = nullptr;
  std::span<const DrawCall> draws;
  std::span<const Chunk> chunks;
  const RasterOptions* options = nullptr;
  const ClearValues* clear = nullptr;
  int tiles_x = 0;
  int tiles_y = 0;
};

/// Geometry stage for chunk `index`: fetch, clip, set up and bin its triangles into `chunk`.
/// `first_triangle` lists the global index of each draw's first triangle (plus the total).
void process_chunk(std::int64_t index, std::span<const DrawCall> draws,
                   std::span<const std::uint64_t> first_triangle, const FrameBuffer& fb,
                   const RasterOptions& options, int tiles_x, int tiles_y, Chunk& chunk);

/// Raster stage for one tile: clears it if asked, then rasterises and shades its triangles in
/// submission order. Adds its counters to `stats`.
void render_tile(const FrameContext& ctx, int tile, RasterStats& stats);

}  // namespace tessera::raster::detail
