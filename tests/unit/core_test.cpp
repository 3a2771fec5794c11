// Tests of tessera/core.h: status plumbing, size limits, image views, sRGB curves, parallel
// loops.
#include "tessera/core.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

#include "tessera/core.h"
#include "tessera/procedural.h"

namespace tessera {
namespace {

TEST(Result, CarriesValueOrStatus) {
  Result<int> good = 42;
  ASSERT_TRUE(good.ok());
  EXPECT_EQ(*good, 42);
  Result<int> bad = Status::error(ErrorCode::corrupt_data, "x.png: broken");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().code, ErrorCode::corrupt_data);
  EXPECT_EQ(bad.status().message, "x.png: broken");
  EXPECT_STREQ(error_code_name(ErrorCode::too_large), "too_large");
}

TEST(ImageSize, LimitsCheckedBeforeAllocation) {
  EXPECT_TRUE(check_image_size(1, 1, "a").ok());
  EXPECT_TRUE(check_image_size(kMaxImageDimension, 4096, "a").ok());
  EXPECT_EQ(check_image_size(0, 5, "a").code, ErrorCode::corrupt_data);
  EXPECT_EQ(check_image_size(-3, 5, "a").code, ErrorCode::corrupt_data);
  EXPECT_EQ(check_image_size(kMaxImageDimension + 1, 1, "a").code, ErrorCode::too_large);
  const Status s = check_image_size(kMaxImageDimension, kMaxImageDimension, "big.png");
  EXPECT_EQ(s.code, ErrorCode::too_large);
  EXPECT_NE(s.message.find("big.png"), std::string::npos);
  EXPECT_EQ(s.message.find('\n'), std::string::npos);
}

// Bytes 0, 1, 2, ... (mod 251) from `seed`, so that every texel and channel differs.
std::vector<std::uint8_t> counting_bytes(std::size_t n, int seed) {
  std::vector<std::uint8_t> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = std::uint8_t((i + std::size_t(seed)) % 251);
  return v;
}

// The packing every layout must give: texel (x, y) read through the view's own formula.
std::vector<std::uint8_t> reference_rgba(const ImageView8& v, bool opaque) {
  std::vector<std::uint8_t> out;
  for (int y = 0; y < v.height; ++y) {
    for (int x = 0; x < v.width; ++x) {
      const std::uint8_t* p =
          v.data + std::ptrdiff_t(y) * v.row_stride + std::ptrdiff_t(x) * v.pixel_stride;
      out.insert(out.end(),
                 {p[0], p[1], p[2], v.channels == 4 && !opaque ? p[3] : std::uint8_t{255}});
    }
  }
  return out;
}

// Widths 1-37 cover the 16-texel SIMD steps of packed RGB and every tail length; the layouts
// are packed RGB and RGBA, padded texels and rows, a vertical flip (negative row stride) and a
// broadcast texel (pixel stride 0).
TEST(ImageView, CopyToRgba8MatchesTheViewFormulaForEveryLayout) {
  for (int w = 1; w <= 37; ++w) {
    const int h = 3;
    struct Layout {
      int channels;
      std::ptrdiff_t pixel_stride, row_pad;
      bool flip;
    };
    const Layout layouts[] = {{3, 3, 0, false}, {4, 4, 0, false}, {3, 4, 0, false},
                              {3, 3, 5, false}, {4, 4, 8, false}, {3, 3, 0, true},
                              {4, 4, 0, true},  {4, 6, 3, false}, {3, 0, 7, false}};
    for (const Layout& l : layouts) {
      const std::ptrdiff_t row = std::ptrdiff_t(w - 1) * l.pixel_stride + l.channels + l.row_pad;
      const std::vector<std::uint8_t> bytes = counting_bytes(std::size_t(row * h), w);
      ImageView8 v{bytes.data(), w, h, l.channels, l.pixel_stride, row, l.channels == 4};
      if (l.flip) {
        v.data = bytes.data() + row * (h - 1);
        v.row_stride = -row;
      }
      ASSERT_TRUE(check_view(v, "view").ok());
      for (bool opaque : {false, true}) {
        std::vector<std::uint8_t> out(std::size_t(w) * h * 4, 0xcd);
        copy_to_rgba8(v, out.data(), opaque);
        EXPECT_EQ(out, reference_rgba(v, opaque))
            << "width " << w << ", " << l.channels << " channels, stride " << l.pixel_stride
            << ", row pad " << l.row_pad << (l.flip ? ", flipped" : "")
            << (opaque ? ", opaque" : "");
      }
      const ImageRGBA8 image = to_image(v);
      EXPECT_EQ(image.pixels, reference_rgba(v, false));
      EXPECT_EQ(image.has_alpha, l.channels == 4);
    }
  }
}

// all_opaque reads every alpha byte, packed (two texels a step, odd counts too) or strided, and
// is true for RGB views whatever follows their texels.
TEST(ImageView, AllOpaqueFindsAnyTranslucentTexel) {
  for (int w : {1, 2, 3, 7, 8}) {
    ImageRGBA8 image(w, 3);
    for (std::size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = 255;
    EXPECT_TRUE(all_opaque(ImageView8::of(image))) << w;
    const ImageView8 rgb{image.pixels.data(), w, 3, 3, 4, std::ptrdiff_t(w) * 4, false};
    for (int k = 0; k < w * 3; ++k) {
      image.pixels[std::size_t(k) * 4 + 3] = 254;
      EXPECT_FALSE(all_opaque(ImageView8::of(image))) << w << " texel " << k;
      ImageView8 strided = ImageView8::of(image);
      strided.row_stride = -strided.row_stride;
      strided.data += std::ptrdiff_t(w) * 4 * 2;  // flipped: not packed, read texel by texel
      EXPECT_FALSE(all_opaque(strided)) << w << " texel " << k;
      image.pixels[std::size_t(k) * 4 + 2] = 7;  // RGB views never look at byte 3
      EXPECT_TRUE(all_opaque(rgb));
      image.pixels[std::size_t(k) * 4 + 3] = 255;
    }
  }
}

TEST(ImageView, OfAnImageIsPackedAndChecked) {
  ImageRGBA8 image(5, 3);
  image.has_alpha = true;
  const ImageView8 v = ImageView8::of(image);
  EXPECT_TRUE(v.packed_rgba());
  EXPECT_EQ(v.at(2, 1), image.at(2, 1));
  EXPECT_TRUE(v.has_alpha);
  EXPECT_TRUE(check_view(v, "v").ok());
  ImageView8 bad = v;
  bad.channels = 2;
  EXPECT_EQ(check_view(bad, "v").code, ErrorCode::invalid_argument);
  bad = v;
  bad.channels = 3;  // alpha without an alpha channel
  EXPECT_EQ(check_view(bad, "v").code, ErrorCode::invalid_argument);
  bad = v;
  bad.data = nullptr;
  EXPECT_EQ(check_view(bad, "v").code, ErrorCode::invalid_argument);
  bad = v;
  bad.width = kMaxImageDimension + 1;
  const Status s = check_view(bad, "huge");
  EXPECT_EQ(s.code, ErrorCode::too_large);
  EXPECT_NE(s.message.find("huge"), std::string::npos);
}

TEST(Srgb, ExactCurveAtKnownPoints) {
  EXPECT_FLOAT_EQ(srgb_to_linear(0.0f), 0.0f);
  EXPECT_FLOAT_EQ(srgb_to_linear(1.0f), 1.0f);
  // Linear segment and its boundary.
  EXPECT_NEAR(srgb_to_linear(0.04045f), 0.04045 / 12.92, 1e-8);
  EXPECT_NEAR(srgb_to_linear(0.02f), 0.02 / 12.92, 1e-8);
  // Power segment: ((0.5 + 0.055) / 1.055)^2.4 = 0.21404114...
  EXPECT_NEAR(srgb_to_linear(0.5f), 0.214041140, 1e-6);
  EXPECT_NEAR(linear_to_srgb(0.214041140f), 0.5, 1e-6);
  EXPECT_NEAR(linear_to_srgb(0.001f), 0.01292, 1e-7);
  // Clamping.
  EXPECT_EQ(srgb_to_linear(-1.0f), 0.0f);
  EXPECT_EQ(linear_to_srgb(2.0f), 1.0f);
}

TEST(Srgb, EightBitRoundTripIsExact) {
  for (int v = 0; v < 256; ++v) {
    EXPECT_EQ(linear_to_srgb8(srgb8_to_linear(std::uint8_t(v))), v) << v;
  }
  // The curve is continuous at the segment boundary.
  EXPECT_NEAR(srgb_to_linear(0.04045f), srgb_to_linear(0.040451f), 1e-6);
}

TEST(Srgb, ImageConversionRoundTrips) {
  const ImageRGBA8 img = make_procedural(Procedural::foliage, 64, 48);
  const ImageRGBAF lin = to_linear(img, {2});
  EXPECT_NEAR(lin.at(3, 5)[3], img.at(3, 5)[3] / 255.0f, 1e-7);
  const ImageRGBA8 back = to_srgb8(lin, {1});
  EXPECT_EQ(back.pixels, img.pixels);
}

TEST(Parallel, CoversRangeOnceWithFixedChunks) {
  for (int threads : {1, 2, 3, 0}) {
    std::vector<int> hits(1000, 0);
    std::vector<std::int64_t> starts(1000, -1);
    parallel_for(0, 1000, 64,
                 [&](std::int64_t b, std::int64_t e) {
                   EXPECT_EQ(b % 64, 0);
                   EXPECT_LE(e - b, 64);
                   for (std::int64_t i = b; i < e; ++i) {
                     ++hits[i];
                     starts[i] = b;
                   }
                 },
                 {threads});
    for (int i = 0; i < 1000; ++i) {
      EXPECT_EQ(hits[i], 1);
      EXPECT_EQ(starts[i], (i / 64) * 64);
    }
  }
  int calls = 0;
  parallel_for(5, 5, 1, [&](std::int64_t, std::int64_t) { ++calls; });
  EXPECT_EQ(calls, 0);
}

TEST(Parallel, SumIsBitIdenticalForAnyThreadCount) {
  auto chunk = [](std::int64_t b, std::int64_t e) {
    double s = 0.0;
    for (std::int64_t i = b; i < e; ++i) s += 1.0 / double(i + 1) * std::sin(double(i));
    return s;
  };
  const double one = parallel_sum(0, 200000, 1000, chunk, {1});
  for (int threads : {2, 4, 0}) {
    EXPECT_EQ(parallel_sum(0, 200000, 1000, chunk, {threads}), one);
  }
}

TEST(Parallel, NestedLoopsComplete) {
  std::atomic<int> total{0};
  parallel_for(0, 8, 1,
               [&](std::int64_t, std::int64_t) {
                 parallel_for(0, 100, 10,
                              [&](std::int64_t b, std::int64_t e) { total += int(e - b); }, {2});
               },
               {2});
  EXPECT_EQ(total.load(), 800);
}

TEST(Procedural, DeterministicAndDistinct) {
  for (Procedural kind : all_procedurals()) {
    const ImageRGBA8 a = make_procedural(kind, 64, 32, 5);
    const ImageRGBA8 b = make_procedural(kind, 64, 32, 5);
    EXPECT_EQ(a.pixels, b.pixels) << procedural_name(kind);
    EXPECT_EQ(a.has_alpha, kind == Procedural::foliage);
  }
  EXPECT_NE(make_procedural(Procedural::noise, 32, 32, 1).pixels,
            make_procedural(Procedural::noise, 32, 32, 2).pixels);
}

TEST(Timing, MedianLeavesNanOutAndAveragesTheMiddleTwo) {
  EXPECT_EQ(median({}), 0.0);
  EXPECT_EQ(median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_EQ(median({4.0, 1.0, 2.0, 3.0}), 2.5);
  EXPECT_EQ(median({std::nan(""), 5.0, 1.0}), 3.0);
  EXPECT_EQ(median({std::nan("")}), 0.0);
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_GE(ms_since(t0), 0.0);
}

}  // namespace
}  // namespace tessera
