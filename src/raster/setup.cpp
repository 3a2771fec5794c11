// Geometry stage: vertex fetch, trivial reject, homogeneous clipping, projection and snapping,
// culling, triangle set-up (edge functions, interpolation planes) and binning into tiles.
// One call handles one fixed chunk of input triangles and writes only that chunk's output.
#include <algorithm>
#include <cmath>

#include "raster/clip_kernel.h"
#include "raster/raster_internal.h"
#include "raster/raster_kernel.h"

namespace tessera::raster::detail {

namespace {

struct Viewport {
  double gw, gh;           // grid size in pixels
  double z_scale, z_bias;  // window depth = z_ndc * z_scale + z_bias
  std::int32_t max_x, max_y;
};

/// Sets up one (possibly clipped) triangle given clip-space positions and varying pointers.
/// Appends to `chunk` unless it is culled; returns true when a triangle was emitted.
bool setup_triangle(const float* const p[3], const float* const v[3], int nv, const DrawCall& draw,
                    std::uint32_t draw_index, std::uint32_t prim_id, const Viewport& vp,
                    Chunk& chunk) {
  std::int64_t fx[3], fy[3];
  double zw[3], iw[3];
  for (int i = 0; i < 3; ++i) {
    const double w = p[i][3];
    if (!(w > 1e-30)) return false;
    iw[i] = 1.0 / w;
    const double gx = (double(p[i][0]) * iw[i] + 1.0) * 0.5 * vp.gw;
    const double gy = (1.0 - double(p[i][1]) * iw[i]) * 0.5 * vp.gh;
    // Guard-band clipping keeps |g| near 2^18; this also rejects NaN and infinities.
    constexpr double kLimit = 2.0 * kGuardBandPixels + 65536.0;
    if (!(std::fabs(gx) <= kLimit && std::fabs(gy) <= kLimit)) return false;
    fx[i] = snap(gx);
    fy[i] = snap(gy);
    zw[i] = std::clamp(double(p[i][2]) * iw[i] * vp.z_scale + vp.z_bias, 0.0, 1.0);
  }
  const std::int64_t area = doubled_area(fx, fy);
  if (area == 0) return false;
  // area < 0 <=> counter-clockwise in NDC (y up), see raster.h.
  const bool ccw = area < 0;
  const bool front = ccw == draw.front_ccw;
  if ((draw.cull == CullMode::back && !front) || (draw.cull == CullMode::front && front)) {
    return false;
  }
  // Normalise the winding so the interior is on the positive side of every edge.
  int idx[3] = {0, 1, 2};
  if (area < 0) std::swap(idx[1], idx[2]);
  std::int64_t x[3], y[3];
  for (int i = 0; i < 3; ++i) {
    x[i] = fx[idx[i]];
    y[i] = fy[idx[i]];
  }

  std::int64_t bx0, bx1, by0, by1;
  pixel_range(std::min({x[0], x[1], x[2]}), std::max({x[0], x[1], x[2]}), bx0, bx1);
  pixel_range(std::min({y[0], y[1], y[2]}), std::max({y[0], y[1], y[2]}), by0, by1);
  bx0 = std::max<std::int64_t>(bx0, 0);
  by0 = std::max<std::int64_t>(by0, 0);
  bx1 = std::min<std::int64_t>(bx1, vp.max_x);
  by1 = std::min<std::int64_t>(by1, vp.max_y);
  if (bx0 > bx1 || by0 > by1) return false;

  TriSetup t;
  for (int e = 0; e < 3; ++e) {
    const int i = e, j = (e + 1) % 3;
    const Edge edge = make_edge(x[i], y[i], x[j], y[j]);
    t.a[e] = edge.a;
    t.b[e] = edge.b;
    t.c[e] = edge.c;
  }
  t.x0 = std::int32_t(bx0);
  t.y0 = std::int32_t(by0);
  t.x1 = std::int32_t(bx1);
  t.y1 = std::int32_t(by1);

  PlaneBasis g;
  const double s = 1.0 / double(kSubpixel);
  g.px0 = double(x[0]) * s;
  g.py0 = double(y[0]) * s;
  g.e1x = double(x[1] - x[0]) * s;
  g.e1y = double(y[1] - y[0]) * s;
  g.e2x = double(x[2] - x[0]) * s;
  g.e2y = double(y[2] - y[0]) * s;
  g.inv_area = 1.0 / (g.e1x * g.e2y - g.e2x * g.e1y);
  g.ax = double(bx0);
  g.ay = double(by0);
  const int i0 = idx[0], i1 = idx[1], i2 = idx[2];
  make_plane(g, zw[i0], zw[i1], zw[i2], t.z);
  make_plane(g, iw[i0], iw[i1], iw[i2], t.inv_w);
  make_plane(g, 0.0, iw[i1], 0.0, t.l1);
  make_plane(g, 0.0, 0.0, iw[i2], t.l2);

  t.primitive_id = prim_id;
  t.draw = draw_index;
  t.front_facing = front;
  t.varying_offset = std::uint32_t(chunk.varyings.size());
  if (nv > 0) {
    const int n4 = padded_varyings(nv);
    const std::size_t o = chunk.varyings.size();
    chunk.varyings.resize(o + 3 * std::size_t(n4), 0.0f);
    float* out = &chunk.varyings[o];
    const float* v0 = v[i0];
    const float* v1 = v[i1];
    const float* v2 = v[i2];
    for (int k = 0; k < nv; ++k) {
      out[k] = v0[k];
      out[n4 + k] = v1[k] - v0[k];
      out[2 * n4 + k] = v2[k] - v0[k];
    }
  }
  chunk.tris.push_back(t);
  return true;
}

void bin_chunk(int tiles_x, int tiles_y, Chunk& chunk) {
  const std::size_t tiles = std::size_t(tiles_x) * std::size_t(tiles_y);
  chunk.tile_offsets.assign(tiles + 1, 0);
  for (const TriSetup& t : chunk.tris) {
    for (int ty = t.y0 / kTileSize; ty <= t.y1 / kTileSize; ++ty) {
      for (int tx = t.x0 / kTileSize; tx <= t.x1 / kTileSize; ++tx) {
        ++chunk.tile_offsets[std::size_t(ty) * tiles_x + tx + 1];
      }
    }
  }
  for (std::size_t i = 0; i < tiles; ++i) chunk.tile_offsets[i + 1] += chunk.tile_offsets[i];
  chunk.items.resize(chunk.tile_offsets[tiles]);
  // Fill in triangle order; a running cursor per tile keeps submission order inside each bin.
  std::vector<std::uint32_t>& pos = chunk.cursor;
  pos.assign(chunk.tile_offsets.begin(), chunk.tile_offsets.end() - 1);
  for (std::uint32_t i = 0; i < chunk.tris.size(); ++i) {
    const TriSetup& t = chunk.tris[i];
    for (int ty = t.y0 / kTileSize; ty <= t.y1 / kTileSize; ++ty) {
      for (int tx = t.x0 / kTileSize; tx <= t.x1 / kTileSize; ++tx) {
        chunk.items[pos[std::size_t(ty) * tiles_x + tx]++] = i;
      }
    }
  }
}

}  // namespace

void process_chunk(std::int64_t index, std::span<const DrawCall> draws,
                   std::span<const std::uint64_t> first_triangle, const FrameBuffer& fb,
                   const RasterOptions& options, int tiles_x, int tiles_y, Chunk& chunk) {
  chunk.tris.clear();
  chunk.varyings.clear();
  chunk.stats = {};
  chunk.bad_index = false;

  const bool gl_depth = options.clip_depth == ClipDepth::negative_one_to_one;
  Viewport vp;
  vp.gw = fb.grid_width();
  vp.gh = fb.grid_height();
  vp.z_scale = gl_depth ? 0.5 : 1.0;
  vp.z_bias = gl_depth ? 0.5 : 0.0;
  vp.max_x = fb.grid_width() - 1;
  vp.max_y = fb.grid_height() - 1;
  ClipParams cp;
  cp.near_z_weight = gl_depth ? 1.0f : 0.0f;
  cp.guard_x = float(2.0 * kGuardBandPixels / vp.gw);
  cp.guard_y = float(2.0 * kGuardBandPixels / vp.gh);

  const std::uint64_t begin = std::uint64_t(index) * kChunkTriangles;
  const std::uint64_t end = std::min<std::uint64_t>(begin + kChunkTriangles, first_triangle.back());
  // The draw holding `begin`: the last draw whose first triangle is <= begin.
  std::size_t d =
      std::size_t(std::upper_bound(first_triangle.begin(), first_triangle.end(), begin) -
                  first_triangle.begin()) -
      1;
  ClipVertex poly[kMaxClipVertices], scratch[kMaxClipVertices];
  for (std::uint64_t tri = begin; tri < end; ++tri) {
    while (tri >= first_triangle[d + 1]) ++d;
    const DrawCall& draw = draws[d];
    const std::uint64_t local = tri - first_triangle[d];
    std::uint32_t vi[3];
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t slot = local * 3 + std::uint64_t(k);
      vi[k] = draw.indices ? draw.indices[slot] : std::uint32_t(slot);
    }
    if (vi[0] >= draw.vertex_count || vi[1] >= draw.vertex_count || vi[2] >= draw.vertex_count) {
      chunk.bad_index = true;
      return;
    }
    ++chunk.stats.triangles_in;
    const int nv = draw.varying_count;
    const float* p[3];
    const float* v[3];
    for (int k = 0; k < 3; ++k) {
      p[k] = draw.positions + std::size_t(vi[k]) * 4;
      v[k] = nv > 0 ? draw.varyings + std::size_t(vi[k]) * std::size_t(nv) : nullptr;
    }
    const std::uint32_t prim_id = draw.primitive_id_base + std::uint32_t(local);
    const std::uint32_t oc0 = outcode(p[0], cp), oc1 = outcode(p[1], cp), oc2 = outcode(p[2], cp);
    if (oc0 & oc1 & oc2 & kRejectMask) {
      ++chunk.stats.triangles_culled;
      continue;
    }
    const std::uint32_t clip = (oc0 | oc1 | oc2) & kMustClipMask;
    if (!clip) {
      if (setup_triangle(p, v, nv, draw, std::uint32_t(d), prim_id, vp, chunk)) {
        ++chunk.stats.triangles_setup;
      } else {
        ++chunk.stats.triangles_culled;
      }
      continue;
    }
    ++chunk.stats.triangles_clipped;
    for (int k = 0; k < 3; ++k) {
      std::copy(p[k], p[k] + 4, poly[k].p);
      if (nv > 0) std::copy(v[k], v[k] + nv, poly[k].v);
    }
    const int n = clip_polygon(clip, poly, scratch, nv, cp);
    bool any = false;
    for (int k = 1; k + 1 < n; ++k) {
      const float* fp[3] = {poly[0].p, poly[k].p, poly[k + 1].p};
      const float* fv[3] = {poly[0].v, poly[k].v, poly[k + 1].v};
      if (setup_triangle(fp, fv, nv, draw, std::uint32_t(d), prim_id, vp, chunk)) {
        ++chunk.stats.triangles_setup;
        any = true;
      }
    }
    if (!any) ++chunk.stats.triangles_culled;
  }
  bin_chunk(tiles_x, tiles_y, chunk);
}

}  // namespace tessera::raster::detail
