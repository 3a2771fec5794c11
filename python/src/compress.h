// The Python keywords of `encode` / `encode_file` (the CLI's option names and values, held in
// texture_file::RecordedOptions) as the library's `texture_file::CompressOptions`, and library
// messages in the keywords' words.
#pragma once

#include <string>

#include "tessera/core.h"
#include "tessera/texture_file.h"

namespace tessera::python {

/// The library options for the keywords `words` (RecordedOptions: the CLI's option names and
/// defaults) and `threads` (as -j: 0 = all hardware threads): texture_file::compress_options
/// with the keywords' spelling, so an invalid_argument status names the keyword and the values
/// it takes, or the two keywords that conflict ("normal_map and srgb: a normal map holds
/// vectors, never sRGB colour", "mip_filter='lanczos' needs mipmaps=True or mip_levels=N").
Result<texture_file::CompressOptions> keyword_options(const texture_file::RecordedOptions& words,
                                                      int threads);

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
