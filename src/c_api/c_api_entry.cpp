// The extern "C" entry points of tessera/tessera_c.h, each forwarding to its implementation
// (c_api_entry.h). This file sees the C header alone, so its debug information (it is built
// with -g: src/CMakeLists.txt) is the C ABI that abidiff checks against tests/c_api/abi/.
#include "c_api/c_api_entry.h"

extern "C" {

const char* tessera_error_string(tessera_error code) {
  return tessera::c_api::entry::error_string(code);
}

const char* tessera_version(void) { return tessera::c_api::entry::version(); }

tessera_error tessera_context_config_init(tessera_context_config* config) {
  return tessera::c_api::entry::context_config_init(config);
}

tessera_error tessera_context_create(const tessera_context_config* config,
                                     tessera_context** context) {
  return tessera::c_api::entry::context_create(config, context);
}

void tessera_context_free(tessera_context* context) {
  tessera::c_api::entry::context_free(context);
}

const char* tessera_context_last_error(const tessera_context* context) {
  return tessera::c_api::entry::context_last_error(context);
}

tessera_error tessera_encode_options_init(tessera_encode_options* options) {
  return tessera::c_api::entry::encode_options_init(options);
}

tessera_error tessera_encode(tessera_context* context, const tessera_image* images,
                             uint32_t image_count, const tessera_encode_options* options,
                             tessera_texture** texture) {
  return tessera::c_api::entry::encode(context, images, image_count, options, texture);
}

tessera_error tessera_pvrtc_level_size(tessera_format format, uint32_t width, uint32_t height,
                                       size_t* size) {
  return tessera::c_api::entry::pvrtc_level_size(format, width, height, size);
}

tessera_error tessera_pvrtc_encode(tessera_context* context, const tessera_image* image,
                                   const tessera_encode_options* options, uint8_t* blocks,
                                   size_t capacity, size_t* size) {
  return tessera::c_api::entry::pvrtc_encode(context, image, options, blocks, capacity, size);
}

tessera_error tessera_pvrtc_decode(tessera_context* context, tessera_format format, uint32_t width,
                                   uint32_t height, const uint8_t* blocks, size_t blocks_size,
                                   uint8_t* rgba, size_t row_pitch, size_t capacity) {
  return tessera::c_api::entry::pvrtc_decode(context, format, width, height, blocks, blocks_size,
                                             rgba, row_pitch, capacity);
}

tessera_error tessera_texture_get_info(const tessera_texture* texture, tessera_texture_info* info) {
  return tessera::c_api::entry::texture_get_info(texture, info);
}

tessera_error tessera_texture_get_blocks(const tessera_texture* texture, uint32_t level,
                                         uint32_t layer, uint32_t face, const uint8_t** blocks,
                                         size_t* size) {
  return tessera::c_api::entry::texture_get_blocks(texture, level, layer, face, blocks, size);
}

tessera_error tessera_texture_decode(tessera_context* context, const tessera_texture* texture,
                                     uint32_t level, uint32_t layer, uint32_t face, uint8_t* rgba,
                                     size_t row_pitch, size_t capacity) {
  return tessera::c_api::entry::texture_decode(context, texture, level, layer, face, rgba,
                                               row_pitch, capacity);
}

void tessera_texture_free(tessera_texture* texture) {
  tessera::c_api::entry::texture_free(texture);
}

tessera_error tessera_texture_read_memory(tessera_context* context, const void* data, size_t size,
                                          tessera_texture** texture) {
  return tessera::c_api::entry::texture_read_memory(context, data, size, texture);
}

tessera_error tessera_texture_read_file(tessera_context* context, const char* path,
                                        tessera_texture** texture) {
  return tessera::c_api::entry::texture_read_file(context, path, texture);
}

tessera_error tessera_texture_write_memory(tessera_context* context, tessera_texture* texture,
                                           tessera_container container, int32_t zstd_level,
                                           void* data, size_t capacity, size_t* size) {
  return tessera::c_api::entry::texture_write_memory(context, texture, container, zstd_level, data,
                                                     capacity, size);
}

tessera_error tessera_texture_write_alloc(tessera_context* context, tessera_texture* texture,
                                          tessera_container container, int32_t zstd_level,
                                          void** data, size_t* size) {
  return tessera::c_api::entry::texture_write_alloc(context, texture, container, zstd_level, data,
                                                    size);
}

tessera_error tessera_texture_write_file(tessera_context* context, const tessera_texture* texture,
                                         const char* path, int32_t zstd_level) {
  return tessera::c_api::entry::texture_write_file(context, texture, path, zstd_level);
}

void tessera_free(void* data) { tessera::c_api::entry::free(data); }

tessera_error tessera_compare(tessera_context* context, const tessera_image* a,
                              const tessera_image* b, int32_t compute_ssim,
                              tessera_metrics* metrics) {
  return tessera::c_api::entry::compare(context, a, b, compute_ssim, metrics);
}

}  // extern "C"
