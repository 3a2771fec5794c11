// The KTX 2.0 test textures (ktx2_test.cpp, ktx2_oracle_writer.cpp): real PVRTC encodes of small
// procedural images in every shape the container holds.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "tessera/procedural.h"
#include "tessera/texture_file.h"

namespace tessera::test {

/// One texture to write: format, size, shape, colour flags, and the zstd level to write it with.
struct Ktx2Variant {
  std::string name;
  pvrtc::Format format = pvrtc::Format::pvrtc1_4bpp;
  int width = 16;
  int height = 16;
  bool mipmaps = false;
  int faces = 1;
  int layers = 1;
  bool array = false;
  bool alpha = false;  ///< Encode foliage (cut-out and soft alpha) rather than opaque bricks.
  bool srgb = false;
  bool premultiplied = false;
  int zstd_level = 0;
};

/// Every shape and flag: 4/2 bpp, sRGB and linear, premultiplied, mips, cube map, array of 3,
/// array of 1, cube map array, opaque and with alpha, none / zstd 3 / zstd 19.
inline std::vector<Ktx2Variant> ktx2_variants() {
  using F = pvrtc::Format;
  std::vector<Ktx2Variant> v;
  auto add = [&](Ktx2Variant x) { v.push_back(std::move(x)); };
  add({"4bpp-linear-opaque", F::pvrtc1_4bpp, 16, 16, false, 1, 1, false, false, false, false, 0});
  add({"4bpp-srgb-alpha-mips", F::pvrtc1_4bpp, 32, 16, true, 1, 1, false, true, true, false, 0});
  add({"2bpp-linear-alpha-premultiplied-mips", F::pvrtc1_2bpp, 16, 16, true, 1, 1, false, true,
       false, true, 0});
  add({"2bpp-srgb-opaque", F::pvrtc1_2bpp, 32, 8, false, 1, 1, false, false, true, false, 0});
  add({"4bpp-cube-mips", F::pvrtc1_4bpp, 16, 16, true, 6, 1, false, false, false, false, 0});
  add({"4bpp-array3-alpha-mips", F::pvrtc1_4bpp, 16, 8, true, 1, 3, true, true, true, false, 0});
  add({"4bpp-array1", F::pvrtc1_4bpp, 8, 8, false, 1, 1, true, false, false, false, 0});
  add({"2bpp-cube-array2-srgb-mips", F::pvrtc1_2bpp, 8, 8, true, 6, 2, true, false, true, false,
       0});
  add({"4bpp-srgb-alpha-mips-zstd3", F::pvrtc1_4bpp, 32, 16, true, 1, 1, false, true, true, false,
       3});
  add({"2bpp-linear-opaque-zstd19", F::pvrtc1_2bpp, 16, 16, false, 1, 1, false, false, false, false,
       19});
  add({"4bpp-cube-array2-alpha-premultiplied-mips-zstd3", F::pvrtc1_4bpp, 16, 16, true, 6, 2, true,
       true, false, true, 3});
  add({"2bpp-array3-srgb-mips-zstd19", F::pvrtc1_2bpp, 32, 16, true, 1, 3, true, false, true, false,
       19});
  return v;
}

/// Encodes `v`'s images (one procedural image per layer and face, each with its own seed) with
/// `compress_image` and assembles the texture, levels layer-major then face.
inline Result<texture_file::CompressedTexture> encode_ktx2_variant(const Ktx2Variant& v) {
  texture_file::CompressOptions options;
  options.encode.format = v.format;
  options.encode.quality = pvrtc::Quality::fast;
  options.encode.threads = 1;
  options.mipmaps = v.mipmaps;
  options.srgb = v.srgb;
  texture_file::CompressedTexture tex;
  tex.format = v.format;
  tex.width = v.width;
  tex.height = v.height;
  tex.srgb = v.srgb;
  tex.premultiplied = v.premultiplied;
  tex.faces = v.faces;
  tex.layers = v.layers;
  tex.array = v.array;
  tex.has_alpha = false;
  for (int image = 0; image < v.faces * v.layers; ++image) {
    const Procedural kind = v.alpha ? Procedural::foliage : Procedural::bricks;
    Result<texture_file::CompressedImage> c = texture_file::compress_image(
        make_procedural(kind, v.width, v.height, std::uint32_t(image + 1)), options, v.name);
    if (!c) return c.status();
    tex.has_alpha = tex.has_alpha || c->texture.has_alpha;
    if (tex.levels.empty()) tex.levels.resize(c->texture.levels.size());
    for (std::size_t i = 0; i < tex.levels.size(); ++i) {
      const auto& l = c->texture.levels[i];
      tex.levels[i].insert(tex.levels[i].end(), l.begin(), l.end());
    }
  }
  return tex;
}

}  // namespace tessera::test
