/* tessera/tessera_c.h — the C API of tessera's PVRTC1 codec and texture containers.
 *
 * What: PVRTC1 4 and 2 bpp encoding (the quality presets and the asset options: alpha bleed,
 *   premultiplied alpha, alpha-weighted error, normal maps, sRGB, mip chains, cube maps and
 *   arrays) from pixels the caller owns, decoding, PVR v3 / KTX 1.1 / KTX 2.0 (+ Zstandard)
 *   from and to memory and files, and PSNR / SSIM of two images. C99, no C++ type, no
 *   exception crosses it: any language's plain FFI binds it (Python ctypes, Rust, C#, Go, Zig).
 *   A thin layer over the C++ API (tessera/pvrtc.h, tessera/texture_file.h, tessera/metrics.h):
 *   the same options give the same bytes as `tessera compress` and the C++ calls.
 * Model: astcenc.h and PVRTexLib.h. One `tessera_context` per thread of work carries the thread
 *   count, the progress callback and the last error message; options are structs that carry
 *   their own size (`struct_size`, set by their `*_init` function) so that fields can be added
 *   without breaking callers built against an older header; every call returns a
 *   `tessera_error` (`tessera_error_string`), and a failed call with a context leaves a
 *   one-line message in `tessera_context_last_error`.
 * Memory: inputs are borrowed for the duration of the call. Outputs go into caller-owned
 *   buffers (pass the buffer and its capacity; too small gives TESSERA_ERROR_BUFFER_TOO_SMALL,
 *   nothing written, and the needed size in `*size`; a NULL buffer with capacity 0 only asks
 *   for the size) or into library memory (`*_alloc` functions, freed with `tessera_free`).
 *   Textures (`tessera_texture`) are opaque, library-owned, freed with `tessera_texture_free`.
 * Bad input (NULL pointers, short buffers, a pitch below a row, sizes PVRTC cannot hold, a
 *   truncated or corrupt container, an options struct of unknown size) gives an error code and
 *   a message, never a crash, and writes nothing to the caller's outputs.
 * Threads: stated per function. In short: a context (and the textures a call is given) is used
 *   by one thread at a time; different contexts may run at once on different threads; functions
 *   without a context are thread-safe. Output bytes never depend on the thread count.
 * Linking: `pkg-config --cflags --libs tessera` (the shared library libtessera.so.0, which
 *   exports only `tessera_*` and the C++ `tessera::` API), or CMake `tessera::shared`.
 * Guide: docs/c_api.md. Tests: tests/c_api/ (c_api_test.cpp: each call against the C++ API byte
 *   for byte; c_api_bad_input_test.cpp: every bad input; consumer.c and consumer_ctypes.py
 *   against `tessera compress` from an installed tree; the exported symbols; abidiff against
 *   tests/c_api/abi/); the fuzzer fuzz/fuzz_c_api_read.cpp; scripts/package.sh (the .debs).
 */
#ifndef TESSERA_TESSERA_C_H
#define TESSERA_TESSERA_C_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Version of this interface: bumped when a function or a struct field is added. */
#define TESSERA_C_API_VERSION 1

/* Enumerations are 32-bit ints in C and C++ alike; in C++ every int32_t value is a valid value
 * of them (a fixed underlying type), so a caller's out-of-range value is an error code, never
 * undefined behaviour inside the library. */
#ifdef __cplusplus
#define TESSERA_ENUM(name) enum name : int32_t
#else
#define TESSERA_ENUM(name) enum name
#endif

/* ---------------------------------------------------------------------------------------- */
/* Errors                                                                                   */
/* ---------------------------------------------------------------------------------------- */

/** What every call returns. The first seven mirror tessera::ErrorCode. */
typedef TESSERA_ENUM(tessera_error){
    TESSERA_SUCCESS = 0,
    TESSERA_ERROR_INVALID_ARGUMENT = 1, /**< A value out of range or options that conflict. */
    TESSERA_ERROR_IO = 2,               /**< A file could not be opened, read or written. */
    TESSERA_ERROR_CORRUPT_DATA = 3,     /**< Truncated or inconsistent container bytes. */
    TESSERA_ERROR_UNSUPPORTED = 4,      /**< A valid file using a feature tessera lacks. */
    TESSERA_ERROR_TOO_LARGE = 5,        /**< A size beyond tessera's limits. */
    TESSERA_ERROR_SIZE_MISMATCH = 6,    /**< Images that must share a size do not. */
    TESSERA_ERROR_NULL_POINTER = 7,     /**< A required pointer argument is NULL. */
    TESSERA_ERROR_BUFFER_TOO_SMALL = 8, /**< The output buffer is short; `*size` says how big. */
    TESSERA_ERROR_BAD_STRUCT_SIZE = 9,  /**< An options struct's `struct_size` is unknown. */
    TESSERA_ERROR_CANCELLED = 10,       /**< The progress callback asked to stop. */
    TESSERA_ERROR_OUT_OF_MEMORY = 11,   /**< An allocation failed. */
    TESSERA_ERROR_INTERNAL = 12         /**< A bug in tessera (please report it). */
} tessera_error;

/** Static English name of a code ("buffer too small"); "unknown error" for other values.
 *  Thread-safe. */
const char* tessera_error_string(tessera_error code);

/** The library's version, "MAJOR.MINOR.PATCH" (static string). Thread-safe. */
const char* tessera_version(void);

/* ---------------------------------------------------------------------------------------- */
/* Context                                                                                  */
/* ---------------------------------------------------------------------------------------- */

/** Progress of a long call: `fraction` in [0, 1], never decreasing, the last call of a
 *  successful encode exactly 1. Called on the thread that made the call, between the encoder's
 *  passes. Return 0 to go on, anything else to cancel: the call then returns
 *  TESSERA_ERROR_CANCELLED at its next progress point and writes no output. */
typedef int (*tessera_progress_fn)(void* user_data, double fraction);

/** How a context works; fill with `tessera_context_config_init`. */
typedef struct tessera_context_config {
  uint32_t struct_size;         /**< sizeof(tessera_context_config), set by the init. */
  int32_t threads;              /**< Worker threads, 0 = all hardware threads (default). */
  tessera_progress_fn progress; /**< NULL (default): no progress calls. */
  void* progress_user_data;     /**< Passed back to `progress`. */
} tessera_context_config;

/** Fills `config` with the defaults and sets `struct_size`. Thread-safe. */
tessera_error tessera_context_config_init(tessera_context_config* config);

/** A reusable context: thread count, progress callback, last error message. */
typedef struct tessera_context tessera_context;

/** Creates a context. `config` may be NULL (the defaults). On error `*context` is set to NULL
 *  (when `context` is not NULL). Thread-safe. */
tessera_error tessera_context_create(const tessera_context_config* config,
                                     tessera_context** context);
/** Frees a context (NULL is a no-op). Not with a call on it in flight. */
void tessera_context_free(tessera_context* context);
/** The message of the last failed call on `context` ("" after a success, or for NULL); valid
 *  until the next call on the context. Same thread rule as the context. */
const char* tessera_context_last_error(const tessera_context* context);

/* ---------------------------------------------------------------------------------------- */
/* Images                                                                                   */
/* ---------------------------------------------------------------------------------------- */

/** RGBA8 pixels the caller owns: texel (x, y) at pixels + y * row_pitch + 4 * x, R, G, B, A. */
typedef struct tessera_image {
  const uint8_t* pixels;
  uint32_t width;
  uint32_t height;
  size_t row_pitch;  /**< Bytes from one row to the next, at least 4 * width; 0 = 4 * width. */
  int32_t has_alpha; /**< Nonzero: alpha is meaningful (an RGBA source). An alpha of 255
                          everywhere still gives an RGB texture, as `tessera compress`. */
} tessera_image;

/* ---------------------------------------------------------------------------------------- */
/* Encoding                                                                                 */
/* ---------------------------------------------------------------------------------------- */

typedef TESSERA_ENUM(tessera_format){
    TESSERA_FORMAT_PVRTC1_4BPP = 0, /**< 4x4 texels per 64-bit block. */
    TESSERA_FORMAT_PVRTC1_2BPP = 1  /**< 8x4 texels per 64-bit block. */
} tessera_format;

/** The encoder's effort (tessera/pvrtc.h, pvrtc::Quality). */
typedef TESSERA_ENUM(tessera_quality){TESSERA_QUALITY_FAST = 0, TESSERA_QUALITY_NORMAL = 1,
                                      TESSERA_QUALITY_HIGH = 2} tessera_quality;

typedef TESSERA_ENUM(tessera_mip_filter){TESSERA_MIP_FILTER_BOX = 0, TESSERA_MIP_FILTER_LANCZOS = 1,
                                         TESSERA_MIP_FILTER_KAISER = 2} tessera_mip_filter;

/** `tessera_encode_options::flags`: the asset options of `tessera compress`, same names. */
#define TESSERA_FLAG_MIPMAPS 0x0001u        /**< Encode the mip chain (see mip_levels). */
#define TESSERA_FLAG_SRGB 0x0002u           /**< sRGB texture, filtered in linear light. */
#define TESSERA_FLAG_PREMULTIPLY 0x0004u    /**< Multiply colour by alpha; mark it. */
#define TESSERA_FLAG_ALPHA_BLEED 0x0008u    /**< Colour of nearest visible texel under alpha 0. */
#define TESSERA_FLAG_ALPHA_WEIGHTED 0x0010u /**< Weight colour error by alpha (4 bpp only). */
#define TESSERA_FLAG_NORMAL_MAP 0x0020u     /**< RGB holds unit vectors (never with SRGB). */
#define TESSERA_FLAG_FLIP_Y 0x0040u         /**< Flip every image upside down first. */
#define TESSERA_FLAG_RESIZE_POT 0x0080u     /**< Resample non-power-of-two input (Lanczos-3). */

/** Encoder and pipeline options; fill with `tessera_encode_options_init`. The defaults are
 *  `tessera compress`'s: 4 bpp, normal quality, no mips, linear colour, one 2D image. */
typedef struct tessera_encode_options {
  uint32_t struct_size; /**< sizeof(tessera_encode_options), set by the init. */
  tessera_format format;
  tessera_quality quality;
  int32_t iterations;            /**< Refinement sweeps, -1 = the preset's (default). */
  int32_t exact_search_rounds;   /**< Exact endpoint search rounds, 0 = the preset's. */
  uint32_t flags;                /**< TESSERA_FLAG_* bits. */
  int32_t mip_levels;            /**< At most this many levels (0 = full chain); >0 implies
                                      TESSERA_FLAG_MIPMAPS. */
  tessera_mip_filter mip_filter; /**< Needs mips, like `--mip-filter`. */
  int32_t faces;                 /**< 1 (default), or 6 for a cube map: +X, -X, +Y, -Y, +Z, -Z. */
  int32_t array;                 /**< Nonzero: the images are the layers of an array texture. */
} tessera_encode_options;

/** Fills `options` with the defaults and sets `struct_size`. Thread-safe. */
tessera_error tessera_encode_options_init(tessera_encode_options* options);

/** An encoded (or read) texture: a 2D texture, cube map or array, with its mip chain. */
typedef struct tessera_texture tessera_texture;

/** Encodes `image_count` images (layer-major then face: `faces` per layer; one layer unless
 *  `array`) into a new texture, as `tessera compress` does the same files: the same bytes.
 *  `options` may be NULL (the defaults). On success `*texture` owns the result (free it with
 *  `tessera_texture_free`); on error it is set to NULL. Uses the context's threads and
 *  progress callback. Thread rule: the context's. */
tessera_error tessera_encode(tessera_context* context, const tessera_image* images,
                             uint32_t image_count, const tessera_encode_options* options,
                             tessera_texture** texture);

/** Bytes of one level of PVRTC1 blocks for `width` x `height` (powers of two, at most 65536;
 *  otherwise TESSERA_ERROR_INVALID_ARGUMENT). Thread-safe. */
tessera_error tessera_pvrtc_level_size(tessera_format format, uint32_t width, uint32_t height,
                                       size_t* size);

/** Encodes one image into raw PVRTC1 blocks (level 0 as a PVR v3 file holds it, Morton order)
 *  in the caller's `blocks` (capacity `capacity` bytes; `*size` gets the level size).
 *  `options` as for `tessera_encode` but without mips, faces or arrays (INVALID_ARGUMENT).
 *  Thread rule: the context's. */
tessera_error tessera_pvrtc_encode(tessera_context* context, const tessera_image* image,
                                   const tessera_encode_options* options, uint8_t* blocks,
                                   size_t capacity, size_t* size);

/** Decodes `blocks_size` bytes of raw blocks of a `width` x `height` level into the caller's
 *  RGBA8 buffer (`row_pitch` >= 4 * width, 0 = packed; `capacity` at least
 *  row_pitch * (height - 1) + 4 * width). Bit-exact with PVRTexTool. Thread rule: the
 *  context's. */
tessera_error tessera_pvrtc_decode(tessera_context* context, tessera_format format, uint32_t width,
                                   uint32_t height, const uint8_t* blocks, size_t blocks_size,
                                   uint8_t* rgba, size_t row_pitch, size_t capacity);

/* ---------------------------------------------------------------------------------------- */
/* Textures and containers                                                                  */
/* ---------------------------------------------------------------------------------------- */

typedef TESSERA_ENUM(tessera_container){
    TESSERA_CONTAINER_PVR3 = 0, /**< PVR v3 (.pvr). */
    TESSERA_CONTAINER_KTX1 = 1, /**< KTX 1.1 (.ktx). */
    TESSERA_CONTAINER_KTX2 = 2  /**< KTX 2.0 (.ktx2), optionally Zstandard-supercompressed. */
} tessera_container;

/** What a texture holds (`tessera_texture_get_info`). */
typedef struct tessera_texture_info {
  uint32_t struct_size; /**< Set by the caller to sizeof(tessera_texture_info). */
  tessera_format format;
  uint32_t width; /**< Of level 0. */
  uint32_t height;
  uint32_t levels;   /**< Mip levels, level 0 included. */
  uint32_t faces;    /**< 1, or 6 for a cube map. */
  uint32_t layers;   /**< Array layers (1 unless an array). */
  int32_t array;     /**< Nonzero: an array texture (even of one layer). */
  int32_t has_alpha; /**< RGBA (nonzero) or RGB pixel format. */
  int32_t srgb;
  int32_t premultiplied;
} tessera_texture_info;

/** Fills `info`; `info->struct_size` must be set first. Thread-safe (reads only). */
tessera_error tessera_texture_get_info(const tessera_texture* texture, tessera_texture_info* info);

/** The raw blocks of image (layer, face) of `level`: a pointer into the texture (valid while
 *  it lives) and its byte count. Thread-safe (reads only). */
tessera_error tessera_texture_get_blocks(const tessera_texture* texture, uint32_t level,
                                         uint32_t layer, uint32_t face, const uint8_t** blocks,
                                         size_t* size);

/** Decodes image (layer, face) of `level` to RGBA8 in the caller's buffer (pitch and capacity
 *  as `tessera_pvrtc_decode`; the level's size from `tessera_texture_get_info`, halved per
 *  level, at least 1). Thread rule: the context's. */
tessera_error tessera_texture_decode(tessera_context* context, const tessera_texture* texture,
                                     uint32_t level, uint32_t layer, uint32_t face, uint8_t* rgba,
                                     size_t row_pitch, size_t capacity);

/** Frees a texture (NULL is a no-op). */
void tessera_texture_free(tessera_texture* texture);

/** Parses a PVR v3, KTX 1.1 or KTX 2.0 file held in memory (chosen by its magic). Safe on any
 *  bytes: sizes are checked before allocating. Thread rule: the context's. */
tessera_error tessera_texture_read_memory(tessera_context* context, const void* data, size_t size,
                                          tessera_texture** texture);
/** Reads a .pvr, .ktx or .ktx2 file (format by magic). Thread rule: the context's. */
tessera_error tessera_texture_read_file(tessera_context* context, const char* path,
                                        tessera_texture** texture);

/** Serialises `texture` in `container` into the caller's `data` (capacity bytes); `*size` gets
 *  the file's size (also when the buffer is too small, or `data` is NULL with capacity 0).
 *  `zstd_level`: KTX 2.0 Zstandard level 1..22, 0 = none (nonzero needs KTX2). Thread rule: the
 *  context's, and the texture is not used elsewhere meanwhile (the last file is cached in it,
 *  so asking for the size and then the bytes serialises once). */
tessera_error tessera_texture_write_memory(tessera_context* context, tessera_texture* texture,
                                           tessera_container container, int32_t zstd_level,
                                           void* data, size_t capacity, size_t* size);
/** As `tessera_texture_write_memory`, into library memory: `*data` (free with
 *  `tessera_free`) and `*size`. */
tessera_error tessera_texture_write_alloc(tessera_context* context, tessera_texture* texture,
                                          tessera_container container, int32_t zstd_level,
                                          void** data, size_t* size);
/** Writes `path` atomically, in the container its extension names (.pvr, .ktx, .ktx2).
 *  Thread rule: the context's. */
tessera_error tessera_texture_write_file(tessera_context* context, const tessera_texture* texture,
                                         const char* path, int32_t zstd_level);

/** Frees memory the library allocated (`*_alloc`); NULL is a no-op. Thread-safe. */
void tessera_free(void* data);

/* ---------------------------------------------------------------------------------------- */
/* Metrics                                                                                  */
/* ---------------------------------------------------------------------------------------- */

/** Full-reference comparison (tessera/metrics.h): PSNR over RGB, peak 255 (+infinity when
 *  identical), alpha PSNR when either image has alpha, SSIM on Rec.709 luma (scikit-image's
 *  Gaussian SSIM), the largest absolute channel difference. */
typedef struct tessera_metrics {
  uint32_t struct_size; /**< Set by the caller to sizeof(tessera_metrics). */
  double mse_rgb;
  double psnr_rgb;
  int32_t has_alpha;
  double mse_alpha;
  double psnr_alpha;
  double ssim;
  int32_t max_abs;
} tessera_metrics;

/** Compares `a` against `b` (same size, else TESSERA_ERROR_SIZE_MISMATCH); `compute_ssim` 0
 *  skips SSIM (then 1). Uses the context's threads. Thread rule: the context's. */
tessera_error tessera_compare(tessera_context* context, const tessera_image* a,
                              const tessera_image* b, int32_t compute_ssim,
                              tessera_metrics* metrics);

#ifdef __cplusplus
}
#endif

#endif /* TESSERA_TESSERA_C_H */
