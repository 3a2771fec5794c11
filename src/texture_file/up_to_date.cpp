// The up-to-date record beside each output of `tessera compress --skip-up-to-date` and
// `tessera.batch` (texture_file.h): built, compared and written here only, so that both
// front ends keep the same bytes and each skips what the other made.
#include <sys/stat.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>

#include "tessera/io.h"
#include "tessera/texture_file.h"

#ifndef TESSERA_VERSION_STRING
#error "TESSERA_VERSION_STRING must be defined by the build (src/CMakeLists.txt)"
#endif

namespace tessera::texture_file {

namespace {

std::int64_t mtime_ns(const struct stat& st) {
  return std::int64_t(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
}

Status stat_input(const std::string& path, struct stat& st) {
  if (path == "-") {
    return Status::error(ErrorCode::invalid_argument,
                         "-: standard input has no up-to-date record (no file to compare with)");
  }
  if (::stat(path.c_str(), &st) != 0) {
    return Status::error(ErrorCode::io_error, path + ": cannot examine: " + std::strerror(errno));
  }
  return Status::success();
}

Result<nlohmann::json> record_json(const RecordedOptions& options,
                                   std::span<const std::string> inputs) {
  nlohmann::json j = {{"tessera", TESSERA_VERSION_STRING},
                      {"container", options.container},
                      {"options",
                       {{"exact_search_rounds", options.exact_search_rounds},
                        {"format", options.format},
                        {"iterations", options.iterations},
                        {"mipmaps", options.mipmaps},
                        {"quality", options.quality},
                        {"resize_pot", options.resize_pot},
                        {"srgb", options.srgb}}}};
  // The options added later are recorded only when they are not their defaults, so that the
  // records of runs without them stay as they were and still match.
  nlohmann::json& o = j["options"];
  if (options.mip_levels) o["mip_levels"] = options.mip_levels;
  if (options.mip_filter != "box") o["mip_filter"] = options.mip_filter;
  if (options.flip_y) o["flip_y"] = true;
  if (options.premultiply) o["premultiply"] = true;
  if (options.alpha_bleed) o["alpha_bleed"] = true;
  if (options.alpha_weighted) o["alpha_weighted"] = true;
  if (options.normal_map) o["normal_map"] = true;
  if (options.zstd) o["zstd"] = options.zstd;
  if (options.cube) o["cube"] = true;
  if (options.array) o["array"] = true;
  if (inputs.size() == 1) {
    struct stat st {};
    if (Status s = stat_input(inputs.front(), st); !s.ok()) return s;
    j["input_size"] = std::int64_t(st.st_size);
    j["input_mtime_ns"] = mtime_ns(st);
    return j;
  }
  nlohmann::json list = nlohmann::json::array();
  for (const std::string& in : inputs) {
    struct stat st {};
    if (Status s = stat_input(in, st); !s.ok()) return s;
    list.push_back({{"path", in}, {"size", std::int64_t(st.st_size)}, {"mtime_ns", mtime_ns(st)}});
  }
  j["inputs"] = list;
  return j;
}

}  // namespace

Result<std::string> up_to_date_record(const RecordedOptions& options,
                                      std::span<const std::string> inputs) {
  Result<nlohmann::json> j = record_json(options, inputs);
  if (!j) return j.status();
  // A path that is not UTF-8 is written with U+FFFD for its bad bytes instead of failing after
  // the output was written (such a record never matches: that output is always made again).
  return j->dump(1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

bool is_up_to_date(const RecordedOptions& options, std::span<const std::string> inputs,
                   const std::string& output) {
  struct stat out {};
  if (::stat(output.c_str(), &out) != 0) return false;
  for (const std::string& input : inputs) {
    struct stat in {};
    if (input == "-" || ::stat(input.c_str(), &in) != 0 || mtime_ns(out) <= mtime_ns(in)) {
      return false;
    }
  }
  Result<std::vector<std::uint8_t>> text = io::read_file(output + kRecordSuffix, 1 << 20);
  if (!text) return false;
  const nlohmann::json stored = nlohmann::json::parse(text->begin(), text->end(), nullptr, false);
  Result<nlohmann::json> now = record_json(options, inputs);
  return !stored.is_discarded() && now && stored == *now;
}

Status write_up_to_date_record(const std::string& output, const std::string& record) {
  return io::write_file_atomic(
      output + kRecordSuffix,
      {reinterpret_cast<const std::uint8_t*>(record.data()), record.size()});
}

}  // namespace tessera::texture_file
