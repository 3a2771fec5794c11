// Texture files: container detection, validation, decoding a level, reading and writing.
#include "tessera/texture_file.h"

#include <algorithm>
#include <cctype>
#include <cstring>

#include "tessera/io.h"
#include "tessera/mipmap.h"
#include "texture_file/container_bytes.h"

namespace tessera::texture_file {

int CompressedTexture::level_width(int level) const { return mip_dimension(width, level); }
int CompressedTexture::level_height(int level) const { return mip_dimension(height, level); }

const char* container_name(ContainerFormat format) {
  switch (format) {
    case ContainerFormat::pvr3:
      return "PVR v3";
    case ContainerFormat::ktx1:
      return "KTX 1.1";
    case ContainerFormat::unknown:
      break;
  }
  return "unknown";
}

ContainerFormat detect_container(std::span<const std::uint8_t> bytes) {
  if (bytes.size() >= 4) {
    const std::uint32_t magic = container::load_u32(bytes, 0);
    // Both byte orders: parse_pvr3 explains why a big-endian file is rejected.
    if (magic == 0x03525650u || magic == 0x50565203u) return ContainerFormat::pvr3;
  }
  // Legacy PVR v2 (header size 52, "PVR!" at offset 44): parse_pvr3 says it is unsupported.
  if (bytes.size() >= 52 && container::load_u32(bytes, 0) == 52 &&
      container::load_u32(bytes, 44) == 0x21525650u) {
    return ContainerFormat::pvr3;
  }
  if (bytes.size() >= 12 && std::memcmp(bytes.data(), "\xABKTX 11\xBB\r\n\x1A\n", 12) == 0) {
    return ContainerFormat::ktx1;
  }
  return ContainerFormat::unknown;
}

ContainerFormat container_from_extension(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  const std::size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) {
    return ContainerFormat::unknown;
  }
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == "pvr") return ContainerFormat::pvr3;
  if (ext == "ktx") return ContainerFormat::ktx1;
  return ContainerFormat::unknown;
}

std::string texture_format_name(const CompressedTexture& texture) {
  std::string s = texture.format == pvrtc::Format::pvrtc1_4bpp ? "PVRTC1 4bpp" : "PVRTC1 2bpp";
  s += texture.has_alpha ? " RGBA" : " RGB";
  return s;
}

Status validate_texture(const CompressedTexture& texture, const std::string& what) {
  if (Status s = check_image_size(texture.width, texture.height, what); !s.ok()) return s;
  if (Status s = pvrtc::check_dimensions(texture.width, texture.height, what); !s.ok()) return s;
  const int possible = mip_level_count(texture.width, texture.height);
  if (texture.levels.empty() || texture.level_count() > possible) {
    return Status::error(ErrorCode::invalid_argument,
                         what + ": " + std::to_string(texture.levels.size()) +
                             " levels for " + std::to_string(texture.width) + "x" +
                             std::to_string(texture.height) + " (1 to " +
                             std::to_string(possible) + " allowed)");
  }
  for (int i = 0; i < texture.level_count(); ++i) {
    const std::size_t expected =
        pvrtc::level_size(texture.format, texture.level_width(i), texture.level_height(i));
    if (texture.levels[std::size_t(i)].size() != expected) {
      return Status::error(ErrorCode::invalid_argument,
                           what + ": level " + std::to_string(i) + " holds " +
                               std::to_string(texture.levels[std::size_t(i)].size()) +
                               " bytes, expected " + std::to_string(expected));
    }
  }
  return Status::success();
}

Result<ImageRGBA8> decode_texture_level(const CompressedTexture& texture, int level,
                                        const Parallel& parallel) {
  if (level < 0 || level >= texture.level_count()) {
    return Status::error(ErrorCode::invalid_argument,
                         "level " + std::to_string(level) + " is out of range (the texture has " +
                             std::to_string(texture.level_count()) + " level(s), 0 to " +
                             std::to_string(texture.level_count() - 1) + ")");
  }
  Result<ImageRGBA8> img =
      pvrtc::decode(texture.levels[std::size_t(level)], texture.format,
                    texture.level_width(level), texture.level_height(level), parallel);
  if (!img) return img;
  if (!texture.has_alpha) {
    for (std::size_t i = 3; i < img->pixels.size(); i += 4) img->pixels[i] = 255;
    img->has_alpha = false;
  } else {
    img->has_alpha = true;
  }
  return img;
}

Result<CompressedTexture> parse_texture(std::span<const std::uint8_t> bytes,
                                        const std::string& name) {
  switch (detect_container(bytes)) {
    case ContainerFormat::pvr3:
      return parse_pvr3(bytes, name);
    case ContainerFormat::ktx1:
      return parse_ktx1(bytes, name);
    case ContainerFormat::unknown:
      break;
  }
  if (bytes.empty()) return Status::error(ErrorCode::corrupt_data, name + ": empty file");
  return Status::error(ErrorCode::corrupt_data,
                       name + ": not a PVR v3 or KTX 1.1 texture (unrecognised magic)");
}

Result<CompressedTexture> read_texture_file(const std::string& path) {
  Result<std::vector<std::uint8_t>> bytes = io::read_file(path);
  if (!bytes) return bytes.status();
  return parse_texture(*bytes, io::io_name(path));
}

Status write_texture_file(const std::string& path, const CompressedTexture& texture) {
  if (Status s = validate_texture(texture, path); !s.ok()) return s;
  Result<std::vector<std::uint8_t>> bytes = std::vector<std::uint8_t>{};
  switch (container_from_extension(path)) {
    case ContainerFormat::pvr3:
      bytes = serialise_pvr3(texture);
      break;
    case ContainerFormat::ktx1:
      bytes = serialise_ktx1(texture);
      break;
    case ContainerFormat::unknown:
      return Status::error(ErrorCode::invalid_argument,
                           path + ": unknown texture extension (use .pvr or .ktx)");
  }
  if (!bytes) return bytes.status();
  return io::write_file_atomic(path, *bytes);
}

}  // namespace tessera::texture_file
