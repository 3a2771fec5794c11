// The encoder's progress hook (EncodeOptions::progress) and compress_image's mapping of it
// over a mip chain: reports never go backwards, the last is exactly 1.0, every report comes
// from the calling thread, and the output bytes are the same with and without a hook; and
// compress_view, the same pipeline on pixels the caller owns.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "tessera/procedural.h"
#include "tessera/pvrtc.h"
#include "tessera/texture_file.h"

namespace tessera::pvrtc {
namespace {

struct Recorder {
  std::vector<double> fractions;
  bool other_thread = false;
  std::thread::id caller = std::this_thread::get_id();
  std::function<void(double)> hook() {
    return [this](double f) {
      if (std::this_thread::get_id() != caller) other_thread = true;
      fractions.push_back(f);
    };
  }
};

void expect_well_formed(const Recorder& r, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_FALSE(r.fractions.empty());
  EXPECT_FALSE(r.other_thread) << "a report came from a worker thread";
  EXPECT_EQ(r.fractions.front(), 0.0);
  EXPECT_EQ(r.fractions.back(), 1.0);
  for (std::size_t i = 1; i < r.fractions.size(); ++i) {
    EXPECT_GT(r.fractions[i], r.fractions[i - 1]) << "report " << i;
  }
  for (double f : r.fractions) {
    EXPECT_GE(f, 0.0);
    EXPECT_LE(f, 1.0);
  }
}

struct Case {
  Format format;
  Quality quality;
  int iterations;
  int exact_search_rounds;
  const char* name;
};

TEST(PvrtcProgress, MonotonicEndsAtOneAndLeavesTheBytesAlone) {
  const Case cases[] = {
      {Format::pvrtc1_4bpp, Quality::fast, -1, 0, "4bpp fast"},
      {Format::pvrtc1_4bpp, Quality::normal, -1, 0, "4bpp normal"},
      {Format::pvrtc1_4bpp, Quality::high, -1, 0, "4bpp high"},
      {Format::pvrtc1_2bpp, Quality::normal, -1, 0, "2bpp normal"},
      {Format::pvrtc1_2bpp, Quality::high, -1, 0, "2bpp high"},
      {Format::pvrtc1_4bpp, Quality::fast, 2, 0, "4bpp fast, 2 sweeps"},
      {Format::pvrtc1_4bpp, Quality::normal, -1, 3, "4bpp normal, 3 search rounds"},
      {Format::pvrtc1_2bpp, Quality::high, -1, 2, "2bpp high, search rounds override"},
  };
  for (Procedural kind : {Procedural::foliage, Procedural::text}) {
    const ImageRGBA8 img = make_procedural(kind, 128, 64);
    for (const Case& c : cases) {
      EncodeOptions o;
      o.format = c.format;
      o.quality = c.quality;
      o.iterations = c.iterations;
      o.exact_search_rounds = c.exact_search_rounds;
      o.threads = 2;
      Result<std::vector<std::uint8_t>> plain = encode(img, o);
      ASSERT_TRUE(plain.ok()) << plain.status().message;
      Recorder r;
      o.progress = r.hook();
      Result<std::vector<std::uint8_t>> hooked = encode(img, o);
      ASSERT_TRUE(hooked.ok()) << hooked.status().message;
      const std::string what = std::string(procedural_name(kind)) + ", " + c.name;
      EXPECT_EQ(*plain, *hooked) << what << ": the hook changed the output";
      expect_well_formed(r, what);
      if (c.quality == Quality::high && c.exact_search_rounds == 0) {
        EXPECT_GE(r.fractions.size(), 8u) << what << ": too few reports for a long encode";
      }
    }
  }
}

TEST(PvrtcProgress, SmallAndPaddedLevels) {
  for (int size : {1, 4, 8}) {
    const ImageRGBA8 img = make_procedural(Procedural::bricks, size, size);
    EncodeOptions o;
    o.quality = Quality::high;
    Recorder r;
    o.progress = r.hook();
    ASSERT_TRUE(encode(img, o).ok());
    expect_well_formed(r, std::to_string(size) + "x" + std::to_string(size));
  }
}

TEST(PvrtcProgress, NoReportsAfterAFailedEncode) {
  ImageRGBA8 img(3, 4);  // not a power of two
  EncodeOptions o;
  Recorder r;
  o.progress = r.hook();
  EXPECT_FALSE(encode(img, o).ok());
  EXPECT_TRUE(r.fractions.empty());
}

TEST(PvrtcProgress, CompressImageCoversTheMipChainByPixels) {
  const ImageRGBA8 img = make_procedural(Procedural::foliage, 128, 128);
  texture_file::CompressOptions o;
  o.encode.quality = Quality::normal;
  o.mipmaps = true;
  Result<texture_file::CompressedImage> plain = texture_file::compress_image(img, o, "plain");
  ASSERT_TRUE(plain.ok()) << plain.status().message;
  Recorder r;
  o.encode.progress = r.hook();
  Result<texture_file::CompressedImage> hooked = texture_file::compress_image(img, o, "hooked");
  ASSERT_TRUE(hooked.ok()) << hooked.status().message;
  ASSERT_EQ(plain->texture.levels.size(), hooked->texture.levels.size());
  for (std::size_t i = 0; i < plain->texture.levels.size(); ++i) {
    EXPECT_EQ(plain->texture.levels[i], hooked->texture.levels[i]) << "level " << i;
  }
  expect_well_formed(r, "mip chain");
  // Level 0 holds 3/4 of the chain's pixels: the reports pass through about 0.75 (level 1
  // starting) and do not reach 1.0 before the last level.
  bool near_three_quarters = false;
  for (double f : r.fractions) near_three_quarters |= f > 0.70 && f < 0.80;
  EXPECT_TRUE(near_three_quarters);
  EXPECT_EQ(std::count(r.fractions.begin(), r.fractions.end(), 1.0), 1);
}

// compress_view (what tessera.encode calls on a numpy array) is compress_image on the view's
// packed copy: the same texture, alpha detection and errors, for the in-place path (RGB and
// RGBA, power of two, one level) and the copying one (mip chain, resample); its progress is as
// well formed.
TEST(PvrtcProgress, CompressViewIsCompressImageOfItsCopy) {
  const ImageRGBA8 foliage = make_procedural(Procedural::foliage, 64, 32);
  ImageRGBA8 opaque = foliage;
  for (std::size_t i = 3; i < opaque.pixels.size(); i += 4) opaque.pixels[i] = 255;
  std::vector<std::uint8_t> rgb;
  for (std::size_t i = 0; i < foliage.pixels.size(); i += 4) {
    rgb.insert(rgb.end(), foliage.pixels.begin() + std::ptrdiff_t(i),
               foliage.pixels.begin() + std::ptrdiff_t(i) + 3);
  }
  const ImageRGBA8 odd = make_procedural(Procedural::bricks, 40, 24);
  const ImageView8 views[] = {ImageView8::of(foliage), ImageView8::of(opaque),
                              ImageView8{rgb.data(), 64, 32, 3, 3, 64 * 3, false},
                              ImageView8::of(odd)};
  for (const ImageView8& view : views) {
    for (int variant = 0; variant < 3; ++variant) {
      texture_file::CompressOptions o;
      o.encode.quality = Quality::fast;
      o.mipmaps = variant == 1;
      o.resize_pot = variant == 2;
      o.encode.format = variant == 2 ? Format::pvrtc1_2bpp : Format::pvrtc1_4bpp;
      const std::string what = std::to_string(view.width) + "x" + std::to_string(view.height) +
                               " " + std::to_string(view.channels) + "ch, variant " +
                               std::to_string(variant);
      Result<texture_file::CompressedImage> owned =
          texture_file::compress_image(to_image(view), o, "img");
      Recorder r;
      o.encode.progress = r.hook();
      Result<texture_file::CompressedTexture> viewed = texture_file::compress_view(view, o, "img");
      ASSERT_EQ(owned.ok(), viewed.ok()) << what;
      if (!owned.ok()) {
        EXPECT_EQ(owned.status().message, viewed.status().message) << what;
        EXPECT_TRUE(r.fractions.empty()) << what;
        continue;
      }
      EXPECT_EQ(owned->texture.levels, viewed->levels) << what;
      EXPECT_EQ(owned->texture.has_alpha, viewed->has_alpha) << what;
      EXPECT_EQ(owned->texture.width, viewed->width) << what;
      EXPECT_EQ(owned->texture.format, viewed->format) << what;
      expect_well_formed(r, what);
    }
  }
  // The opaque RGBA view gives an RGB texture, the translucent one keeps its alpha.
  texture_file::CompressOptions o;
  o.encode.quality = Quality::fast;
  EXPECT_FALSE(texture_file::compress_view(views[1], o, "o")->has_alpha);
  EXPECT_TRUE(texture_file::compress_view(views[0], o, "t")->has_alpha);
  Result<texture_file::CompressedTexture> bad = texture_file::compress_view(views[3], o, "odd");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message.rfind("odd: size 40x24 is not a power of two", 0), 0u)
      << bad.status().message;
}

}  // namespace
}  // namespace tessera::pvrtc
