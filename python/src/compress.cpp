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

Result<texture_file::CompressOptions> keyword_options(const texture_file::RecordedOptions& words,
                                                      int threads) {
  // Python's spelling: the keyword, then ='word', =True or =N.
  const auto keyword = [](std::string_view field, std::string_view value) {
    std::string s(field);
    if (value.empty()) return s;
    if (value == "True" || value == "N") return s + "=" + std::string(value);
    return s + "='" + std::string(value) + "'";
  };
  return texture_file::compress_options(words, threads, keyword);
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
