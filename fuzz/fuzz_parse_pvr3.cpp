// libFuzzer target: PVR v3 parsing on arbitrary bytes. A file that parses must decode every
// image (level, layer, face), re-serialise and parse back to the same texture.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "tessera/texture_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> bytes(data, size);
  tessera::Result<tessera::texture_file::CompressedTexture> tex =
      tessera::texture_file::parse_pvr3(bytes, "fuzz.pvr");
  if (!tex) {
    if (tex.status().message.empty()) std::abort();
    return 0;
  }
  // Every image of every level decodes (faces and layers included).
  for (int i = 0; i < tex->level_count(); ++i) {
    for (int layer = 0; layer < tex->layers; ++layer) {
      for (int face = 0; face < tex->faces; ++face) {
        if (!tessera::texture_file::decode_texture_image(*tex, i, layer, face, {1}).ok()) {
          std::abort();
        }
      }
    }
  }
  tessera::Result<std::vector<std::uint8_t>> again = tessera::texture_file::serialise_pvr3(*tex);
  if (!again) std::abort();
  tessera::Result<tessera::texture_file::CompressedTexture> back =
      tessera::texture_file::parse_pvr3(*again, "again.pvr");
  if (!back || back->levels != tex->levels || back->width != tex->width ||
      back->height != tex->height || back->format != tex->format || back->faces != tex->faces ||
      back->layers != tex->layers) {
    std::abort();
  }
  return 0;
}
