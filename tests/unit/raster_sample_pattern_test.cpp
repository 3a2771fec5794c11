// Explicit sample patterns (FrameBufferDesc::sample_pattern): the standard pattern given
// explicitly renders bit for bit as the default; custom patterns (a mirrored 2x, counts that
// have no standard pattern, a single off-centre sample) cover exactly the samples that a direct
// point-in-triangle test at their positions puts inside, and depth is taken at the sample;
// FrameBuffer::create rejects wrong counts and offsets outside the pixel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "raster_test_support.h"
#include "tessera/raster.h"

namespace tessera::raster {
namespace {

using namespace tessera::raster::test_util;

// A power of two: grid positions on the 1/256 grid stay exact through clip space.
constexpr int kSize = 64;

FrameBuffer make_pattern_fb(int w, int h, std::vector<SampleOffset> pattern, bool ids = false,
                            bool counts = false) {
  FrameBufferDesc d;
  d.width = w;
  d.height = h;
  d.msaa = int(pattern.size());
  d.channels = 4;
  d.primitive_ids = ids;
  d.coverage_counts = counts;
  d.sample_pattern = std::move(pattern);
  Result<FrameBuffer> fb = FrameBuffer::create(d);
  EXPECT_TRUE(fb.ok()) << fb.status().message;
  return std::move(fb).value();
}

/// Bit-for-bit equality of two frame-buffer arrays (spans of the same type).
template <typename Span>
bool same_bits(Span a, Span b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size_bytes()) == 0;
}

std::vector<SampleOffset> standard(int n) {
  const std::span<const SampleOffset> p = sample_positions(n);
  return {p.begin(), p.end()};
}

/// A triangle with vertices on the 1/256-pixel grid (so snapping is exact), in grid pixels.
struct Tri {
  double x[3], y[3], z[3];
};

Tri random_tri(std::mt19937& rng, int size, double extent) {
  std::uniform_real_distribution<double> centre(4.0, size - 4.0), off(-extent, extent);
  std::uniform_real_distribution<double> depth(0.1, 0.9);
  Tri t;
  const double cx = centre(rng), cy = centre(rng);
  for (int i = 0; i < 3; ++i) {
    t.x[i] = std::round((cx + off(rng)) * 256.0) / 256.0;
    t.y[i] = std::round((cy + off(rng)) * 256.0) / 256.0;
    t.z[i] = depth(rng);
  }
  return t;
}

/// Direct point-in-triangle test of grid point (px, py) given in 1/256 pixel, exact in
/// integers: +1 strictly inside, 0 outside, -1 on an edge (the fill rule decides those).
int point_in_triangle(const Tri& t, std::int64_t px, std::int64_t py) {
  std::int64_t X[3], Y[3];
  for (int i = 0; i < 3; ++i) {
    X[i] = std::llround(t.x[i] * 256.0);
    Y[i] = std::llround(t.y[i] * 256.0);
  }
  const std::int64_t area = (X[1] - X[0]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[1] - Y[0]);
  if (area == 0) return 0;
  bool inside = true;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const std::int64_t e = (X[j] - X[i]) * (py - Y[i]) - (Y[j] - Y[i]) * (px - X[i]);
    if (e == 0) return -1;
    inside = inside && (e > 0) == (area > 0);
  }
  return inside ? 1 : 0;
}

Mesh mesh_of(const Tri& t, int size) {
  Mesh m(3);
  std::uint32_t id[3];
  for (int i = 0; i < 3; ++i) {
    id[i] = m.add(t.x[i], t.y[i], size, size, t.z[i], 1.0,
                  {float(t.x[i]) / float(size), float(t.y[i]) / float(size), float(i)});
  }
  m.tri(id[0], id[1], id[2]);
  return m;
}

void colour_shader(const ShadeInput& in, float* out) {
  out[0] = in.varyings[0];
  out[1] = in.varyings[1];
  out[2] = in.varyings[2] * 0.25f;
  out[3] = 1.0f;
}

// The standard pattern given explicitly is the default, bit for bit: samples, depth, ids,
// coverage counts, statistics and the resolve, with centre and centroid shading.
TEST(RasterSamplePattern, ExplicitStandardPatternIsBitIdentical) {
  std::mt19937 rng(77);
  for (int n : kRates) {
    Mesh m(3);
    for (int k = 0; k < 40; ++k) {
      const Tri t = random_tri(rng, kSize, k % 2 ? 20.0 : 4.0);
      std::uint32_t id[3];
      for (int i = 0; i < 3; ++i) {
        id[i] = m.add(t.x[i], t.y[i], kSize, kSize, t.z[i], 1.0,
                      {float(k) / 40.0f, float(t.x[i]) / kSize, float(t.y[i]) / kSize});
      }
      m.tri(id[0], id[1], id[2]);
    }
    for (bool centroid : {false, true}) {
      DrawCall d = m.draw(colour_shader);
      d.centroid = centroid;
      d.depth_test = DepthTest::less_equal;
      FrameBuffer a = make_fb(kSize, kSize, n, 1, 4, true, true);
      FrameBuffer b = make_pattern_fb(kSize, kSize, standard(n), true, true);
      ASSERT_EQ(b.msaa(), n);
      Rasteriser r({.threads = 2});
      const RasterStats sa = render_ok(r, a, d);
      const RasterStats sb = render_ok(r, b, d);
      EXPECT_EQ(sa.quads, sb.quads);
      EXPECT_EQ(sa.samples_written, sb.samples_written);
      EXPECT_EQ(sa.lanes_shaded, sb.lanes_shaded);
      EXPECT_TRUE(same_bits(a.data(), b.data())) << n << "x centroid " << centroid;
      EXPECT_TRUE(same_bits(a.depth_data(), b.depth_data())) << n << "x";
      EXPECT_TRUE(same_bits(a.primitive_id_data(), b.primitive_id_data())) << n << "x";
      EXPECT_TRUE(same_bits(a.coverage_count_data(), b.coverage_count_data())) << n << "x";
      EXPECT_EQ(resolve_srgb8(a).pixels, resolve_srgb8(b).pixels) << n << "x";
    }
  }
}

// Custom patterns: every sample's coverage is the point-in-triangle test at its own position
// (ties on an edge left to the fill rule), on triangles small (one block) and large (trivially
// accepted blocks); counts without a standard pattern (3, 6) and a custom 8 (the 32-bit and
// four-wide paths) included. The mirrored 2x pattern covers differently from the standard 2x.
TEST(RasterSamplePattern, CoverageIsThePointInTriangleTestAtEachSample) {
  const std::vector<std::vector<SampleOffset>> patterns = {
      {{-4, 4}, {4, -4}},  // the standard 2x mirrored: its diagonal is the other one
      {{-7, -7}, {7, 0}, {0, 7}},
      {{-8, -8}, {7, 7}, {-8, 7}, {7, -8}, {0, 0}, {3, -5}},
      {{-3, 1}, {1, 3}, {-5, -1}, {3, -5}, {5, 5}, {1, -7}, {-7, 7}, {7, 1}},
  };
  Rasteriser r({.threads = 1});
  for (const std::vector<SampleOffset>& pattern : patterns) {
    const int n = int(pattern.size());
    std::mt19937 rng(1000 + std::uint32_t(n));
    int checked = 0, ties = 0, mirrored_differs = 0;
    for (int k = 0; k < 24; ++k) {
      const Tri t = random_tri(rng, kSize, k % 3 == 0 ? 3.0 : 22.0);
      const Mesh m = mesh_of(t, kSize);
      FrameBuffer fb = make_pattern_fb(kSize, kSize, pattern, false, true);
      render_ok(r, fb, m.draw());
      FrameBuffer std2;
      if (n == 2) {
        std2 = make_fb(kSize, kSize, 2, 1, 4, false, true);
        render_ok(r, std2, m.draw());
      }
      for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
          for (int s = 0; s < n; ++s) {
            const std::int64_t px = 256 * x + 128 + 16 * pattern[std::size_t(s)].x;
            const std::int64_t py = 256 * y + 128 + 16 * pattern[std::size_t(s)].y;
            const int in = point_in_triangle(t, px, py);
            if (in < 0) {
              ++ties;
              continue;
            }
            ASSERT_EQ(fb.coverage_count(x, y, s), std::uint32_t(in))
                << n << " samples, triangle " << k << ", pixel " << x << "," << y << " sample "
                << s;
            ++checked;
          }
          if (n == 2) {
            const std::uint32_t a = fb.coverage_count(x, y, 0) + fb.coverage_count(x, y, 1);
            const std::uint32_t b = std2.coverage_count(x, y, 0) + std2.coverage_count(x, y, 1);
            mirrored_differs += a != b;
          }
        }
      }
    }
    EXPECT_GT(checked, 1000 * n);
    EXPECT_LT(ties, checked / 50);
    if (n == 2) {
      EXPECT_GT(mirrored_differs, 20);
    }
  }
}

// A triangle edge through the pixel centres along the standard 2x diagonal (x = y): the mirrored
// pattern puts one sample on each side of it, so the edge pixels are half covered, where the
// standard pattern has both samples on the edge itself (left to the fill rule: all or nothing).
TEST(RasterSamplePattern, MirroredTwoSamplesSplitAnEdgeTheStandardOneDoesNot) {
  Mesh m(0);
  const auto a = m.add(0, 0, kSize, kSize), b = m.add(kSize, kSize, kSize, kSize);
  const auto c = m.add(0, kSize, kSize, kSize);
  m.tri(a, b, c);  // below the diagonal
  Rasteriser r({.threads = 1});
  FrameBuffer mirrored = make_pattern_fb(kSize, kSize, {{-4, 4}, {4, -4}}, false, true);
  FrameBuffer standard2 = make_fb(kSize, kSize, 2, 1, 4, false, true);
  render_ok(r, mirrored, m.draw());
  render_ok(r, standard2, m.draw());
  for (int i = 1; i < kSize - 1; ++i) {
    // Pixel (i, i): its centre is on the edge.
    EXPECT_EQ(mirrored.coverage_count(i, i, 0), 1u) << i;  // (-4, +4): below
    EXPECT_EQ(mirrored.coverage_count(i, i, 1), 0u) << i;  // (+4, -4): above
    EXPECT_EQ(standard2.coverage_count(i, i, 0), standard2.coverage_count(i, i, 1)) << i;
  }
}

// One sample off the centre: coverage is that of a 1x frame whose geometry is shifted by minus
// the offset (exactly, on the 1/256 grid), and depth is taken at the sample, not the centre.
TEST(RasterSamplePattern, SingleOffCentreSampleCoversAndTestsDepthAtTheSample) {
  const SampleOffset o{5, -3};
  std::mt19937 rng(5);
  Rasteriser r({.threads = 1});
  for (int k = 0; k < 12; ++k) {
    const Tri t = random_tri(rng, kSize, 18.0);
    Tri shifted = t;
    for (int i = 0; i < 3; ++i) {
      shifted.x[i] -= o.x / 16.0;
      shifted.y[i] -= o.y / 16.0;
    }
    FrameBuffer fb = make_pattern_fb(kSize, kSize, {o}, false, true);
    FrameBuffer ref = make_fb(kSize, kSize, 1, 1, 4, false, true);
    render_ok(r, fb, mesh_of(t, kSize).draw());
    render_ok(r, ref, mesh_of(shifted, kSize).draw());
    int covered = 0;
    for (int y = 0; y < kSize; ++y) {
      for (int x = 0; x < kSize; ++x) {
        ASSERT_EQ(fb.coverage_count(x, y, 0), ref.coverage_count(x, y, 0)) << x << "," << y;
        if (!fb.coverage_count(x, y, 0)) continue;
        ++covered;
        EXPECT_NEAR(fb.depth(x, y, 0), ref.depth(x, y, 0), 1e-5f) << x << "," << y;
      }
    }
    EXPECT_GT(covered, 0);
  }
}

TEST(RasterSamplePattern, OffsetsInEffectAndCopies) {
  for (int n : kRates) {
    FrameBuffer fb = make_fb(8, 8, n);
    EXPECT_TRUE(std::ranges::equal(fb.sample_offsets(), sample_positions(n))) << n;
  }
  EXPECT_TRUE(std::ranges::equal(FrameBuffer().sample_offsets(), sample_positions(1)));
  const std::vector<SampleOffset> p = {{-7, -7}, {7, 0}, {0, 7}};
  FrameBuffer fb = make_pattern_fb(8, 8, p);
  EXPECT_EQ(fb.msaa(), 3);
  EXPECT_EQ(fb.sample_count(), 8u * 8u * 3u);
  EXPECT_TRUE(std::ranges::equal(fb.sample_offsets(), p));
  const FrameBuffer copy = fb.clone();
  EXPECT_TRUE(std::ranges::equal(copy.sample_offsets(), p));
  EXPECT_EQ(copy.desc().sample_pattern, p);
  const FrameBuffer moved = std::move(fb);
  EXPECT_TRUE(std::ranges::equal(moved.sample_offsets(), p));
}

TEST(RasterSamplePattern, ValidationNamesTheProblem) {
  const auto create = [](int msaa, std::vector<SampleOffset> pattern) {
    FrameBufferDesc d;
    d.width = 8;
    d.height = 8;
    d.msaa = msaa;
    d.sample_pattern = std::move(pattern);
    return FrameBuffer::create(d);
  };
  const auto fails_with = [](const Result<FrameBuffer>& r, const std::string& text) {
    ASSERT_FALSE(r.ok()) << text;
    EXPECT_EQ(r.status().code, ErrorCode::invalid_argument);
    EXPECT_NE(r.status().message.find(text), std::string::npos) << r.status().message;
  };
  // Counts: the pattern has one offset per sample.
  fails_with(create(2, {{0, 0}, {1, 1}, {2, 2}}), "the sample pattern has 3 offsets but msaa is 2");
  fails_with(create(4, {{0, 0}}), "has 1 offset but msaa is 4");
  fails_with(create(17, std::vector<SampleOffset>(17)), "msaa must be in [1, 16] (got 17)");
  fails_with(create(0, {{0, 0}}), "msaa must be in [1, 16] (got 0)");
  // Offsets: inside the pixel, [-8, 7] on each axis.
  fails_with(create(2, {{0, 0}, {8, 0}}), "offset 1 (8, 0) is outside [-8, 7]");
  fails_with(create(2, {{0, -9}, {0, 0}}), "offset 0 (0, -9) is outside [-8, 7]");
  fails_with(create(1, {{-8, 9}}), "outside [-8, 7]");
  // Without a pattern, the rate must have a standard one (as before).
  fails_with(create(3, {}), "msaa must be 1, 2, 4, 8 or 16 (got 3)");
  // The corners of the range are fine, and so are duplicates and any count up to 16.
  EXPECT_TRUE(create(2, {{-8, -8}, {7, 7}}).ok());
  EXPECT_TRUE(create(2, {{1, 1}, {1, 1}}).ok());
  EXPECT_TRUE(create(16, std::vector<SampleOffset>(16, SampleOffset{3, -2})).ok());
}

}  // namespace
}  // namespace tessera::raster
