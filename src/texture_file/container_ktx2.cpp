// KTX 2.0 container: reader and writer for PVRTC1, with optional Zstandard supercompression.
//
// Layout: 12-byte identifier, nine u32 fields (vkFormat, typeSize, pixelWidth, pixelHeight,
// pixelDepth, layerCount, faceCount, levelCount, supercompressionScheme), the index (dfd and
// kvd offset/length u32, sgd offset/length u64), the level index (per level, level 0 first:
// byteOffset, byteLength, uncompressedByteLength, u64 each), the Data Format Descriptor, the
// key/value data, then the levels' data, smallest level first. Every offset and length is
// checked in 64 bits against the file size, and every level's size against what the header's
// shape requires, before anything is allocated.
//
// What tessera reads and writes:
// KTX 2.0 (the Khronos container Vulkan, three.js and glTF pipelines read): vkFormat
// VK_FORMAT_PVRTC1_{2,4}BPP_{UNORM,SRGB}_BLOCK_IMG, layerCount 0 unless an array, a Data Format
// Descriptor (one basic block: colour model PVRTC, BT.709 primaries, sRGB or linear transfer
// function, the ALPHA_PREMULTIPLIED flag, texel block 4x4 or 8x4, 8 bytes per block, one 64-bit
// sample), the keys "KTXorientation" = "rd" and "KTXwriter" = "tessera <version>", a level
// index (level 0 first; the data is stored smallest level first, 8-byte aligned), and optional
// Zstandard supercompression (`Ktx2Options`: one frame per level, declaring its size; levels
// then unaligned). The reader takes levelCount 0 as one level, wants the DFD to agree with
// vkFormat, and refuses BasisLZ / ZLIB supercompression, 1D and 3D textures; each zstd frame
// must declare exactly the level size the header's shape gives and be long enough to expand
// that far (at most 128 KiB per 3 bytes) before the level is allocated, and never decompresses
// past it. KTX 2.0 has no RGB/RGBA distinction for PVRTC: a file read back has alpha when any
// block can decode a texel with alpha below 255 (`pvrtc::may_have_alpha`: a translucent
// endpoint or a 4 bpp punch-through texel).
#include <algorithm>
#include <cstring>
#include <string>

#include "tessera/image_mipmap.h"
#include "tessera/texture_file.h"
#include "texture_file/container_bytes.h"
#include "texture_file/ktx2_format.h"

#ifndef TESSERA_VERSION_STRING
#error "TESSERA_VERSION_STRING must be defined by the build (src/CMakeLists.txt)"
#endif

namespace tessera::texture_file {

namespace {

using namespace container;  // NOLINT(google-build-using-namespace): container_bytes.h

std::string scheme_name(std::uint32_t scheme) {
  switch (scheme) {
    case ktx2::kSchemeNone:
      return "none";
    case ktx2::kSchemeBasisLz:
      return "BasisLZ";
    case ktx2::kSchemeZstd:
      return "Zstandard";
    case ktx2::kSchemeZlib:
      return "ZLIB";
    default:
      return "unknown";
  }
}

/// Where one level's bytes lie in the file.
struct LevelEntry {
  std::uint64_t offset = 0;
  std::uint64_t length = 0;
  std::uint64_t uncompressed = 0;
};

/// Walks the key/value entries: each is a u32 length, the bytes, padding to 4. Only the
/// structure is checked; tessera needs no key.
Status check_key_values(std::span<const std::uint8_t> kvd, const std::string& name) {
  std::size_t at = 0;
  while (at < kvd.size()) {
    if (kvd.size() - at < 4) return corrupt(name, "malformed key/value data (partial entry size)");
    const std::uint32_t n = load_u32(kvd, at);
    at += 4;
    if (n > kvd.size() - at) {
      return corrupt(
          name, "malformed key/value data (entry of " + plural_bytes(n) + " overruns the block)");
    }
    at += n;
    at += std::min<std::size_t>((4 - n % 4) % 4, kvd.size() - at);
  }
  return Status::success();
}

void append_key_value(std::vector<std::uint8_t>& kvd, const std::string& key,
                      const std::string& value) {
  const std::size_t n = key.size() + 1 + value.size() + 1;  // both NUL-terminated
  container::store_u32(kvd, std::uint32_t(n));
  kvd.insert(kvd.end(), key.begin(), key.end());
  kvd.push_back(0);
  kvd.insert(kvd.end(), value.begin(), value.end());
  kvd.push_back(0);
  kvd.insert(kvd.end(), (4 - n % 4) % 4, 0);
}

std::uint64_t align_up(std::uint64_t v, std::uint64_t a) { return (v + a - 1) / a * a; }

/// The header fields parse_ktx2 reads, and what its checks derive from them.
struct Header {
  std::uint32_t vk_format = 0;
  std::uint32_t type_size = 0;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::uint32_t depth = 0;
  std::uint32_t layer_count = 0;
  std::uint32_t faces = 0;
  std::uint32_t level_count = 0;
  std::uint32_t scheme = 0;
  std::uint64_t dfd_offset = 0;
  std::uint64_t dfd_length = 0;
  std::uint64_t kvd_offset = 0;
  std::uint64_t kvd_length = 0;
  std::uint64_t sgd_length = 0;
  std::uint64_t size = 0;
  const ktx2::VkPvrtcFormat* vk = nullptr;
  std::uint32_t levels = 0;        ///< levelCount, 0 read as 1.
  std::uint64_t index_end = 0;     ///< The end of the level index.
  std::uint64_t metadata_end = 0;  ///< The end of the DFD and key/value data.
  ktx2::DfdInfo dfd;
};

Result<Header> read_header(std::span<const std::uint8_t> bytes, const std::string& name) {
  if (bytes.size() < ktx2::kIdentifier.size() ||
      std::memcmp(bytes.data(), ktx2::kIdentifier.data(), ktx2::kIdentifier.size()) != 0) {
    return corrupt(name, "not a KTX 2.0 file (bad identifier)");
  }
  if (bytes.size() < ktx2::kHeaderSize) {
    return corrupt(name, "truncated KTX 2.0 header: " + plural_bytes(bytes.size()) + " of " +
                             std::to_string(ktx2::kHeaderSize));
  }
  Header h;
  h.vk_format = load_u32(bytes, 12);
  h.type_size = load_u32(bytes, 16);
  h.width = load_u32(bytes, 20);
  h.height = load_u32(bytes, 24);
  h.depth = load_u32(bytes, 28);
  h.layer_count = load_u32(bytes, 32);
  h.faces = load_u32(bytes, 36);
  h.level_count = load_u32(bytes, 40);
  h.scheme = load_u32(bytes, 44);
  h.dfd_offset = load_u32(bytes, 48);
  h.dfd_length = load_u32(bytes, 52);
  h.kvd_offset = load_u32(bytes, 56);
  h.kvd_length = load_u32(bytes, 60);
  h.sgd_length = load_u64(bytes, 72);
  h.size = bytes.size();

  h.vk = ktx2::find_vk_format(h.vk_format);
  if (!h.vk) {
    const std::string vk_name = ktx2::vk_format_name(h.vk_format);
    return unsupported(name, "vkFormat " + std::to_string(h.vk_format) +
                                 (vk_name.empty() ? "" : " (" + vk_name + ")") +
                                 " is not supported (only PVRTC1: "
                                 "VK_FORMAT_PVRTC1_{2,4}BPP_{UNORM,SRGB}_BLOCK_IMG)");
  }
  if (h.scheme != ktx2::kSchemeNone && h.scheme != ktx2::kSchemeZstd) {
    return unsupported(name, "supercompressionScheme " + std::to_string(h.scheme) + " (" +
                                 scheme_name(h.scheme) +
                                 ") is not supported (only 0, none, and 2, Zstandard)");
  }
  if (h.type_size != 1) {
    return corrupt(name, "typeSize " + std::to_string(h.type_size) +
                             " (block-compressed formats have typeSize 1)");
  }
  if (h.width == 0) return corrupt(name, "pixelWidth 0");
  if (h.height == 0) return unsupported(name, "1D textures (pixelHeight 0) are not supported");
  if (h.depth != 0) {
    return unsupported(
        name, "3D textures (pixelDepth " + std::to_string(h.depth) + ") are not supported");
  }
  if (h.faces != 1 && h.faces != 6) {
    return corrupt(name, "faceCount " + std::to_string(h.faces) + " (1, or 6 for a cube map)");
  }
  if (h.faces == 6 && h.width != h.height) {
    return corrupt(name, "a cube map's faces must be square, not " + size_text(h.width, h.height));
  }
  const std::uint32_t max_layers = std::uint32_t(kMaxTextureImages) / h.faces;
  if (h.layer_count > max_layers) {
    return Status::error(ErrorCode::too_large,
                         name + ": layerCount " + std::to_string(h.layer_count) +
                             " exceeds tessera's limit of " + std::to_string(max_layers) +
                             (h.faces == 6 ? " cube map layers" : " layers"));
  }
  if (Status s = check_image_size(h.width, h.height, name); !s.ok()) return s;
  if (Status s = pvrtc::check_dimensions(int(h.width), int(h.height), name); !s.ok()) return s;
  const int possible = mip_level_count(int(h.width), int(h.height));
  // levelCount 0 means "one level; the loader generates the rest".
  h.levels = std::max<std::uint32_t>(h.level_count, 1);
  if (h.levels > std::uint32_t(possible)) {
    return corrupt(name, "levelCount " + std::to_string(h.level_count) + " is impossible for " +
                             size_text(h.width, h.height) + " (1 to " + std::to_string(possible) +
                             ")");
  }
  h.index_end = ktx2::kHeaderSize + ktx2::kLevelEntrySize * h.levels;
  if (h.index_end > h.size) {
    return corrupt(name, "truncated: the level index of " + std::to_string(h.levels) +
                             " level(s) ends at byte " + std::to_string(h.index_end) +
                             ", past the end of the file (" + plural_bytes(h.size) + ")");
  }
  return h;
}

/// The Data Format Descriptor, then the key/value data, in that order after the level index;
/// no supercompression global data. Sets h.dfd and h.metadata_end.
Status read_metadata(std::span<const std::uint8_t> bytes, Header& h, const std::string& name) {
  if (h.dfd_length == 0) return corrupt(name, "no Data Format Descriptor (dfdByteLength 0)");
  if (h.dfd_offset < h.index_end) {
    return corrupt(name, "dfdByteOffset " + std::to_string(h.dfd_offset) +
                             " lies inside the header or level index (which end at byte " +
                             std::to_string(h.index_end) + ")");
  }
  if (h.dfd_offset > h.size || h.dfd_length > h.size - h.dfd_offset) {
    return corrupt(name, "truncated: the Data Format Descriptor (" + plural_bytes(h.dfd_length) +
                             " at byte " + std::to_string(h.dfd_offset) +
                             ") extends past the end of the file (" + plural_bytes(h.size) + ")");
  }
  Result<ktx2::DfdInfo> dfd = ktx2::read_dfd(
      bytes.subspan(std::size_t(h.dfd_offset), std::size_t(h.dfd_length)), *h.vk, name);
  if (!dfd) return dfd.status();
  h.dfd = *dfd;
  h.metadata_end = h.dfd_offset + h.dfd_length;
  if (h.kvd_length != 0) {
    if (h.kvd_offset < h.metadata_end) {
      return corrupt(name, "kvdByteOffset " + std::to_string(h.kvd_offset) +
                               " lies before the end of the Data Format Descriptor (byte " +
                               std::to_string(h.metadata_end) + ")");
    }
    if (h.kvd_offset > h.size || h.kvd_length > h.size - h.kvd_offset) {
      return corrupt(name, "truncated: the key/value data (" + plural_bytes(h.kvd_length) +
                               " at byte " + std::to_string(h.kvd_offset) +
                               ") extends past the end of the file (" + plural_bytes(h.size) + ")");
    }
    const auto kvd = bytes.subspan(std::size_t(h.kvd_offset), std::size_t(h.kvd_length));
    if (Status s = check_key_values(kvd, name); !s.ok()) return s;
    h.metadata_end = h.kvd_offset + h.kvd_length;
  }
  if (h.sgd_length != 0) {
    return corrupt(name, "supercompression global data of " + plural_bytes(h.sgd_length) +
                             " (scheme " + scheme_name(h.scheme) + " has none)");
  }
  return Status::success();
}

/// The level index: every level's range and sizes, all checked before any level is read.
Result<std::vector<LevelEntry>> read_level_index(std::span<const std::uint8_t> bytes,
                                                 const Header& h, const CompressedTexture& tex,
                                                 const std::string& name) {
  std::vector<LevelEntry> entries(h.levels);
  for (std::uint32_t i = 0; i < h.levels; ++i) {
    const std::size_t at = ktx2::kHeaderSize + ktx2::kLevelEntrySize * i;
    LevelEntry& e = entries[i];
    e.offset = load_u64(bytes, at);
    e.length = load_u64(bytes, at + 8);
    e.uncompressed = load_u64(bytes, at + 16);
    const std::string level = "level " + std::to_string(i);
    const std::uint64_t expected =
        std::uint64_t(tex.image_size(int(i))) * std::uint64_t(tex.image_count());
    if (e.uncompressed != expected) {
      return corrupt(name, level + " uncompressedByteLength " + std::to_string(e.uncompressed) +
                               " does not match " + std::to_string(tex.level_width(int(i))) + "x" +
                               std::to_string(tex.level_height(int(i))) + " PVRTC x " +
                               std::to_string(tex.image_count()) + " image(s) (" +
                               plural_bytes(expected) + ")");
    }
    if (h.scheme == ktx2::kSchemeNone) {
      if (e.length != e.uncompressed) {
        return corrupt(name, level + " byteLength " + std::to_string(e.length) +
                                 " differs from its uncompressedByteLength " +
                                 std::to_string(e.uncompressed) + " (not supercompressed)");
      }
      if (e.offset % ktx2::kLevelAlignment != 0) {
        return corrupt(name, level + " byteOffset " + std::to_string(e.offset) +
                                 " is not a multiple of " + std::to_string(ktx2::kLevelAlignment));
      }
    } else if (!ktx2::zstd_expansion_possible(e.length, e.uncompressed)) {
      // Also keeps a lying header from making the reader allocate what no data can fill.
      return corrupt(name, level + ": " + plural_bytes(e.length) +
                               " of Zstandard data cannot hold " + plural_bytes(e.uncompressed));
    }
    if (e.offset < h.metadata_end) {
      return corrupt(name, level + " byteOffset " + std::to_string(e.offset) +
                               " lies inside the header, index or metadata (which end at byte " +
                               std::to_string(h.metadata_end) + ")");
    }
    if (e.offset > h.size || e.length > h.size - e.offset) {
      return corrupt(name, "truncated: " + level + " (" + plural_bytes(e.length) + " at byte " +
                               std::to_string(e.offset) + ") extends past the end of the file (" +
                               plural_bytes(h.size) + ")");
    }
  }
  std::vector<std::uint32_t> order(h.levels);
  for (std::uint32_t i = 0; i < h.levels; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return entries[a].offset < entries[b].offset;
  });
  for (std::size_t k = 1; k < order.size(); ++k) {
    const LevelEntry& prev = entries[order[k - 1]];
    if (entries[order[k]].offset < prev.offset + prev.length) {
      return corrupt(name, "levels " + std::to_string(order[k - 1]) + " and " +
                               std::to_string(order[k]) + " overlap (bytes " +
                               std::to_string(prev.offset) + "+" + std::to_string(prev.length) +
                               " and " + std::to_string(entries[order[k]].offset) + ")");
    }
  }
  return entries;
}

}  // namespace

Result<CompressedTexture> parse_ktx2(std::span<const std::uint8_t> bytes, const std::string& name) {
  Result<Header> header = read_header(bytes, name);
  if (!header) return header.status();
  Header& h = *header;
  if (Status s = read_metadata(bytes, h, name); !s.ok()) return s;
  CompressedTexture tex;
  tex.format = h.vk->format;
  tex.width = int(h.width);
  tex.height = int(h.height);
  tex.srgb = h.dfd.srgb;
  tex.premultiplied = h.dfd.premultiplied;
  tex.faces = int(h.faces);
  tex.array = h.layer_count > 0;
  tex.layers = tex.array ? int(h.layer_count) : 1;

  Result<std::vector<LevelEntry>> index = read_level_index(bytes, h, tex, name);
  if (!index) return index.status();
  const std::vector<LevelEntry>& entries = *index;
  tex.levels.reserve(h.levels);
  for (std::uint32_t i = 0; i < h.levels; ++i) {
    const LevelEntry& e = entries[i];
    const auto data = bytes.subspan(std::size_t(e.offset), std::size_t(e.length));
    if (h.scheme == ktx2::kSchemeNone) {
      tex.levels.emplace_back(data.begin(), data.end());
      continue;
    }
    std::vector<std::uint8_t> raw(std::size_t(e.uncompressed));
    if (Status s = ktx2::zstd_decompress(data, raw, name + ": level " + std::to_string(i));
        !s.ok()) {
      return s;
    }
    tex.levels.push_back(std::move(raw));
  }
  tex.has_alpha = std::any_of(tex.levels.begin(), tex.levels.end(),
                              [&](const auto& l) { return pvrtc::may_have_alpha(l, tex.format); });
  return tex;
}

Result<std::vector<std::uint8_t>> serialise_ktx2(const CompressedTexture& texture,
                                                 const Ktx2Options& options) {
  if (Status s = validate_texture(texture, "KTX 2.0 output"); !s.ok()) return s;
  if (options.zstd_level < 0 || options.zstd_level > 22) {
    return Status::error(ErrorCode::invalid_argument, "KTX 2.0 output: zstd level " +
                                                          std::to_string(options.zstd_level) +
                                                          " is out of range (0 = none, 1 to 22)");
  }
  const bool zstd = options.zstd_level > 0;
  const std::size_t levels = texture.levels.size();

  // Level payloads: the raw bytes, or one Zstandard frame per level.
  std::vector<std::vector<std::uint8_t>> packed;
  if (zstd) {
    packed.reserve(levels);
    for (const auto& l : texture.levels) {
      Result<std::vector<std::uint8_t>> c = ktx2::zstd_compress(l, options.zstd_level);
      if (!c) return c.status();
      packed.push_back(std::move(*c));
    }
  }
  auto payload = [&](std::size_t i) -> const std::vector<std::uint8_t>& {
    return zstd ? packed[i] : texture.levels[i];
  };

  const std::vector<std::uint8_t> dfd =
      ktx2::make_dfd(texture.format, texture.srgb, texture.premultiplied);
  std::vector<std::uint8_t> kvd;  // keys in byte order, as the specification requires
  append_key_value(kvd, "KTXorientation", "rd");
  append_key_value(kvd, "KTXwriter", "tessera " TESSERA_VERSION_STRING);

  const std::uint64_t dfd_offset = ktx2::kHeaderSize + ktx2::kLevelEntrySize * levels;
  const std::uint64_t kvd_offset = dfd_offset + dfd.size();
  const std::uint64_t alignment = zstd ? 1 : ktx2::kLevelAlignment;
  // Levels are stored smallest first; each starts aligned (without supercompression).
  std::vector<std::uint64_t> offsets(levels);
  std::uint64_t end = kvd_offset + kvd.size();
  for (std::size_t i = levels; i-- > 0;) {
    offsets[i] = align_up(end, alignment);
    end = offsets[i] + payload(i).size();
  }

  std::vector<std::uint8_t> out(ktx2::kIdentifier.begin(), ktx2::kIdentifier.end());
  out.reserve(std::size_t(end));
  const ktx2::VkPvrtcFormat& vk = ktx2::vk_format_for(texture.format, texture.srgb);
  container::store_u32(out, vk.vk_format);
  container::store_u32(out, 1);  // typeSize
  container::store_u32(out, std::uint32_t(texture.width));
  container::store_u32(out, std::uint32_t(texture.height));
  container::store_u32(out, 0);  // pixelDepth
  container::store_u32(out, texture.array ? std::uint32_t(texture.layers) : 0);
  container::store_u32(out, std::uint32_t(texture.faces));
  container::store_u32(out, std::uint32_t(levels));
  container::store_u32(out, zstd ? ktx2::kSchemeZstd : ktx2::kSchemeNone);
  container::store_u32(out, std::uint32_t(dfd_offset));
  container::store_u32(out, std::uint32_t(dfd.size()));
  container::store_u32(out, std::uint32_t(kvd_offset));
  container::store_u32(out, std::uint32_t(kvd.size()));
  container::store_u64(out, 0);  // sgdByteOffset: no supercompression global data
  container::store_u64(out, 0);  // sgdByteLength
  for (std::size_t i = 0; i < levels; ++i) {
    container::store_u64(out, offsets[i]);
    container::store_u64(out, payload(i).size());
    container::store_u64(out, texture.levels[i].size());
  }
  out.insert(out.end(), dfd.begin(), dfd.end());
  out.insert(out.end(), kvd.begin(), kvd.end());
  for (std::size_t i = levels; i-- > 0;) {
    out.resize(std::size_t(offsets[i]), 0);  // alignment padding
    out.insert(out.end(), payload(i).begin(), payload(i).end());
  }
  return out;
}

}  // namespace tessera::texture_file
