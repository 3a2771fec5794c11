// tessera/texture_file.h — compressed texture containers (PVR v3, KTX 1.1, KTX 2.0) and the
// image-to-texture pipeline.
//
// What: a `CompressedTexture` is a 2D texture, a cube map (6 faces) or an array of either, with
//   an optional mip chain, every image of one size, PVRTC format and colour space; readers and
//   writers for the three containers, and `compress_images` / `compress_image` (images ->
//   prepared chains -> PVRTC blocks -> a texture).
// Where: src/texture_file/; each container's layout and what tessera reads and writes of it is
//   at the top of its file (container_pvr.cpp, container_ktx.cpp, container_ktx2.cpp).
// Reading: every size is checked against the byte count before allocating (a lying header gives
//   `corrupt_data`, never a huge allocation); errors are one line naming the file.
// Writing: files PVRTexTool and OpenGL ES / Vulkan loaders accept; `write_texture_file` is
//   atomic. KTX 2.0 has no RGB/RGBA distinction: a file read back has alpha when any block can
//   decode a texel with alpha below 255 (`pvrtc::may_have_alpha`).
// Tests: tests/unit/texture_file_test.cpp, texture_file_io_test.cpp, ktx2_test.cpp,
// compress_words_test.cpp, texture_shape_test.cpp; tests/oracle/ (PVRTexTool, ktx-parse).
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/core.h"
#include "tessera/image_mipmap.h"
#include "tessera/metrics.h"
#include "tessera/pvrtc.h"

namespace tessera::texture_file {

/// A PVRTC texture: a 2D texture, a cube map, or an array of either, with its mip chain.
struct CompressedTexture {
  pvrtc::Format format = pvrtc::Format::pvrtc1_4bpp;
  int width = 0;
  int height = 0;
  bool has_alpha = true;       ///< RGBA (true) or RGB pixel format code in the container.
  bool srgb = false;           ///< Colour space flag (PVR v3 colour space / KTX sRGB format).
  bool premultiplied = false;  ///< Colour is premultiplied by alpha (PVR v3 flag 0x02, KTX 2.0
                               ///< DFD flag ALPHA_PREMULTIPLIED; KTX 1.1 cannot say it).
  int faces = 1;               ///< 1, or 6 for a cube map: +X, -X, +Y, -Y, +Z, -Z.
  int layers = 1;              ///< Array layers (PVR v3 surfaces); 1 unless `array`.
  bool array = false;          ///< An array texture (KTX numberOfArrayElements = layers), even
                               ///< with one layer; PVR v3 cannot tell an array of one from a
                               ///< plain texture and reads back `array` = layers > 1.
  /// Level i (level 0 first) holds `image_count()` images of level_width(i) x level_height(i),
  /// each `pvrtc::level_size` bytes, layer-major then face (the order of PVR v3 and KTX):
  /// image (layer, face) starts at byte (layer * faces + face) * image_size(i).
  std::vector<std::vector<std::uint8_t>> levels;

  int level_count() const { return int(levels.size()); }
  int level_width(int level) const;
  int level_height(int level) const;
  bool is_cube() const { return faces == 6; }
  /// Images per level: faces x layers.
  int image_count() const { return faces * layers; }
  /// Bytes of one image of `level`.
  std::size_t image_size(int level) const;
  /// The bytes of image (layer, face) of `level`; all three must be in range (unchecked
  /// beyond a debug check: see `check_image_index`).
  std::span<const std::uint8_t> image(int level, int layer = 0, int face = 0) const;
};

/// Checks that (level, layer, face) names an image of `texture`; the message names the
/// out-of-range one and the valid range ("face 6 is out of range (the cube map has faces 0 to
/// 5)").
Status check_image_index(const CompressedTexture& texture, int level, int layer, int face);

/// Checks a texture before it is written: power-of-two size (square for a cube map), 1 or 6
/// faces, 1..kMaxTextureImages images, 1..mip_level_count levels, every level exactly
/// `image_count() * pvrtc::level_size` bytes. `what` names it in the message.
Status validate_texture(const CompressedTexture& texture, const std::string& what);

/// Most images (faces x layers) a texture may hold: PVRTexTool's and Vulkan's usual array
/// limit, and a bound readers check before they allocate.
inline constexpr int kMaxTextureImages = 2048 * 6;

/// Decodes image (layer, face) of `level` to RGBA8. RGB formats (has_alpha false) decode with
/// alpha forced to 255 and `has_alpha` false. Fails with invalid_argument (see
/// `check_image_index`) when an index is out of range.
Result<ImageRGBA8> decode_texture_image(const CompressedTexture& texture, int level, int layer,
                                        int face, const Parallel& parallel = {});
/// `decode_texture_image(texture, level, 0, 0)`: level `level` of a 2D texture.
Result<ImageRGBA8> decode_texture_level(const CompressedTexture& texture, int level,
                                        const Parallel& parallel = {});

/// "2D texture", "cube map", "array of 3 layers", "cube map array of 2 layers".
std::string texture_shape_name(const CompressedTexture& texture);

/// Human-readable name of a PVRTC format ("PVRTC1 4bpp RGBA", ...).
std::string texture_format_name(const CompressedTexture& texture);

/// Options of the whole image-to-texture pipeline that `tessera compress`, its batch mode, the
/// Python module and `tessera.batch` share, so all of them write the same bytes. The steps, in
/// order, for every image: `flip_y`, alpha detection, resampling (`resize_pot`), `premultiply`,
/// the mip chain (`mipmaps`, `mip_levels`, `mip_filter`), `alpha_bleed` of every level, and the
/// encodes.
struct CompressOptions {
  /// Format, quality, schedule overrides, threads. Its `progress` hook, if set, follows the
  /// whole texture (each image and level weighted by its pixels), on the calling thread,
  /// ending at 1.0.
  pvrtc::EncodeOptions encode;
  bool mipmaps = false;  ///< Encode a mip chain (see `mip_levels`, `mip_filter`).
  int mip_levels = 0;    ///< With `mipmaps`: at most this many levels, level 0 included
                         ///< (0 = down to 1x1).
  image::MipFilter mip_filter =
      image::MipFilter::box;  ///< How each level is made (image_mipmap.h).
  bool srgb = false;          ///< Mark the texture sRGB and filter (mips, resize, premultiply) in
                              ///< linear light.
  bool resize_pot = false;    ///< Resample non-power-of-two input (Lanczos-3); else it is an error.
  bool flip_y = false;        ///< Flip every image upside down first (row 0 becomes the last), for
                              ///< pipelines whose texture origin is bottom-left.
  /// Multiply colour by alpha (in linear light with `srgb`) and mark the texture premultiplied.
  /// Images without alpha are left as they are (the CLI warns).
  bool premultiply = false;
  /// Give every fully transparent texel (alpha 0) the colour of the nearest visible one
  /// (`image::bleed_alpha`), so that PVRTC's block interpolation and texture filtering do not
  /// pull invisible colours into visible edges. Straight alpha only: with `premultiply` it is
  /// an invalid_argument error (transparent texels are black there already).
  bool alpha_bleed = false;
  /// The input's RGB is a unit vector, x, y, z mapped from [-1, 1] to [0, 255]: the encoder
  /// chooses modulation by the angle a renormalising renderer sees (`EncodeOptions::normal_map`),
  /// mip levels are averaged as vectors and renormalised, and the texture is never sRGB (with
  /// `srgb` it is an invalid_argument error). Level 0 is encoded as given: renormalising and
  /// requantising it would move every vector's direction by up to a rounding step
  /// (`image::normalise_normals` does that for a pipeline that wants it).
  bool normal_map = false;
};

/// How the images given to `compress_images` form one texture.
struct TextureShape {
  int faces = 1;       ///< 1, or 6 for a cube map (faces +X, -X, +Y, -Y, +Z, -Z).
  bool array = false;  ///< The images (groups of `faces`) are the layers of an array texture.
};

/// What `compress_image` / `compress_images` made.
struct CompressedImage {
  CompressedTexture texture;
  /// Level 0 of every image as encoded (after flipping, resizing, premultiplication and
  /// bleeding), layer-major then face: what the texture's level 0 approximates.
  std::vector<ImageRGBA8> sources;
  bool resized = false;  ///< The input was not a power of two and was resampled.
  double encode_ms = 0;  ///< Wall time of the encodes (all images and levels), milliseconds.
};

/// Compresses one decoded image: an alpha channel that is 255 everywhere gives an RGB texture;
/// a non-power-of-two size is an `invalid_argument` error naming `name` and the size to
/// resample to (or is resampled with `resize_pot`); then the steps of `CompressOptions`.
/// Deterministic: the same image and options give the same texture for any `encode.threads`.
Result<CompressedImage> compress_image(ImageRGBA8 image, const CompressOptions& options,
                                       const std::string& name);

/// Compresses a cube map, an array or a cube map array: `images` are the faces and layers,
/// layer-major then face (`shape.faces` per layer; without `shape.array` exactly `shape.faces`
/// images). All must have one size (square for a cube map); each is encoded as
/// `compress_image` would encode it alone, and the texture has alpha when any image does.
/// `names[i]` names image i in messages ("b.png: 128x64, but a.png is 256x256 (every face and
/// layer needs one size)").
Result<CompressedImage> compress_images(std::vector<ImageRGBA8> images, const TextureShape& shape,
                                        const CompressOptions& options,
                                        std::span<const std::string> names);

/// The error of level 0 of `texture` against `sources`, what it approximates (one image per face
/// of every layer, layer-major then face: `CompressedImage::sources`), pooled over the images as
/// astcenc's -tl mode reports one image: the MSE averaged, then the PSNR; the SSIM averaged;
/// the largest absolute difference. `tessera compress` prints and writes this. A count other
/// than `texture.image_count()` is an invalid_argument error, a source of another size a
/// size_mismatch; `threads` as `metrics::CompareOptions::threads`.
Result<metrics::ImageComparison> measure_level0(const CompressedTexture& texture,
                                                std::span<const ImageRGBA8> sources,
                                                int threads = 0);

/// The same texture as `compress_image(to_image(image), options, name).texture`, from pixels
/// the caller owns: a power-of-two view without a mip chain and without preprocessing (flip,
/// premultiply, bleed, normal map) is encoded where it lies (packed RGBA read in place, other
/// layouts packed in one pass; see `pvrtc::encode`), so no copy of the image precedes the
/// encode; otherwise the view is copied once into the owning pipeline. This is the call
/// `tessera.encode` makes on a numpy array.
Result<CompressedTexture> compress_view(const ImageView8& image, const CompressOptions& options,
                                        const std::string& name);

/// Container formats.
enum class ContainerFormat { unknown, pvr3, ktx1, ktx2 };

/// "PVR v3", "KTX 1.1", "KTX 2.0" or "unknown".
const char* container_name(ContainerFormat format);

/// Detects PVR v3 / KTX 1.1 / KTX 2.0 by magic.
ContainerFormat detect_container(std::span<const std::uint8_t> bytes);
/// Chooses by file extension (.pvr, .ktx, .ktx2; case-insensitive); unknown otherwise.
ContainerFormat container_from_extension(const std::string& path);

/// How a KTX 2.0 file is written.
struct Ktx2Options {
  /// Zstandard supercompression of every level (supercompressionScheme 2) at this zstd level,
  /// 1 to 22; 0 = none.
  int zstd_level = 0;
};

/// Parses a PVR v3 / KTX 1.1 / KTX 2.0 file held in memory. Safe on arbitrary input: every
/// size is checked against `bytes.size()` before anything is allocated (and, for KTX 2.0 with
/// zstd, every level's decompressed size against what its header promises). `name` prefixes
/// messages.
Result<CompressedTexture> parse_pvr3(std::span<const std::uint8_t> bytes, const std::string& name);
Result<CompressedTexture> parse_ktx1(std::span<const std::uint8_t> bytes, const std::string& name);
Result<CompressedTexture> parse_ktx2(std::span<const std::uint8_t> bytes, const std::string& name);
/// Parses any of the three (chosen by magic); unknown magic gives corrupt_data.
Result<CompressedTexture> parse_texture(std::span<const std::uint8_t> bytes,
                                        const std::string& name);
/// Serialises a texture (validated with `validate_texture` first).
Result<std::vector<std::uint8_t>> serialise_pvr3(const CompressedTexture& texture);
Result<std::vector<std::uint8_t>> serialise_ktx1(const CompressedTexture& texture);
Result<std::vector<std::uint8_t>> serialise_ktx2(const CompressedTexture& texture,
                                                 const Ktx2Options& options = {});
/// Serialises in `container` (pvr3, ktx1 or ktx2; `ktx2` options apply to KTX 2.0 only).
Result<std::vector<std::uint8_t>> serialise_texture(const CompressedTexture& texture,
                                                    ContainerFormat container,
                                                    const Ktx2Options& ktx2 = {});

/// Reads a .pvr, .ktx or .ktx2 file (format by magic).
Result<CompressedTexture> read_texture_file(const std::string& path);
/// Writes by extension (.pvr, .ktx or .ktx2), atomically.
Status write_texture_file(const std::string& path, const CompressedTexture& texture,
                          const Ktx2Options& ktx2 = {});

/// The options an up-to-date record keeps (see `up_to_date_record`): those of `tessera
/// compress` and of `tessera.batch`, in their words and as the user gave them (`mip_levels` 3
/// with `mipmaps` false is recorded so, although it implies a mip chain).
struct RecordedOptions {
  std::string container = "pvr";    ///< "pvr", "ktx" or "ktx2".
  std::string format = "pvrtc1-4";  ///< "pvrtc1-4" or "pvrtc1-2".
  std::string quality = "normal";   ///< "fast", "normal" or "high".
  int iterations = -1;              ///< -1: the quality preset's schedule.
  int exact_search_rounds = 0;      ///< 0: the quality preset's schedule.
  bool mipmaps = false;
  int mip_levels = 0;              ///< 0: the full chain (with `mipmaps`).
  std::string mip_filter = "box";  ///< "box", "lanczos" or "kaiser".
  bool srgb = false;
  bool resize_pot = false;
  bool flip_y = false;
  bool premultiply = false;
  bool alpha_bleed = false;
  bool alpha_weighted = false;
  bool normal_map = false;
  int zstd = 0;        ///< KTX 2.0 Zstandard level, 1..22; 0 = none.
  bool cube = false;   ///< The inputs are the faces of a cube map.
  bool array = false;  ///< The inputs are the layers of an array.
};

/// How a front end spells an option in its messages: `field` is a RecordedOptions member
/// ("normal_map", "mip_filter"), `value` the word given with it ("" for the option alone, "True"
/// for a switch that is on, "N" for a number). The CLI writes "--mip-filter lanczos" and
/// "--mipmaps", Python "mip_filter='lanczos'" and "mipmaps=True"; empty = the member's name,
/// then "=value" when there is one.
using OptionSpeller = std::function<std::string(std::string_view field, std::string_view value)>;

/// The options `words` name (what a user typed: `tessera compress`'s flags, Python's keywords,
/// an up-to-date record), checked and converted: the one conversion of the CLI, Python, the
/// batch and the benchmarks. invalid_argument, naming the options as `spell` spells them, for a
/// word that is not one of its values or a number out of range ("quality: 'best' is not one of
/// 'fast', 'normal', 'high'") and for two options that conflict ("normal_map and srgb: a normal
/// map holds vectors, never sRGB colour"). `container`, `zstd`, `cube` and `array` belong to
/// the container and the texture's shape, not to CompressOptions (not checked here); `threads`
/// as EncodeOptions::threads (>= 0).
Result<CompressOptions> compress_options(const RecordedOptions& words, int threads,
                                         const OptionSpeller& spell = {});

/// What is appended to an output's path to name its up-to-date record ("a.pvr.json").
inline constexpr const char* kRecordSuffix = ".json";

/// The up-to-date record of an output made from `inputs` with `options`: what `tessera compress
/// --skip-up-to-date` and `tessera.batch` keep beside each output (OUTPUT.json) to skip work
/// that is already done. A JSON object, keys sorted, one-space indent, ending in a newline:
/// - "tessera": the library's version (a new version redoes everything);
/// - "container": `options.container`;
/// - "options": "exact_search_rounds", "format", "iterations", "mipmaps", "quality",
///   "resize_pot" and "srgb" always; "mip_levels", "mip_filter", "flip_y", "premultiply",
///   "alpha_bleed", "alpha_weighted", "normal_map", "zstd", "cube" and "array" only when they
///   are not their defaults, so that the records of runs without them stay as they were before
///   those options existed;
/// - one input: "input_size" (bytes) and "input_mtime_ns" (modification time, nanoseconds
///   since the epoch); several (a cube map or array): "inputs", a list of {"path", "size",
///   "mtime_ns"} in the order given.
/// The same options and inputs give the same bytes. Fails (naming the file) when an input
/// cannot be examined, e.g. "-" (standard input).
Result<std::string> up_to_date_record(const RecordedOptions& options,
                                      std::span<const std::string> inputs);

/// True when `output` is up to date: it exists, its modification time is later than every
/// input's, and OUTPUT.json holds the record `up_to_date_record` gives now (the same JSON
/// value). False when any of that cannot be read (no record, an unreadable or malformed one, an
/// input that is "-" or gone): the output is then made again.
bool is_up_to_date(const RecordedOptions& options, std::span<const std::string> inputs,
                   const std::string& output);

/// Writes `record` to OUTPUT.json atomically. Write it after the output itself, so that an
/// interrupted run never leaves an output that looks complete without being so.
Status write_up_to_date_record(const std::string& output, const std::string& record);

}  // namespace tessera::texture_file
