// tessera view: the model behind the page (inputs, encodes, the images and metrics the page
// shows), the static export and the local server. The page itself (share/tessera/view/) is
// embedded into the binary at build time (view_assets.cpp, generated).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "compress.h"
#include "tessera/texture_file.h"

namespace tessera::cli {

/// One opened input: an image (encoded by the view) or a texture file (decoded as it is).
struct ViewInput {
  std::string path;  ///< As given (or found in a folder).
  std::string name;  ///< File name shown on the page.
  bool is_texture = false;
  ImageRGBA8 image;  ///< An image input, as read (a group's first).
  /// A --cube / --array input (a group): its files and images, faces +X, -X, +Y, -Y, +Z, -Z
  /// or layers in order, encoded as one texture of `shape`; empty for one image or a texture.
  std::vector<std::string> sources;
  std::vector<ImageRGBA8> images;
  texture_file::TextureShape shape;
  texture_file::CompressedTexture texture;  ///< A texture input, as read.
  std::vector<std::uint8_t> file;           ///< A texture input's file (its download).
  std::string error;                        ///< One line when it could not be read; else "".
};

/// The encoder settings a view result is made with: the subset of `tessera compress`'s options
/// the page offers.
struct ViewSettings {
  std::string format = "pvrtc1-4";
  std::string quality = "normal";
  bool alpha_bleed = false;
  bool alpha_weighted = false;
  bool premultiply = false;
  bool normal_map = false;
  bool srgb = false;
  int mip_levels = 0;  ///< 0: no mip chain; N: N levels (`--mip-levels N`).
  std::string mip_filter = "box";
  bool resize_pot = false;  ///< `--resize-pot`: resample a non-power-of-two input.
  std::string label;        ///< Shown on the page ("normal", "high + weighted"); "" = derived.
};

/// The settings in `j` (the page's JSON), checked: an unknown value or a combination `tessera
/// compress` refuses is an error whose message names it.
Result<ViewSettings> settings_from_json(const nlohmann::json& j);
nlohmann::json settings_to_json(const ViewSettings& s);
/// The `tessera compress` arguments of these settings for `input`, writing `output`.
CompressArgs compress_args(const ViewSettings& s, const std::string& input,
                           const std::string& output);
/// The exact `tessera compress` command line that writes the same texture.
std::string compress_command(const ViewSettings& s, const std::string& input,
                             const std::string& output);
/// The same for several inputs of `shape` (`--cube` with 6 faces, `--array` with layers).
CompressArgs compress_args(const ViewSettings& s, const std::vector<std::string>& inputs,
                           const std::string& output, texture_file::TextureShape shape);
std::string compress_command(const ViewSettings& s, const std::vector<std::string>& inputs,
                             const std::string& output, texture_file::TextureShape shape);

/// Content-addressed bytes the page loads (PNG images, SVG colour bars, texture files): the
/// key is a hash of the bytes, so an image shared by several results is kept once; a lazy
/// blob's key names what it is made from.
class BlobStore {
 public:
  struct Blob {
    std::string mime;
    std::vector<std::uint8_t> bytes;
  };
  /// Stores `bytes` and returns its key (16 hex digits).
  std::string put(std::string mime, std::vector<std::uint8_t> bytes);
  /// Registers a blob that `make` makes on its first `get` (a heatmap the page may never
  /// show) under `key` (16 hex digits naming what it is made of). Returns `key`.
  std::string put_lazy(std::string key, std::string mime,
                       std::function<std::vector<std::uint8_t>()> make);
  /// The blob of `key` (made now when it is a lazy one), or null.
  std::shared_ptr<const Blob> get(const std::string& key) const;
  /// Whether `key` names a blob, made or lazy (never makes one).
  bool has(const std::string& key) const;
  /// The libdeflate level of the PNG images put here (view_png.h): fast for the server, small
  /// for the static export.
  int png_level = 1;
  /// Every key, for the static export.
  std::vector<std::string> keys() const;
  /// Drops the blob of `key` (a result evicted under the memory budget).
  void erase(const std::string& key);
  /// The bytes of every blob held.
  std::size_t bytes() const;

 private:
  struct Lazy {
    std::string mime;
    std::function<std::vector<std::uint8_t>()> make;
    std::once_flag once;
    std::shared_ptr<const Blob> blob;
  };
  mutable std::mutex mutex_;
  mutable std::size_t bytes_ = 0;
  mutable std::map<std::string, std::shared_ptr<const Blob>> blobs_;
  mutable std::map<std::string, std::shared_ptr<Lazy>> lazy_;
};

/// Reads the inputs: files by their bytes (images, .pvr/.ktx/.ktx2), folders as the images
/// and textures in them (not recursive, in name order; links that resolve outside the folder are
/// skipped with a line on stderr). A file that cannot be read becomes an input with `error` set
/// (the view shows it and goes on); a missing folder too.
std::vector<ViewInput> load_view_inputs(const std::vector<std::string>& paths);

/// One input of the images `paths` as one texture of `shape` (`tessera view --cube` / `--array`,
/// the checks of `tessera compress`'s): named after their files' common stem ("sky_px.png",
/// ..., "sky_nz.png": "sky"); a file that cannot be read, a wrong count or mixed sizes set
/// `error`.
ViewInput load_view_group(const std::vector<std::string>& paths, texture_file::TextureShape shape);

/// The files an input encodes (a group's, or its own path) and the texture file's name the
/// view writes for it ("sky.pvr").
std::vector<std::string> view_sources(const ViewInput& input);
std::string view_output_name(const ViewInput& input);

/// True when an image input (or group) has a side that is not a power of two: PVRTC1 needs
/// `--resize-pot` for it.
bool needs_resize_pot(const ViewInput& input);

/// The input's own images as the page shows them before (or without) an encode: every face or
/// layer's texels as `originals` [{face, layer, width, height, original}] in `j` (input_json's),
/// for an input that cannot be encoded as it is (not a power of two).
void add_originals(nlohmann::json& j, const ViewInput& input, BlobStore& blobs);

/// An input made of a file's `bytes` (an image, or a .pvr/.ktx/.ktx2 by its magic), as
/// load_view_inputs reads a file: bytes it cannot read give an input with `error` set.
ViewInput view_input_from_bytes(const std::string& path, const std::string& name,
                                std::vector<std::uint8_t> bytes);

/// The overview's thumbnail of an input (image or texture level 0): at most `size` texels a
/// side, box-reduced, as a PNG blob of `blobs`; "" for an input with an error.
std::string put_thumbnail(const ViewInput& input, int size, int threads, BlobStore& blobs);

/// Level 0 (layer 0, face 0) of the texture file `file` decoded to PNG, as `tessera decompress`
/// writes it.
Result<std::vector<std::uint8_t>> decoded_png(const std::vector<std::uint8_t>& file, int threads);

/// The texture file `file` in `container` ("pvr", "ktx", "ktx2"): the bytes `tessera compress
/// -o NAME.<container>` writes for the same texture (KTX 2.0 without supercompression).
Result<std::vector<std::uint8_t>> convert_texture(const std::vector<std::uint8_t>& file,
                                                  const std::string& container);

/// `name` as a file name for an input opened from the page: its last path component, at most
/// 255 bytes, "opened" when nothing is left.
std::string opened_file_name(const std::string& name);

/// `j` as JSON text; strings that are not UTF-8 (a file name in another encoding) are written
/// with U+FFFD for their bad bytes rather than throwing.
std::string dump_json(const nlohmann::json& j);

/// The page's description of an input (without results).
nlohmann::json input_json(const ViewInput& input, int index);
/// input_json's fields of a group (shape, faces, layers, sources) and of an input that needs
/// --resize-pot (needs_resize_pot, note: one line naming the fix).
void add_group_json(nlohmann::json& j, const ViewInput& input);

/// Encodes an image input with `settings` as `tessera compress` would (same library calls,
/// same bytes), decodes every level, face and layer and measures each against what was
/// encoded; images (PNG), heatmaps (made when first fetched) and the texture go into `blobs`.
/// `progress` (may be empty) gets the fraction of the whole job done, the encode and the steps
/// after it, always below 1. Returns the result's JSON (see view.js for its fields).
Result<nlohmann::json> encode_view_result(const ViewInput& input, const ViewSettings& settings,
                                          int threads, BlobStore& blobs,
                                          const std::function<void(double)>& progress);

/// The result of a texture input: its decoded images, level 0 measured against `reference`
/// when given (the image it was made from: see `texture_pairs`), else against nothing.
Result<nlohmann::json> texture_view_result(const ViewInput& input, int threads, BlobStore& blobs,
                                           const ImageRGBA8* reference = nullptr);
/// The same with a reference for every image of level 0 (layer-major then face: a group's
/// `images` against a cube map or array file made from them).
Result<nlohmann::json> texture_view_result(const ViewInput& input, int threads, BlobStore& blobs,
                                           const std::vector<ImageRGBA8>& references);

/// The references of a texture input paired with image input `image` (texture_pairs): the
/// image, or a group's images.
std::vector<ImageRGBA8> pair_references(const ViewInput& image);

/// (texture, image) input indices of a texture and an image with the same file stem and
/// size ("sprite.pvr", "sprite.png"), or of a cube map or array and a --cube / --array input of
/// the same stem, shape and size: the texture is shown as a result of the image too.
std::vector<std::pair<int, int>> texture_pairs(const std::vector<ViewInput>& inputs);

/// The settings the static export encodes by default: fast, normal, high and, for an input with
/// alpha, normal with --alpha-bleed and with --alpha-weighted.
/// With `resize_pot`, each with --resize-pot.
std::vector<ViewSettings> default_export_settings(bool has_alpha, bool resize_pot = false);

/// The page (HTML with its script and style inline) with `data` as its start-up JSON.
std::string view_page(const nlohmann::json& data);

/// Writes the self-contained static view of `inputs` (every image through every setting of
/// `settings`, or `default_export_settings(.., resize_pot)` when empty) to `output`
/// (atomically; "-" = stdout): blobs inlined as data: URIs, no server needed. An input that
/// cannot be read or encoded shows its one-line error on the page (and in `errors`); the
/// others are written. Only when no input works is it an error, and nothing is written.
Status write_view_export(const std::vector<ViewInput>& inputs,
                         const std::vector<ViewSettings>& settings, int threads,
                         const std::string& output, std::vector<std::string>* errors = nullptr,
                         bool resize_pot = false);

/// How `tessera view` serves.
struct ViewServeOptions {
  int port = 0;      ///< 0 = a random free port.
  bool open = true;  ///< Open the URL in a browser (xdg-open) when a display is there.
  bool quiet = false;
  int threads = 0;
  std::vector<ViewSettings> initial;  ///< Settings of the first encode of each image.
  /// Memory for results (their images, heatmaps and files): beyond it the least recently used
  /// results that are not pinned are evicted. The inputs are not counted: each image input as
  /// read, and its original's PNG for the page's first draw once the page asks for it
  /// (view_originals.h), are kept while the server runs.
  std::size_t memory_budget = std::size_t{512} << 20;
};

/// Serves the view on 127.0.0.1 until SIGINT or SIGTERM; prints the URL (with its token) on
/// stdout. Returns the exit code.
int serve_view(std::vector<ViewInput> inputs, const ViewServeOptions& options);

/// The embedded page assets (share/tessera/view/*), by file name; "" when unknown.
std::string_view view_asset(std::string_view name);

}  // namespace tessera::cli
