// Pins ssim_plane and ssim_map to the last bit: against a plain scalar reference that evaluates
// every value in the order the library promises (separable passes, each moment summed from 0
// with the taps ascending, products formed as (w * a) * b, per-band sums over bands of 32 output
// rows added in band order). A 2-D 11x11 form would round differently, so it is no reference.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "tessera/metrics.h"

namespace tessera::metrics {
namespace {

constexpr int kR = 5;
constexpr int kW = 2 * kR + 1;

std::array<double, kW> reference_weights() {
  std::array<double, kW> w{};
  double sum = 0.0;
  for (int i = -kR; i <= kR; ++i) {
    w[i + kR] = std::exp(-0.5 * double(i * i) / (1.5 * 1.5));
    sum += w[i + kR];
  }
  for (double& v : w) v /= sum;
  return w;
}

struct Reference {
  double mean = 0.0;
  std::vector<float> map;
};

/// The scalar, array-of-structs SSIM (one band of 32 output rows at a time, bands in order).
Reference reference_ssim(const std::vector<float>& a, const std::vector<float>& b, int width,
                         int height, double data_range) {
  const std::array<double, kW> w = reference_weights();
  const double c1 = (0.01 * data_range) * (0.01 * data_range);
  const double c2 = (0.03 * data_range) * (0.03 * data_range);
  const int ow = width - 2 * kR, oh = height - 2 * kR;
  Reference ref;
  ref.map.resize(std::size_t(ow) * std::size_t(oh));
  double total = 0.0;
  for (int y0 = 0; y0 < oh; y0 += 32) {
    const int y1 = std::min(oh, y0 + 32);
    const int rows = (y1 - y0) + 2 * kR;
    std::vector<double> h(std::size_t(rows) * std::size_t(ow) * 5);
    for (int r = 0; r < rows; ++r) {
      for (int x = 0; x < ow; ++x) {
        double mx = 0, my = 0, mxx = 0, myy = 0, mxy = 0;
        for (int k = 0; k < kW; ++k) {
          const std::size_t i = std::size_t(y0 + r) * std::size_t(width) + std::size_t(x + k);
          const double va = a[i], vb = b[i], wk = w[std::size_t(k)];
          mx += wk * va;
          my += wk * vb;
          mxx += wk * va * va;
          myy += wk * vb * vb;
          mxy += wk * va * vb;
        }
        double* m = &h[(std::size_t(r) * std::size_t(ow) + std::size_t(x)) * 5];
        m[0] = mx;
        m[1] = my;
        m[2] = mxx;
        m[3] = myy;
        m[4] = mxy;
      }
    }
    double band = 0.0;
    for (int y = 0; y < y1 - y0; ++y) {
      for (int x = 0; x < ow; ++x) {
        double m[5] = {0, 0, 0, 0, 0};
        for (int k = 0; k < kW; ++k) {
          const double* hm = &h[(std::size_t(y + k) * std::size_t(ow) + std::size_t(x)) * 5];
          for (int c = 0; c < 5; ++c) m[c] += w[std::size_t(k)] * hm[c];
        }
        const double vx = m[2] - m[0] * m[0];
        const double vy = m[3] - m[1] * m[1];
        const double vxy = m[4] - m[0] * m[1];
        const double s = ((2.0 * m[0] * m[1] + c1) * (2.0 * vxy + c2)) /
                         ((m[0] * m[0] + m[1] * m[1] + c1) * (vx + vy + c2));
        ref.map[std::size_t(y0 + y) * std::size_t(ow) + std::size_t(x)] = float(s);
        band += s;
      }
    }
    total += band;
  }
  ref.mean = total / (double(oh) * double(ow));
  return ref;
}

/// A plane of `scale`-range values: a smooth ramp plus hashed noise, `seed` decorrelating planes.
std::vector<float> test_plane(int width, int height, std::uint32_t seed, float scale) {
  std::vector<float> p(std::size_t(width) * std::size_t(height));
  std::uint32_t h = seed * 2654435761u + 1u;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      h = h * 1664525u + 1013904223u;
      const float noise = float(h >> 8) / float(1u << 24);  // [0, 1)
      const float ramp = float(x + 2 * y) / float(width + 2 * height);
      p[std::size_t(y) * std::size_t(width) + std::size_t(x)] =
          scale * (0.6f * ramp + 0.4f * noise);
    }
  }
  return p;
}

struct Size {
  int width, height;
};

// Heights around the 32-row bands (42: one band, 43: two, 75: three, 300: ten) and the 128-row
// tasks (139: 129 output rows); widths around the 128-column tiles (138: 128 output columns,
// 139: 129) and the window (11).
constexpr Size kSizes[] = {{37, 42}, {64, 43}, {50, 75},  {139, 300}, {138, 139},
                           {11, 11}, {11, 40}, {300, 11}, {12, 200},  {275, 33}};

TEST(SsimExact, PlaneAndMapEqualTheScalarReferenceForAnyThreadCount) {
  for (const Size& size : kSizes) {
    const std::vector<float> a = test_plane(size.width, size.height, 1, 255.0f);
    std::vector<float> b = test_plane(size.width, size.height, 2, 255.0f);
    for (std::size_t i = 0; i < b.size(); ++i) b[i] = 0.7f * a[i] + 0.3f * b[i];
    const Reference ref = reference_ssim(a, b, size.width, size.height, 255.0);
    for (int threads : {1, 2, 4}) {
      SCOPED_TRACE(testing::Message()
                   << size.width << "x" << size.height << ", " << threads << " threads");
      const SsimOptions options{.data_range = 255.0, .threads = threads};
      EXPECT_EQ(ssim_plane(a, b, size.width, size.height, options), ref.mean);
      const std::vector<float> map = ssim_map(a, b, size.width, size.height, options);
      ASSERT_EQ(map.size(), ref.map.size());
      std::size_t differing = 0;
      for (std::size_t i = 0; i < map.size(); ++i) differing += map[i] != ref.map[i] ? 1 : 0;
      EXPECT_EQ(differing, 0u);
    }
  }
}

TEST(SsimExact, UnitDataRangeEqualsTheScalarReference) {
  const int width = 90, height = 75;
  const std::vector<float> a = test_plane(width, height, 3, 1.0f);
  const std::vector<float> b = test_plane(width, height, 4, 1.0f);
  const Reference ref = reference_ssim(a, b, width, height, 1.0);
  EXPECT_EQ(ssim_plane(a, b, width, height, {.data_range = 1.0, .threads = 2}), ref.mean);
  EXPECT_LT(ref.mean, 0.9);  // the planes differ: a test of something
}

TEST(SsimExact, GrayImagesEqualTheReferenceOnTheirLuma) {
  ImageRGBA8 a(75, 43), b(75, 43);
  std::uint32_t h = 7;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    h = h * 1664525u + 1013904223u;
    a.pixels[i] = std::uint8_t(h >> 24);
    b.pixels[i] = std::uint8_t((int(a.pixels[i]) * 3 + int((h >> 16) & 63u)) / 4);
  }
  const Reference ref = reference_ssim(luma709(a), luma709(b), 75, 43, 255.0);
  for (int threads : {1, 2, 4}) EXPECT_EQ(*ssim_gray(a, b, {threads}), ref.mean) << threads;
}

}  // namespace
}  // namespace tessera::metrics
