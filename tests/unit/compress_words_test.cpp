// texture_file::compress_options: the words a user typed (RecordedOptions) to CompressOptions,
// the one conversion of the CLI, Python, the batch and the benchmarks.
#include <gtest/gtest.h>

#include <string>
#include <string_view>

#include "tessera/texture_file.h"

namespace tessera::texture_file {
namespace {

TEST(CompressWords, DefaultsAreTheCliDefaults) {
  Result<CompressOptions> o = compress_options(RecordedOptions{}, 3);
  ASSERT_TRUE(o) << o.status().message;
  EXPECT_EQ(o->encode.format, pvrtc::Format::pvrtc1_4bpp);
  EXPECT_EQ(o->encode.quality, pvrtc::Quality::normal);
  EXPECT_EQ(o->encode.iterations, -1);
  EXPECT_EQ(o->encode.exact_search_rounds, 0);
  EXPECT_EQ(o->encode.threads, 3);
  EXPECT_FALSE(o->mipmaps);
  EXPECT_EQ(o->mip_filter, image::MipFilter::box);
  EXPECT_FALSE(o->srgb || o->resize_pot || o->flip_y || o->premultiply || o->alpha_bleed ||
               o->normal_map || o->encode.alpha_weighted);
}

TEST(CompressWords, EveryWordMapsToItsOption) {
  RecordedOptions w;
  w.format = "pvrtc1-2";
  w.quality = "high";
  w.iterations = 4;
  w.exact_search_rounds = 2;
  w.mip_levels = 3;  // implies the chain, as --mip-levels N does
  w.mip_filter = "kaiser";
  w.srgb = true;
  w.resize_pot = true;
  w.flip_y = true;
  w.alpha_bleed = true;
  Result<CompressOptions> o = compress_options(w, 0);
  ASSERT_TRUE(o) << o.status().message;
  EXPECT_EQ(o->encode.format, pvrtc::Format::pvrtc1_2bpp);
  EXPECT_EQ(o->encode.quality, pvrtc::Quality::high);
  EXPECT_EQ(o->encode.iterations, 4);
  EXPECT_EQ(o->encode.exact_search_rounds, 2);
  EXPECT_TRUE(o->mipmaps);
  EXPECT_EQ(o->mip_levels, 3);
  EXPECT_EQ(o->mip_filter, image::MipFilter::kaiser);
  EXPECT_TRUE(o->srgb && o->resize_pot && o->flip_y && o->alpha_bleed);
  w = RecordedOptions{};
  w.quality = "fast";
  w.mipmaps = true;
  w.mip_filter = "lanczos";
  w.premultiply = true;
  w.normal_map = true;
  o = compress_options(w, 0);
  ASSERT_TRUE(o) << o.status().message;
  EXPECT_EQ(o->encode.quality, pvrtc::Quality::fast);
  EXPECT_EQ(o->mip_filter, image::MipFilter::lanczos);
  EXPECT_TRUE(o->premultiply && o->normal_map && o->mipmaps);
}

/// The message for `w`, spelled as the CLI spells its flags.
std::string cli_message(const RecordedOptions& w) {
  const auto flag = [](std::string_view field, std::string_view value) {
    std::string f = "--" + std::string(field);
    for (char& c : f) c = c == '_' ? '-' : c;
    return value.empty() || value == "True" ? f : f + " " + std::string(value);
  };
  Result<CompressOptions> o = compress_options(w, 0, flag);
  EXPECT_FALSE(o);
  return o ? "" : o.status().message;
}

TEST(CompressWords, BadWordsAndConflictsNameTheOptionsInTheCallersSpelling) {
  RecordedOptions w;
  w.quality = "best";
  EXPECT_EQ(cli_message(w), "--quality: 'best' is not one of 'fast', 'normal', 'high'");
  Result<CompressOptions> o = compress_options(w, 0);  // default spelling: the member's name
  ASSERT_FALSE(o);
  EXPECT_EQ(o.status().code, ErrorCode::invalid_argument);
  EXPECT_EQ(o.status().message, "quality: 'best' is not one of 'fast', 'normal', 'high'");
  w = RecordedOptions{};
  w.format = "pvrtc2";
  EXPECT_EQ(cli_message(w), "--format: 'pvrtc2' is not one of 'pvrtc1-4', 'pvrtc1-2'");
  w = RecordedOptions{};
  w.mip_levels = 18;
  EXPECT_EQ(cli_message(w), "--mip-levels: 18 is not in [0, 17]");
  w = RecordedOptions{};
  w.iterations = -2;
  EXPECT_EQ(cli_message(w), "--iterations: -2 is not in [-1, 1000]");
  w = RecordedOptions{};
  w.normal_map = w.srgb = true;
  EXPECT_EQ(cli_message(w),
            "--normal-map and --srgb: a normal map holds vectors, never sRGB colour");
  w = RecordedOptions{};
  w.alpha_weighted = true;
  w.format = "pvrtc1-2";
  EXPECT_EQ(cli_message(w),
            "--alpha-weighted and --format pvrtc1-2: alpha-weighted colour error is for 4 bpp "
            "only");
  w = RecordedOptions{};
  w.mip_filter = "lanczos";
  EXPECT_EQ(cli_message(w), "--mip-filter lanczos needs --mipmaps or --mip-levels N");
  EXPECT_FALSE(compress_options(RecordedOptions{}, -1));
}

}  // namespace
}  // namespace tessera::texture_file
