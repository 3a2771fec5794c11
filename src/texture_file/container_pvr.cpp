// PVR v3 container (the format PVRTexTool writes): reader and writer for PVRTC1 textures.
//
// Header, 52 bytes little-endian: version, flags, pixel format (u64), colour space, channel
// type, height, width, depth, surfaces, faces, mip count, metadata size; then the metadata
// block and the levels, largest first, each holding its surfaces (array layers), each of
// those its faces. PVR v3 has no array flag: more than one surface reads back as an array. Every
// field is checked before it is used to size anything, and the level data must match the header
// exactly (no missing or trailing bytes).
//
// What tessera reads and writes:
// PVR v3 (what PVRTexTool writes): 52-byte little-endian header, a metadata block (tessera
// writes PVRTexTool's 15-byte orientation entry and skips any metadata when reading), then per
// level, largest first, per surface (array layer), per face, one image of `pvrtc::level_size`
// bytes. Pixel formats 0..3 (PVRTC1 2bpp RGB, 2bpp RGBA, 4bpp RGB, 4bpp RGBA) are supported;
// depth must be 1, faces 1 or 6. Big-endian PVR files are rejected.
#include <string>

#include "tessera/image_mipmap.h"
#include "tessera/texture_file.h"
#include "texture_file/container_bytes.h"

namespace tessera::texture_file {

namespace {

using namespace container;  // NOLINT(google-build-using-namespace): container_bytes.h

constexpr std::uint32_t kPvr3Magic = 0x03525650u;         // "PVR\3" read little-endian
constexpr std::uint32_t kPvr3MagicSwapped = 0x50565203u;  // the same written big-endian
constexpr std::size_t kHeaderSize = 52;
constexpr std::uint32_t kFlagPremultiplied = 0x02;

/// Names of the compressed PVR v3 pixel formats, for messages about unsupported files.
std::string pixel_format_name(std::uint64_t format) {
  if (format >> 32) {
    // Uncompressed: low 4 bytes are channel letters, high 4 bytes the bit widths.
    std::string s = "uncompressed ";
    for (int i = 0; i < 4; ++i) {
      const char c = char(format >> (8 * i));
      if (c >= 'a' && c <= 'z') s += c;
    }
    for (int i = 0; i < 4; ++i) {
      const unsigned bits = unsigned(format >> (32 + 8 * i)) & 0xFF;
      if (bits) s += std::to_string(bits);
    }
    return s;
  }
  static const char* const kNames[] = {
      "PVRTC1 2bpp RGB",
      "PVRTC1 2bpp RGBA",
      "PVRTC1 4bpp RGB",
      "PVRTC1 4bpp RGBA",
      "PVRTC2 2bpp",
      "PVRTC2 4bpp",
      "ETC1",
      "BC1 (DXT1)",
      "DXT2",
      "BC2 (DXT3)",
      "DXT4",
      "BC3 (DXT5)",
      "BC4",
      "BC5",
      "BC6",
      "BC7",
      "UYVY",
      "YUY2",
      "BW 1bpp",
      "R9G9B9E5",
      "RGBG8888",
      "GRGB8888",
      "ETC2 RGB",
      "ETC2 RGBA",
      "ETC2 RGB A1",
      "EAC R11",
      "EAC RG11",
  };
  if (format < std::size(kNames)) return kNames[format];
  if (format <= 56) return "ASTC (format " + std::to_string(format) + ")";
  return "pixel format " + std::to_string(format);
}

}  // namespace

Result<CompressedTexture> parse_pvr3(std::span<const std::uint8_t> bytes, const std::string& name) {
  if (bytes.size() < 4) {
    return corrupt(name, "not a PVR v3 file (only " + plural_bytes(bytes.size()) + ")");
  }
  const std::uint32_t magic = load_u32(bytes, 0);
  if (magic == kPvr3MagicSwapped) {
    return unsupported(name, "big-endian PVR v3 file (byte-swapped header) is not supported");
  }
  if (magic != kPvr3Magic) {
    if (bytes.size() >= 52 && load_u32(bytes, 44) == 0x21525650u) {  // "PVR!" at offset 44
      return unsupported(name, "legacy PVR v2 file is not supported (convert it to PVR v3)");
    }
    return corrupt(name, "not a PVR v3 file (bad magic " + hex32(magic) + ", expected " +
                             hex32(kPvr3Magic) + ")");
  }
  if (bytes.size() < kHeaderSize) {
    return corrupt(name, "truncated PVR v3 header: " + plural_bytes(bytes.size()) + " of " +
                             std::to_string(kHeaderSize));
  }
  const std::uint32_t flags = load_u32(bytes, 4);
  const std::uint64_t pixel_format = load_u64(bytes, 8);
  const std::uint32_t colour_space = load_u32(bytes, 16);
  const std::uint32_t height = load_u32(bytes, 24);
  const std::uint32_t width = load_u32(bytes, 28);
  const std::uint32_t depth = load_u32(bytes, 32);
  const std::uint32_t surfaces = load_u32(bytes, 36);
  const std::uint32_t faces = load_u32(bytes, 40);
  const std::uint32_t mip_count = load_u32(bytes, 44);
  const std::uint32_t metadata_size = load_u32(bytes, 48);

  if (pixel_format > 3) {
    return unsupported(name, "pixel format " + pixel_format_name(pixel_format) +
                                 " is not supported (only PVRTC1 2bpp/4bpp, formats 0-3)");
  }
  if (colour_space > 1) {
    return corrupt(name, "unknown colour space " + std::to_string(colour_space) +
                             " (expected 0 linear or 1 sRGB)");
  }
  if (depth != 1) {
    return unsupported(
        name, "depth " + std::to_string(depth) + " is not supported (3D textures; only depth 1)");
  }
  if (faces != 1 && faces != 6) {
    return unsupported(name,
                       std::to_string(faces) + " faces are not supported (1, or 6 for a cube map)");
  }
  if (surfaces == 0 || surfaces > std::uint32_t(kMaxTextureImages) / faces) {
    return corrupt(name, std::to_string(surfaces) + " surfaces (array layers): 1 to " +
                             std::to_string(std::uint32_t(kMaxTextureImages) / faces) +
                             " supported");
  }
  if (faces == 6 && width != height) {
    return corrupt(name, "cube map faces of " + std::to_string(width) + "x" +
                             std::to_string(height) + " are not square");
  }
  if (width == 0 || height == 0) {
    return corrupt(name, "zero size " + std::to_string(width) + "x" + std::to_string(height));
  }
  if (Status s = check_image_size(width, height, name); !s.ok()) return s;
  if (Status s = pvrtc::check_dimensions(int(width), int(height), name); !s.ok()) return s;
  const int possible = mip_level_count(int(width), int(height));
  if (mip_count == 0 || mip_count > std::uint32_t(possible)) {
    return corrupt(name, "mip count " + std::to_string(mip_count) + " is impossible for " +
                             std::to_string(width) + "x" + std::to_string(height) + " (1 to " +
                             std::to_string(possible) + ")");
  }
  const std::size_t after_header = bytes.size() - kHeaderSize;
  if (metadata_size > after_header) {
    return corrupt(name, "truncated: metadata size " + std::to_string(metadata_size) +
                             " exceeds the " + plural_bytes(after_header) + " after the header");
  }

  CompressedTexture tex;
  tex.format = pixel_format >= 2 ? pvrtc::Format::pvrtc1_4bpp : pvrtc::Format::pvrtc1_2bpp;
  tex.has_alpha = (pixel_format & 1) != 0;
  tex.srgb = colour_space == 1;
  tex.premultiplied = (flags & kFlagPremultiplied) != 0;
  tex.width = int(width);
  tex.height = int(height);
  tex.faces = int(faces);
  tex.layers = int(surfaces);
  tex.array = surfaces > 1;
  const std::uint64_t images = std::uint64_t(tex.image_count());

  std::uint64_t needed = 0;
  for (int i = 0; i < int(mip_count); ++i) needed += images * tex.image_size(i);
  const std::size_t data_start = kHeaderSize + metadata_size;
  const std::size_t available = bytes.size() - data_start;
  if (available < needed) {
    return corrupt(name, "truncated: " + std::to_string(mip_count) + " level(s) need " +
                             plural_bytes(needed) + " of data, file has " +
                             plural_bytes(available));
  }
  if (available > needed) {
    return corrupt(name, plural_bytes(available - needed) + " of unexpected data after the " +
                             std::to_string(mip_count) + " level(s) (" + plural_bytes(needed) +
                             " expected)");
  }
  std::size_t at = data_start;
  tex.levels.reserve(mip_count);
  for (int i = 0; i < int(mip_count); ++i) {
    const std::size_t n = std::size_t(images) * tex.image_size(i);
    tex.levels.emplace_back(bytes.begin() + std::ptrdiff_t(at),
                            bytes.begin() + std::ptrdiff_t(at + n));
    at += n;
  }
  return tex;
}

Result<std::vector<std::uint8_t>> serialise_pvr3(const CompressedTexture& texture) {
  if (Status s = validate_texture(texture, "PVR v3 output"); !s.ok()) return s;
  std::size_t total = kHeaderSize + 15;
  for (const auto& l : texture.levels) total += l.size();
  std::vector<std::uint8_t> out;
  out.reserve(total);
  const bool is4 = texture.format == pvrtc::Format::pvrtc1_4bpp;
  const std::uint64_t pixel_format = (is4 ? 2u : 0u) + (texture.has_alpha ? 1u : 0u);
  container::store_u32(out, kPvr3Magic);
  container::store_u32(out, texture.premultiplied ? kFlagPremultiplied : 0u);
  container::store_u64(out, pixel_format);
  container::store_u32(out, texture.srgb ? 1u : 0u);  // colour space
  container::store_u32(out, 0);                       // channel type: unsigned normalised byte
  container::store_u32(out, std::uint32_t(texture.height));
  container::store_u32(out, std::uint32_t(texture.width));
  container::store_u32(out, 1);                              // depth
  container::store_u32(out, std::uint32_t(texture.layers));  // surfaces
  container::store_u32(out, std::uint32_t(texture.faces));
  container::store_u32(out, std::uint32_t(texture.levels.size()));
  container::store_u32(out, 15);  // metadata size
  // PVRTexTool's orientation metadata: FourCC "PVR\3", key 3, 3 bytes (x, y, z) = 0:
  // left-to-right, top-down, front-to-back.
  container::store_u32(out, kPvr3Magic);
  container::store_u32(out, 3);
  container::store_u32(out, 3);
  out.insert(out.end(), {0, 0, 0});
  for (const auto& l : texture.levels) out.insert(out.end(), l.begin(), l.end());
  return out;
}

}  // namespace tessera::texture_file
