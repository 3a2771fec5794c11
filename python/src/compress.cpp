// Keyword checking and conversion for encode / encode_file; see compress.h.
#include "compress.h"

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
  if (k.threads < 0) return bad("threads: " + std::to_string(k.threads) + " is negative");
  texture_file::CompressOptions o;
  o.encode.format =
      k.format == "pvrtc1-2" ? pvrtc::Format::pvrtc1_2bpp : pvrtc::Format::pvrtc1_4bpp;
  o.encode.quality = k.quality == "fast"   ? pvrtc::Quality::fast
                     : k.quality == "high" ? pvrtc::Quality::high
                                           : pvrtc::Quality::normal;
  o.encode.iterations = k.iterations;
  o.encode.exact_search_rounds = k.exact_search_rounds;
  o.encode.threads = k.threads;
  o.mipmaps = k.mipmaps;
  o.srgb = k.srgb;
  o.resize_pot = k.resize_pot;
  return o;
}

}  // namespace tessera::python
