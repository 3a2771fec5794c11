// Helpers shared by the rasteriser test programs (raster_test.cpp, raster_output_test.cpp):
// meshes given in grid pixels, frame-buffer creation and checked rendering.
#pragma once

#include <gtest/gtest.h>

#include <span>
#include <vector>

#include "tessera/raster.h"

namespace tessera::raster::test_util {

inline constexpr int kRates[] = {1, 2, 4, 8, 16};

/// Vertices given in grid pixels (x right, y down) at depth `z` (window depth) and w = 1,
/// converted to OpenGL clip space for a gw x gh grid.
struct Mesh {
  std::vector<float> pos;
  std::vector<float> var;
  std::vector<std::uint32_t> idx;
  int nv = 0;

  explicit Mesh(int varyings) : nv(varyings) {}
  std::uint32_t add(double gx, double gy, int gw, int gh, double z = 0.5, double w = 1.0,
                    std::vector<float> v = {}) {
    pos.push_back(float((2.0 * gx / gw - 1.0) * w));
    pos.push_back(float((1.0 - 2.0 * gy / gh) * w));
    pos.push_back(float((2.0 * z - 1.0) * w));
    pos.push_back(float(w));
    v.resize(std::size_t(nv), 0.0f);
    var.insert(var.end(), v.begin(), v.end());
    return std::uint32_t(pos.size() / 4 - 1);
  }
  void tri(std::uint32_t a, std::uint32_t b, std::uint32_t c) { idx.insert(idx.end(), {a, b, c}); }
  DrawCall draw(ShadeFn shader = {}) const {
    DrawCall d;
    d.positions = pos.data();
    d.varyings = var.empty() ? nullptr : var.data();
    d.varying_count = nv;
    d.vertex_count = pos.size() / 4;
    d.indices = idx.data();
    d.index_count = idx.size();
    d.shader = std::move(shader);
    d.cull = CullMode::none;
    return d;
  }
};

inline FrameBuffer make_fb(int w, int h, int msaa = 1, int ssaa = 1, int channels = 4,
                           bool ids = false, bool counts = false) {
  FrameBufferDesc d;
  d.width = w;
  d.height = h;
  d.msaa = msaa;
  d.ssaa = ssaa;
  d.channels = channels;
  d.primitive_ids = ids;
  d.coverage_counts = counts;
  auto fb = FrameBuffer::create(d);
  EXPECT_TRUE(fb.ok()) << fb.status().message;
  return std::move(fb).value();
}

inline RasterStats render_ok(Rasteriser& r, FrameBuffer& fb, std::span<const DrawCall> draws) {
  ClearValues clear;
  auto res = r.render(fb, draws, &clear);
  EXPECT_TRUE(res.ok()) << res.status().message;
  return res.ok() ? *res : RasterStats{};
}

inline RasterStats render_ok(Rasteriser& r, FrameBuffer& fb, const DrawCall& draw) {
  return render_ok(r, fb, std::span<const DrawCall>(&draw, 1));
}

}  // namespace tessera::raster::test_util
