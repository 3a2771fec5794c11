// The C API's contexts, error strings and the checks shared by its entry points
// (tessera/tessera_c.h).
#include <cstdlib>
#include <cstring>
#include <limits>

#include "c_api/c_api_internal.h"

namespace tessera::c_api {

tessera_error fail(tessera_context* context, tessera_error code, const std::string& message) {
  if (context != nullptr) {
    try {
      context->last_error = message;
    } catch (...) {
      context->last_error.clear();  // no memory for the message: the code still says it
    }
  }
  return code;
}

tessera_error fail(tessera_context* context, const Status& status) {
  tessera_error code = TESSERA_ERROR_INTERNAL;
  switch (status.code) {
    case ErrorCode::ok:
      code = TESSERA_SUCCESS;
      break;
    case ErrorCode::invalid_argument:
      code = TESSERA_ERROR_INVALID_ARGUMENT;
      break;
    case ErrorCode::io_error:
      code = TESSERA_ERROR_IO;
      break;
    case ErrorCode::corrupt_data:
      code = TESSERA_ERROR_CORRUPT_DATA;
      break;
    case ErrorCode::unsupported:
      code = TESSERA_ERROR_UNSUPPORTED;
      break;
    case ErrorCode::too_large:
      code = TESSERA_ERROR_TOO_LARGE;
      break;
    case ErrorCode::size_mismatch:
      code = TESSERA_ERROR_SIZE_MISMATCH;
      break;
    case ErrorCode::out_of_memory:
      code = TESSERA_ERROR_OUT_OF_MEMORY;
      break;
    case ErrorCode::device_lost:
      code = TESSERA_ERROR_INTERNAL;
      break;  // the codec has no device
  }
  return fail(context, code, status.message);
}

tessera_error require(tessera_context* context, const void* p, const char* what) {
  if (p != nullptr) return TESSERA_SUCCESS;
  return fail(context, TESSERA_ERROR_NULL_POINTER, std::string(what) + " is NULL");
}

tessera_error image_view(tessera_context* context, const tessera_image* image, const char* what,
                         ImageView8& view) {
  if (image == nullptr) return require(context, image, what);
  if (image->pixels == nullptr) {
    return fail(context, TESSERA_ERROR_NULL_POINTER, std::string(what) + ": pixels is NULL");
  }
  if (image->width == 0 || image->height == 0 || image->width > std::uint32_t(kMaxImageDimension) ||
      image->height > std::uint32_t(kMaxImageDimension)) {
    return fail(context, TESSERA_ERROR_INVALID_ARGUMENT,
                std::string(what) + ": " + size_text(image->width, image->height) +
                    " is not a size tessera takes (1 to " + std::to_string(kMaxImageDimension) +
                    " each way)");
  }
  const std::size_t row = std::size_t(image->width) * 4;
  const std::size_t pitch = image->row_pitch == 0 ? row : image->row_pitch;
  if (pitch < row || pitch > std::size_t(std::numeric_limits<std::ptrdiff_t>::max()) /
                                 std::size_t(image->height)) {
    return fail(context, TESSERA_ERROR_INVALID_ARGUMENT,
                std::string(what) + ": row_pitch " + std::to_string(image->row_pitch) +
                    " is less than a row of " + std::to_string(image->width) + " RGBA8 texels (" +
                    std::to_string(row) + " bytes)");
  }
  view = ImageView8{image->pixels,         int(image->width),    int(image->height), 4, 4,
                    std::ptrdiff_t(pitch), image->has_alpha != 0};
  if (Status s = check_view(view, what); !s.ok()) return fail(context, s);
  return TESSERA_SUCCESS;
}

tessera_error check_rgba_output(tessera_context* context, std::uint32_t width, std::uint32_t height,
                                const std::uint8_t* rgba, std::size_t& row_pitch,
                                std::size_t capacity) {
  if (tessera_error e = require(context, rgba, "rgba"); e != TESSERA_SUCCESS) return e;
  const std::size_t row = std::size_t(width) * 4;
  if (row_pitch == 0) row_pitch = row;
  if (row_pitch < row) {
    return fail(context, TESSERA_ERROR_INVALID_ARGUMENT,
                "row_pitch " + std::to_string(row_pitch) + " is less than a row of " +
                    std::to_string(width) + " RGBA8 texels (" + std::to_string(row) + " bytes)");
  }
  if (height > 0 && row_pitch > (std::numeric_limits<std::size_t>::max() - row) / height) {
    return fail(context, TESSERA_ERROR_INVALID_ARGUMENT, "row_pitch is too large");
  }
  const std::size_t needed = height == 0 ? 0 : row_pitch * (height - 1) + row;
  if (capacity < needed) {
    return fail(context, TESSERA_ERROR_BUFFER_TOO_SMALL,
                "the RGBA8 buffer holds " + std::to_string(capacity) + " bytes; " +
                    size_text(width, height) + " with row_pitch " + std::to_string(row_pitch) +
                    " needs " + std::to_string(needed));
  }
  return TESSERA_SUCCESS;
}

void copy_rows(const ImageRGBA8& image, std::uint8_t* rgba, std::size_t row_pitch) {
  const std::size_t row = std::size_t(image.width) * 4;
  for (int y = 0; y < image.height; ++y) {
    std::memcpy(rgba + std::size_t(y) * row_pitch, image.pixels.data() + std::size_t(y) * row, row);
  }
}

}  // namespace tessera::c_api

using tessera::c_api::guarded;

namespace tessera::c_api::entry {

const char* error_string(tessera_error code) {
  switch (code) {
    case TESSERA_SUCCESS:
      return "success";
    case TESSERA_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case TESSERA_ERROR_IO:
      return "input/output error";
    case TESSERA_ERROR_CORRUPT_DATA:
      return "corrupt data";
    case TESSERA_ERROR_UNSUPPORTED:
      return "unsupported";
    case TESSERA_ERROR_TOO_LARGE:
      return "too large";
    case TESSERA_ERROR_SIZE_MISMATCH:
      return "size mismatch";
    case TESSERA_ERROR_NULL_POINTER:
      return "null pointer";
    case TESSERA_ERROR_BUFFER_TOO_SMALL:
      return "buffer too small";
    case TESSERA_ERROR_BAD_STRUCT_SIZE:
      return "bad struct size";
    case TESSERA_ERROR_CANCELLED:
      return "cancelled";
    case TESSERA_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case TESSERA_ERROR_INTERNAL:
      return "internal error";
  }
  return "unknown error";
}

const char* version(void) { return TESSERA_VERSION_STRING; }

tessera_error context_config_init(tessera_context_config* config) {
  if (config == nullptr) return TESSERA_ERROR_NULL_POINTER;
  *config = tessera_context_config{};
  config->struct_size = sizeof(tessera_context_config);
  return TESSERA_SUCCESS;
}

tessera_error context_create(const tessera_context_config* config, tessera_context** context) {
  if (context == nullptr) return TESSERA_ERROR_NULL_POINTER;
  *context = nullptr;
  tessera_context_config c{};
  tessera_context_config_init(&c);
  if (config != nullptr) {
    if (config->struct_size != sizeof(tessera_context_config)) {
      return TESSERA_ERROR_BAD_STRUCT_SIZE;
    }
    c = *config;
  }
  if (c.threads < 0) return TESSERA_ERROR_INVALID_ARGUMENT;
  return guarded(nullptr, [&] {
    *context = new tessera_context{c, {}};
    return TESSERA_SUCCESS;
  });
}

void context_free(tessera_context* context) { delete context; }

const char* context_last_error(const tessera_context* context) {
  return context == nullptr ? "" : context->last_error.c_str();
}

void free(void* data) { std::free(data); }

}  // namespace tessera::c_api::entry
