// libFuzzer target: the C API's readers (tessera/tessera_c.h) on arbitrary bytes, through the
// C entry points only. A read that fails must say why (a code and a message) and return no
// texture; one that succeeds must give a texture whose info is consistent, whose every image
// decodes into a padded caller buffer without touching the padding, and which writes to each
// container (size query, one byte short, exact) and reads back with the same info and blocks.
// Seeds: the PVR v3, KTX 1.1 and KTX 2.0 corpora of the container fuzzers.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "tessera/tessera_c.h"

namespace {

void require(bool ok) {
  if (!ok) std::abort();
}

bool same_info(const tessera_texture_info& a, const tessera_texture_info& b) {
  return a.format == b.format && a.width == b.width && a.height == b.height &&
         a.levels == b.levels && a.faces == b.faces && a.layers == b.layers && a.srgb == b.srgb;
}

tessera_texture_info info_of(const tessera_texture* texture) {
  tessera_texture_info info{};
  info.struct_size = sizeof info;
  require(tessera_texture_get_info(texture, &info) == TESSERA_SUCCESS);
  require(info.width > 0 && info.height > 0 && info.levels > 0 && info.layers > 0);
  require(info.faces == 1 || info.faces == 6);
  return info;
}

/// Every image of every level decodes into a buffer with 8 bytes of padding a row.
void decode_all(tessera_context* context, const tessera_texture* texture,
                const tessera_texture_info& info) {
  for (std::uint32_t level = 0; level < info.levels; ++level) {
    const std::uint32_t w = info.width >> level ? info.width >> level : 1;
    const std::uint32_t h = info.height >> level ? info.height >> level : 1;
    const std::size_t pitch = std::size_t(w) * 4 + 8;
    std::vector<std::uint8_t> rgba(pitch * h, 0xa5);
    for (std::uint32_t layer = 0; layer < info.layers; ++layer) {
      for (std::uint32_t face = 0; face < info.faces; ++face) {
        require(tessera_texture_decode(context, texture, level, layer, face, rgba.data(), pitch,
                                       rgba.size()) == TESSERA_SUCCESS);
        for (std::uint32_t y = 0; y < h; ++y) {
          for (std::size_t x = std::size_t(w) * 4; x < pitch; ++x) {
            require(rgba[y * pitch + x] == 0xa5);
          }
        }
      }
    }
  }
  std::vector<std::uint8_t> one(4);
  require(tessera_texture_decode(context, texture, info.levels, 0, 0, one.data(), 0, one.size()) ==
          TESSERA_ERROR_INVALID_ARGUMENT);
}

/// Written to `container` and read back: the same info and level-0 blocks.
void round_trip(tessera_context* context, tessera_texture* texture,
                const tessera_texture_info& info, tessera_container container) {
  std::size_t size = 0;
  require(tessera_texture_write_memory(context, texture, container, 0, nullptr, 0, &size) ==
          TESSERA_SUCCESS);
  require(size > 0);
  std::vector<std::uint8_t> file(size, 0x5a);
  std::size_t again = 0;
  require(tessera_texture_write_memory(context, texture, container, 0, file.data(), size - 1,
                                       &again) == TESSERA_ERROR_BUFFER_TOO_SMALL);
  require(again == size && file[0] == 0x5a);
  require(tessera_texture_write_memory(context, texture, container, 0, file.data(), size, &again) ==
          TESSERA_SUCCESS);
  tessera_texture* back = nullptr;
  require(tessera_texture_read_memory(context, file.data(), file.size(), &back) == TESSERA_SUCCESS);
  require(same_info(info_of(back), info));
  const std::uint8_t* a = nullptr;
  const std::uint8_t* b = nullptr;
  std::size_t na = 0, nb = 0;
  require(tessera_texture_get_blocks(texture, 0, 0, 0, &a, &na) == TESSERA_SUCCESS);
  require(tessera_texture_get_blocks(back, 0, 0, 0, &b, &nb) == TESSERA_SUCCESS);
  require(na == nb && std::memcmp(a, b, na) == 0);
  tessera_texture_free(back);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static tessera_context* context = [] {
    tessera_context_config config;
    tessera_context_config_init(&config);
    config.threads = 1;
    tessera_context* c = nullptr;
    require(tessera_context_create(&config, &c) == TESSERA_SUCCESS);
    return c;
  }();
  tessera_texture* texture = reinterpret_cast<tessera_texture*>(&context);  // must become NULL
  // A copy of exactly `size` bytes, so that a read past the end is caught by ASan.
  std::vector<std::uint8_t> bytes(data, data + size);
  const tessera_error e =
      tessera_texture_read_memory(context, size ? bytes.data() : data, size, &texture);
  if (e != TESSERA_SUCCESS) {
    require(texture == nullptr);
    require(std::strlen(tessera_context_last_error(context)) > 0);
    require(e != TESSERA_ERROR_INTERNAL);
    return 0;
  }
  const tessera_texture_info info = info_of(texture);
  // Zstandard levels may expand enormously: decode and re-write modest textures only.
  std::size_t total = 0;
  for (std::uint32_t level = 0; level < info.levels; ++level) {
    const std::uint8_t* blocks = nullptr;
    std::size_t n = 0;
    require(tessera_texture_get_blocks(texture, level, 0, 0, &blocks, &n) == TESSERA_SUCCESS);
    total += n * info.faces * info.layers;
  }
  if (total <= (std::size_t{1} << 16)) {
    decode_all(context, texture, info);
    for (tessera_container c :
         {TESSERA_CONTAINER_PVR3, TESSERA_CONTAINER_KTX1, TESSERA_CONTAINER_KTX2}) {
      round_trip(context, texture, info, c);
    }
  }
  tessera_texture_free(texture);
  return 0;
}
