// Internal to tessera_gl: where a renderer's GLSL files are (share/tessera/glsl), found the same
// way by every GL renderer and the engine component, and how a float is written into generated
// GLSL (shader.cpp).
#pragma once

#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>

#include "tessera/core.h"

namespace tessera::gl {

/// The folder holding every one of `files`: `given` when not empty (io_error naming the first
/// file missing there), else $TESSERA_GLSL_DIR, else <executable>/../share/tessera/glsl, else
/// <executable>/../../share/tessera/glsl (a build folder inside the source tree). `what` names
/// the renderer and `option` its folder option in the error when none has them.
Result<std::filesystem::path> find_glsl_dir(const std::filesystem::path& given,
                                            std::initializer_list<const char*> files,
                                            std::string_view what, std::string_view option);

/// `v` as a GLSL float literal that reads back to the same float (9 significant digits, always
/// with a decimal point).
std::string glsl_float(float v);

}  // namespace tessera::gl
