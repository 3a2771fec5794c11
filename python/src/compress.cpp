// Keyword checking and conversion for encode / encode_file; see compress.h.
#include "compress.h"

#include <string_view>
#include <utility>

namespace tessera::python {

namespace {

Status bad(const std::string& message) {
  return Status::error(ErrorCode::invalid_argument, message);
}

}  // namespace

Result<texture_file::CompressOptions> compress_options(const CompressKeywords& k) {
  if (k.format != "pvrtc1-4" && k.format != "pvrtc1-2") {
    return bad("format: '" + k.format + "' is not one of 'pvrtc1-4', 'pvrtc1-2'");
  }
  if (k.quality != "fast" && k.quality != "normal" && k.quality != "high") {
    return bad("quality: '" + k.quality + "' is not one of 'fast', 'normal', 'high'");
  }
  if (k.iterations < -1 || k.iterations > 1000) {
    return bad("iterations: " + std::to_string(k.iterations) + " is not in [-1, 1000]");
  }
  if (k.exact_search_rounds < 0 || k.exact_search_rounds > 1000) {
    return bad("exact_search_rounds: " + std::to_string(k.exact_search_rounds) +
               " is not in [0, 1000]");
  }
  if (k.mip_levels < 0 || k.mip_levels > 17) {
    return bad("mip_levels: " + std::to_string(k.mip_levels) + " is not in [0, 17]");
  }
  if (k.mip_filter != "box" && k.mip_filter != "lanczos" && k.mip_filter != "kaiser") {
    return bad("mip_filter: '" + k.mip_filter + "' is not one of 'box', 'lanczos', 'kaiser'");
  }
  if (k.threads < 0) return bad("threads: " + std::to_string(k.threads) + " is negative");
  // The CLI's usage errors (compress_usage_problem), in keywords.
  if (k.normal_map && k.srgb) {
    return bad("normal_map and srgb: a normal map holds vectors, never sRGB colour");
  }
  if (k.premultiply && k.alpha_bleed) {
    return bad(
        "alpha_bleed and premultiply: bleeding is for straight alpha (premultiplied "
        "transparent texels are black already)");
  }
  if (k.alpha_weighted && k.premultiply) {
    return bad(
        "alpha_weighted and premultiply: weighting is for straight alpha (premultiplied "
        "colour carries alpha already)");
  }
  if (k.alpha_weighted && k.format == "pvrtc1-2") {
    return bad(
        "alpha_weighted and format='pvrtc1-2': alpha-weighted colour error is for 4 bpp only");
  }
  if (k.mip_filter != "box" && !k.mipmaps && k.mip_levels == 0) {
    return bad("mip_filter='" + k.mip_filter + "' needs mipmaps=True or mip_levels=N");
  }
  texture_file::CompressOptions o;
  o.encode.format =
      k.format == "pvrtc1-2" ? pvrtc::Format::pvrtc1_2bpp : pvrtc::Format::pvrtc1_4bpp;
  o.encode.quality = k.quality == "fast"   ? pvrtc::Quality::fast
                     : k.quality == "high" ? pvrtc::Quality::high
                                           : pvrtc::Quality::normal;
  o.encode.iterations = k.iterations;
  o.encode.exact_search_rounds = k.exact_search_rounds;
  o.encode.threads = k.threads;
  o.mipmaps = k.mipmaps || k.mip_levels > 0;
  o.mip_levels = k.mip_levels;
  o.mip_filter = k.mip_filter == "lanczos"  ? image::MipFilter::lanczos
                 : k.mip_filter == "kaiser" ? image::MipFilter::kaiser
                                            : image::MipFilter::box;
  o.srgb = k.srgb;
  o.resize_pot = k.resize_pot;
  o.flip_y = k.flip_y;
  o.premultiply = k.premultiply;
  o.alpha_bleed = k.alpha_bleed;
  o.encode.alpha_weighted = k.alpha_weighted;
  o.normal_map = k.normal_map;
  return o;
}

std::string python_option_names(std::string message) {
  // The library's words for its options, each replaced once (the CLI's cli_option_names does
  // the same with its flags).
  static constexpr std::pair<std::string_view, std::string_view> kNames[] = {
      {"with resize_pot", "with resize_pot=True"},
      {"(use array)", "(use array=True)"},
      {"(with array: ", "(with array=True: "}};
  for (const auto& [library, keyword] : kNames) {
    if (const std::size_t at = message.find(library); at != std::string::npos) {
      message.replace(at, library.size(), keyword);
    }
  }
  return message;
}

Status check_zstd(int zstd, bool ktx2, const std::string& container_words) {
  if (zstd < 0 || zstd > 22) {
    return bad("zstd: " + std::to_string(zstd) + " is not in [0, 22]");
  }
  if (zstd != 0 && !ktx2) {
    return bad("zstd needs a KTX 2.0 output (" + container_words + ")");
  }
  return Status::success();
}

}  // namespace tessera::python
