// libFuzzer target: KTX 2.0 parsing on arbitrary bytes (Zstandard levels included). A file that
// parses must be a valid texture whose images decode, and must re-serialise (without and with
// zstd) and parse back to the same texture. A zstd level may legitimately expand ~43000-fold,
// so decoding and re-serialising are limited to textures of modest size (the parse itself is
// not: its bounds are what is being tested).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "tessera/texture_file.h"

namespace {

bool same(const tessera::texture_file::CompressedTexture& a,
          const tessera::texture_file::CompressedTexture& b) {
  return a.levels == b.levels && a.width == b.width && a.height == b.height &&
         a.format == b.format && a.has_alpha == b.has_alpha && a.srgb == b.srgb &&
         a.premultiplied == b.premultiplied && a.faces == b.faces && a.layers == b.layers &&
         a.array == b.array;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace tf = tessera::texture_file;
  const std::span<const std::uint8_t> bytes(data, size);
  tessera::Result<tf::CompressedTexture> tex = tf::parse_ktx2(bytes, "fuzz.ktx2");
  if (!tex) {
    if (tex.status().message.empty()) std::abort();
    return 0;
  }
  if (!tf::validate_texture(*tex, "parsed").ok()) std::abort();
  std::size_t total = 0;
  for (const auto& l : tex->levels) total += l.size();
  if (total > (std::size_t{1} << 18)) return 0;
  for (int i = 0; i < tex->level_count(); ++i) {
    for (int layer = 0; layer < tex->layers; ++layer) {
      for (int face = 0; face < tex->faces; ++face) {
        if (!tf::decode_texture_image(*tex, i, layer, face, {1}).ok()) std::abort();
      }
    }
  }
  for (int zstd_level : {0, 1}) {
    tessera::Result<std::vector<std::uint8_t>> again =
        tf::serialise_ktx2(*tex, tf::Ktx2Options{zstd_level});
    if (!again) std::abort();
    tessera::Result<tf::CompressedTexture> back = tf::parse_ktx2(*again, "again.ktx2");
    if (!back || !same(*back, *tex)) std::abort();
  }
  return 0;
}
