// Helper of ktx2_oracle_test.py (beside this file): writes every KTX 2.0 test variant
// (tests/support/ktx2_test_util.h, real PVRTC encodes) into OUT_DIR with `write_texture_file`,
// checks that `read_texture_file` reads each back identical, and writes OUT_DIR/manifest.json: per
// file the texture's fields and its levels' bytes (hex), which the test holds against what
// ktx-parse reads.
//
// Usage: ktx2_oracle_writer OUT_DIR     exit 0, or 1 naming what differed
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "ktx2_test_util.h"
#include "tessera/texture_file.h"

namespace {

using tessera::texture_file::CompressedTexture;

std::string hex(const std::vector<std::uint8_t>& bytes) {
  static const char kDigits[] = "0123456789abcdef";
  std::string s;
  s.reserve(bytes.size() * 2);
  for (std::uint8_t b : bytes) {
    s += kDigits[b >> 4];
    s += kDigits[b & 15];
  }
  return s;
}

/// The first field in which `a` and `b` differ, or "".
std::string difference(const CompressedTexture& a, const CompressedTexture& b) {
  if (a.format != b.format) return "format";
  if (a.width != b.width || a.height != b.height) return "size";
  if (a.has_alpha != b.has_alpha) return "has_alpha";
  if (a.srgb != b.srgb) return "srgb";
  if (a.premultiplied != b.premultiplied) return "premultiplied";
  if (a.faces != b.faces) return "faces";
  if (a.layers != b.layers || a.array != b.array) return "layers";
  if (a.levels != b.levels) return "level bytes";
  return "";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: ktx2_oracle_writer OUT_DIR\n");
    return 2;
  }
  const std::string dir = argv[1];
  nlohmann::json manifest = nlohmann::json::array();
  int failures = 0;
  for (const tessera::test::Ktx2Variant& v : tessera::test::ktx2_variants()) {
    tessera::Result<CompressedTexture> tex = tessera::test::encode_ktx2_variant(v);
    if (!tex) {
      std::fprintf(stderr, "%s: encode failed: %s\n", v.name.c_str(), tex.status().message.c_str());
      return 1;
    }
    const std::string path = dir + "/" + v.name + ".ktx2";
    if (tessera::Status s = tessera::texture_file::write_texture_file(
            path, *tex, tessera::texture_file::Ktx2Options{v.zstd_level});
        !s.ok()) {
      std::fprintf(stderr, "%s\n", s.message.c_str());
      return 1;
    }
    tessera::Result<CompressedTexture> back = tessera::texture_file::read_texture_file(path);
    if (!back) {
      std::fprintf(stderr, "tessera cannot read back %s\n", back.status().message.c_str());
      ++failures;
    } else if (const std::string d = difference(*tex, *back); !d.empty()) {
      std::fprintf(stderr, "%s: read back with a different %s\n", path.c_str(), d.c_str());
      ++failures;
    }
    nlohmann::json levels = nlohmann::json::array();
    for (const auto& l : tex->levels) levels.push_back(hex(l));
    manifest.push_back(
        {{"name", v.name},
         {"file", path},
         {"format", v.format == tessera::pvrtc::Format::pvrtc1_4bpp ? "4bpp" : "2bpp"},
         {"width", tex->width},
         {"height", tex->height},
         {"faces", tex->faces},
         {"layers", tex->layers},
         {"array", tex->array},
         {"srgb", tex->srgb},
         {"premultiplied", tex->premultiplied},
         {"has_alpha", tex->has_alpha},
         {"zstd_level", v.zstd_level},
         {"levels", levels}});
  }
  std::ofstream(dir + "/manifest.json") << manifest.dump(1) << "\n";
  return failures == 0 ? 0 : 1;
}
