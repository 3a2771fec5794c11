// Shader programs: `#include` expansion with `#line` bookkeeping, compilation, linking, and
// info logs turned into one "FILE:LINE: message" line.
#include <algorithm>
#include <cstdlib>
#include <regex>
#include <set>
#include <sstream>

#include "gl/gl_api.h"
#include "gl/glsl_dir.h"
#include "tessera/gl.h"
#include "tessera/io.h"

namespace tessera::gl {

using namespace api;  // NOLINT(google-build-using-namespace): the loaded GL entry points

namespace {

constexpr int kMaxIncludeDepth = 32;
constexpr int kMaxFiles = 2147483647 / kIncludeLineStride - 1;

// First line number of source-string `index` (see kIncludeLineStride).
long line_base(int index) { return long(index) * kIncludeLineStride; }

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

struct Expander {
  const ShaderOptions& options;
  ExpandedSource out;
  std::set<std::filesystem::path> included;
  bool version_seen = false;

  Status expand(const std::string& text, const std::filesystem::path& dir, int index,
                int depth) {
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
      std::vector<std::filesystem::path> candidates;
      if (!dir.empty()) candidates.push_back(dir / target);
      for (const auto& p : options.include_paths) candidates.push_back(p / target);
      std::filesystem::path found;
      std::error_code ec;
      for (const auto& c : candidates) {
        if (std::filesystem::is_regular_file(c, ec)) {
          found = c;
          break;
        }
      }
      if (found.empty()) {
        std::string searched;
        for (const auto& c : candidates) {
          searched += (searched.empty() ? "" : ", ") + c.parent_path().string();
        }
        return Status::error(ErrorCode::io_error,
                             where + "cannot find include file \"" + target + "\" (searched: " +
                                 (searched.empty() ? "no folders" : searched) + ")");
      }
      const std::filesystem::path canonical = std::filesystem::weakly_canonical(found, ec);
      if (!included.insert(ec ? found : canonical).second) {
        out.text += "\n";  // already included: expands to nothing (keeps the line count)
        continue;
      }
      Result<std::vector<std::uint8_t>> bytes = io::read_file(found.string());
      if (!bytes) return bytes.status();
      const int child = int(out.files.size());
      if (child > kMaxFiles) {
        return Status::error(ErrorCode::invalid_argument, where + "more than " +
                                                              std::to_string(kMaxFiles) +
                                                              " included files");
      }
      out.files.push_back(found.string());
      out.text += "#line " + std::to_string(line_base(child) + 1) + " " + std::to_string(child) +
                  "\n";
      const std::string child_text(bytes->begin(), bytes->end());
      if (Status s = expand(child_text, found.parent_path(), child, depth + 1); !s.ok()) return s;
      out.text += "#line " + std::to_string(line_base(index) + line_no + 1) + " " +
                  std::to_string(index) + "\n";
    }
    return Status::success();
  }
};

GLenum stage_enum(ShaderStage s) {
  switch (s) {
    case ShaderStage::vertex: return GL_VERTEX_SHADER;
    case ShaderStage::fragment: return GL_FRAGMENT_SHADER;
    case ShaderStage::compute: return GL_COMPUTE_SHADER;
    case ShaderStage::geometry: return GL_GEOMETRY_SHADER;
    case ShaderStage::tess_control: return GL_TESS_CONTROL_SHADER;
    case ShaderStage::tess_evaluation: return GL_TESS_EVALUATION_SHADER;
  }
  return GL_FRAGMENT_SHADER;
}

std::string trim(std::string s) {
  while (!s.empty() && (s.back() == ' ' || s.back() == '\n' || s.back() == '\r')) s.pop_back();
  std::size_t b = 0;
  while (b < s.size() && s[b] == ' ') ++b;
  return s.substr(b);
}

}  // namespace

Result<ExpandedSource> expand_includes(const ShaderSource& source, const ShaderOptions& options) {
  Expander e{options, {}, {}, false};
  e.out.files.push_back(source.name);
  std::filesystem::path dir;
  std::error_code ec;
  if (std::filesystem::is_regular_file(source.name, ec)) {
    dir = std::filesystem::path(source.name).parent_path();
    if (dir.empty()) dir = ".";
    e.included.insert(std::filesystem::weakly_canonical(source.name, ec));
  }
  const bool has_version =
      std::ranges::any_of(split_lines(source.text), [](const std::string& l) {
        return is_version_line(l);
      });
  if (!has_version) {
    for (const std::string& p : options.preamble) e.out.text += p + "\n";
    if (!options.preamble.empty()) e.out.text += "#line 1 0\n";
  }
  if (Status s = e.expand(source.text, dir, 0, 0); !s.ok()) return s;
  return std::move(e.out);
}

std::string format_shader_log(std::string_view log, const std::vector<std::string>& files) {
  // Mesa: "0:12(5): error: ..."; NVIDIA: "0(12) : error C1008: ..."; glslang: "ERROR: 0:12: ...".
  static const std::regex mesa(R"(^\s*(\d+):(\d+)\(\d+\):\s*(.*)$)");
  static const std::regex nvidia(R"(^\s*(\d+)\((\d+)\)\s*:\s*(.*)$)");
  static const std::regex glslang(R"(^\s*ERROR:\s*(\d+):(\d+):\s*(.*)$)");
  const std::vector<std::string> lines = split_lines(std::string(log));
  std::string fallback;
  auto located = [&](const std::smatch& m) {
    // Line numbers from kIncludeLineStride up identify the file themselves (some drivers,
    // Mesa 22 among them, report source-string 0 for errors inside included files).
    std::size_t index = std::size_t(std::stoul(m[1].str()));
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
        std::regex_match(line, m, nvidia)) {
      return located(m);
    }
  }
  for (const std::string& line : lines) {  // no error line: the first located message
    std::smatch m;
    if (std::regex_match(line, m, mesa) || std::regex_match(line, m, nvidia)) return located(m);
  }
  return fallback.empty() ? "unknown shader error (empty info log)" : fallback;
}

int Program::uniform(const char* name) const { return glGetUniformLocation(get(), name); }

Result<Program> link_program(const std::vector<ShaderSource>& stages,
                             const ShaderOptions& options) {
  if (stages.empty()) {
    return Status::error(ErrorCode::invalid_argument, "link_program: no shader stages");
  }
  Object program = create_object(ObjectType::program);
  std::vector<Object> shaders;
  std::string names;
  for (const ShaderSource& src : stages) {
    names += (names.empty() ? "" : ", ") + src.name;
    Result<ExpandedSource> expanded = expand_includes(src, options);
    if (!expanded) return expanded.status();
    Object shader = create_object(ObjectType::shader, stage_enum(src.stage));
    const char* text = expanded->text.c_str();
    glShaderSource(shader.get(), 1, &text, nullptr);
    glCompileShader(shader.get());
    GLint ok = 0, length = 0;
    glGetShaderiv(shader.get(), GL_COMPILE_STATUS, &ok);
    if (!ok) {
      glGetShaderiv(shader.get(), GL_INFO_LOG_LENGTH, &length);
      std::string log(std::size_t(std::max(length, 1)), '\0');
      glGetShaderInfoLog(shader.get(), GLsizei(log.size()), nullptr, log.data());
      log.resize(log.find('\0') == std::string::npos ? log.size() : log.find('\0'));
      return Status::error(ErrorCode::invalid_argument,
                           format_shader_log(log, expanded->files));
    }
    glAttachShader(program.get(), shader.get());
    shaders.push_back(std::move(shader));
  }
  glLinkProgram(program.get());
  for (const Object& s : shaders) glDetachShader(program.get(), s.get());
  GLint ok = 0, length = 0;
  glGetProgramiv(program.get(), GL_LINK_STATUS, &ok);
  if (!ok) {
    glGetProgramiv(program.get(), GL_INFO_LOG_LENGTH, &length);
    std::string log(std::size_t(std::max(length, 1)), '\0');
    glGetProgramInfoLog(program.get(), GLsizei(log.size()), nullptr, log.data());
    log.resize(log.find('\0') == std::string::npos ? log.size() : log.find('\0'));
    std::string first;
    for (const std::string& l : split_lines(log)) {
      if (!trim(l).empty()) {
        first = trim(l);
        break;
      }
    }
    return Status::error(ErrorCode::invalid_argument,
                         "link error (" + names + "): " + (first.empty() ? "no log" : first));
  }
  if (Status s = check_errors("link_program (" + names + ")"); !s.ok()) return s;
  return Program(std::move(program));
}

std::string glsl_float(float v) {
  std::ostringstream o;
  o.precision(9);
  o << std::showpoint << v;
  return o.str();
}

Result<std::filesystem::path> find_glsl_dir(const std::filesystem::path& given,
                                            std::initializer_list<const char*> files,
                                            std::string_view what, std::string_view option) {
  const auto missing = [&](const std::filesystem::path& dir) -> const char* {
    std::error_code ec;
    for (const char* f : files) {
      if (!std::filesystem::is_regular_file(dir / f, ec)) return f;
    }
    return nullptr;
  };
  if (!given.empty()) {
    if (const char* f = missing(given)) {
      return Status::error(ErrorCode::io_error, given.string() + ": no " + f + " there");
    }
    return given;
  }
  std::vector<std::filesystem::path> tried;
  if (const char* env = std::getenv("TESSERA_GLSL_DIR"); env && *env) tried.emplace_back(env);
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    tried.push_back(exe.parent_path() / ".." / "share" / "tessera" / "glsl");
    tried.push_back(exe.parent_path() / ".." / ".." / "share" / "tessera" / "glsl");
  }
  for (const auto& d : tried) {
    if (!missing(d)) return d.lexically_normal();
  }
  return Status::error(ErrorCode::io_error, std::string(what) +
                                                ": share/tessera/glsl not found (set "
                                                "TESSERA_GLSL_DIR or " +
                                                std::string(option) + ")");
}

Result<ShaderSource> load_shader(ShaderStage stage, const std::filesystem::path& path) {
  Result<std::vector<std::uint8_t>> bytes = io::read_file(path.string());
  if (!bytes) return bytes.status();
  ShaderSource s;
  s.stage = stage;
  s.text.assign(bytes->begin(), bytes->end());
  s.name = path.string();
  return s;
}

}  // namespace tessera::gl
