// Internal: the line handling of shader sources and compiler / linker logs, shared by the GLSL
// library (src/glsl/glsl.cpp) and the GL backend's link errors (src/gl/shader.cpp). Pure.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace tessera::glsl::detail {

/// Splits `text` at '\n' (a trailing '\r' is dropped from each line; no empty line is added
/// after a final '\n').
std::vector<std::string> split_lines(const std::string& text);

/// `s` without trailing spaces, '\n' and '\r' and without leading spaces.
std::string trim(std::string s);

/// The first line of `log` that is not empty once trimmed, trimmed; "" when there is none.
std::string first_nonempty_line(std::string_view log);

}  // namespace tessera::glsl::detail
