// The C API's textures and containers (tessera/tessera_c.h): info, blocks and decoding of a
// texture_file::CompressedTexture, and PVR v3 / KTX 1.1 / KTX 2.0 from and to memory and files.
#include <cstdlib>
#include <cstring>
#include <memory>
#include <span>
#include <string>

#include "c_api/c_api_internal.h"

namespace tessera::c_api {
namespace {

namespace tf = texture_file;

tessera_error bad(tessera_context* context, const std::string& message) {
  return fail(context, TESSERA_ERROR_INVALID_ARGUMENT, message);
}

tessera_error check_zstd(tessera_context* context, std::int32_t zstd_level, bool ktx2) {
  if (zstd_level < 0 || zstd_level > 22) {
    return bad(context, "zstd_level " + std::to_string(zstd_level) + " is not in [0, 22]");
  }
  if (zstd_level != 0 && !ktx2) return bad(context, "zstd_level needs a KTX 2.0 output");
  return TESSERA_SUCCESS;
}

/// The texture's file in `container`, serialised once per (container, zstd level).
tessera_error serialise(tessera_context* context, tessera_texture* texture,
                        tessera_container container, std::int32_t zstd_level) {
  if (tessera_error e = require(context, texture, "texture"); e != TESSERA_SUCCESS) return e;
  if (container != TESSERA_CONTAINER_PVR3 && container != TESSERA_CONTAINER_KTX1 &&
      container != TESSERA_CONTAINER_KTX2) {
    return bad(context,
               "container " + std::to_string(int(container)) + " is not a tessera_container");
  }
  if (tessera_error e = check_zstd(context, zstd_level, container == TESSERA_CONTAINER_KTX2);
      e != TESSERA_SUCCESS) {
    return e;
  }
  if (texture->cached_container == int(container) && texture->cached_zstd == zstd_level) {
    return TESSERA_SUCCESS;
  }
  const tf::ContainerFormat format = container == TESSERA_CONTAINER_KTX1 ? tf::ContainerFormat::ktx1
                                     : container == TESSERA_CONTAINER_KTX2
                                         ? tf::ContainerFormat::ktx2
                                         : tf::ContainerFormat::pvr3;
  Result<std::vector<std::uint8_t>> file =
      tf::serialise_texture(texture->texture, format, tf::Ktx2Options{zstd_level});
  if (!file) return fail(context, file.status());
  texture->cached_container = -1;
  texture->cached_file = std::move(file).value();
  texture->cached_container = int(container);
  texture->cached_zstd = zstd_level;
  return TESSERA_SUCCESS;
}

tessera_error adopt(tessera_context* context, Result<tf::CompressedTexture> parsed,
                    tessera_texture** texture) {
  if (!parsed) return fail(context, parsed.status());
  auto made = std::make_unique<tessera_texture>();
  made->texture = std::move(parsed).value();
  *texture = made.release();
  return TESSERA_SUCCESS;
}

tessera_error check_index(tessera_context* context, const tessera_texture* texture,
                          std::uint32_t level, std::uint32_t layer, std::uint32_t face) {
  if (tessera_error e = require(context, texture, "texture"); e != TESSERA_SUCCESS) return e;
  constexpr std::uint32_t kMax = 1u << 30;  // keeps the int conversion below exact
  if (level >= kMax || layer >= kMax || face >= kMax) {
    return bad(context, "level, layer or face is out of range");
  }
  if (Status s = tf::check_image_index(texture->texture, int(level), int(layer), int(face));
      !s.ok()) {
    return fail(context, s);
  }
  return TESSERA_SUCCESS;
}

}  // namespace
}  // namespace tessera::c_api

using tessera::c_api::fail;
using tessera::c_api::guarded;
using tessera::c_api::require;

namespace tessera::c_api::entry {

tessera_error texture_get_info(const tessera_texture* texture, tessera_texture_info* info) {
  if (texture == nullptr || info == nullptr) return TESSERA_ERROR_NULL_POINTER;
  if (info->struct_size != sizeof(tessera_texture_info)) return TESSERA_ERROR_BAD_STRUCT_SIZE;
  const tessera::texture_file::CompressedTexture& t = texture->texture;
  tessera_texture_info out{};
  out.struct_size = sizeof(tessera_texture_info);
  out.format = t.format == tessera::pvrtc::Format::pvrtc1_2bpp ? TESSERA_FORMAT_PVRTC1_2BPP
                                                               : TESSERA_FORMAT_PVRTC1_4BPP;
  out.width = std::uint32_t(t.width);
  out.height = std::uint32_t(t.height);
  out.levels = std::uint32_t(t.level_count());
  out.faces = std::uint32_t(t.faces);
  out.layers = std::uint32_t(t.layers);
  out.array = t.array ? 1 : 0;
  out.has_alpha = t.has_alpha ? 1 : 0;
  out.srgb = t.srgb ? 1 : 0;
  out.premultiplied = t.premultiplied ? 1 : 0;
  *info = out;
  return TESSERA_SUCCESS;
}

tessera_error texture_get_blocks(const tessera_texture* texture, uint32_t level, uint32_t layer,
                                 uint32_t face, const uint8_t** blocks, size_t* size) {
  if (texture == nullptr || blocks == nullptr || size == nullptr) {
    return TESSERA_ERROR_NULL_POINTER;
  }
  return guarded(nullptr, [&] {
    if (tessera_error e = tessera::c_api::check_index(nullptr, texture, level, layer, face);
        e != TESSERA_SUCCESS) {
      return e;
    }
    const std::span<const std::uint8_t> image =
        texture->texture.image(int(level), int(layer), int(face));
    *blocks = image.data();
    *size = image.size();
    return TESSERA_SUCCESS;
  });
}

tessera_error texture_decode(tessera_context* context, const tessera_texture* texture,
                             uint32_t level, uint32_t layer, uint32_t face, uint8_t* rgba,
                             size_t row_pitch, size_t capacity) {
  if (context == nullptr) return TESSERA_ERROR_NULL_POINTER;
  return guarded(context, [&] {
    if (tessera_error e = tessera::c_api::check_index(context, texture, level, layer, face);
        e != TESSERA_SUCCESS) {
      return e;
    }
    const tessera::texture_file::CompressedTexture& t = texture->texture;
    const auto w = std::uint32_t(t.level_width(int(level)));
    const auto h = std::uint32_t(t.level_height(int(level)));
    if (tessera_error e =
            tessera::c_api::check_rgba_output(context, w, h, rgba, row_pitch, capacity);
        e != TESSERA_SUCCESS) {
      return e;
    }
    tessera::Result<tessera::ImageRGBA8> decoded = tessera::texture_file::decode_texture_image(
        t, int(level), int(layer), int(face), tessera::Parallel{context->config.threads});
    if (!decoded) return fail(context, decoded.status());
    tessera::c_api::copy_rows(*decoded, rgba, row_pitch);
    return TESSERA_SUCCESS;
  });
}

void texture_free(tessera_texture* texture) { delete texture; }

tessera_error texture_read_memory(tessera_context* context, const void* data, size_t size,
                                  tessera_texture** texture) {
  if (texture != nullptr) *texture = nullptr;
  if (context == nullptr) return TESSERA_ERROR_NULL_POINTER;
  return guarded(context, [&] {
    if (tessera_error e = require(context, data, "data"); e != TESSERA_SUCCESS) return e;
    if (tessera_error e = require(context, texture, "texture"); e != TESSERA_SUCCESS) return e;
    const std::span<const std::uint8_t> bytes(static_cast<const std::uint8_t*>(data), size);
    return tessera::c_api::adopt(context, tessera::texture_file::parse_texture(bytes, "memory"),
                                 texture);
  });
}

tessera_error texture_read_file(tessera_context* context, const char* path,
                                tessera_texture** texture) {
  if (texture != nullptr) *texture = nullptr;
  if (context == nullptr) return TESSERA_ERROR_NULL_POINTER;
  return guarded(context, [&] {
    if (tessera_error e = require(context, path, "path"); e != TESSERA_SUCCESS) return e;
    if (tessera_error e = require(context, texture, "texture"); e != TESSERA_SUCCESS) return e;
    return tessera::c_api::adopt(context, tessera::texture_file::read_texture_file(path), texture);
  });
}

tessera_error texture_write_memory(tessera_context* context, tessera_texture* texture,
                                   tessera_container container, int32_t zstd_level, void* data,
                                   size_t capacity, size_t* size) {
  if (context == nullptr) return TESSERA_ERROR_NULL_POINTER;
  return guarded(context, [&] {
    if (tessera_error e = require(context, size, "size"); e != TESSERA_SUCCESS) return e;
    if (tessera_error e = tessera::c_api::serialise(context, texture, container, zstd_level);
        e != TESSERA_SUCCESS) {
      return e;
    }
    const std::vector<std::uint8_t>& file = texture->cached_file;
    *size = file.size();
    if (data == nullptr && capacity == 0) return TESSERA_SUCCESS;
    if (tessera_error e = require(context, data, "data"); e != TESSERA_SUCCESS) return e;
    if (capacity < file.size()) {
      return fail(context, TESSERA_ERROR_BUFFER_TOO_SMALL,
                  "data holds " + std::to_string(capacity) + " bytes; the file needs " +
                      std::to_string(file.size()));
    }
    std::memcpy(data, file.data(), file.size());
    return TESSERA_SUCCESS;
  });
}

tessera_error texture_write_alloc(tessera_context* context, tessera_texture* texture,
                                  tessera_container container, int32_t zstd_level, void** data,
                                  size_t* size) {
  if (data != nullptr) *data = nullptr;
  if (context == nullptr) return TESSERA_ERROR_NULL_POINTER;
  return guarded(context, [&] {
    if (tessera_error e = require(context, data, "data"); e != TESSERA_SUCCESS) return e;
    if (tessera_error e = require(context, size, "size"); e != TESSERA_SUCCESS) return e;
    if (tessera_error e = tessera::c_api::serialise(context, texture, container, zstd_level);
        e != TESSERA_SUCCESS) {
      return e;
    }
    const std::vector<std::uint8_t>& file = texture->cached_file;
    void* out = std::malloc(file.empty() ? 1 : file.size());
    if (out == nullptr) return fail(context, TESSERA_ERROR_OUT_OF_MEMORY, "out of memory");
    std::memcpy(out, file.data(), file.size());
    *data = out;
    *size = file.size();
    return TESSERA_SUCCESS;
  });
}

tessera_error texture_write_file(tessera_context* context, const tessera_texture* texture,
                                 const char* path, int32_t zstd_level) {
  if (context == nullptr) return TESSERA_ERROR_NULL_POINTER;
  return guarded(context, [&] {
    if (tessera_error e = require(context, texture, "texture"); e != TESSERA_SUCCESS) return e;
    if (tessera_error e = require(context, path, "path"); e != TESSERA_SUCCESS) return e;
    const tessera::texture_file::ContainerFormat format =
        tessera::texture_file::container_from_extension(path);
    if (format == tessera::texture_file::ContainerFormat::unknown) {
      return fail(context, TESSERA_ERROR_INVALID_ARGUMENT,
                  std::string(path) + ": unknown extension (use .pvr, .ktx or .ktx2)");
    }
    if (tessera_error e = tessera::c_api::check_zstd(
            context, zstd_level, format == tessera::texture_file::ContainerFormat::ktx2);
        e != TESSERA_SUCCESS) {
      return e;
    }
    tessera::texture_file::Ktx2Options ktx2;
    ktx2.zstd_level = zstd_level;
    return fail(context, tessera::texture_file::write_texture_file(path, texture->texture, ktx2));
  });
}

}  // namespace tessera::c_api::entry
