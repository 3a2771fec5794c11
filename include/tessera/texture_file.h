// tessera/texture_file.h — compressed texture containers: PVR v3 and KTX 1.1.
//
// Readers validate every size against the actual byte count before allocating (a lying header
// gives `corrupt_data`, never a huge allocation) and return one-line errors naming the file.
// Writers produce files PVRTexTool and OpenGL ES loaders accept; write them with
// `write_texture_file`, which is atomic.
//
// PVR v3 (what PVRTexTool writes): 52-byte little-endian header, a metadata block (tessera
// writes PVRTexTool's 15-byte orientation entry and skips any metadata when reading), then the
// levels, largest first, each `pvrtc::level_size` bytes. Pixel formats 0..3 (PVRTC1 2bpp RGB,
// 2bpp RGBA, 4bpp RGB, 4bpp RGBA) are supported; depth, surfaces and faces must be 1.
// Big-endian PVR files are rejected.
//
// KTX 1.1: 64-byte header, glType 0 / glFormat 0, glInternalFormat one of the
// GL_IMG_texture_compression_pvrtc (0x8C00..0x8C03) or GL_EXT_pvrtc_sRGB (0x8A54..0x8A57)
// formats, key/value data (tessera writes "KTXorientation" = "S=r,T=d"), then per level a
// u32 imageSize and the data padded to 4 bytes. Both byte orders are read; files are written
// little-endian. 2D textures only (no arrays, cube maps or 3D). Note: PVRTexTool 4.17 reads
// the 0x8C0x formats but rejects the sRGB EXT ones, and itself writes sRGB data as 0x8C0x.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "tessera/core.h"
#include "tessera/pvrtc.h"

namespace tessera::texture_file {

/// A PVRTC texture with its mip chain (level 0 first).
struct CompressedTexture {
  pvrtc::Format format = pvrtc::Format::pvrtc1_4bpp;
  int width = 0;
  int height = 0;
  bool has_alpha = true;       ///< RGBA (true) or RGB pixel format code in the container.
  bool srgb = false;           ///< Colour space flag (PVR v3 colour space / KTX sRGB format).
  bool premultiplied = false;  ///< PVR v3 flag 0x02.
  std::vector<std::vector<std::uint8_t>> levels;  ///< Level i is (width>>i) x (height>>i), min 1.

  int level_count() const { return int(levels.size()); }
  int level_width(int level) const;
  int level_height(int level) const;
};

/// Checks a texture before it is written: power-of-two size, 1..mip_level_count levels, every
/// level exactly `pvrtc::level_size` bytes. `what` names it in the message.
Status validate_texture(const CompressedTexture& texture, const std::string& what);

/// Decodes level `level` to RGBA8. RGB formats (has_alpha false) decode with alpha forced to
/// 255 and `has_alpha` false. Fails with invalid_argument when `level` is out of range.
Result<ImageRGBA8> decode_texture_level(const CompressedTexture& texture, int level,
                                        const Parallel& parallel = {});

/// Human-readable name of a PVRTC format ("PVRTC1 4bpp RGBA", ...).
std::string texture_format_name(const CompressedTexture& texture);

/// Options of the whole image-to-texture pipeline that `tessera compress`, its batch mode, the
/// Python module and `tessera.batch` share, so all of them write the same bytes.
struct CompressOptions {
  /// Format, quality, schedule overrides, threads. Its `progress` hook, if set, follows the
  /// whole chain (each level weighted by its pixels), on the calling thread, ending at 1.0.
  pvrtc::EncodeOptions encode;
  bool mipmaps = false;     ///< Encode the full chain (2x2 box, alpha-weighted).
  bool srgb = false;        ///< Mark the texture sRGB and filter (mips, resize) in linear light.
  bool resize_pot = false;  ///< Resample non-power-of-two input (Lanczos-3); else it is an error.
};

/// What `compress_image` made.
struct CompressedImage {
  CompressedTexture texture;
  ImageRGBA8 source;      ///< Level 0 as encoded: the input after alpha detection and resizing.
  bool resized = false;   ///< The input was not a power of two and was resampled.
  double encode_ms = 0;   ///< Wall time of the encodes (all levels), milliseconds.
};

/// Compresses one decoded image: an alpha channel that is 255 everywhere gives an RGB texture;
/// a non-power-of-two size is an `invalid_argument` error naming `name` and the size to
/// resample to (or is resampled with `resize_pot`); then the mip chain (when asked) and every
/// level's encode. Deterministic: the same image and options give the same texture for any
/// `encode.threads`.
Result<CompressedImage> compress_image(ImageRGBA8 image, const CompressOptions& options,
                                       const std::string& name);

/// The same texture as `compress_image(to_image(image), options, name).texture`, from pixels
/// the caller owns: a power-of-two view without a mip chain is encoded where it lies (packed
/// RGBA read in place, other layouts packed in one pass; see `pvrtc::encode`), so no copy of
/// the image precedes the encode; otherwise the view is copied once into the owning pipeline.
/// This is the call `tessera.encode` makes on a numpy array.
Result<CompressedTexture> compress_view(const ImageView8& image, const CompressOptions& options,
                                        const std::string& name);

/// Container formats.
enum class ContainerFormat { unknown, pvr3, ktx1 };

/// "PVR v3", "KTX 1.1" or "unknown".
const char* container_name(ContainerFormat format);

/// Detects PVR v3 / KTX 1.1 by magic.
ContainerFormat detect_container(std::span<const std::uint8_t> bytes);
/// Chooses by file extension (.pvr, .ktx; case-insensitive); unknown otherwise.
ContainerFormat container_from_extension(const std::string& path);

/// Parses a PVR v3 / KTX 1.1 file held in memory. Safe on arbitrary input: every size is
/// checked against `bytes.size()` before anything is allocated. `name` prefixes messages.
Result<CompressedTexture> parse_pvr3(std::span<const std::uint8_t> bytes, const std::string& name);
Result<CompressedTexture> parse_ktx1(std::span<const std::uint8_t> bytes, const std::string& name);
/// Parses either container (chosen by magic); unknown magic gives corrupt_data.
Result<CompressedTexture> parse_texture(std::span<const std::uint8_t> bytes,
                                        const std::string& name);
/// Serialises a texture (validated with `validate_texture` first).
Result<std::vector<std::uint8_t>> serialise_pvr3(const CompressedTexture& texture);
Result<std::vector<std::uint8_t>> serialise_ktx1(const CompressedTexture& texture);

/// Reads a .pvr or .ktx file (format by magic).
Result<CompressedTexture> read_texture_file(const std::string& path);
/// Writes by extension (.pvr or .ktx), atomically.
Status write_texture_file(const std::string& path, const CompressedTexture& texture);

}  // namespace tessera::texture_file
