// libFuzzer target: Ptex (.ptx) parsing on arbitrary bytes. A file that parses must have
// consistent face data, and, for quad meshes, build a face texture set that samples finitely.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "tessera/faces.h"
#include "tessera/ptex.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> bytes(data, size);
  tessera::ptex::ParseOptions options;
  options.max_floats = std::uint64_t{1} << 22;  // keep the fuzzer's memory small
  tessera::Result<tessera::ptex::PtexFile> file =
      tessera::ptex::parse_ptex(bytes, "fuzz.ptx", options);
  if (!file) {
    const std::string& m = file.status().message;
    if (m.empty() || m.find('\n') != std::string::npos || m.rfind("fuzz.ptx: ", 0) != 0) {
      std::abort();
    }
    return 0;
  }
  if (file->texels.size() != file->faces.size()) std::abort();
  for (std::size_t f = 0; f < file->faces.size(); ++f) {
    const auto& fi = file->faces[f];
    if (file->texels[f].size() !=
        std::size_t(fi.width()) * std::size_t(fi.height()) * std::size_t(file->channels)) {
      std::abort();
    }
  }
  // Adjacency from the file may be inconsistent; building and sampling must stay safe.
  if (file->face_count() <= 64) {
    tessera::Result<tessera::faces::FaceTextureSet> set =
        tessera::faces::FaceTextureSet::from_ptex(*file, "fuzz.ptx", {1});
    if (set) {
      tessera::faces::SampleOptions o;
      o.method = tessera::faces::SeamMethod::traverse_corners;
      for (int f = 0; f < set->face_count(); ++f) {
        (void)tessera::faces::sample_face(*set, f, {-0.1f, 0.5f}, {0.3f, 0.0f, 0.0f, 0.05f}, o);
      }
    }
  }
  return 0;
}
