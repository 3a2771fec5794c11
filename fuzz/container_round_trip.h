// What fuzz_parse_pvr3 and fuzz_parse_ktx1 check on arbitrary bytes: a file that parses must
// decode every image (level, layer, face), re-serialise and parse back to the same texture; a
// file that does not must say why. Aborts (a libFuzzer crash) on any failure.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <string>

#include "tessera/texture_file.h"

namespace tessera::fuzz {

/// `parse(bytes, name)` and `serialise(texture)` are the container's reader and writer.
template <class Parse, class Serialise>
int container_round_trip(std::span<const std::uint8_t> bytes, Parse parse, Serialise serialise,
                         const std::string& name, const std::string& again_name) {
  Result<texture_file::CompressedTexture> tex = parse(bytes, name);
  if (!tex) {
    if (tex.status().message.empty()) std::abort();
    return 0;
  }
  // Every image of every level decodes (faces and layers included).
  for (int i = 0; i < tex->level_count(); ++i) {
    for (int layer = 0; layer < tex->layers; ++layer) {
      for (int face = 0; face < tex->faces; ++face) {
        if (!texture_file::decode_texture_image(*tex, i, layer, face, {1}).ok()) std::abort();
      }
    }
  }
  Result<std::vector<std::uint8_t>> again = serialise(*tex);
  if (!again) std::abort();
  Result<texture_file::CompressedTexture> back = parse(*again, again_name);
  if (!back || back->levels != tex->levels || back->width != tex->width ||
      back->height != tex->height || back->format != tex->format || back->faces != tex->faces ||
      back->layers != tex->layers) {
    std::abort();
  }
  return 0;
}

}  // namespace tessera::fuzz
