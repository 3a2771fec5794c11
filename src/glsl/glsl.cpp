// The shipped GLSL library as strings (embedded at build time, src/core/embedded.h), `#include`
// expansion with `#line` bookkeeping, and compiler logs turned into one "FILE:LINE: message".
#include "tessera/glsl.h"

#include <algorithm>
#include <cstdlib>
#include <regex>
#include <set>
#include <sstream>

#include "core/embedded.h"
#include "glsl/log_text.h"
#include "tessera/io.h"

namespace tessera::glsl {

namespace detail {

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(std::move(line));
    if (end == text.size() || end + 1 == text.size()) break;  // no empty line after a final \n
    start = end + 1;
  }
  return lines;
}

std::string trim(std::string s) {
  while (!s.empty() && (s.back() == ' ' || s.back() == '\n' || s.back() == '\r')) s.pop_back();
  std::size_t b = 0;
  while (b < s.size() && s[b] == ' ') ++b;
  return s.substr(b);
}

std::string first_nonempty_line(std::string_view log) {
  for (const std::string& line : split_lines(std::string(log))) {
    if (std::string t = trim(line); !t.empty()) return t;
  }
  return {};
}

}  // namespace detail

namespace {

using detail::split_lines;
using detail::trim;

constexpr int kMaxIncludeDepth = 32;
constexpr int kMaxFiles = 2147483647 / kIncludeLineStride - 1;

// First line number of source-string `index` (see kIncludeLineStride).
long line_base(int index) { return long(index) * kIncludeLineStride; }

// The quoted name of an `#include "x"` line, or "" when the line is not one.
std::string include_target(const std::string& line) {
  static const std::regex re(R"re(^\s*#\s*include\s*"([^"]+)"\s*(//.*)?$)re");
  std::smatch m;
  return std::regex_match(line, m, re) ? m[1].str() : std::string();
}

bool is_version_line(const std::string& line) {
  static const std::regex re(R"(^\s*#\s*version\b.*$)");
  return std::regex_match(line, re);
}

const EmbeddedFile* find_embedded(std::string_view name) {
  const auto files = embedded::glsl_files();
  const auto it =
      std::lower_bound(files.begin(), files.end(), name,
                       [](const EmbeddedFile& f, std::string_view n) { return f.name < n; });
  return it != files.end() && it->name == name ? &*it : nullptr;
}

// The folder the shipped files are read from instead of the embedded copies ("" = embedded).
std::filesystem::path override_dir(const std::filesystem::path& dir) {
  if (!dir.empty()) return dir;
  if (const char* env = std::getenv("TESSERA_GLSL_DIR"); env && *env) return env;
  return {};
}

// One file found for an `#include`: its name in messages, a key for include-once, its text.
struct Included {
  std::string name, key, text;
  std::filesystem::path dir;  // its folder, for its own includes ("" for embedded files)
};

struct Expander {
  const ExpandOptions& options;
  Expanded out;
  std::set<std::string> included;
  bool version_seen = false;

  // Finds `target` beside the including file, on the include paths, then among the shipped
  // files; io_error naming the including file and line when it is nowhere.
  Result<Included> find(const std::string& target, const std::filesystem::path& dir,
                        const std::string& where) {
    std::vector<std::filesystem::path> candidates;
    if (!dir.empty()) candidates.push_back(dir / target);
    for (const auto& p : options.include_paths) candidates.push_back(p / target);
    std::error_code ec;
    for (const auto& c : candidates) {
      if (!std::filesystem::is_regular_file(c, ec)) continue;
      Result<std::vector<std::uint8_t>> bytes = io::read_file(c.string());
      if (!bytes) return bytes.status();
      const std::filesystem::path canonical = std::filesystem::weakly_canonical(c, ec);
      return Included{c.string(), (ec ? c : canonical).string(),
                      std::string(bytes->begin(), bytes->end()), c.parent_path()};
    }
    if (options.shipped_includes &&
        (!override_dir(options.shipped_dir).empty() || find_embedded(target) != nullptr)) {
      Result<std::string> text = shipped_source(target, options.shipped_dir);
      if (!text) return Status::error(text.status().code, where + text.status().message);
      return Included{target, "shipped:" + target, std::move(*text), {}};
    }
    std::string searched;
    for (const auto& c : candidates) {
      searched += (searched.empty() ? "" : ", ") + c.parent_path().string();
    }
    if (options.shipped_includes) searched += std::string(searched.empty() ? "" : ", ") + "shipped";
    return Status::error(ErrorCode::io_error,
                         where + "cannot find include file \"" + target +
                             "\" (searched: " + (searched.empty() ? "no folders" : searched) + ")");
  }

  Status expand(const std::string& text, const std::filesystem::path& dir, int index, int depth) {
    const std::vector<std::string> lines = split_lines(text);
    for (std::size_t i = 0; i < lines.size(); ++i) {
      const std::string& line = lines[i];
      const int line_no = int(i) + 1;
      if (depth == 0 && index == 0 && !version_seen && is_version_line(line)) {
        version_seen = true;
        out.text += line + "\n";
        for (const std::string& p : options.preamble) out.text += p + "\n";
        out.text += "#line " + std::to_string(line_no + 1) + " 0\n";
        continue;
      }
      const std::string target = include_target(line);
      if (target.empty()) {
        out.text += line + "\n";
        continue;
      }
      const std::string where =
          out.files[std::size_t(index)] + ":" + std::to_string(line_no) + ": ";
      if (depth >= kMaxIncludeDepth) {
        return Status::error(ErrorCode::invalid_argument,
                             where + "#include nested more than 32 deep");
      }
      Result<Included> found = find(target, dir, where);
      if (!found) return found.status();
      if (!included.insert(found->key).second) {
        out.text += "\n";  // already included: expands to nothing (keeps the line count)
        continue;
      }
      const int child = int(out.files.size());
      if (child > kMaxFiles) {
        return Status::error(ErrorCode::invalid_argument,
                             where + "more than " + std::to_string(kMaxFiles) + " included files");
      }
      out.files.push_back(found->name);
      out.text +=
          "#line " + std::to_string(line_base(child) + 1) + " " + std::to_string(child) + "\n";
      if (Status s = expand(found->text, found->dir, child, depth + 1); !s.ok()) return s;
      out.text += "#line " + std::to_string(line_base(index) + line_no + 1) + " " +
                  std::to_string(index) + "\n";
    }
    return Status::success();
  }
};

}  // namespace

std::vector<std::string> shipped_files() {
  std::vector<std::string> names;
  for (const EmbeddedFile& f : embedded::glsl_files()) names.emplace_back(f.name);
  return names;
}

Result<std::string> shipped_source(std::string_view name, const std::filesystem::path& dir) {
  const std::filesystem::path folder = override_dir(dir);
  if (!folder.empty()) {
    const std::filesystem::path path = folder / std::string(name);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
      return Status::error(ErrorCode::io_error, path.string() + ": no such GLSL file (" +
                                                    (dir.empty() ? "TESSERA_GLSL_DIR" : "folder") +
                                                    " " + folder.string() + ")");
    }
    Result<std::vector<std::uint8_t>> bytes = io::read_file(path.string());
    if (!bytes) return bytes.status();
    return std::string(bytes->begin(), bytes->end());
  }
  if (const EmbeddedFile* f = find_embedded(name)) return std::string(f->data);
  return Status::error(ErrorCode::io_error,
                       std::string(name) + ": not a shipped GLSL file of tessera");
}

Result<Source> shipped_shader(Stage stage, std::string_view name,
                              const std::filesystem::path& dir) {
  Result<std::string> text = shipped_source(name, dir);
  if (!text) return text.status();
  const std::filesystem::path folder = override_dir(dir);
  return Source{stage, std::move(*text),
                folder.empty() ? std::string(name) : (folder / std::string(name)).string()};
}

Result<Source> load_shader(Stage stage, const std::filesystem::path& path) {
  Result<std::vector<std::uint8_t>> bytes = io::read_file(path.string());
  if (!bytes) return bytes.status();
  return Source{stage, std::string(bytes->begin(), bytes->end()), path.string()};
}

Result<Expanded> expand_includes(const Source& source, const ExpandOptions& options) {
  Expander e{options, {}, {}, false};
  e.out.files.push_back(source.name);
  std::filesystem::path dir;
  std::error_code ec;
  if (std::filesystem::is_regular_file(source.name, ec)) {
    dir = std::filesystem::path(source.name).parent_path();
    if (dir.empty()) dir = ".";
    e.included.insert(std::filesystem::weakly_canonical(source.name, ec).string());
  }
  const bool has_version = std::ranges::any_of(
      split_lines(source.text), [](const std::string& l) { return is_version_line(l); });
  if (!has_version) {
    for (const std::string& p : options.preamble) e.out.text += p + "\n";
    if (!options.preamble.empty()) e.out.text += "#line 1 0\n";
  }
  if (Status s = e.expand(source.text, dir, 0, 0); !s.ok()) return s;
  return std::move(e.out);
}

std::string format_log(std::string_view log, const std::vector<std::string>& files) {
  // Mesa: "0:12(5): error: ..."; NVIDIA: "0(12) : error C1008: ..."; glslang: "ERROR: 0:12: ...";
  // shaderc: "name:12: error: ..." (the name it was given for the top-level source).
  static const std::regex mesa(R"(^\s*(\d+):(\d+)\(\d+\):\s*(.*)$)");
  static const std::regex nvidia(R"(^\s*(\d+)\((\d+)\)\s*:\s*(.*)$)");
  static const std::regex glslang(R"(^\s*ERROR:\s*(\d+):(\d+):\s*(.*)$)");
  static const std::regex shaderc(R"(^\s*()[^:\s][^:]*:(\d+):\s*(error:.*)$)");
  const std::vector<std::string> lines = split_lines(std::string(log));
  std::string fallback;
  auto located = [&](const std::smatch& m) {
    // Line numbers from kIncludeLineStride up identify the file themselves (some drivers,
    // Mesa 22 among them, report source-string 0 for errors inside included files).
    std::size_t index = m[1].length() ? std::size_t(std::stoul(m[1].str())) : 0;
    unsigned long line = std::stoul(m[2].str());
    if (line >= unsigned(kIncludeLineStride) || files.size() > 1) {
      index = line / unsigned(kIncludeLineStride);
      line %= unsigned(kIncludeLineStride);
    }
    const std::string file =
        index < files.size() ? files[index] : "source " + std::to_string(index);
    return file + ":" + std::to_string(line) + ": " + trim(m[3].str());
  };
  for (const std::string& line : lines) {
    if (fallback.empty() && !trim(line).empty()) fallback = trim(line);
    if (line.find("rror") == std::string::npos && line.find("RROR") == std::string::npos) {
      continue;  // not an error / ERROR line
    }
    std::smatch m;
    if (std::regex_match(line, m, glslang) || std::regex_match(line, m, mesa) ||
        std::regex_match(line, m, nvidia) || std::regex_match(line, m, shaderc)) {
      return located(m);
    }
  }
  for (const std::string& line : lines) {  // no error line: the first located message
    std::smatch m;
    if (std::regex_match(line, m, mesa) || std::regex_match(line, m, nvidia)) return located(m);
  }
  return fallback.empty() ? "unknown shader error (empty info log)" : fallback;
}

std::string float_literal(float v) {
  std::ostringstream o;
  o.precision(9);
  o << std::showpoint << v;
  return o.str();
}

}  // namespace tessera::glsl
