// The Python keywords of `encode` / `encode_file` (the CLI's option names and values) as the
// library's `texture_file::CompressOptions`, checked the way the CLI's parser checks them.
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
  bool srgb = false;
  bool resize_pot = false;
  int threads = 0;  ///< As -j: 0 = all hardware threads.
};

/// The library options for `keywords`, or an invalid_argument status naming the keyword and
/// the values it takes.
Result<texture_file::CompressOptions> compress_options(const CompressKeywords& keywords);

}  // namespace tessera::python
