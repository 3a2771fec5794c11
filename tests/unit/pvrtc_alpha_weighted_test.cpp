// EncodeOptions::alpha_weighted (label `unit`): the weighted modulation choice returns the
// weighted total error exactly (the refinement relies on it), opaque texels weigh what they
// weigh without it (an opaque image encoded as RGBA gives the same bytes, every quality), it is
// a no-op for RGB input, it lowers the error of colour x alpha (what a blending renderer shows)
// on a hard cutout without costing much alpha, the output does not depend on the thread count,
// and 2 bpp is an error. The SIMD backends' bytes with the option on are compared by
// pvrtc_arch_bytes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "pvrtc/encode/encode_internal.h"
#include "tessera/metrics.h"
#include "tessera/procedural.h"
#include "tessera/pvrtc.h"
#include "tessera/texture_file.h"

namespace tessera::pvrtc {
namespace {

// Margins of LowersVisibleErrorOnACutout: about half the gain in colour x alpha PSNR the
// option showed on this cutout at normal and at high (some 6 dB), and how much alpha PSNR it
// may lose there (it gained 9 dB and more).
constexpr double kMinGainDb = 3.0;
constexpr double kMaxAlphaLossDb = 0.5;

std::vector<std::uint8_t> encode_ok(const ImageRGBA8& img, const EncodeOptions& o) {
  Result<std::vector<std::uint8_t>> r = encode(img, o);
  EXPECT_TRUE(r.ok()) << r.status().message;
  return r.ok() ? std::move(r).value() : std::vector<std::uint8_t>{};
}

/// A hard cutout: photo-like noise where its luma exceeds the median, fully transparent
/// elsewhere, with unrelated colour under the transparent texels.
ImageRGBA8 cutout(int w, int h) {
  ImageRGBA8 img = make_procedural(Procedural::noise, w, h, 11);
  const ImageRGBA8 under = make_procedural(Procedural::bricks, w, h, 3);
  std::vector<int> luma(img.pixel_count());
  for (std::size_t i = 0; i < luma.size(); ++i) {
    const std::uint8_t* p = &img.pixels[i * 4];
    luma[i] = 2 * p[0] + 7 * p[1] + p[2];
  }
  std::vector<int> sorted = luma;
  std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(sorted.size() / 2),
                   sorted.end());
  const int median = sorted[sorted.size() / 2];
  for (std::size_t i = 0; i < luma.size(); ++i) {
    std::uint8_t* p = &img.pixels[i * 4];
    if (luma[i] > median) {
      p[3] = 255;
    } else {
      for (int c = 0; c < 3; ++c) p[c] = under.pixels[i * 4 + std::size_t(c)];
      p[3] = 0;
    }
  }
  img.has_alpha = true;
  return img;
}

metrics::ImageComparison compare_to(const ImageRGBA8& src, const std::vector<std::uint8_t>& bytes) {
  Result<ImageRGBA8> dec = decode(bytes, Format::pvrtc1_4bpp, src.width, src.height);
  EXPECT_TRUE(dec.ok());
  metrics::CompareOptions co;
  co.compute_ssim = false;
  co.premultiplied = true;
  Result<metrics::ImageComparison> c = metrics::compare_images(src, dec.value(), co);
  EXPECT_TRUE(c.ok());
  return c.value();
}

// The encoder hands the error `choose_modulation` returns to the refinement in place of a
// decode, so with colour scales it must be exactly the weighted `total_error` too: RGBA foliage
// (translucent and transparent texels), punch-through allowed, with and without mode 1.
TEST(PvrtcAlphaWeighted, ChooseModulationReturnsTheWeightedTotalError) {
  using namespace detail;
  const ImageRGBA8 img = make_procedural(Procedural::foliage, 32, 32);
  ASSERT_TRUE(img.has_alpha);
  for (Quality q : {Quality::fast, Quality::normal}) {
    EncodeOptions o;
    o.quality = q;
    const std::vector<std::uint8_t> data = encode_ok(img, o);
    for (bool mode1 : {false, true}) {
      EncoderState s;
      s.g = make_grid(Format::pvrtc1_4bpp, img.width, img.height);
      s.alpha_mode = s.punch = true;
      s.mode1 = mode1;
      s.threads = 1;
      s.own_target(img.pixels);
      std::vector<std::uint64_t> w(s.g.blocks());
      load_words(s.g, data.data(), w.data());
      for (std::uint64_t word : w) {
        s.mod.push_back(std::uint32_t(word));
        s.mode.push_back(std::uint8_t((word >> 32) & 1));
        s.ca.push_back(std::uint16_t((word >> 32) & 0xfffe));
        s.cb.push_back(std::uint16_t(word >> 48));
      }
      for (std::size_t i = 0; i < s.g.texels(); ++i) {
        s.colour_scale.push_back(std::uint8_t(colour_scale_of(s.target[i * 4 + 3])));
      }
      const std::uint64_t returned = choose_modulation(s);
      EXPECT_EQ(returned, total_error(s)) << "quality " << int(q) << (mode1 ? " mode1" : "");
      EncoderState plain = s;
      plain.colour_scale.clear();
      EXPECT_LT(returned, choose_modulation(plain));  // translucent texels weigh less
    }
  }
}

TEST(PvrtcAlphaWeighted, OpaqueTexelsWeighAsBefore) {
  // Forced RGBA on opaque images: every colour scale is 16, so every weighted kernel (the
  // modulation choice, the exact search's evaluators, the least-squares sums, reseed and
  // crossover) must give exactly the unweighted scores.
  for (Procedural kind : {Procedural::noise, Procedural::bricks}) {
    const ImageRGBA8 img = make_procedural(kind, 64, 64, 5);
    for (Quality q : {Quality::fast, Quality::normal, Quality::high}) {
      EncodeOptions plain;
      plain.quality = q;
      plain.force_alpha = true;
      EncodeOptions weighted = plain;
      weighted.alpha_weighted = true;
      EXPECT_EQ(encode_ok(img, plain), encode_ok(img, weighted))
          << procedural_name(kind) << " quality " << int(q);
    }
  }
}

TEST(PvrtcAlphaWeighted, NoOpWithoutAlpha) {
  ImageRGBA8 img = cutout(64, 64);
  img.has_alpha = false;  // alpha ignored: the option has nothing to weigh by
  EncodeOptions plain;
  plain.quality = Quality::normal;
  EncodeOptions weighted = plain;
  weighted.alpha_weighted = true;
  EXPECT_EQ(encode_ok(img, plain), encode_ok(img, weighted));
}

TEST(PvrtcAlphaWeighted, LowersVisibleErrorOnACutout) {
  const ImageRGBA8 img = cutout(128, 128);
  for (Quality q : {Quality::normal, Quality::high}) {
    EncodeOptions plain;
    plain.quality = q;
    EncodeOptions weighted = plain;
    weighted.alpha_weighted = true;
    const metrics::ImageComparison a = compare_to(img, encode_ok(img, plain));
    const metrics::ImageComparison b = compare_to(img, encode_ok(img, weighted));
    EXPECT_GT(b.psnr_premultiplied, a.psnr_premultiplied + kMinGainDb) << "quality " << int(q);
    EXPECT_GT(b.psnr_alpha, a.psnr_alpha - kMaxAlphaLossDb) << "quality " << int(q);
  }
}

TEST(PvrtcAlphaWeighted, IdenticalForAnyThreadCount) {
  const ImageRGBA8 img = cutout(64, 64);
  EncodeOptions o;
  o.quality = Quality::high;
  o.alpha_weighted = true;
  o.threads = 1;
  const std::vector<std::uint8_t> one = encode_ok(img, o);
  o.threads = 4;
  EXPECT_EQ(one, encode_ok(img, o));
}

TEST(PvrtcAlphaWeighted, TwoBppIsAnError) {
  const ImageRGBA8 img = cutout(32, 32);
  EncodeOptions o;
  o.format = Format::pvrtc1_2bpp;
  o.alpha_weighted = true;
  Result<std::vector<std::uint8_t>> r = encode(img, o);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code, ErrorCode::invalid_argument);
  EXPECT_NE(r.status().message.find("alpha_weighted"), std::string::npos) << r.status().message;
  EXPECT_NE(r.status().message.find("2 bpp"), std::string::npos) << r.status().message;
}

TEST(PvrtcAlphaWeighted, CompressRejectsPremultiplyAnd2Bpp) {
  const ImageRGBA8 img = cutout(32, 32);
  texture_file::CompressOptions o;
  o.encode.alpha_weighted = true;
  o.premultiply = true;
  Result<texture_file::CompressedImage> r = texture_file::compress_image(img, o, "a.png");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message.find("alpha_weighted applies to straight alpha"), std::string::npos)
      << r.status().message;
  o.premultiply = false;
  o.encode.format = Format::pvrtc1_2bpp;
  r = texture_file::compress_image(img, o, "a.png");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message.find("alpha_weighted and the 2 bpp format"), std::string::npos)
      << r.status().message;
}

}  // namespace
}  // namespace tessera::pvrtc
