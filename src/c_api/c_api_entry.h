// The C API's implementations behind the extern "C" entry points of c_api_entry.cpp (internal):
// one per function of tessera/tessera_c.h, same name without the `tessera_` prefix, same
// arguments. They take and return C types only, so that c_api_entry.cpp, the one file of the
// C API built with debug information, describes the C ABI and nothing of C++ (what abidiff
// compares with tests/c_api/abi/). Each catches every exception (c_api_internal.h, `guarded`).
#pragma once

#include "tessera/tessera_c.h"

namespace tessera::c_api::entry {

const char* error_string(tessera_error code);
const char* version(void);
tessera_error context_config_init(tessera_context_config* config);
tessera_error context_create(const tessera_context_config* config, tessera_context** context);
void context_free(tessera_context* context);
const char* context_last_error(const tessera_context* context);
tessera_error encode_options_init(tessera_encode_options* options);
tessera_error encode(tessera_context* context, const tessera_image* images, uint32_t image_count,
                     const tessera_encode_options* options, tessera_texture** texture);
tessera_error pvrtc_level_size(tessera_format format, uint32_t width, uint32_t height,
                               size_t* size);
tessera_error pvrtc_encode(tessera_context* context, const tessera_image* image,
                           const tessera_encode_options* options, uint8_t* blocks, size_t capacity,
                           size_t* size);
tessera_error pvrtc_decode(tessera_context* context, tessera_format format, uint32_t width,
                           uint32_t height, const uint8_t* blocks, size_t blocks_size,
                           uint8_t* rgba, size_t row_pitch, size_t capacity);
tessera_error texture_get_info(const tessera_texture* texture, tessera_texture_info* info);
tessera_error texture_get_blocks(const tessera_texture* texture, uint32_t level, uint32_t layer,
                                 uint32_t face, const uint8_t** blocks, size_t* size);
tessera_error texture_decode(tessera_context* context, const tessera_texture* texture,
                             uint32_t level, uint32_t layer, uint32_t face, uint8_t* rgba,
                             size_t row_pitch, size_t capacity);
void texture_free(tessera_texture* texture);
tessera_error texture_read_memory(tessera_context* context, const void* data, size_t size,
                                  tessera_texture** texture);
tessera_error texture_read_file(tessera_context* context, const char* path,
                                tessera_texture** texture);
tessera_error texture_write_memory(tessera_context* context, tessera_texture* texture,
                                   tessera_container container, int32_t zstd_level, void* data,
                                   size_t capacity, size_t* size);
tessera_error texture_write_alloc(tessera_context* context, tessera_texture* texture,
                                  tessera_container container, int32_t zstd_level, void** data,
                                  size_t* size);
tessera_error texture_write_file(tessera_context* context, const tessera_texture* texture,
                                 const char* path, int32_t zstd_level);
void free(void* data);
tessera_error compare(tessera_context* context, const tessera_image* a, const tessera_image* b,
                      int32_t compute_ssim, tessera_metrics* metrics);

}  // namespace tessera::c_api::entry
