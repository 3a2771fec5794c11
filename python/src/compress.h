// The Python keywords of `encode` / `encode_file` (the CLI's option names and values) as the
// library's `texture_file::CompressOptions`, checked the way the CLI's parser checks them, and
// library messages in the keywords' words.
#pragma once

#include <string>

#include "tessera/core.h"
#include "tessera/texture_file.h"

namespace tessera::python {

/// The options of `tessera compress`, with the CLI's names and defaults.
struct CompressKeywords {
  std::string format = "pvrtc1-4";  ///< "pvrtc1-4" or "pvrtc1-2".
  std::string quality = "normal";   ///< "fast", "normal" or "high".
  int iterations = -1;              ///< -1..1000, as --iterations.
  int exact_search_rounds = 0;      ///< 0..1000, as --exact-search-rounds.
  bool mipmaps = false;
  int mip_levels = 0;              ///< 0..17; > 0 implies `mipmaps`, as --mip-levels N does.
  std::string mip_filter = "box";  ///< "box", "lanczos" or "kaiser".
  bool srgb = false;
  bool resize_pot = false;
  bool flip_y = false;
  bool premultiply = false;
  bool alpha_bleed = false;
  bool alpha_weighted = false;  ///< As --alpha-weighted (4 bpp, straight alpha).
  bool normal_map = false;
  int threads = 0;  ///< As -j: 0 = all hardware threads.
};

/// The library options for `keywords`, or an invalid_argument status naming the keyword and
/// the values it takes, or the two keywords that conflict (the CLI's usage errors, in
/// keywords: "normal_map and srgb: a normal map holds vectors, never sRGB colour").
Result<texture_file::CompressOptions> compress_options(const CompressKeywords& keywords);

/// A library message with the library's option names as Python keywords ("resample to 64x64
/// with resize_pot" -> "... with resize_pot=True"), as the CLI shows its flags.
std::string python_option_names(std::string message);

/// `result`, its message (if it failed) in Python's words (`python_option_names`).
template <class T>
Result<T> in_python_words(Result<T> result) {
  if (result) return result;
  Status s = result.status();
  s.message = python_option_names(std::move(s.message));
  return s;
}

/// Checks the `zstd` keyword of `to_bytes` / `write`: 0..22, and not 0 only for KTX 2.0
/// (`container_words` says how the container is chosen, e.g. "container='ktx2'").
Status check_zstd(int zstd, bool ktx2, const std::string& container_words);

}  // namespace tessera::python
