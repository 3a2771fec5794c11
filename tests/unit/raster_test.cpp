// Rasteriser tests: sample patterns, half-plane coverage, watertightness (top-left rule),
// perspective-correct interpolation, near/far and guard-band clipping, depth ordering, quad
// derivatives with helper pixels and centroid. Output-side tests are in raster_output_test.cpp.
#include "tessera/raster.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "raster_test_support.h"

namespace tessera::raster {
namespace {

using namespace tessera::raster::test_util;

TEST(RasterSamples, D3DStandardPatterns) {
  for (int n : kRates) {
    const auto p = sample_positions(n);
    ASSERT_EQ(int(p.size()), n);
    for (const SampleOffset& s : p) {
      EXPECT_GE(s.x, -8);
      EXPECT_LE(s.x, 7);
      EXPECT_GE(s.y, -8);
      EXPECT_LE(s.y, 7);
    }
  }
  EXPECT_TRUE(sample_positions(3).empty());
  EXPECT_FALSE(valid_msaa(32));
  EXPECT_EQ(sample_positions(2)[0].x, 4);
  EXPECT_EQ(sample_positions(4)[0].x, -2);
  EXPECT_EQ(sample_positions(4)[0].y, -6);
  EXPECT_EQ(sample_positions(8)[7].x, 7);
  EXPECT_EQ(sample_positions(8)[7].y, -7);
  EXPECT_EQ(sample_positions(16)[15].x, -7);
  EXPECT_EQ(sample_positions(16)[15].y, -8);
}

// A half-plane whose edge passes exactly through a pixel centre covers 0.5 +- 1/N of that
// pixel's samples; pixels farther than half a diagonal from the edge are fully in or out.
TEST(RasterCoverage, HalfPlaneThroughPixelCentre) {
  constexpr int kSize = 64;
  std::mt19937 rng(1234);
  std::uniform_int_distribution<int> dir(-64, 64);
  std::uniform_int_distribution<int> pix(8, kSize - 9);
  Rasteriser r({.threads = 1});
  for (int n : kRates) {
    const auto pos = sample_positions(n);
    int tested = 0;
    while (tested < 40) {
      const int dx = dir(rng), dy = dir(rng);
      if (dx == 0 && dy == 0) continue;
      // Skip directions through a sample (the fill rule, not the pattern, decides those).
      bool on_sample = false;
      for (const SampleOffset& s : pos) on_sample |= (s.x || s.y) && dx * s.y - dy * s.x == 0;
      if (on_sample) continue;
      const double cx = pix(rng) + 0.5, cy = pix(rng) + 0.5;
      // Edge P0 -> P1 through the centre, P2 far on the normal side; all coordinates are
      // integers or half-integers, so the snapped edge passes exactly through the centre.
      const double k = std::ceil(400.0 / std::hypot(double(dx), double(dy)));
      const double ux = dx * k, uy = dy * k;
      Mesh m(0);
      const auto a = m.add(cx - ux, cy - uy, kSize, kSize);
      const auto b = m.add(cx + ux, cy + uy, kSize, kSize);
      const auto c = m.add(cx - uy, cy + ux, kSize, kSize);
      m.tri(a, b, c);
      FrameBuffer fb = make_fb(kSize, kSize, n, 1, 1, false, true);
      render_ok(r, fb, m.draw());
      const int px = int(cx), py = int(cy);
      int covered = 0;
      for (int s = 0; s < n; ++s) covered += int(fb.coverage_count(px, py, s));
      if (n == 1) {
        EXPECT_TRUE(covered == 0 || covered == 1);
      } else {
        EXPECT_NEAR(double(covered) / n, 0.5, 1.0 / n + 1e-12)
            << "msaa " << n << " dir " << dx << "," << dy;
      }
      // Far from the edge: all or nothing, on the side of P2.
      const double len = std::hypot(double(dx), double(dy));
      for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
          const double side = ((x + 0.5 - cx) * dy - (y + 0.5 - cy) * dx) / len;
          if (std::fabs(side) < 0.75) continue;
          int cov = 0;
          for (int s = 0; s < n; ++s) cov += int(fb.coverage_count(x, y, s));
          const bool inside = side < 0;  // P2 = centre + (-uy, ux) lies at side < 0
          ASSERT_EQ(cov, inside ? n : 0) << "msaa " << n << " pixel " << x << "," << y;
        }
      }
      ++tested;
    }
  }
}

// A jittered grid mesh (random diagonals) larger than the screen covers every sample exactly
// once, at every MSAA rate: no cracks, no double coverage.
TEST(RasterCoverage, WatertightSharedEdges) {
  constexpr int kW = 96, kH = 80, kCells = 12;
  for (int n : kRates) {
    for (int variant = 0; variant < 2; ++variant) {
      std::mt19937 rng(77 + n * 10 + variant);
      // Below 1/4 cell, so every quad stays convex and either diagonal is valid.
      std::uniform_real_distribution<double> jitter(-0.24, 0.24);
      std::uniform_real_distribution<double> wdist(0.5, 3.0);
      std::bernoulli_distribution flip(0.5);
      Mesh m(0);
      const double cw = (kW + 20.0) / kCells, ch = (kH + 20.0) / kCells;
      std::vector<std::uint32_t> ids;
      for (int j = 0; j <= kCells; ++j) {
        for (int i = 0; i <= kCells; ++i) {
          double x = -10.0 + i * cw, y = -10.0 + j * ch;
          if (i > 0 && i < kCells) x += jitter(rng) * cw;
          if (j > 0 && j < kCells) y += jitter(rng) * ch;
          // Variant 1: perspective (random w per vertex; same screen position).
          const double w = variant == 1 ? wdist(rng) : 1.0;
          ids.push_back(m.add(x, y, kW, kH, 0.5, w));
        }
      }
      for (int j = 0; j < kCells; ++j) {
        for (int i = 0; i < kCells; ++i) {
          const auto a = ids[std::size_t(j * (kCells + 1) + i)], b = a + 1;
          const auto c = a + kCells + 1, d = c + 1;
          if (flip(rng)) {
            m.tri(a, b, d);
            m.tri(a, d, c);
          } else {
            m.tri(a, b, c);
            m.tri(b, d, c);
          }
        }
      }
      FrameBuffer fb = make_fb(kW, kH, n, 1, 1, false, true);
      Rasteriser r({.threads = 2});
      render_ok(r, fb, m.draw());
      for (std::size_t i = 0; i < fb.sample_count(); ++i) {
        ASSERT_EQ(fb.coverage_count_data()[i], 1u)
            << "msaa " << n << " variant " << variant << " sample " << i;
      }
    }
  }
}

// Two triangles far beyond the guard band (vertices at +-10^7 pixels) are clipped against it
// and still cover every sample exactly once.
TEST(RasterClipping, GuardBandClippedQuadIsWatertight) {
  constexpr int kW = 40, kH = 30;
  for (int n : {1, 4}) {
    Mesh m(0);
    const double far = 1e7;
    // The shared diagonal a-c crosses the screen through (20.3, 15.1).
    const auto a = m.add(20.3 - far, 15.1 - 0.75 * far, kW, kH), b = m.add(far, -far, kW, kH);
    const auto c = m.add(20.3 + far, 15.1 + 0.75 * far, kW, kH), d = m.add(-far, far, kW, kH);
    m.tri(a, b, c);
    m.tri(a, c, d);
    FrameBuffer fb = make_fb(kW, kH, n, 1, 1, true, true);
    Rasteriser r({.threads = 1});
    const RasterStats st = render_ok(r, fb, m.draw());
    EXPECT_EQ(fb.primitive_id(0, kH - 1, 0), 1u);  // below the diagonal
    EXPECT_EQ(fb.primitive_id(kW - 1, 0, 0), 0u);  // above it
    EXPECT_EQ(st.triangles_clipped, 2u);
    EXPECT_GE(st.triangles_setup, 2u);
    for (std::size_t i = 0; i < fb.sample_count(); ++i) {
      ASSERT_EQ(fb.coverage_count_data()[i], 1u) << "msaa " << n << " sample " << i;
    }
  }
}

// Top-left rule on axis-aligned edges through sample positions: a sample exactly on a shared
// vertical edge belongs to the triangle on its right (left edge), on a shared horizontal edge
// to the triangle below it (top edge).
TEST(RasterCoverage, TopLeftRuleOnSamplePositions) {
  constexpr int kSize = 32;
  Rasteriser r({.threads = 1});
  for (int n : kRates) {
    const auto pos = sample_positions(n);
    for (int s = 0; s < n; ++s) {
      for (int vertical = 0; vertical < 2; ++vertical) {
        const double edge =
            12.5 + (vertical ? pos[std::size_t(s)].x : pos[std::size_t(s)].y) / 16.0;
        Mesh m(0);
        // Two rectangles [4, edge] and [edge, 24] along one axis, [4, 24] along the other.
        auto add = [&](double u, double v) {
          return vertical ? m.add(u, v, kSize, kSize) : m.add(v, u, kSize, kSize);
        };
        const auto a0 = add(4, 4), a1 = add(edge, 4), a2 = add(edge, 24), a3 = add(4, 24);
        const auto b1 = add(24, 4), b2 = add(24, 24);
        m.tri(a0, a1, a2);
        m.tri(a0, a2, a3);
        m.tri(a1, b1, b2);
        m.tri(a1, b2, a2);
        FrameBuffer fb = make_fb(kSize, kSize, n, 1, 1, true, true);
        render_ok(r, fb, m.draw());
        const int px = vertical ? 12 : 14, py = vertical ? 14 : 12;
        EXPECT_EQ(fb.coverage_count(px, py, s), 1u);
        const std::uint32_t id = fb.primitive_id(px, py, s);
        EXPECT_TRUE(id == 2 || id == 3)
            << "msaa " << n << " sample " << s << (vertical ? " vertical" : " horizontal")
            << " went to primitive " << id;
      }
    }
  }
}

/// GL perspective projection of a view-space point (camera at origin looking down -z).
std::array<float, 4> project(double x, double y, double z, double near = 0.1, double far = 100.0) {
  const double f = 1.0;  // 90 degree field of view, aspect 1
  return {float(f * x), float(f * y),
          float((far + near) / (near - far) * z + 2.0 * far * near / (near - far)), float(-z)};
}

/// A draw of `pos` (clip-space x, y, z, w per vertex) with two varyings per vertex (`var`), no
/// culling, whose shader writes (varying 0, varying 1, 1): channel 2 marks the covered samples.
DrawCall two_varying_draw(const std::vector<float>& pos, const std::vector<float>& var) {
  DrawCall d;
  d.positions = pos.data();
  d.varyings = var.data();
  d.varying_count = 2;
  d.vertex_count = pos.size() / 4;
  d.cull = CullMode::none;
  d.shader = [](const ShadeInput& in, float* out) {
    out[0] = in.varyings[0];
    out[1] = in.varyings[1];
    out[2] = 1.0f;
  };
  return d;
}

// Perspective-correct interpolation on a tilted quad against the analytic ray/plane value.
TEST(RasterInterpolation, PerspectiveCorrectOnTiltedQuad) {
  constexpr int kSize = 64;
  // Plane z = -(3 + 1.5 y): bottom of the quad near, top far.
  auto zof = [](double y) { return -(3.0 + 1.5 * y); };
  std::vector<float> pos, var;
  const double corners[4][2] = {{-2, -1.5}, {2, -1.5}, {2, 1.5}, {-2, 1.5}};
  for (const auto& c : corners) {
    const auto p = project(c[0], c[1], zof(c[1]));
    pos.insert(pos.end(), p.begin(), p.end());
    var.push_back(float(c[0]));
    var.push_back(float(c[1]));
  }
  const std::uint32_t idx[] = {0, 1, 2, 0, 2, 3};
  DrawCall d = two_varying_draw(pos, var);
  d.indices = idx;
  d.index_count = 6;
  FrameBuffer fb = make_fb(kSize, kSize);
  Rasteriser r({.threads = 1});
  render_ok(r, fb, d);
  int checked = 0;
  double max_err = 0.0;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const float* o = fb.data(x, y, 0);
      if (o[2] != 1.0f) continue;
      // Ray through the pixel centre: NDC (nx, ny); x_v = nx w, y_v = ny w, w = 3 + 1.5 y_v.
      const double nx = (x + 0.5) / kSize * 2.0 - 1.0;
      const double ny = 1.0 - (y + 0.5) / kSize * 2.0;
      const double yv = 3.0 * ny / (1.0 - 1.5 * ny);
      const double xv = nx * (3.0 + 1.5 * yv);
      max_err = std::max({max_err, std::fabs(o[0] - xv), std::fabs(o[1] - yv)});
      ++checked;
    }
  }
  EXPECT_GT(checked, 500);
  EXPECT_LT(max_err, 2e-3);
}

// A triangle crossing the camera plane is clipped at the near plane: coverage and varyings
// match the analytic ray/triangle intersection restricted to the front of the near plane.
TEST(RasterClipping, NearPlaneTriangleCrossingCamera) {
  constexpr int kSize = 64;
  const double near = 0.5;
  const double v[3][3] = {{-3.0, -1.0, 2.0}, {3.0, -1.0, -6.0}, {0.0, 2.0, -4.0}};
  std::vector<float> pos, var;
  for (int i = 0; i < 3; ++i) {
    const auto p = project(v[i][0], v[i][1], v[i][2], near);
    pos.insert(pos.end(), p.begin(), p.end());
    var.push_back(i == 1 ? 1.0f : 0.0f);  // barycentric of vertex 1
    var.push_back(i == 2 ? 1.0f : 0.0f);  // barycentric of vertex 2
  }
  const DrawCall d = two_varying_draw(pos, var);
  FrameBuffer fb = make_fb(kSize, kSize);
  Rasteriser r({.threads = 1});
  const RasterStats st = render_ok(r, fb, d);
  EXPECT_EQ(st.triangles_clipped, 1u);
  int mismatches = 0, covered = 0;
  double max_err = 0.0;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const double dir[3] = {(x + 0.5) / kSize * 2.0 - 1.0, 1.0 - (y + 0.5) / kSize * 2.0, -1.0};
      // Ray o + t dir (o = 0) against the triangle (Moller-Trumbore).
      double e1[3], e2[3], pv[3], qv[3];
      for (int k = 0; k < 3; ++k) {
        e1[k] = v[1][k] - v[0][k];
        e2[k] = v[2][k] - v[0][k];
      }
      pv[0] = dir[1] * e2[2] - dir[2] * e2[1];
      pv[1] = dir[2] * e2[0] - dir[0] * e2[2];
      pv[2] = dir[0] * e2[1] - dir[1] * e2[0];
      const double det = e1[0] * pv[0] + e1[1] * pv[1] + e1[2] * pv[2];
      const double tv[3] = {-v[0][0], -v[0][1], -v[0][2]};
      const double bu = (tv[0] * pv[0] + tv[1] * pv[1] + tv[2] * pv[2]) / det;
      qv[0] = tv[1] * e1[2] - tv[2] * e1[1];
      qv[1] = tv[2] * e1[0] - tv[0] * e1[2];
      qv[2] = tv[0] * e1[1] - tv[1] * e1[0];
      const double bv = (dir[0] * qv[0] + dir[1] * qv[1] + dir[2] * qv[2]) / det;
      const double t = (e2[0] * qv[0] + e2[1] * qv[1] + e2[2] * qv[2]) / det;
      const bool inside = bu >= 0 && bv >= 0 && bu + bv <= 1 && t >= near;
      const double margin = std::min({bu, bv, 1 - bu - bv, (t - near) * 4.0});
      const bool got = fb.data(x, y, 0)[2] == 1.0f;
      if (got) {
        ++covered;
        max_err = std::max(
            {max_err, std::fabs(fb.data(x, y, 0)[0] - bu), std::fabs(fb.data(x, y, 0)[1] - bv)});
      }
      if (got != inside && std::fabs(margin) > 0.02) ++mismatches;
    }
  }
  EXPECT_GT(covered, 300);
  EXPECT_EQ(mismatches, 0);
  EXPECT_LT(max_err, 2e-3);
}

// Both depth conventions clip at their near plane.
TEST(RasterClipping, ZeroToOneDepthConvention) {
  constexpr int kSize = 16;
  // Full-screen triangle pair at z/w = -0.25 (in front of the GL near plane z = -w but
  // behind the D3D one z = 0) and a second pair at z/w = 0.5.
  std::vector<float> pos;
  auto quad = [&](float z) {
    const float c[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (const auto& p : c) pos.insert(pos.end(), {p[0], p[1], z, 1.0f});
  };
  quad(-0.25f);
  quad(0.5f);
  const std::uint32_t idx[] = {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7};
  DrawCall d;
  d.positions = pos.data();
  d.vertex_count = 8;
  d.indices = idx;
  d.index_count = 12;
  FrameBuffer fb = make_fb(kSize, kSize, 1, 1, 1, true);
  Rasteriser gl({.threads = 1});
  render_ok(gl, fb, d);
  EXPECT_EQ(fb.primitive_id(5, 5, 0) / 2, 0u);  // GL: z = -0.25 w is visible and nearer
  EXPECT_NEAR(fb.depth(5, 5, 0), 0.375f, 1e-6f);
  Rasteriser dx({.threads = 1, .clip_depth = ClipDepth::zero_to_one});
  render_ok(dx, fb, d);
  EXPECT_EQ(fb.primitive_id(5, 5, 0) / 2, 1u);  // D3D: z < 0 is clipped away
  EXPECT_NEAR(fb.depth(5, 5, 0), 0.5f, 1e-6f);
}

TEST(RasterDepth, OrderingAndTests) {
  constexpr int kSize = 32;
  auto scene = [&](double z_first, double z_second) {
    Mesh m(0);
    const double zz[2] = {z_first, z_second};
    for (double z : zz) {
      const auto a = m.add(2, 2, kSize, kSize, z), b = m.add(30, 2, kSize, kSize, z);
      const auto c = m.add(2, 30, kSize, kSize, z);
      m.tri(a, b, c);
    }
    return m;
  };
  Rasteriser r({.threads = 1});
  const std::pair<double, double> orders[] = {{0.3, 0.6}, {0.6, 0.3}};
  for (const auto& [z0, z1] : orders) {
    Mesh m = scene(z0, z1);
    FrameBuffer fb = make_fb(kSize, kSize, 4, 1, 1, true);
    render_ok(r, fb, m.draw());
    const std::uint32_t nearer = z0 < z1 ? 0 : 1;
    for (int s = 0; s < 4; ++s) {
      EXPECT_EQ(fb.primitive_id(8, 8, s), nearer);
      EXPECT_NEAR(fb.depth(8, 8, s), std::min(z0, z1), 1e-6);
    }
  }
  const std::pair<DepthTest, std::uint32_t> tests[] = {{DepthTest::less, 0},
                                                       {DepthTest::less_equal, 1},
                                                       {DepthTest::equal, 1},
                                                       {DepthTest::always, 1}};
  for (const auto& [test, winner] : tests) {
    Mesh m = scene(0.4, 0.4);
    DrawCall d = m.draw();
    d.depth_test = test;
    FrameBuffer fb = make_fb(kSize, kSize, 1, 1, 1, true);
    if (test == DepthTest::equal) {
      // Equal only passes where the depth is already 0.4: prime it with a depth-only pass.
      DrawCall prime = d;
      prime.depth_test = DepthTest::less;
      prime.index_count = 3;
      prime.primitive_id_base = 100;
      const DrawCall both[] = {prime, d};
      ClearValues clear;
      ASSERT_TRUE(r.render(fb, both, &clear).ok());
    } else {
      render_ok(r, fb, d);
    }
    EXPECT_EQ(fb.primitive_id(8, 8, 0), winner);
  }
  // depth_write = false leaves depth untouched.
  Mesh m = scene(0.4, 0.2);
  DrawCall d = m.draw();
  d.depth_write = false;
  FrameBuffer fb = make_fb(kSize, kSize, 1, 1, 1, true);
  render_ok(r, fb, d);
  EXPECT_EQ(fb.depth(8, 8, 0), 1.0f);
  EXPECT_EQ(fb.primitive_id(8, 8, 0), 1u);
}

// u = x/8 has ddx = 1/8 and ddy = 0 at every shaded pixel, edges included (helper pixels
// extrapolate the plane), for fine and coarse derivatives; v = y/4 has ddy = 1/4.
TEST(RasterDerivatives, LinearVaryingsIncludingEdges) {
  constexpr int kSize = 48;
  for (Derivatives mode : {Derivatives::fine, Derivatives::coarse}) {
    for (int n : {1, 4}) {
      Mesh m(2);
      const double verts[3][2] = {{3.25, 5.125}, {44.75, 9.875}, {13.25, 41.5}};
      std::uint32_t id[3];
      for (int i = 0; i < 3; ++i) {
        id[i] = m.add(verts[i][0], verts[i][1], kSize, kSize, 0.5, 1.0,
                      {float(verts[i][0] / 8.0), float(verts[i][1] / 4.0)});
      }
      m.tri(id[0], id[1], id[2]);
      std::atomic<int> helpers{0};
      DrawCall d = m.draw([&](const ShadeInput& in, float* out) {
        out[0] = in.ddx[0];
        out[1] = in.ddy[0];
        out[2] = in.ddx[1];
        out[3] = in.ddy[1];
        if (in.helper) ++helpers;
      });
      FrameBuffer fb = make_fb(kSize, kSize, n);
      Rasteriser r({.threads = 1, .derivatives = mode, .shade_helpers = true});
      const RasterStats st = render_ok(r, fb, d);
      EXPECT_GT(st.helper_lanes, 0u);
      EXPECT_EQ(std::uint64_t(helpers.load()), st.helper_lanes);
      int written = 0;
      for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
          for (int s = 0; s < n; ++s) {
            if (fb.depth(x, y, s) == 1.0f) continue;
            const float* o = fb.data(x, y, s);
            ASSERT_NEAR(o[0], 0.125f, 1e-5f) << x << "," << y;
            ASSERT_NEAR(o[1], 0.0f, 1e-5f) << x << "," << y;
            ASSERT_NEAR(o[2], 0.0f, 1e-5f) << x << "," << y;
            ASSERT_NEAR(o[3], 0.25f, 1e-5f) << x << "," << y;
            ++written;
          }
        }
      }
      EXPECT_GT(written, 300 * n);
    }
  }
}

// Centroid interpolation moves the shading point of partially covered pixels onto a covered
// sample; fully covered pixels shade at the centre.
TEST(RasterInterpolation, CentroidShadesInsideTheTriangle) {
  constexpr int kSize = 32;
  Mesh m(1);
  const double verts[3][2] = {{1.25, 2.25}, {30.125, 4.75}, {6.375, 29.5}};
  std::uint32_t id[3];
  for (int i = 0; i < 3; ++i) {
    id[i] = m.add(verts[i][0], verts[i][1], kSize, kSize, 0.5, 1.0, {float(verts[i][0])});
  }
  m.tri(id[0], id[1], id[2]);
  for (bool centroid : {false, true}) {
    DrawCall d = m.draw([](const ShadeInput& in, float* out) {
      out[0] = in.varyings[0] - in.x;  // u = x: zero wherever u is taken at in.x
      out[1] = in.x - float(in.px) - 0.5f;
      out[2] = float(std::popcount(in.coverage));
    });
    d.centroid = centroid;
    FrameBuffer fb = make_fb(kSize, kSize, 4);
    Rasteriser r({.threads = 1});
    render_ok(r, fb, d);
    int partial = 0, moved = 0;
    for (int y = 0; y < kSize; ++y) {
      for (int x = 0; x < kSize; ++x) {
        const float* o = fb.data(x, y, 0);
        if (fb.depth(x, y, 0) == 1.0f) continue;
        EXPECT_NEAR(o[0], 0.0f, 1e-4f);
        if (o[2] < 4.0f) {
          ++partial;
          moved += o[1] != 0.0f;
        } else {
          EXPECT_EQ(o[1], 0.0f);
        }
      }
    }
    EXPECT_GT(partial, 10);
    if (centroid) {
      EXPECT_EQ(moved, partial);
    } else {
      EXPECT_EQ(moved, 0);
    }
  }
}

/// A random scene with overlapping, clipped and perspective triangles.
}  // namespace
}  // namespace tessera::raster
