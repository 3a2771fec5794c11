// Rasteriser driver: validates the draws, runs the geometry stage over fixed chunks of
// triangles in parallel, then the raster stage over tiles in parallel, and sums the counters.
//
// The pipeline: `Rasteriser::render` runs a geometry stage (fetch, clip, snap, cull, set up, bin;
// parallel over fixed chunks of 1024 input triangles) and then a raster stage (parallel over
// tiles: optional clear, 8x8 block trivial accept/reject, 2x2 quads, early depth test, shading,
// per-sample writes). Memory: the rasteriser keeps its per-chunk buffers between calls.
#include <string>

#include "raster/raster_internal.h"

namespace tessera::raster {

struct Rasteriser::Impl {
  std::vector<detail::Chunk> chunks;  ///< Reused between frames (keeps their capacity).
  std::vector<RasterStats> tile_stats;
  std::vector<std::uint64_t> first_triangle;
};

Rasteriser::Rasteriser(const RasterOptions& options)
    : options_(options), impl_(std::make_unique<Impl>()) {}
Rasteriser::~Rasteriser() = default;
Rasteriser::Rasteriser(Rasteriser&&) noexcept = default;
Rasteriser& Rasteriser::operator=(Rasteriser&&) noexcept = default;

namespace {

Status validate(const FrameBuffer& fb, std::span<const DrawCall> draws) {
  if (fb.sample_count() == 0) {
    return Status::error(ErrorCode::invalid_argument, "raster: empty frame buffer");
  }
  for (std::size_t i = 0; i < draws.size(); ++i) {
    const DrawCall& d = draws[i];
    const std::string where = "raster: draw " + std::to_string(i) + ": ";
    if (d.varying_count < 0 || d.varying_count > kMaxVaryings) {
      return Status::error(ErrorCode::invalid_argument, where + "varying_count must be in [0, " +
                                                            std::to_string(kMaxVaryings) + "]");
    }
    if (d.vertex_count > 0 && !d.positions) {
      return Status::error(ErrorCode::invalid_argument, where + "positions are null");
    }
    if (d.vertex_count > 0 && d.varying_count > 0 && !d.varyings) {
      return Status::error(ErrorCode::invalid_argument, where + "varyings are null");
    }
    if (d.vertex_count > 0xFFFFFFFFull) {
      return Status::error(ErrorCode::too_large, where + "more than 2^32 vertices");
    }
    const std::size_t n = d.indices ? d.index_count : d.vertex_count;
    if (n % 3 != 0) {
      return Status::error(ErrorCode::invalid_argument,
                           where + "index (or vertex) count is not a multiple of 3");
    }
  }
  return Status::success();
}

}  // namespace

Result<RasterStats> Rasteriser::render(FrameBuffer& fb, std::span<const DrawCall> draws,
                                       const ClearValues* clear) {
  if (Status s = validate(fb, draws); !s.ok()) return s;
  Impl& im = *impl_;
  const int threads = options_.threads;

  im.first_triangle.assign(1, 0);
  for (const DrawCall& d : draws) {
    const std::size_t n = d.indices ? d.index_count : d.vertex_count;
    im.first_triangle.push_back(im.first_triangle.back() + n / 3);
  }
  const std::uint64_t total = im.first_triangle.back();
  const std::int64_t nchunks =
      std::int64_t((total + detail::kChunkTriangles - 1) / detail::kChunkTriangles);
  if (im.chunks.size() < std::size_t(nchunks)) im.chunks.resize(std::size_t(nchunks));

  const int tiles_x = (fb.grid_width() + kTileSize - 1) / kTileSize;
  const int tiles_y = (fb.grid_height() + kTileSize - 1) / kTileSize;
  const int tiles = tiles_x * tiles_y;

  // Geometry stage: one task per chunk, each writing only its own chunk.
  parallel_for(0, nchunks, 1,
               [&](std::int64_t c0, std::int64_t c1) {
                 for (std::int64_t c = c0; c < c1; ++c) {
                   detail::process_chunk(c, draws, im.first_triangle, fb, options_, tiles_x,
                                         tiles_y, im.chunks[std::size_t(c)]);
                 }
               },
               {threads});

  RasterStats stats;
  const std::span<const detail::Chunk> chunks(im.chunks.data(), std::size_t(nchunks));
  for (const detail::Chunk& c : chunks) {
    if (c.bad_index) {
      return Status::error(ErrorCode::invalid_argument,
                           "raster: an index is out of range of its draw's vertices");
    }
    stats.triangles_in += c.stats.triangles_in;
    stats.triangles_culled += c.stats.triangles_culled;
    stats.triangles_clipped += c.stats.triangles_clipped;
    stats.triangles_setup += c.stats.triangles_setup;
  }

  // Raster stage: one task per tile.
  detail::FrameContext ctx;
  ctx.fb = &fb;
  ctx.draws = draws;
  ctx.chunks = chunks;
  ctx.options = &options_;
  ctx.clear = clear;
  ctx.tiles_x = tiles_x;
  ctx.tiles_y = tiles_y;
  im.tile_stats.assign(std::size_t(tiles), RasterStats{});
  parallel_for(0, tiles, 1,
               [&](std::int64_t t0, std::int64_t t1) {
                 for (std::int64_t t = t0; t < t1; ++t) {
                   detail::render_tile(ctx, int(t), im.tile_stats[std::size_t(t)]);
                 }
               },
               {threads});
  for (const RasterStats& t : im.tile_stats) {
    stats.quads += t.quads;
    stats.lanes_shaded += t.lanes_shaded;
    stats.helper_lanes += t.helper_lanes;
    stats.samples_written += t.samples_written;
  }
  return stats;
}

}  // namespace tessera::raster
