// EncodeOptions::normal_map (label `unit`): the modulation chosen by angle keeps every block's
// endpoints, never raises a texel's angle to the source vector, lowers the mean on a bumpy
// normal map (4 bpp), and gives the same bytes for any thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "tessera/pvrtc.h"

namespace tessera::pvrtc {
namespace {

/// A bumpy normal map: unit vectors from a height field of ripples and bumps.
ImageRGBA8 bumpy_normals(int w, int h) {
  ImageRGBA8 img(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const double dx = 0.6 * std::cos(x / 3.0) + 0.3 * std::sin((x + 2 * y) / 5.0);
      const double dy = 0.6 * std::sin(y / 4.0) - 0.2 * std::cos((3 * x - y) / 7.0);
      const double len = std::sqrt(dx * dx + dy * dy + 1.0);
      const double v[3] = {-dx / len, -dy / len, 1.0 / len};
      std::uint8_t* p = img.at(x, y);
      for (int c = 0; c < 3; ++c) p[c] = std::uint8_t(std::lround((v[c] + 1.0) * 127.5));
      p[3] = 255;
    }
  }
  return img;
}

double angle_deg(const std::uint8_t* a, const std::uint8_t* b) {
  double va[3], vb[3], la = 0, lb = 0, dot = 0;
  for (int c = 0; c < 3; ++c) {
    va[c] = a[c] * (2.0 / 255.0) - 1.0;
    vb[c] = b[c] * (2.0 / 255.0) - 1.0;
    la += va[c] * va[c];
    lb += vb[c] * vb[c];
    dot += va[c] * vb[c];
  }
  const double cosv = std::clamp(dot / std::sqrt(la * lb), -1.0, 1.0);
  return std::acos(cosv) * 180.0 / 3.14159265358979323846;
}

std::vector<std::uint64_t> words(const std::vector<std::uint8_t>& bytes) {
  std::vector<std::uint64_t> w(bytes.size() / 8);
  std::memcpy(w.data(), bytes.data(), bytes.size());
  return w;
}

TEST(PvrtcNormalMap, KeepsEndpointsAndNeverRaisesATexelsAngle) {
  const ImageRGBA8 src = bumpy_normals(64, 32);
  for (Format f : {Format::pvrtc1_4bpp, Format::pvrtc1_2bpp}) {
    for (Quality q : {Quality::fast, Quality::normal}) {
      EncodeOptions plain;
      plain.format = f;
      plain.quality = q;
      EncodeOptions angular = plain;
      angular.normal_map = true;
      const Result<std::vector<std::uint8_t>> a = encode(src, plain), b = encode(src, angular);
      ASSERT_TRUE(a.ok() && b.ok());
      const std::vector<std::uint64_t> wa = words(*a), wb = words(*b);
      int changed = 0;
      for (std::size_t i = 0; i < wa.size(); ++i) {
        // Bits 32-63: endpoints and the mode bit; the pass changes modulation only.
        EXPECT_EQ(wa[i] >> 32, wb[i] >> 32) << i;
        changed += (wa[i] & 0xFFFFFFFFu) != (wb[i] & 0xFFFFFFFFu);
      }
      const Result<ImageRGBA8> da = decode(*a, f, 64, 32), db = decode(*b, f, 64, 32);
      ASSERT_TRUE(da.ok() && db.ok());
      double sum_a = 0, sum_b = 0;
      for (int y = 0; y < 32; ++y) {
        for (int x = 0; x < 64; ++x) {
          const double ea = angle_deg(da->at(x, y), src.at(x, y));
          const double eb = angle_deg(db->at(x, y), src.at(x, y));
          EXPECT_LE(eb, ea + 1e-9) << x << "," << y;
          sum_a += ea;
          sum_b += eb;
        }
      }
      // 4 bpp: every texel picks its own modulation. 2 bpp: only blocks in direct mode do, and
      // this smooth map encodes every block interpolated, so nothing may change there.
      if (f == Format::pvrtc1_4bpp) {
        EXPECT_GT(changed, 0);
        EXPECT_LT(sum_b, sum_a) << "quality " << int(q);
      }
    }
  }
}

TEST(PvrtcNormalMap, SameBytesForAnyThreadCount) {
  const ImageRGBA8 src = bumpy_normals(128, 64);
  EncodeOptions o;
  o.normal_map = true;
  o.threads = 1;
  const Result<std::vector<std::uint8_t>> one = encode(src, o);
  o.threads = 3;
  const Result<std::vector<std::uint8_t>> three = encode(src, o);
  ASSERT_TRUE(one.ok() && three.ok());
  EXPECT_EQ(*one, *three);
}

}  // namespace
}  // namespace tessera::pvrtc
