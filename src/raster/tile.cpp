// Raster stage for one screen tile: 8x8 block trivial accept/reject, 2x2 quad coverage with
// per-sample masks, early depth test, perspective-correct interpolation at the four quad
// pixels (helpers included), quad derivatives, shading once per pixel, and per-sample writes.
// A tile is owned by one task and its triangles are visited in submission order, so the
// result does not depend on how tiles are spread over threads.
#include <algorithm>
#include <bit>
#include <cstring>

#include "core/check.h"
#include "raster/raster_internal.h"
#include "raster/raster_kernel.h"

namespace tessera::raster::detail {

namespace {

/// Bits set in a 16-bit mask (std::popcount is a libgcc call without POPCNT, which baseline
/// x86-64 lacks).
inline std::uint32_t popcount16(std::uint32_t v) {
  v = v - ((v >> 1) & 0x5555u);
  v = (v & 0x3333u) + ((v >> 2) & 0x3333u);
  v = (v + (v >> 4)) & 0x0F0Fu;
  return (v + (v >> 8)) & 0x1Fu;
}

/// Bits set in a 4-bit mask.
inline std::uint32_t popcount4(std::uint32_t v) { return (0x4332322132212110ull >> (4 * v)) & 15u; }

/// Per-frame sample tables derived from the frame buffer's sample positions.
struct SampleTable {
  int count = 1;
  /// One sample at the pixel centre (the standard 1x pattern): the single-sample fast path,
  /// which tests depth at the centre. An explicit one-sample pattern elsewhere takes the
  /// general path, which tests it at the sample.
  bool single = true;
  std::uint32_t full = 1;
  const SampleOffset* pos = nullptr;
  std::int64_t fx[kMaxSamples];  ///< Fixed-point position inside the pixel (from its corner).
  std::int64_t fy[kMaxSamples];
  float ox[kMaxSamples];  ///< Offset from the pixel centre in pixels.
  float oy[kMaxSamples];
};

/// The steps of TileRasteriser::quad are inlined into it whatever the compiler's heuristics.
#define TESSERA_QUAD_STEP [[gnu::always_inline]] inline

/// One quad's per-lane values, handed from step to step (lane = pixel (lane & 1, lane >> 1)).
struct QuadLanes {
  int ns = 1;           ///< Samples per pixel.
  std::size_t base[4];  ///< Each lane's first sample in the frame buffer.
  vf32x4 ldx, ldy;      ///< Lane centres relative to the triangle's origin.
  alignas(16) float ldx_lanes[4], ldy_lanes[4];
  alignas(16) float zc[4];                  ///< The depth plane at the lane centres,
  alignas(16) float zcl[4];                 ///< and clamped to [0, 1].
  alignas(16) float iw[4];                  ///< 1/w at the lane centres.
  std::uint32_t visible[4] = {0, 0, 0, 0};  ///< Covered samples that pass the depth test.
  std::uint32_t helpers = 0;                ///< Bit per lane without a visible sample.
};

class TileRasteriser {
 public:
  TileRasteriser(const FrameContext& ctx, int x0, int y0, int x1, int y1, RasterStats& stats)
      : ctx_(ctx),
        fb_(*ctx.fb),
        opt_(*ctx.options),
        rx0_(x0),
        ry0_(y0),
        rx1_(x1),
        ry1_(y1),
        stats_(stats) {
    // The positions in effect: the standard pattern, or the description's explicit one.
    const auto pos = fb_.sample_offsets();
    st_.count = int(pos.size());
    st_.single = st_.count == 1 && pos[0] == SampleOffset{};
    st_.full = (1u << st_.count) - 1u;
    st_.pos = pos.data();
    for (int s = 0; s < st_.count; ++s) {
      st_.fx[s] = sample_fixed(pos[std::size_t(s)].x);
      st_.fy[s] = sample_fixed(pos[std::size_t(s)].y);
      st_.ox[s] = float(pos[std::size_t(s)].x) / 16.0f;
      st_.oy[s] = float(pos[std::size_t(s)].y) / 16.0f;
    }
    gw_ = fb_.grid_width();
    gh_ = fb_.grid_height();
    channels_ = fb_.channels();
    data_ = fb_.data().data();
    depth_ = fb_.depth_data().data();
    ids_ = fb_.desc().primitive_ids ? fb_.primitive_id_data().data() : nullptr;
    counts_ = fb_.desc().coverage_counts ? fb_.coverage_count_data().data() : nullptr;
  }

  void triangle(const TriSetup& t, const float* varyings);

 private:
  using QuadFn = void (TileRasteriser::*)(int, int, std::uint32_t*);
  /// One 2x2 quad; `kSingle`: one sample per pixel, at the centre (st_.single).
  template <int N4, bool kSingle>
  void quad(int qx, int qy, std::uint32_t* mask);
  // The steps of `quad`, in order; force-inlined so that the kernel compiles as one function
  // (the same instructions as before the split: docs/benchmarks/raster_history.md).
  template <bool kSingle>
  TESSERA_QUAD_STEP void quad_depth(int qx, int qy, const std::uint32_t* mask, QuadLanes& q);
  template <int N4>
  TESSERA_QUAD_STEP void quad_varyings(QuadLanes& q);
  TESSERA_QUAD_STEP std::uint32_t quad_shaded_lanes(QuadLanes& q);
  template <int N4>
  TESSERA_QUAD_STEP void quad_shade(int qx, int qy, const std::uint32_t* mask, std::uint32_t active,
                                    const QuadLanes& q);
  template <bool kSingle>
  TESSERA_QUAD_STEP void quad_write(const QuadLanes& q);

  const FrameContext& ctx_;
  FrameBuffer& fb_;
  const RasterOptions& opt_;
  int rx0_, ry0_, rx1_, ry1_;  // tile rectangle, exclusive max
  RasterStats& stats_;
  SampleTable st_;
  int gw_ = 0, gh_ = 0, channels_ = 4;
  float* data_ = nullptr;
  float* depth_ = nullptr;
  std::uint32_t* ids_ = nullptr;
  std::uint32_t* counts_ = nullptr;

  // Current triangle.
  const TriSetup* t_ = nullptr;
  const DrawCall* draw_ = nullptr;
  const float* tv_ = nullptr;  // varying block
  QuadFn quad_fn_ = nullptr;
  bool has_shader_ = false;  // draw_->shader or draw_->quad_shader is set
  ShadeInput in_;            // fields shared by the triangle's invocations
  ShadeInput lanes_[4];      // per-lane inputs of the quad shader
  std::int64_t off_[3][kMaxSamples];
  alignas(16) std::int32_t off32_[3][kMaxSamples];  // narrow triangles: off_ as int32
  alignas(16) float dz_[kMaxSamples];

  // Quad scratch.
  alignas(16) float zs_[4][kMaxSamples];
  alignas(16) float v_[4][kMaxVaryings];
  // Quad derivatives, shared by the lanes that see the same difference: fine ddx of row r in
  // ddx_[r], fine ddy of column c in ddy_[c]; coarse derivatives use ddx_[0] / ddy_[0] for
  // every lane (lanes_[lane].ddx / .ddy point at the right one).
  alignas(16) float ddx_[2][kMaxVaryings];
  alignas(16) float ddy_[2][kMaxVaryings];
  alignas(16) float vc_[4][kMaxVaryings];
  alignas(16) float out_[4][kMaxChannels];
};

void TileRasteriser::triangle(const TriSetup& t, const float* varyings) {
  const int x0 = std::max(t.x0, rx0_) & ~1;
  const int y0 = std::max(t.y0, ry0_) & ~1;
  const int x1 = std::min(t.x1, rx1_ - 1);
  const int y1 = std::min(t.y1, ry1_ - 1);
  if (x0 > x1 || y0 > y1) return;
  t_ = &t;
  draw_ = &ctx_.draws[t.draw];
  tv_ = varyings;
  const bool single = st_.single;
  switch (padded_varyings(draw_->varying_count)) {
    case 0:
      quad_fn_ = single ? &TileRasteriser::quad<0, true> : &TileRasteriser::quad<0, false>;
      break;
    case 4:
      quad_fn_ = single ? &TileRasteriser::quad<4, true> : &TileRasteriser::quad<4, false>;
      break;
    case 8:
      quad_fn_ = single ? &TileRasteriser::quad<8, true> : &TileRasteriser::quad<8, false>;
      break;
    case 12:
      quad_fn_ = single ? &TileRasteriser::quad<12, true> : &TileRasteriser::quad<12, false>;
      break;
    default:
      quad_fn_ = single ? &TileRasteriser::quad<16, true> : &TileRasteriser::quad<16, false>;
      break;
  }
  in_ = ShadeInput{};
  in_.varying_count = draw_->varying_count;
  in_.quad_varyings = {v_[0], v_[1], v_[2], v_[3]};
  in_.primitive_id = t.primitive_id;
  in_.front_facing = t.front_facing;
  const bool fine = opt_.derivatives == Derivatives::fine;
  for (int lane = 0; lane < 4; ++lane) {
    ShadeInput& l = lanes_[lane];
    l = in_;
    l.varyings = v_[lane];
    l.ddx = ddx_[fine ? lane >> 1 : 0];
    l.ddy = ddy_[fine ? lane & 1 : 0];
    l.lane = lane;
  }
  has_shader_ = draw_->shader || draw_->quad_shader;
  const int ns = st_.count;
  for (int e = 0; e < 3; ++e) {
    for (int s = 0; s < ns; ++s) off_[e][s] = t.a[e] * st_.fx[s] + t.b[e] * st_.fy[s];
  }
  for (int s = 0; s < ns; ++s) dz_[s] = t.z[1] * st_.ox[s] + t.z[2] * st_.oy[s];
  const std::int64_t* off[3] = {off_[0], off_[1], off_[2]};
  // Narrow triangles take the 32-bit coverage path at 4, 8 and 16 samples (at 1 and 2 the
  // 64-bit path, two lanes per vector, is as fast).
  bool narrow = ns % 4 == 0;
  for (int e = 0; e < 3; ++e) {
    narrow = narrow && t.a[e] < kNarrowEdgeLimit && t.a[e] > -kNarrowEdgeLimit &&
             t.b[e] < kNarrowEdgeLimit && t.b[e] > -kNarrowEdgeLimit;
  }
  std::int32_t sx32[3] = {0, 0, 0}, sy32[3] = {0, 0, 0};
  if (narrow) {
    for (int e = 0; e < 3; ++e) {
      sx32[e] = std::int32_t(t.a[e] * kSubpixel);
      sy32[e] = std::int32_t(t.b[e] * kSubpixel);
      for (int s = 0; s < ns; ++s) off32_[e][s] = std::int32_t(off_[e][s]);
    }
  }
  const Edge edges[3] = {
      {t.a[0], t.b[0], t.c[0]}, {t.a[1], t.b[1], t.c[1]}, {t.a[2], t.b[2], t.c[2]}};
  const std::int64_t step_x[3] = {t.a[0] * kSubpixel, t.a[1] * kSubpixel, t.a[2] * kSubpixel};
  const std::int64_t step_y[3] = {t.b[0] * kSubpixel, t.b[1] * kSubpixel, t.b[2] * kSubpixel};
  // Samples of pixel p lie in [256 p, 256 p + 240]; a block's sample region is therefore
  // [256 bx, 256 (bx + 8) - 16] on each axis.
  constexpr std::int64_t kBlockSpan = std::int64_t(kBlockSize) * kSubpixel - kSubpixel / 16;
  const bool small = x1 - x0 < kBlockSize && y1 - y0 < kBlockSize;

  for (int by = small ? y0 : (y0 & ~(kBlockSize - 1)); by <= y1; by += kBlockSize) {
    for (int bx = small ? x0 : (x0 & ~(kBlockSize - 1)); bx <= x1; bx += kBlockSize) {
      bool accept = false;
      if (!small) {
        const std::int64_t fx0 = std::int64_t(bx) * kSubpixel;
        const std::int64_t fy0 = std::int64_t(by) * kSubpixel;
        int worst = 1;
        for (int e = 0; e < 3 && worst >= 0; ++e) {
          worst = std::min(worst,
                           classify_block(edges[e], fx0, fy0, fx0 + kBlockSpan, fy0 + kBlockSpan));
        }
        if (worst < 0) continue;
        accept = worst > 0;
      }
      const int qx0 = std::max(bx, x0), qy0 = std::max(by, y0);
      const int qx1 = small ? x1 : std::min(bx + kBlockSize - 1, x1);
      const int qy1 = small ? y1 : std::min(by + kBlockSize - 1, y1);
      for (int qy = qy0; qy <= qy1; qy += 2) {
        const std::int64_t fy = std::int64_t(qy) * kSubpixel;
        const std::int64_t fx0 = std::int64_t(qx0) * kSubpixel;
        // Edge values at the row's first quad, stepped by two pixels per quad (exact).
        std::int64_t e0[3];
        for (int e = 0; e < 3; ++e) e0[e] = edges[e].c + edges[e].a * fx0 + edges[e].b * fy;
        for (int qx = qx0; qx <= qx1; qx += 2) {
          std::uint32_t mask[4];
          if (accept) {
            mask[0] = mask[1] = mask[2] = mask[3] = st_.full;
          } else {
            if (narrow) {
              quad_coverage32(e0, sx32, sy32, off32_, ns, mask);
            } else {
              quad_coverage(e0, step_x, step_y, off, ns, mask);
            }
          }
          for (int e = 0; e < 3; ++e) e0[e] += 2 * step_x[e];
          if (!(mask[0] | mask[1] | mask[2] | mask[3])) continue;
          (this->*quad_fn_)(qx, qy, mask);
        }
      }
    }
  }
}

template <int N4, bool kSingle>
void TileRasteriser::quad(int qx, int qy, std::uint32_t* mask) {
  // Lanes beyond the grid (odd sizes) are helpers with no coverage.
  if (qx + 1 >= gw_) mask[1] = mask[3] = 0;
  if (qy + 1 >= gh_) mask[2] = mask[3] = 0;
  if (!(mask[0] | mask[1] | mask[2] | mask[3])) return;
  QuadLanes q;
  q.ns = kSingle ? 1 : st_.count;
  const int ns = q.ns;
  // The quad's top-left texel is inside the grid (its other lanes may not be: masked above).
  TESSERA_DCHECK(qx >= 0 && qy >= 0 && qx < gw_ && qy < gh_ && ns >= 1);
  const std::size_t row = std::size_t(gw_);
  q.base[0] = (std::size_t(qy) * row + std::size_t(qx)) * std::size_t(ns);
  q.base[1] = q.base[0] + std::size_t(ns);
  q.base[2] = q.base[0] + row * std::size_t(ns);
  q.base[3] = q.base[2] + std::size_t(ns);

  if (counts_) {
    for (int lane = 0; lane < 4; ++lane) {
      for (int s = 0; s < ns; ++s) counts_[q.base[lane] + std::size_t(s)] += mask[lane] >> s & 1u;
    }
  }
  quad_depth<kSingle>(qx, qy, mask, q);
  if (!(q.visible[0] | q.visible[1] | q.visible[2] | q.visible[3])) return;
  ++stats_.quads;
  quad_varyings<N4>(q);
  const std::uint32_t shaded = quad_shaded_lanes(q);
  const std::uint32_t active = has_shader_ ? shaded : 0u;
  if (active) quad_shade<N4>(qx, qy, mask, active, q);
  quad_write<kSingle>(q);
}

/// Early depth test at every covered sample into q.visible. The depth plane is evaluated at the
/// four lane centres at once (the same operations per lane as `eval_plane`); multisampled
/// lanes keep their clamped sample depths in zs_.
template <bool kSingle>
void TileRasteriser::quad_depth(int qx, int qy, const std::uint32_t* mask, QuadLanes& q) {
  const TriSetup& t = *t_;
  const DrawCall& draw = *draw_;
  const int ns = q.ns;
  const float cdx = float(qx - t.x0) + 0.5f;
  const float cdy = float(qy - t.y0) + 0.5f;
  q.ldx = vf32x4(cdx) + vf32x4(0.0f, 1.0f, 0.0f, 1.0f);
  q.ldy = vf32x4(cdy) + vf32x4(0.0f, 0.0f, 1.0f, 1.0f);
  const vf32x4 zc = eval_plane4(t.z, q.ldx, q.ldy);
  const vf32x4 zcl = clamp01(zc);
  // Lane by lane for the scalar code below.
  simd::storef4_aligned(zc, q.zc);
  simd::storef4_aligned(zcl, q.zcl);
  std::uint32_t* visible = q.visible;
  if (kSingle) {
    const DepthTest test = draw.depth_test;
    if (qx + 1 < gw_ && qy + 1 < gh_) {
      // The whole quad is inside the grid: one compare for the four lanes (depth_mask4 is
      // depth_passes lane-wise), kept for the covered lanes.
      alignas(16) float stored[4];
      std::memcpy(stored, depth_ + q.base[0], 2 * sizeof(float));
      std::memcpy(stored + 2, depth_ + q.base[2], 2 * sizeof(float));
      const std::uint32_t pass = depth_mask4(test, zcl, simd::loadf4_aligned(stored));
      for (int lane = 0; lane < 4; ++lane) {
        visible[lane] = mask[lane] ? (pass >> lane & 1u) : 0u;
      }
    } else {
      for (int lane = 0; lane < 4; ++lane) {
        // Lanes outside the grid have no coverage and must not read.
        visible[lane] =
            mask[lane] ? std::uint32_t(depth_passes(test, q.zcl[lane], depth_[q.base[lane]])) : 0u;
      }
    }
  } else if (ns % 4 == 0) {
    // Four samples per vector: clamp, test, and keep the covered ones.
    for (int lane = 0; lane < 4; ++lane) {
      if (!mask[lane]) continue;
      const float* stored = depth_ + q.base[lane];
      const vf32x4 z0(q.zc[lane]);
      std::uint32_t vis = 0;
      for (int s = 0; s < ns; s += 4) {
        const vf32x4 z = clamp01(z0 + simd::loadf4(dz_ + s));
        simd::storef4(z, zs_[lane] + s);
        vis |= depth_mask4(draw.depth_test, z, simd::loadf4(stored + s)) << s;
      }
      visible[lane] = vis & mask[lane];
    }
  } else {
    for (int lane = 0; lane < 4; ++lane) {
      if (!mask[lane]) continue;
      const float* stored = depth_ + q.base[lane];
      std::uint32_t vis = 0;
      for (int s = 0; s < ns; ++s) {
        if (!(mask[lane] >> s & 1u)) continue;
        const float z = std::clamp(q.zc[lane] + dz_[s], 0.0f, 1.0f);
        zs_[lane][s] = z;
        vis |= std::uint32_t(depth_passes(draw.depth_test, z, stored[s])) << s;
      }
      visible[lane] = vis;
    }
  }
}

/// Perspective-correct varyings at the four pixel centres into v_: 1/w and the barycentrics for
/// all lanes at once, then N4 varyings per lane.
template <int N4>
void TileRasteriser::quad_varyings(QuadLanes& q) {
  const TriSetup& t = *t_;
  const vf32x4 iw = eval_plane4(t.inv_w, q.ldx, q.ldy);
  const vf32x4 rcp = vf32x4(1.0f) / iw;
  alignas(16) float b1[4], b2[4];
  simd::storef4_aligned(iw, q.iw);
  simd::storef4_aligned(q.ldx, q.ldx_lanes);
  simd::storef4_aligned(q.ldy, q.ldy_lanes);
  simd::storef4_aligned(eval_plane4(t.l1, q.ldx, q.ldy) * rcp, b1);
  simd::storef4_aligned(eval_plane4(t.l2, q.ldx, q.ldy) * rcp, b2);
  for (int lane = 0; lane < 4; ++lane) interpolate_at<N4>(tv_, b1[lane], b2[lane], v_[lane]);
}

/// Helper lanes (no visible sample) into q.helpers; returns the lanes to shade (helpers only on
/// request) and clears the outputs (outputs of lanes that are not shaded are never written to
/// the frame buffer).
std::uint32_t TileRasteriser::quad_shaded_lanes(QuadLanes& q) {
  const int nc = channels_;
  std::uint32_t helpers = 0;
  for (int lane = 0; lane < 4; ++lane) helpers |= std::uint32_t(q.visible[lane] == 0) << lane;
  q.helpers = helpers;
  const std::uint32_t shaded = opt_.shade_helpers ? 15u : (~helpers & 15u);
  stats_.helper_lanes += popcount4(helpers);
  stats_.lanes_shaded += popcount4(shaded);
  if (nc == 4) {
    for (int lane = 0; lane < 4; ++lane) simd::storef4(vf32x4(), out_[lane]);
  } else {
    for (int lane = 0; lane < 4; ++lane) std::fill(out_[lane], out_[lane] + nc, 0.0f);
  }
  return shaded;
}

/// Quad derivatives, the shader inputs of the `active` lanes (centroid-adjusted where asked),
/// and the shader into out_.
template <int N4>
void TileRasteriser::quad_shade(int qx, int qy, const std::uint32_t* mask, std::uint32_t active,
                                const QuadLanes& q) {
  const TriSetup& t = *t_;
  const DrawCall& draw = *draw_;
  // Fine: ddx of each row, ddy of each column; coarse: the top row and left column only.
  for (int i = 0; i < N4; i += 4) {
    simd::storef4(simd::loadf4(v_[1] + i) - simd::loadf4(v_[0] + i), ddx_[0] + i);
    simd::storef4(simd::loadf4(v_[2] + i) - simd::loadf4(v_[0] + i), ddy_[0] + i);
  }
  if (opt_.derivatives == Derivatives::fine) {
    for (int i = 0; i < N4; i += 4) {
      simd::storef4(simd::loadf4(v_[3] + i) - simd::loadf4(v_[2] + i), ddx_[1] + i);
      simd::storef4(simd::loadf4(v_[3] + i) - simd::loadf4(v_[1] + i), ddy_[1] + i);
    }
  }
  const bool centroid = draw.centroid;
  for (int lane = 0; lane < 4; ++lane) {
    if (!(active >> lane & 1u)) continue;
    ShadeInput& in = lanes_[lane];
    in.px = qx + (lane & 1);
    in.py = qy + (lane >> 1);
    in.x = float(in.px) + 0.5f;
    in.y = float(in.py) + 0.5f;
    in.inv_w = q.iw[lane];
    in.depth = q.zcl[lane];
    if (centroid) {
      in.varyings = v_[lane];
      if (mask[lane] && mask[lane] != st_.full) {
        const int s = centroid_sample(mask[lane], st_.pos, q.ns);
        in.x += st_.ox[s];
        in.y += st_.oy[s];
        const float sdx = q.ldx_lanes[lane] + st_.ox[s];
        const float sdy = q.ldy_lanes[lane] + st_.oy[s];
        in.inv_w = interpolate<N4>(t, tv_, sdx, sdy, vc_[lane]);
        in.varyings = vc_[lane];
        in.depth = std::clamp(eval_plane(t.z, sdx, sdy), 0.0f, 1.0f);
      }
    }
    in.coverage = mask[lane];
    in.visible = q.visible[lane];
    in.helper = q.visible[lane] == 0;
  }
  if (draw.quad_shader) {
    draw.quad_shader(lanes_, active, out_[0]);
  } else {
    for (int lane = 0; lane < 4; ++lane) {
      if (active >> lane & 1u) draw.shader(lanes_[lane], out_[lane]);
    }
  }
}

/// Per-sample writes of depth, payload and id for the visible samples.
template <bool kSingle>
void TileRasteriser::quad_write(const QuadLanes& q) {
  const TriSetup& t = *t_;
  const int ns = q.ns;
  const int nc = channels_;
  const bool write_depth = draw_->depth_write;
  if (kSingle) {
    // One sample per pixel (visible[lane] is 0 or 1): the general loop below for one bit.
    stats_.samples_written += popcount4(~q.helpers & 15u);
    for (int lane = 0; lane < 4; ++lane) {
      if (!q.visible[lane]) continue;
      const std::size_t i = q.base[lane];
      if (write_depth) depth_[i] = q.zcl[lane];
      float* d = data_ + i * std::size_t(nc);
      if (nc == 4) {
        std::memcpy(d, out_[lane], 4 * sizeof(float));
      } else {
        std::memcpy(d, out_[lane], std::size_t(nc) * sizeof(float));
      }
      if (ids_) ids_[i] = t.primitive_id;
    }
    return;
  }
  for (int lane = 0; lane < 4; ++lane) {
    std::uint32_t vis = q.visible[lane];
    if (!vis) continue;
    const float* out = out_[lane];
    stats_.samples_written += popcount16(vis);
    if (vis == st_.full && ns % 4 == 0 && nc == 4 && !ids_) {
      // Fully visible multisampled pixel: contiguous depth and colour runs.
      if (write_depth)
        std::memcpy(depth_ + q.base[lane], zs_[lane], std::size_t(ns) * sizeof(float));
      float* d = data_ + q.base[lane] * 4;
      const vf32x4 c = simd::loadf4(out);
      for (int s = 0; s < ns; ++s) simd::storef4(c, d + 4 * s);
      continue;
    }
    while (vis) {
      const int s = std::countr_zero(vis);
      vis &= vis - 1;
      const std::size_t i = q.base[lane] + std::size_t(s);
      if (write_depth) depth_[i] = zs_[lane][s];
      float* d = data_ + i * std::size_t(nc);
      if (nc == 4) {
        std::memcpy(d, out, 4 * sizeof(float));
      } else {
        std::memcpy(d, out, std::size_t(nc) * sizeof(float));
      }
      if (ids_) ids_[i] = t.primitive_id;
    }
  }
}

}  // namespace

void render_tile(const FrameContext& ctx, int tile, RasterStats& stats) {
  TESSERA_DCHECK(tile >= 0 && ctx.tiles_x > 0);
  const int tx = tile % ctx.tiles_x;
  const int ty = tile / ctx.tiles_x;
  FrameBuffer& fb = *ctx.fb;
  const int x0 = tx * kTileSize, y0 = ty * kTileSize;
  const int x1 = std::min(x0 + kTileSize, fb.grid_width());
  const int y1 = std::min(y0 + kTileSize, fb.grid_height());
  TESSERA_DCHECK(x0 < x1 && y0 < y1);  // every tile holds at least one texel of the grid
  if (ctx.clear) fb.clear_rect(x0, y0, x1, y1, ctx.clear->value.data(), ctx.clear->depth);
  TileRasteriser r(ctx, x0, y0, x1, y1, stats);
  for (const Chunk& chunk : ctx.chunks) {
    const std::uint32_t b = chunk.tile_offsets[std::size_t(tile)];
    const std::uint32_t e = chunk.tile_offsets[std::size_t(tile) + 1];
    for (std::uint32_t k = b; k < e; ++k) {
      const TriSetup& t = chunk.tris[chunk.items[k]];
      r.triangle(t, chunk.varyings.data() + t.varying_offset);
    }
  }
}

}  // namespace tessera::raster::detail
