// texture_file::compress_options: the options a user typed (RecordedOptions) as CompressOptions,
// checked once for the CLI, Python, the batch and the benchmarks.
#include <array>
#include <string>
#include <string_view>

#include "tessera/texture_file.h"

namespace tessera::texture_file {

namespace {

Status bad(std::string message) {
  return Status::error(ErrorCode::invalid_argument, std::move(message));
}

/// "'a', 'b', 'c'".
template <std::size_t N>
std::string listed(const std::array<std::string_view, N>& values) {
  std::string s;
  for (std::string_view v : values) s += (s.empty() ? "'" : ", '") + std::string(v) + "'";
  return s;
}

/// Index of `word` in `values`, or -1.
template <std::size_t N>
int index_of(const std::array<std::string_view, N>& values, const std::string& word) {
  for (std::size_t i = 0; i < N; ++i) {
    if (values[i] == word) return int(i);
  }
  return -1;
}

constexpr std::array<std::string_view, 2> kFormats = {"pvrtc1-4", "pvrtc1-2"};
constexpr std::array<std::string_view, 3> kQualities = {"fast", "normal", "high"};
constexpr std::array<std::string_view, 3> kMipFilters = {"box", "lanczos", "kaiser"};
constexpr std::array<pvrtc::Quality, 3> kQualityValues = {
    pvrtc::Quality::fast, pvrtc::Quality::normal, pvrtc::Quality::high};
constexpr std::array<image::MipFilter, 3> kMipFilterValues = {
    image::MipFilter::box, image::MipFilter::lanczos, image::MipFilter::kaiser};

/// The values and ranges of each option.
Status check_words(const RecordedOptions& w, const OptionSpeller& name) {
  if (index_of(kFormats, w.format) < 0) {
    return bad(name("format", "") + ": '" + w.format + "' is not one of " + listed(kFormats));
  }
  if (index_of(kQualities, w.quality) < 0) {
    return bad(name("quality", "") + ": '" + w.quality + "' is not one of " + listed(kQualities));
  }
  if (w.iterations < -1 || w.iterations > 1000) {
    return bad(name("iterations", "") + ": " + std::to_string(w.iterations) +
               " is not in [-1, 1000]");
  }
  if (w.exact_search_rounds < 0 || w.exact_search_rounds > 1000) {
    return bad(name("exact_search_rounds", "") + ": " + std::to_string(w.exact_search_rounds) +
               " is not in [0, 1000]");
  }
  if (w.mip_levels < 0 || w.mip_levels > 17) {
    return bad(name("mip_levels", "") + ": " + std::to_string(w.mip_levels) + " is not in [0, 17]");
  }
  if (index_of(kMipFilters, w.mip_filter) < 0) {
    return bad(name("mip_filter", "") + ": '" + w.mip_filter + "' is not one of " +
               listed(kMipFilters));
  }
  return Status::success();
}

/// Two options that cannot go together (the CLI's usage errors).
Status check_conflicts(const RecordedOptions& w, const OptionSpeller& name) {
  if (w.normal_map && w.srgb) {
    return bad(name("normal_map", "") + " and " + name("srgb", "") +
               ": a normal map holds vectors, never sRGB colour");
  }
  if (w.premultiply && w.alpha_bleed) {
    return bad(name("alpha_bleed", "") + " and " + name("premultiply", "") +
               ": bleeding is for straight alpha (premultiplied transparent texels are black "
               "already)");
  }
  if (w.alpha_weighted && w.premultiply) {
    return bad(name("alpha_weighted", "") + " and " + name("premultiply", "") +
               ": weighting is for straight alpha (premultiplied colour carries alpha already)");
  }
  if (w.alpha_weighted && w.format == "pvrtc1-2") {
    return bad(name("alpha_weighted", "") + " and " + name("format", "pvrtc1-2") +
               ": alpha-weighted colour error is for 4 bpp only");
  }
  if (w.mip_filter != "box" && !w.mipmaps && w.mip_levels == 0) {
    return bad(name("mip_filter", w.mip_filter) + " needs " + name("mipmaps", "True") + " or " +
               name("mip_levels", "N"));
  }
  return Status::success();
}

}  // namespace

Result<CompressOptions> compress_options(const RecordedOptions& words, int threads,
                                         const OptionSpeller& spell) {
  const OptionSpeller name = spell ? spell : [](std::string_view field, std::string_view value) {
    return value.empty() ? std::string(field) : std::string(field) + "=" + std::string(value);
  };
  if (Status s = check_words(words, name); !s.ok()) return s;
  if (Status s = check_conflicts(words, name); !s.ok()) return s;
  if (threads < 0) return bad("threads: " + std::to_string(threads) + " is negative");
  CompressOptions o;
  o.encode.format =
      words.format == "pvrtc1-2" ? pvrtc::Format::pvrtc1_2bpp : pvrtc::Format::pvrtc1_4bpp;
  o.encode.quality = kQualityValues[std::size_t(index_of(kQualities, words.quality))];
  o.encode.iterations = words.iterations;
  o.encode.exact_search_rounds = words.exact_search_rounds;
  o.encode.threads = threads;
  o.encode.alpha_weighted = words.alpha_weighted;
  o.mipmaps = words.mipmaps || words.mip_levels > 0;
  o.mip_levels = words.mip_levels;
  o.mip_filter = kMipFilterValues[std::size_t(index_of(kMipFilters, words.mip_filter))];
  o.srgb = words.srgb;
  o.resize_pot = words.resize_pot;
  o.flip_y = words.flip_y;
  o.premultiply = words.premultiply;
  o.alpha_bleed = words.alpha_bleed;
  o.normal_map = words.normal_map;
  return o;
}

}  // namespace tessera::texture_file
