// tessera/texture_file.h — compressed texture containers: PVR v3 and KTX 1.1.
//
// Readers validate every size against the actual byte count before allocating (a lying header
// gives `corrupt_data`, never a huge allocation) and return one-line errors naming the file.
// Writers produce files PVRTexTool and OpenGL ES loaders accept; write them with
// `write_texture_file`, which is atomic.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "tessera/core.h"
#include "tessera/pvrtc.h"

namespace tessera {

/// A PVRTC texture with its mip chain (level 0 first).
struct CompressedTexture {
  pvrtc::Format format = pvrtc::Format::pvrtc1_4bpp;
  int width = 0;
  int height = 0;
  bool has_alpha = true;       ///< RGBA (true) or RGB pixel format code in the container.
  bool srgb = false;           ///< Colour space flag (PVR v3 colour space / KTX sRGB format).
  bool premultiplied = false;  ///< PVR v3 flag 0x02.
  std::vector<std::vector<std::uint8_t>> levels;  ///< Level i is (width>>i) x (height>>i), min 1.
};

/// Container formats.
enum class ContainerFormat { unknown, pvr3, ktx1 };

/// Detects PVR v3 / KTX 1.1 by magic.
ContainerFormat detect_container(std::span<const std::uint8_t> bytes);
/// Chooses by file extension (.pvr, .ktx; case-insensitive); unknown otherwise.
ContainerFormat container_from_extension(const std::string& path);

Result<CompressedTexture> parse_pvr3(std::span<const std::uint8_t> bytes, const std::string& name);
Result<CompressedTexture> parse_ktx1(std::span<const std::uint8_t> bytes, const std::string& name);
Result<std::vector<std::uint8_t>> serialize_pvr3(const CompressedTexture& texture);
Result<std::vector<std::uint8_t>> serialize_ktx1(const CompressedTexture& texture);

/// Reads a .pvr or .ktx file (format by magic).
Result<CompressedTexture> read_texture_file(const std::string& path);
/// Writes by extension (.pvr or .ktx), atomically.
Status write_texture_file(const std::string& path, const CompressedTexture& texture);

}  // namespace tessera
