// Shader programs: compilation and linking of tessera::glsl sources (tessera/glsl.h expands
// their `#include`s), info logs turned into one "FILE:LINE: message" line.
#include <algorithm>
#include <string>
#include <vector>

#include "gl/gl_api.h"
#include "glsl/log_text.h"
#include "tessera/gl.h"
#include "tessera/glsl.h"

namespace tessera::gl {

using namespace api;  // NOLINT(google-build-using-namespace): the loaded GL entry points

namespace {

GLenum stage_enum(glsl::Stage s) {
  switch (s) {
    case glsl::Stage::vertex:
      return GL_VERTEX_SHADER;
    case glsl::Stage::fragment:
      return GL_FRAGMENT_SHADER;
    case glsl::Stage::compute:
      return GL_COMPUTE_SHADER;
    case glsl::Stage::geometry:
      return GL_GEOMETRY_SHADER;
    case glsl::Stage::tess_control:
      return GL_TESS_CONTROL_SHADER;
    case glsl::Stage::tess_evaluation:
      return GL_TESS_EVALUATION_SHADER;
  }
  return GL_FRAGMENT_SHADER;
}

}  // namespace

int Program::uniform(const char* name) const { return glGetUniformLocation(get(), name); }

Result<Program> link_program(const std::vector<glsl::Source>& stages,
                             const glsl::ExpandOptions& options) {
  if (stages.empty()) {
    return Status::error(ErrorCode::invalid_argument, "link_program: no shader stages");
  }
  if (Status s = check_current_context("link_program (" + stages.front().name + ")"); !s.ok()) {
    return s;
  }
  Object program = create_object(ObjectType::program);
  std::vector<Object> shaders;
  std::string names;
  for (const glsl::Source& src : stages) {
    names += (names.empty() ? "" : ", ") + src.name;
    Result<glsl::Expanded> expanded = glsl::expand_includes(src, options);
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
      return Status::error(ErrorCode::invalid_argument, glsl::format_log(log, expanded->files));
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
    const std::string first = glsl::detail::first_nonempty_line(log);
    return Status::error(ErrorCode::invalid_argument,
                         "link error (" + names + "): " + (first.empty() ? "no log" : first));
  }
  if (Status s = check_errors("link_program (" + names + ")"); !s.ok()) return s;
  return Program(std::move(program));
}

}  // namespace tessera::gl
