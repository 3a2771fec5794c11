// tessera/glsl.h — the shipped GLSL library (share/tessera/glsl) as strings, and `#include`
// expansion for shaders that use it. Part of the core `tessera` library: no OpenGL, no Vulkan.
//
// Contract: the shipped files are embedded in the library at build time (generated from
// share/tessera/glsl, the one source of truth), so nothing here reads a file unless asked to: by
// a non-empty `dir` / `ExpandOptions::include_paths`, an `#include` of a file that lies beside a
// source named by its path, or the development override $TESSERA_GLSL_DIR (a folder read
// instead of the embedded copies). An engine that compiles its own shaders calls
// `expand_includes` on them and compiles the full string itself (glShaderSource, shaderc, ...).
// Every function is pure or reads files only; all are thread-safe.
// Tests: tests/unit/glsl_test.cpp (includes, #line, logs), tests/glsl/ (the shipped GLSL compiled).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/core.h"

namespace tessera::glsl {

/// A pipeline stage, for the compilers that need one (GL shader type, shaderc kind).
enum class Stage { vertex, fragment, compute, geometry, tess_control, tess_evaluation };

/// One stage's source. `name` appears in error messages: a file path, a shipped file's name
/// ("seams_render.frag") or e.g. "engine hook".
struct Source {
  Stage stage = Stage::fragment;
  std::string text;
  std::string name = "<string>";
};

/// The names of the shipped files, sorted ("adaptive_component.glsl", ..., "seams_render.vert").
std::vector<std::string> shipped_files();

/// Returns the text of shipped file `name`: read from `dir` when it is not empty, else from
/// $TESSERA_GLSL_DIR when that is set, else the copy embedded at build time. Fails (io_error)
/// naming the file and the folder it looked in.
Result<std::string> shipped_source(std::string_view name, const std::filesystem::path& dir = {});

/// `shipped_source` as a `Source` of `stage` (its name is `name`, or the path read).
Result<Source> shipped_shader(Stage stage, std::string_view name,
                              const std::filesystem::path& dir = {});

/// Reads a shader file (io_error naming the path) into a `Source` named by its path.
Result<Source> load_shader(Stage stage, const std::filesystem::path& path);

struct ExpandOptions {
  /// Folders searched, in order, for `#include "x"` after the including file's own folder.
  std::vector<std::filesystem::path> include_paths;
  /// Lines inserted after `#version`, e.g. "#define TESSERA_SEAMS_CLASSES 4".
  std::vector<std::string> preamble;
  /// An `#include` found in no folder resolves to the shipped file of that name (see
  /// `shipped_source`; `shipped_dir` is its `dir`).
  bool shipped_includes = true;
  std::filesystem::path shipped_dir;
};

/// Lines of included file N (N >= 1) are numbered from N * kIncludeLineStride + 1 by the
/// `#line` directives `expand_includes` writes, so an info log line number alone identifies the
/// file (Mesa 22 reports source-string 0 for some errors inside included files).
inline constexpr int kIncludeLineStride = 100000;

/// A source after `#include` expansion: `text` carries `#line L N` directives (see
/// kIncludeLineStride), and `files[N]` is the name of source-string number N (0 = the
/// top-level source).
struct Expanded {
  std::string text;
  std::vector<std::string> files;
};

/// Returns `source` with every `#include "x"` line replaced by file x (nested, each file once: a
/// repeated include expands to nothing; at most 32 deep) and the preamble inserted after
/// `#version`. Fails (io_error) naming the including file and line when x is not found.
Result<Expanded> expand_includes(const Source& source, const ExpandOptions& options = {});

/// Returns the first error of a compiler log as "FILE:LINE: message", for Mesa ("0:12(5): error:
/// ..."), NVIDIA ("0(12) : error C1008: ...") and glslang/shaderc ("ERROR: 0:12: ..."; "name:12:
/// error: ...") logs. With more than one file the file is the line number / kIncludeLineStride
/// (the source-string number is not trusted); with one it is the source-string number. Falls
/// back to the first non-empty line of the log. Pure.
std::string format_log(std::string_view log, const std::vector<std::string>& files);

/// `v` as a GLSL float literal that reads back to the same float (9 significant digits, always
/// with a decimal point). Pure.
std::string float_literal(float v);

}  // namespace tessera::glsl
