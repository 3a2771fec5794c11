// Texture files: container detection, validation, decoding a level, reading and writing.
#include "tessera/texture_file.h"

#include <algorithm>
#include <cctype>
#include <cstring>

#include "core/check.h"
#include "tessera/image_mipmap.h"
#include "tessera/io.h"
#include "texture_file/container_bytes.h"

namespace tessera::texture_file {

int CompressedTexture::level_width(int level) const { return mip_dimension(width, level); }
int CompressedTexture::level_height(int level) const { return mip_dimension(height, level); }

std::size_t CompressedTexture::image_size(int level) const {
  return pvrtc::level_size(format, level_width(level), level_height(level));
}

std::span<const std::uint8_t> CompressedTexture::image(int level, int layer, int face) const {
  TESSERA_DCHECK(check_image_index(*this, level, layer, face).ok());
  const std::size_t n = image_size(level);
  const std::size_t at = (std::size_t(layer) * std::size_t(faces) + std::size_t(face)) * n;
  TESSERA_DCHECK(at + n <= levels[std::size_t(level)].size());
  return std::span<const std::uint8_t>(levels[std::size_t(level)]).subspan(at, n);
}

namespace {

Status index_error(const std::string& what, int value, const std::string& owner, int count) {
  return Status::error(ErrorCode::invalid_argument,
                       what + " " + std::to_string(value) + " is out of range (" + owner + " has " +
                           what + "s 0 to " + std::to_string(count - 1) + ")");
}

}  // namespace

Status check_image_index(const CompressedTexture& texture, int level, int layer, int face) {
  if (level < 0 || level >= texture.level_count()) {
    return index_error("level", level, "the texture", texture.level_count());
  }
  if (layer < 0 || layer >= texture.layers) {
    if (!texture.array) {
      return Status::error(ErrorCode::invalid_argument,
                           "layer " + std::to_string(layer) +
                               " is out of range (the texture is not an array: layer 0 only)");
    }
    return index_error("layer", layer, "the array", texture.layers);
  }
  if (face < 0 || face >= texture.faces) {
    if (!texture.is_cube()) {
      return Status::error(ErrorCode::invalid_argument,
                           "face " + std::to_string(face) +
                               " is out of range (the texture is not a cube map: face 0 only)");
    }
    return index_error("face", face, "the cube map", texture.faces);
  }
  return Status::success();
}

std::string texture_shape_name(const CompressedTexture& texture) {
  std::string s = texture.is_cube() ? "cube map" : "2D texture";
  if (texture.array) {
    s = (texture.is_cube() ? "cube map array of " : "array of ") + std::to_string(texture.layers) +
        (texture.layers == 1 ? " layer" : " layers");
  }
  return s;
}

const char* container_name(ContainerFormat format) {
  switch (format) {
    case ContainerFormat::pvr3:
      return "PVR v3";
    case ContainerFormat::ktx1:
      return "KTX 1.1";
    case ContainerFormat::ktx2:
      return "KTX 2.0";
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
  if (bytes.size() >= 12 && std::memcmp(bytes.data(), "\xABKTX 20\xBB\r\n\x1A\n", 12) == 0) {
    return ContainerFormat::ktx2;
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
  if (ext == "ktx2") return ContainerFormat::ktx2;
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
  if (texture.faces != 1 && texture.faces != 6) {
    return Status::error(ErrorCode::invalid_argument, what + ": " + std::to_string(texture.faces) +
                                                          " faces (1, or 6 for a cube map)");
  }
  if (texture.is_cube() && texture.width != texture.height) {
    return Status::error(ErrorCode::invalid_argument,
                         what + ": a cube map's faces must be square, not " +
                             std::to_string(texture.width) + "x" + std::to_string(texture.height));
  }
  if (texture.layers < 1 || texture.image_count() > kMaxTextureImages ||
      (!texture.array && texture.layers != 1)) {
    return Status::error(ErrorCode::invalid_argument,
                         what + ": " + std::to_string(texture.layers) + " layers (1 to " +
                             std::to_string(kMaxTextureImages / texture.faces) +
                             (texture.array ? ")" : "; more than 1 only in an array)"));
  }
  const int possible = mip_level_count(texture.width, texture.height);
  if (texture.levels.empty() || texture.level_count() > possible) {
    return Status::error(ErrorCode::invalid_argument,
                         what + ": " + std::to_string(texture.levels.size()) + " levels for " +
                             std::to_string(texture.width) + "x" + std::to_string(texture.height) +
                             " (1 to " + std::to_string(possible) + " allowed)");
  }
  for (int i = 0; i < texture.level_count(); ++i) {
    const std::size_t expected = texture.image_size(i) * std::size_t(texture.image_count());
    if (texture.levels[std::size_t(i)].size() != expected) {
      return Status::error(ErrorCode::invalid_argument,
                           what + ": level " + std::to_string(i) + " holds " +
                               std::to_string(texture.levels[std::size_t(i)].size()) +
                               " bytes, expected " + std::to_string(expected));
    }
  }
  return Status::success();
}

Result<ImageRGBA8> decode_texture_image(const CompressedTexture& texture, int level, int layer,
                                        int face, const Parallel& parallel) {
  if (Status s = check_image_index(texture, level, layer, face); !s.ok()) return s;
  Result<ImageRGBA8> img =
      pvrtc::decode(texture.image(level, layer, face), texture.format, texture.level_width(level),
                    texture.level_height(level), parallel);
  if (!img) return img;
  if (!texture.has_alpha) {
    for (std::size_t i = 3; i < img->pixels.size(); i += 4) img->pixels[i] = 255;
    img->has_alpha = false;
  } else {
    img->has_alpha = true;
  }
  return img;
}

Result<ImageRGBA8> decode_texture_level(const CompressedTexture& texture, int level,
                                        const Parallel& parallel) {
  return decode_texture_image(texture, level, 0, 0, parallel);
}

Result<CompressedTexture> parse_texture(std::span<const std::uint8_t> bytes,
                                        const std::string& name) {
  switch (detect_container(bytes)) {
    case ContainerFormat::pvr3:
      return parse_pvr3(bytes, name);
    case ContainerFormat::ktx1:
      return parse_ktx1(bytes, name);
    case ContainerFormat::ktx2:
      return parse_ktx2(bytes, name);
    case ContainerFormat::unknown:
      break;
  }
  if (bytes.empty()) return Status::error(ErrorCode::corrupt_data, name + ": empty file");
  return Status::error(ErrorCode::corrupt_data,
                       name + ": not a PVR v3, KTX 1.1 or KTX 2.0 texture (unrecognised magic)");
}

Result<CompressedTexture> read_texture_file(const std::string& path) {
  Result<std::vector<std::uint8_t>> bytes = io::read_file(path);
  if (!bytes) return bytes.status();
  return parse_texture(*bytes, io::io_name(path));
}

Result<std::vector<std::uint8_t>> serialise_texture(const CompressedTexture& texture,
                                                    ContainerFormat container,
                                                    const Ktx2Options& ktx2) {
  switch (container) {
    case ContainerFormat::pvr3:
      return serialise_pvr3(texture);
    case ContainerFormat::ktx1:
      return serialise_ktx1(texture);
    case ContainerFormat::ktx2:
      return serialise_ktx2(texture, ktx2);
    case ContainerFormat::unknown:
      break;
  }
  return Status::error(ErrorCode::invalid_argument, "no container chosen to write the texture");
}

Status write_texture_file(const std::string& path, const CompressedTexture& texture,
                          const Ktx2Options& ktx2) {
  if (Status s = validate_texture(texture, path); !s.ok()) return s;
  const ContainerFormat container = container_from_extension(path);
  if (container == ContainerFormat::unknown) {
    return Status::error(ErrorCode::invalid_argument,
                         path + ": unknown texture extension (use .pvr, .ktx or .ktx2)");
  }
  Result<std::vector<std::uint8_t>> bytes = serialise_texture(texture, container, ktx2);
  if (!bytes) return bytes.status();
  return io::write_file_atomic(path, *bytes);
}

}  // namespace tessera::texture_file
