// KTX 1.1 container: reader (either byte order) and writer (little-endian) for PVRTC1.
//
// Layout: 12-byte identifier, 13 u32 header fields (endianness, glType, glTypeSize, glFormat,
// glInternalFormat, glBaseInternalFormat, pixelWidth, pixelHeight, pixelDepth,
// numberOfArrayElements, numberOfFaces, numberOfMipmapLevels, bytesOfKeyValueData), the
// key/value block, then per level a u32 imageSize, the data and padding to 4 bytes.
//
// What tessera reads and writes:
// KTX 1.1: 64-byte header, glType 0 / glFormat 0, glInternalFormat one of the
// GL_IMG_texture_compression_pvrtc (0x8C00..0x8C03) or GL_EXT_pvrtc_sRGB (0x8A54..0x8A57)
// formats, key/value data (tessera writes "KTXorientation" = "S=r,T=d"), then per level a
// u32 imageSize and the level's images (array elements, then faces) padded to 4 bytes; for a
// cube map that is not an array, imageSize is the size of one face, as the specification says
// (and PVRTexTool writes). Both byte orders are read; files are written little-endian. No 3D
// textures. Note: PVRTexTool 4.17 reads the 0x8C0x formats but rejects the sRGB EXT ones, and
// itself writes sRGB data as 0x8C0x.
#include <array>
#include <cstring>
#include <string>

#include "tessera/image_mipmap.h"
#include "tessera/texture_file.h"
#include "texture_file/container_bytes.h"

namespace tessera::texture_file {

namespace {

using namespace container;  // NOLINT(google-build-using-namespace): container_bytes.h

constexpr std::array<std::uint8_t, 12> kKtxIdentifier = {0xAB, 'K',  'T',  'X',  ' ',  '1',
                                                         '1',  0xBB, '\r', '\n', 0x1A, '\n'};
constexpr std::size_t kHeaderSize = 64;
constexpr std::uint32_t kEndianLittle = 0x04030201u;
constexpr std::uint32_t kEndianBig = 0x01020304u;

constexpr std::uint32_t kGlRgb = 0x1907;
constexpr std::uint32_t kGlRgba = 0x1908;

// GL_IMG_texture_compression_pvrtc and GL_EXT_pvrtc_sRGB.
constexpr std::uint32_t kRgbPvrtc4 = 0x8C00;
constexpr std::uint32_t kRgbPvrtc2 = 0x8C01;
constexpr std::uint32_t kRgbaPvrtc4 = 0x8C02;
constexpr std::uint32_t kRgbaPvrtc2 = 0x8C03;
constexpr std::uint32_t kSrgbPvrtc2 = 0x8A54;
constexpr std::uint32_t kSrgbPvrtc4 = 0x8A55;
constexpr std::uint32_t kSrgbAlphaPvrtc2 = 0x8A56;
constexpr std::uint32_t kSrgbAlphaPvrtc4 = 0x8A57;

struct GlFormat {
  std::uint32_t internal;
  pvrtc::Format format;
  bool alpha;
  bool srgb;
};
constexpr GlFormat kFormats[] = {
    {kRgbPvrtc4, pvrtc::Format::pvrtc1_4bpp, false, false},
    {kRgbPvrtc2, pvrtc::Format::pvrtc1_2bpp, false, false},
    {kRgbaPvrtc4, pvrtc::Format::pvrtc1_4bpp, true, false},
    {kRgbaPvrtc2, pvrtc::Format::pvrtc1_2bpp, true, false},
    {kSrgbPvrtc2, pvrtc::Format::pvrtc1_2bpp, false, true},
    {kSrgbPvrtc4, pvrtc::Format::pvrtc1_4bpp, false, true},
    {kSrgbAlphaPvrtc2, pvrtc::Format::pvrtc1_2bpp, true, true},
    {kSrgbAlphaPvrtc4, pvrtc::Format::pvrtc1_4bpp, true, true},
};

std::size_t pad4(std::size_t n) { return (4 - n % 4) % 4; }

/// The key/value entries (each a u32 size, the bytes, padding to 4) within their block.
Status check_key_values(std::span<const std::uint8_t> bytes, std::uint32_t kv_bytes, bool swap,
                        const std::string& name) {
  std::size_t at = kHeaderSize;
  const std::size_t end = kHeaderSize + kv_bytes;
  while (at < end) {
    if (end - at < 4) return corrupt(name, "malformed key/value data (partial entry size)");
    const std::uint32_t n = load_u32(bytes, at, swap);
    at += 4;
    if (n > end - at) {
      return corrupt(
          name, "malformed key/value data (entry of " + plural_bytes(n) + " overruns the block)");
    }
    at += n;
    at += std::min(pad4(n), end - at);
  }
  return Status::success();
}

/// What parse_ktx1 reads past the header: the byte order, the level count and the levels'
/// start.
struct Layout {
  bool swap = false;
  std::uint32_t mip_levels = 1;
  std::size_t levels_at = 0;
};

/// The identifier, the header and the key/value data; `tex` without its levels.
Status read_header(std::span<const std::uint8_t> bytes, const std::string& name,
                   CompressedTexture& tex, Layout& layout) {
  if (bytes.size() < kKtxIdentifier.size() ||
      std::memcmp(bytes.data(), kKtxIdentifier.data(), kKtxIdentifier.size()) != 0) {
    if (bytes.size() >= 12 && std::memcmp(bytes.data(), "\xABKTX 20\xBB", 8) == 0) {
      return unsupported(name, "KTX 2.0 files are not supported (only KTX 1.1)");
    }
    return corrupt(name, "not a KTX 1.1 file (bad identifier)");
  }
  if (bytes.size() < kHeaderSize) {
    return corrupt(name, "truncated KTX header: " + plural_bytes(bytes.size()) + " of " +
                             std::to_string(kHeaderSize));
  }
  const std::uint32_t endianness = load_u32(bytes, 12);
  if (endianness != kEndianLittle && endianness != kEndianBig) {
    return corrupt(name, "bad KTX endianness field " + hex32(endianness));
  }
  const bool swap = endianness == kEndianBig;
  auto field = [&](int i) { return load_u32(bytes, 12 + 4 * std::size_t(i), swap); };
  const std::uint32_t gl_type = field(1);
  const std::uint32_t gl_format = field(3);
  const std::uint32_t internal = field(4);
  const std::uint32_t width = field(6);
  const std::uint32_t height = field(7);
  const std::uint32_t depth = field(8);
  const std::uint32_t array_elements = field(9);
  const std::uint32_t faces = field(10);
  const std::uint32_t mip_levels_field = field(11);
  const std::uint32_t kv_bytes = field(12);

  if (gl_type != 0 || gl_format != 0) {
    return unsupported(name, "uncompressed KTX data (glType " + hex32(gl_type) + ", glFormat " +
                                 hex32(gl_format) + ") is not supported (only PVRTC1)");
  }
  const GlFormat* fmt = nullptr;
  for (const GlFormat& f : kFormats) {
    if (f.internal == internal) fmt = &f;
  }
  if (!fmt) {
    return unsupported(name, "glInternalFormat " + hex32(internal) +
                                 " is not supported (only PVRTC1: 0x8C00-0x8C03, "
                                 "0x8A54-0x8A57)");
  }
  if (height == 0) return unsupported(name, "1D textures (pixelHeight 0) are not supported");
  if (depth != 0) {
    return unsupported(name,
                       "3D textures (pixelDepth " + std::to_string(depth) + ") are not supported");
  }
  if (faces != 1 && faces != 6) {
    return unsupported(name,
                       std::to_string(faces) + " faces are not supported (1, or 6 for a cube map)");
  }
  if (array_elements > std::uint32_t(kMaxTextureImages) / faces) {
    return corrupt(name, std::to_string(array_elements) + " array elements: at most " +
                             std::to_string(std::uint32_t(kMaxTextureImages) / faces) +
                             " supported");
  }
  if (faces == 6 && width != height) {
    return corrupt(name, "cube map faces of " + std::to_string(width) + "x" +
                             std::to_string(height) + " are not square");
  }
  if (width == 0) return corrupt(name, "zero width");
  if (Status s = check_image_size(width, height, name); !s.ok()) return s;
  if (Status s = pvrtc::check_dimensions(int(width), int(height), name); !s.ok()) return s;
  const int possible = mip_level_count(int(width), int(height));
  // numberOfMipmapLevels 0 means "one level; the loader generates the rest".
  const std::uint32_t mip_levels = mip_levels_field == 0 ? 1 : mip_levels_field;
  if (mip_levels > std::uint32_t(possible)) {
    return corrupt(name, "mip count " + std::to_string(mip_levels) + " is impossible for " +
                             std::to_string(width) + "x" + std::to_string(height) + " (1 to " +
                             std::to_string(possible) + ")");
  }
  if (kv_bytes > bytes.size() - kHeaderSize) {
    return corrupt(name, "truncated: key/value data size " + std::to_string(kv_bytes) +
                             " exceeds the " + plural_bytes(bytes.size() - kHeaderSize) +
                             " after the header");
  }
  if (Status s = check_key_values(bytes, kv_bytes, swap, name); !s.ok()) return s;
  tex.format = fmt->format;
  tex.has_alpha = fmt->alpha;
  tex.srgb = fmt->srgb;
  tex.width = int(width);
  tex.height = int(height);
  tex.faces = int(faces);
  tex.array = array_elements != 0;
  tex.layers = tex.array ? int(array_elements) : 1;
  layout.swap = swap;
  layout.mip_levels = mip_levels;
  layout.levels_at = kHeaderSize + kv_bytes;
  return Status::success();
}

/// The levels after the header (imageSize, the data, padding), to the end of the file.
Status read_levels(std::span<const std::uint8_t> bytes, const std::string& name,
                   const Layout& layout, CompressedTexture& tex) {
  const bool swap = layout.swap;
  const std::uint32_t mip_levels = layout.mip_levels;
  const std::uint32_t faces = std::uint32_t(tex.faces);
  // A cube map that is not an array stores each face with its own padding, and imageSize is
  // the size of one face; otherwise imageSize is the whole level.
  const bool face_by_face = faces == 6 && !tex.array;
  const std::size_t images = std::size_t(tex.image_count());
  std::size_t at = layout.levels_at;
  tex.levels.reserve(mip_levels);
  for (int i = 0; i < int(mip_levels); ++i) {
    const std::size_t expected = tex.image_size(i) * (face_by_face ? 1 : images);
    if (bytes.size() - at < 4) {
      return corrupt(name, "truncated: level " + std::to_string(i) + " of " +
                               std::to_string(mip_levels) + " is missing (file ends at byte " +
                               std::to_string(bytes.size()) + ")");
    }
    const std::uint32_t image_size = load_u32(bytes, at, swap);
    at += 4;
    if (image_size != expected) {
      return corrupt(name,
                     "level " + std::to_string(i) + " imageSize " + std::to_string(image_size) +
                         " does not match " + std::to_string(tex.level_width(i)) + "x" +
                         std::to_string(tex.level_height(i)) + " PVRTC (" + plural_bytes(expected) +
                         (face_by_face ? " per face)"
                          : images > 1 ? " per level)"
                                       : ")"));
    }
    std::vector<std::uint8_t> level;
    for (std::size_t part = 0; part < (face_by_face ? images : 1); ++part) {
      if (bytes.size() - at < expected) {
        return corrupt(name, "truncated: level " + std::to_string(i) +
                                 (face_by_face ? " face " + std::to_string(part) : "") + " needs " +
                                 plural_bytes(expected) + ", file has " +
                                 plural_bytes(bytes.size() - at));
      }
      level.insert(level.end(), bytes.begin() + std::ptrdiff_t(at),
                   bytes.begin() + std::ptrdiff_t(at + expected));
      at += expected;
      at += std::min(pad4(expected), bytes.size() - at);  // cube padding, or mip padding
    }
    tex.levels.push_back(std::move(level));
  }
  if (at != bytes.size()) {
    return corrupt(name, plural_bytes(bytes.size() - at) + " of unexpected data after the " +
                             std::to_string(mip_levels) + " level(s)");
  }
  return Status::success();
}

}  // namespace

Result<CompressedTexture> parse_ktx1(std::span<const std::uint8_t> bytes, const std::string& name) {
  CompressedTexture tex;
  Layout layout;
  if (Status s = read_header(bytes, name, tex, layout); !s.ok()) return s;
  if (Status s = read_levels(bytes, name, layout, tex); !s.ok()) return s;
  return tex;
}

Result<std::vector<std::uint8_t>> serialise_ktx1(const CompressedTexture& texture) {
  if (Status s = validate_texture(texture, "KTX output"); !s.ok()) return s;
  std::uint32_t internal = 0;
  for (const GlFormat& f : kFormats) {
    if (f.format == texture.format && f.alpha == texture.has_alpha && f.srgb == texture.srgb) {
      internal = f.internal;
    }
  }
  static const char kKey[] = "KTXorientation";
  static const char kValue[] = "S=r,T=d";
  const std::uint32_t kv_size = std::uint32_t(sizeof kKey + sizeof kValue);  // both with NUL
  const std::uint32_t kv_bytes = 4 + kv_size + std::uint32_t(pad4(kv_size));

  std::vector<std::uint8_t> out(kKtxIdentifier.begin(), kKtxIdentifier.end());
  container::store_u32(out, kEndianLittle);
  container::store_u32(out, 0);  // glType: compressed
  container::store_u32(out, 1);  // glTypeSize
  container::store_u32(out, 0);  // glFormat: compressed
  container::store_u32(out, internal);
  container::store_u32(out, texture.has_alpha ? kGlRgba : kGlRgb);
  container::store_u32(out, std::uint32_t(texture.width));
  container::store_u32(out, std::uint32_t(texture.height));
  container::store_u32(out, 0);  // pixelDepth
  container::store_u32(out, texture.array ? std::uint32_t(texture.layers) : 0u);
  container::store_u32(out, std::uint32_t(texture.faces));
  container::store_u32(out, std::uint32_t(texture.levels.size()));
  container::store_u32(out, kv_bytes);
  container::store_u32(out, kv_size);
  out.insert(out.end(), kKey, kKey + sizeof kKey);
  out.insert(out.end(), kValue, kValue + sizeof kValue);
  out.insert(out.end(), pad4(kv_size), 0);
  const bool face_by_face = texture.is_cube() && !texture.array;
  for (int i = 0; i < texture.level_count(); ++i) {
    const std::vector<std::uint8_t>& l = texture.levels[std::size_t(i)];
    if (face_by_face) {  // imageSize of one face; each face padded (PVRTC sizes need none)
      container::store_u32(out, std::uint32_t(texture.image_size(i)));
      for (int f = 0; f < texture.faces; ++f) {
        const std::span<const std::uint8_t> face = texture.image(i, 0, f);
        out.insert(out.end(), face.begin(), face.end());
        out.insert(out.end(), pad4(face.size()), 0);
      }
      continue;
    }
    container::store_u32(out, std::uint32_t(l.size()));
    out.insert(out.end(), l.begin(), l.end());
    out.insert(out.end(), pad4(l.size()), 0);
  }
  return out;
}

}  // namespace tessera::texture_file
