// What the C API's files share (internal): the objects behind the opaque handles, the guard
// that keeps exceptions from crossing into C, and the argument checks every entry point makes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <new>
#include <string>
#include <vector>

#include "c_api/c_api_entry.h"
#include "tessera/core.h"
#include "tessera/tessera_c.h"
#include "tessera/texture_file.h"

struct tessera_context {
  tessera_context_config config{};
  std::string last_error;
};

struct tessera_texture {
  tessera::texture_file::CompressedTexture texture;
  /// The last file serialised from it, so that a size query and the write that follows it
  /// serialise (and Zstandard-compress) once.
  int cached_container = -1;
  int cached_zstd = 0;
  std::vector<std::uint8_t> cached_file;
};

namespace tessera::c_api {

/// Thrown by the progress hook when the caller's callback asks to stop; caught by `guarded`.
struct Cancelled {};

/// Records `message` as the context's last error (when there is a context) and returns `code`.
tessera_error fail(tessera_context* context, tessera_error code, const std::string& message);
/// The C code of a C++ status, its message recorded as `fail` does.
tessera_error fail(tessera_context* context, const Status& status);

/// Runs `body` (returning tessera_error) with every exception turned into an error code: the
/// one way the C entry points call into C++. A success clears the context's last error.
template <class Body>
tessera_error guarded(tessera_context* context, Body&& body) noexcept {
  try {
    const tessera_error e = body();
    if (e == TESSERA_SUCCESS && context != nullptr) context->last_error.clear();
    return e;
  } catch (const Cancelled&) {
    return fail(context, TESSERA_ERROR_CANCELLED, "cancelled by the progress callback");
  } catch (const std::bad_alloc&) {
    return fail(context, TESSERA_ERROR_OUT_OF_MEMORY, "out of memory");
  } catch (const std::exception& ex) {
    return fail(context, TESSERA_ERROR_INTERNAL, std::string("internal error: ") + ex.what());
  } catch (...) {
    return fail(context, TESSERA_ERROR_INTERNAL, "internal error: unknown exception");
  }
}

/// NULL_POINTER with a message naming `what` when `p` is null, else success.
tessera_error require(tessera_context* context, const void* p, const char* what);

/// Checks `image` (pixels, size within tessera's limits, a pitch of at least one row) and
/// returns its view; `what` names it in messages.
tessera_error image_view(tessera_context* context, const tessera_image* image, const char* what,
                         ImageView8& view);

/// Checks an output RGBA8 buffer of `width` x `height` with `row_pitch` (0 = packed, which it
/// then becomes) and `capacity` bytes.
tessera_error check_rgba_output(tessera_context* context, std::uint32_t width, std::uint32_t height,
                                const std::uint8_t* rgba, std::size_t& row_pitch,
                                std::size_t capacity);
/// Copies `image` (packed) into the checked output buffer, row by row.
void copy_rows(const ImageRGBA8& image, std::uint8_t* rgba, std::size_t row_pitch);

/// The context's thread count.
inline int threads_of(const tessera_context* context) { return context->config.threads; }

}  // namespace tessera::c_api
