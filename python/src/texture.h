// tessera.Texture: the class, its containers (PVR v3, KTX 1.1, KTX 2.0 with zstd) and pickling.
// Every function here needs the GIL (and releases it around the library's work).
#pragma once

#include <pybind11/pybind11.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <string>

#include "tessera/texture_file.h"

namespace tessera::python {

namespace py = pybind11;

/// The file bytes of `texture` in `container` ("pvr", "ktx" or "ktx2"), KTX 2.0 levels
/// Zstandard-compressed at level `zstd` (1..22; 0 = none, the only value other containers take).
py::bytes texture_to_bytes(const texture_file::CompressedTexture& texture,
                           const std::string& container, int zstd);

/// Writes `texture` to `path` (.pvr, .ktx or .ktx2 by extension; `zstd` for .ktx2), atomically.
void write_texture(const std::filesystem::path& path,
                   const texture_file::CompressedTexture& texture, int zstd);

/// Parses PVR v3 / KTX 1.1 / KTX 2.0 bytes; `name` prefixes messages.
texture_file::CompressedTexture texture_from_bytes(const py::bytes& data, const std::string& name);

/// Adds the class `Texture` to `module`.
void register_texture(py::module_& module);

}  // namespace tessera::python
