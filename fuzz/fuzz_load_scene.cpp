// libFuzzer target: the OBJ and glTF scene loaders on arbitrary bytes. The first byte picks
// the format (even: OBJ, odd: glTF); the rest is written to a scratch file that the loader reads
// like any user file. A scene that loads must be internally consistent.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "tessera/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const bool gltf = data[0] & 1;
  static const std::string base = "/tmp/tessera-fuzz-scene-" + std::to_string(::getpid());
  const std::string path = base + (gltf ? ".gltf" : ".obj");
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return 0;
  std::fwrite(data + 1, 1, size - 1, f);
  std::fclose(f);
  tessera::scene::LoadOptions options;
  options.max_triangles = 1u << 20;
  options.load_textures = false;  // the image decoders have their own target
  tessera::Result<tessera::scene::Scene> s = tessera::scene::load_scene(path, options);
  std::remove(path.c_str());
  if (!s) {
    if (s.status().message.empty()) std::abort();
    return 0;
  }
  for (const auto& m : s->meshes) {
    if (m.normals.size() != m.positions.size() || m.uvs.size() != m.positions.size()) std::abort();
    if (m.material < 0 || std::size_t(m.material) >= s->materials.size()) std::abort();
    for (std::uint32_t i : m.indices) {
      if (i >= m.positions.size()) std::abort();
    }
  }
  return 0;
}
