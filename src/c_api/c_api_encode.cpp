// The C API's encoder, raw PVRTC1 blocks and metrics (tessera/tessera_c.h): the options
// checked as `tessera compress` checks its flags, then texture_file::compress_images /
// compress_view, pvrtc::decode and metrics::compare_images.
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "c_api/c_api_internal.h"
#include "tessera/metrics.h"
#include "tessera/pvrtc.h"

namespace tessera::c_api {
namespace {

constexpr std::uint32_t kKnownFlags = TESSERA_FLAG_MIPMAPS | TESSERA_FLAG_SRGB |
                                      TESSERA_FLAG_PREMULTIPLY | TESSERA_FLAG_ALPHA_BLEED |
                                      TESSERA_FLAG_ALPHA_WEIGHTED | TESSERA_FLAG_NORMAL_MAP |
                                      TESSERA_FLAG_FLIP_Y | TESSERA_FLAG_RESIZE_POT;

tessera_error bad(tessera_context* context, const std::string& message) {
  return fail(context, TESSERA_ERROR_INVALID_ARGUMENT, message);
}

/// The options' ranges and the conflicts `tessera compress` refuses as usage errors.
tessera_error check_options(tessera_context* context, const tessera_encode_options& o) {
  if (o.format != TESSERA_FORMAT_PVRTC1_4BPP && o.format != TESSERA_FORMAT_PVRTC1_2BPP) {
    return bad(context, "format " + std::to_string(int(o.format)) + " is not a tessera_format");
  }
  if (o.quality < TESSERA_QUALITY_FAST || o.quality > TESSERA_QUALITY_HIGH) {
    return bad(context, "quality " + std::to_string(int(o.quality)) + " is not a tessera_quality");
  }
  if (o.mip_filter < TESSERA_MIP_FILTER_BOX || o.mip_filter > TESSERA_MIP_FILTER_KAISER) {
    return bad(context,
               "mip_filter " + std::to_string(int(o.mip_filter)) + " is not a tessera_mip_filter");
  }
  if (o.iterations < -1 || o.iterations > 1000) {
    return bad(context, "iterations " + std::to_string(o.iterations) + " is not in [-1, 1000]");
  }
  if (o.exact_search_rounds < 0 || o.exact_search_rounds > 1000) {
    return bad(context, "exact_search_rounds " + std::to_string(o.exact_search_rounds) +
                            " is not in [0, 1000]");
  }
  if (o.mip_levels < 0 || o.mip_levels > 17) {
    return bad(context, "mip_levels " + std::to_string(o.mip_levels) + " is not in [0, 17]");
  }
  if (o.faces != 1 && o.faces != 6) {
    return bad(context, "faces " + std::to_string(o.faces) + " is neither 1 nor 6");
  }
  if ((o.flags & ~kKnownFlags) != 0) {
    return bad(context, "flags hold unknown bits " + std::to_string(o.flags & ~kKnownFlags));
  }
  const auto has = [&](std::uint32_t flag) { return (o.flags & flag) != 0; };
  if (has(TESSERA_FLAG_NORMAL_MAP) && has(TESSERA_FLAG_SRGB)) {
    return bad(context, "NORMAL_MAP and SRGB: a normal map holds vectors, never sRGB colour");
  }
  if (has(TESSERA_FLAG_PREMULTIPLY) && has(TESSERA_FLAG_ALPHA_BLEED)) {
    return bad(context, "ALPHA_BLEED and PREMULTIPLY: bleeding is for straight alpha");
  }
  if (has(TESSERA_FLAG_ALPHA_WEIGHTED) && has(TESSERA_FLAG_PREMULTIPLY)) {
    return bad(context, "ALPHA_WEIGHTED and PREMULTIPLY: weighting is for straight alpha");
  }
  if (has(TESSERA_FLAG_ALPHA_WEIGHTED) && o.format == TESSERA_FORMAT_PVRTC1_2BPP) {
    return bad(context, "ALPHA_WEIGHTED and PVRTC1_2BPP: alpha-weighted error is for 4 bpp only");
  }
  if (o.mip_filter != TESSERA_MIP_FILTER_BOX && !has(TESSERA_FLAG_MIPMAPS) && o.mip_levels == 0) {
    return bad(context, "a mip_filter other than BOX needs TESSERA_FLAG_MIPMAPS or mip_levels");
  }
  return TESSERA_SUCCESS;
}

/// The caller's options (or the defaults), checked, as the C++ pipeline's.
tessera_error compress_options(tessera_context* context, const tessera_encode_options* given,
                               tessera_encode_options& o, texture_file::CompressOptions& out) {
  tessera_encode_options_init(&o);
  if (given != nullptr) {
    if (given->struct_size != sizeof(tessera_encode_options)) {
      return fail(context, TESSERA_ERROR_BAD_STRUCT_SIZE,
                  "tessera_encode_options::struct_size is " + std::to_string(given->struct_size) +
                      ", not " + std::to_string(sizeof(tessera_encode_options)) +
                      " (call tessera_encode_options_init)");
    }
    o = *given;
  }
  if (tessera_error e = check_options(context, o); e != TESSERA_SUCCESS) return e;
  const auto has = [&](std::uint32_t flag) { return (o.flags & flag) != 0; };
  out = texture_file::CompressOptions{};
  out.encode.format = o.format == TESSERA_FORMAT_PVRTC1_2BPP ? pvrtc::Format::pvrtc1_2bpp
                                                             : pvrtc::Format::pvrtc1_4bpp;
  out.encode.quality = o.quality == TESSERA_QUALITY_FAST   ? pvrtc::Quality::fast
                       : o.quality == TESSERA_QUALITY_HIGH ? pvrtc::Quality::high
                                                           : pvrtc::Quality::normal;
  out.encode.iterations = o.iterations;
  out.encode.exact_search_rounds = o.exact_search_rounds;
  out.encode.threads = threads_of(context);
  out.encode.alpha_weighted = has(TESSERA_FLAG_ALPHA_WEIGHTED);
  out.mipmaps = has(TESSERA_FLAG_MIPMAPS) || o.mip_levels > 0;
  out.mip_levels = o.mip_levels;
  out.mip_filter = o.mip_filter == TESSERA_MIP_FILTER_LANCZOS  ? image::MipFilter::lanczos
                   : o.mip_filter == TESSERA_MIP_FILTER_KAISER ? image::MipFilter::kaiser
                                                               : image::MipFilter::box;
  out.srgb = has(TESSERA_FLAG_SRGB);
  out.resize_pot = has(TESSERA_FLAG_RESIZE_POT);
  out.flip_y = has(TESSERA_FLAG_FLIP_Y);
  out.premultiply = has(TESSERA_FLAG_PREMULTIPLY);
  out.alpha_bleed = has(TESSERA_FLAG_ALPHA_BLEED);
  out.normal_map = has(TESSERA_FLAG_NORMAL_MAP);
  if (const tessera_progress_fn progress = context->config.progress) {
    void* user = context->config.progress_user_data;
    out.encode.progress = [progress, user](double fraction) {
      if (progress(user, fraction) != 0) throw Cancelled{};
    };
  }
  return TESSERA_SUCCESS;
}

tessera_error encode(tessera_context* context, const tessera_image* images,
                     std::uint32_t image_count, const tessera_encode_options* options,
                     tessera_texture** texture) {
  tessera_encode_options o{};
  texture_file::CompressOptions co;
  if (tessera_error e = compress_options(context, options, o, co); e != TESSERA_SUCCESS) return e;
  if (image_count == 0 || image_count > std::uint32_t(texture_file::kMaxTextureImages)) {
    return bad(context, "image_count " + std::to_string(image_count) + " is not in [1, " +
                            std::to_string(texture_file::kMaxTextureImages) + "]");
  }
  std::vector<ImageView8> views(image_count);
  std::vector<std::string> names(image_count);
  for (std::uint32_t i = 0; i < image_count; ++i) {
    names[i] = "images[" + std::to_string(i) + "]";
    if (tessera_error e = image_view(context, &images[i], names[i].c_str(), views[i]);
        e != TESSERA_SUCCESS) {
      return e;
    }
  }
  auto made = std::make_unique<tessera_texture>();
  if (image_count == 1 && o.faces == 1 && o.array == 0) {
    Result<texture_file::CompressedTexture> tex =
        texture_file::compress_view(views[0], co, names[0]);
    if (!tex) return fail(context, tex.status());
    made->texture = std::move(tex).value();
  } else {
    std::vector<ImageRGBA8> owned;
    owned.reserve(image_count);
    for (const ImageView8& v : views) owned.push_back(to_image(v));
    Result<texture_file::CompressedImage> tex = texture_file::compress_images(
        std::move(owned), texture_file::TextureShape{o.faces, o.array != 0}, co, names);
    if (!tex) return fail(context, tex.status());
    made->texture = std::move(tex->texture);
  }
  *texture = made.release();
  return TESSERA_SUCCESS;
}

pvrtc::Format format_of(tessera_format format) {
  return format == TESSERA_FORMAT_PVRTC1_2BPP ? pvrtc::Format::pvrtc1_2bpp
                                              : pvrtc::Format::pvrtc1_4bpp;
}

/// INVALID_ARGUMENT unless `format` is a tessera_format and `width` x `height` a PVRTC level.
tessera_error check_level(tessera_context* context, tessera_format format, std::uint32_t width,
                          std::uint32_t height) {
  if (format != TESSERA_FORMAT_PVRTC1_4BPP && format != TESSERA_FORMAT_PVRTC1_2BPP) {
    return bad(context, "format " + std::to_string(int(format)) + " is not a tessera_format");
  }
  if (width > std::uint32_t(kMaxImageDimension) || height > std::uint32_t(kMaxImageDimension)) {
    return bad(context, size_text(width, height) + " is larger than PVRTC1 levels tessera makes");
  }
  return fail(context, pvrtc::check_dimensions(int(width), int(height), "PVRTC1 level"));
}

tessera_error pvrtc_encode(tessera_context* context, const tessera_image* image,
                           const tessera_encode_options* options, std::uint8_t* blocks,
                           std::size_t capacity, std::size_t* size) {
  tessera_encode_options o{};
  texture_file::CompressOptions co;
  if (tessera_error e = compress_options(context, options, o, co); e != TESSERA_SUCCESS) return e;
  if (co.mipmaps || co.resize_pot || o.faces != 1 || o.array != 0) {
    return bad(context,
               "tessera_pvrtc_encode makes one level of one image: no mips, "
               "RESIZE_POT, faces or array (use tessera_encode)");
  }
  ImageView8 view;
  if (tessera_error e = image_view(context, image, "image", view); e != TESSERA_SUCCESS) return e;
  if (tessera_error e = check_level(context, o.format, image->width, image->height);
      e != TESSERA_SUCCESS) {
    return e;
  }
  const std::size_t needed = pvrtc::level_size(co.encode.format, view.width, view.height);
  *size = needed;
  if (blocks == nullptr && capacity == 0) return TESSERA_SUCCESS;
  if (tessera_error e = require(context, blocks, "blocks"); e != TESSERA_SUCCESS) return e;
  if (capacity < needed) {
    return fail(context, TESSERA_ERROR_BUFFER_TOO_SMALL,
                "blocks holds " + std::to_string(capacity) + " bytes; the level needs " +
                    std::to_string(needed));
  }
  Result<texture_file::CompressedTexture> tex = texture_file::compress_view(view, co, "image");
  if (!tex) return fail(context, tex.status());
  std::memcpy(blocks, tex->levels[0].data(), needed);
  return TESSERA_SUCCESS;
}

tessera_error pvrtc_decode(tessera_context* context, tessera_format format, std::uint32_t width,
                           std::uint32_t height, const std::uint8_t* blocks,
                           std::size_t blocks_size, std::uint8_t* rgba, std::size_t row_pitch,
                           std::size_t capacity) {
  if (tessera_error e = require(context, blocks, "blocks"); e != TESSERA_SUCCESS) return e;
  if (tessera_error e = check_level(context, format, width, height); e != TESSERA_SUCCESS) {
    return e;
  }
  const std::size_t needed = pvrtc::level_size(format_of(format), int(width), int(height));
  if (blocks_size < needed) {
    return bad(context, std::to_string(blocks_size) + " bytes of blocks; a " +
                            size_text(width, height) + " level needs " + std::to_string(needed));
  }
  if (tessera_error e = check_rgba_output(context, width, height, rgba, row_pitch, capacity);
      e != TESSERA_SUCCESS) {
    return e;
  }
  Result<ImageRGBA8> decoded = pvrtc::decode({blocks, needed}, format_of(format), int(width),
                                             int(height), Parallel{threads_of(context)});
  if (!decoded) return fail(context, decoded.status());
  copy_rows(*decoded, rgba, row_pitch);
  return TESSERA_SUCCESS;
}

tessera_error compare(tessera_context* context, const tessera_image* a, const tessera_image* b,
                      std::int32_t compute_ssim, tessera_metrics* metrics) {
  if (tessera_error e = require(context, metrics, "metrics"); e != TESSERA_SUCCESS) return e;
  if (metrics->struct_size != sizeof(tessera_metrics)) {
    return fail(context, TESSERA_ERROR_BAD_STRUCT_SIZE,
                "tessera_metrics::struct_size is " + std::to_string(metrics->struct_size) +
                    ", not " + std::to_string(sizeof(tessera_metrics)));
  }
  ImageView8 va, vb;
  if (tessera_error e = image_view(context, a, "a", va); e != TESSERA_SUCCESS) return e;
  if (tessera_error e = image_view(context, b, "b", vb); e != TESSERA_SUCCESS) return e;
  metrics::CompareOptions options;
  options.compute_ssim = compute_ssim != 0;
  options.threads = threads_of(context);
  Result<metrics::ImageComparison> c = metrics::compare_images(to_image(va), to_image(vb), options);
  if (!c) return fail(context, c.status());
  tessera_metrics m{};
  m.struct_size = sizeof(tessera_metrics);
  m.mse_rgb = c->mse_rgb;
  m.psnr_rgb = c->psnr_rgb;
  m.has_alpha = c->has_alpha ? 1 : 0;
  m.mse_alpha = c->mse_alpha;
  m.psnr_alpha = c->psnr_alpha;
  m.ssim = c->ssim_gray;
  m.max_abs = c->max_abs;
  *metrics = m;
  return TESSERA_SUCCESS;
}

}  // namespace

}  // namespace tessera::c_api

using tessera::c_api::guarded;
using tessera::c_api::require;

namespace tessera::c_api::entry {

tessera_error encode_options_init(tessera_encode_options* options) {
  if (options == nullptr) return TESSERA_ERROR_NULL_POINTER;
  *options = tessera_encode_options{};
  options->struct_size = sizeof(tessera_encode_options);
  options->format = TESSERA_FORMAT_PVRTC1_4BPP;
  options->quality = TESSERA_QUALITY_NORMAL;
  options->iterations = -1;
  options->mip_filter = TESSERA_MIP_FILTER_BOX;
  options->faces = 1;
  return TESSERA_SUCCESS;
}

tessera_error encode(tessera_context* context, const tessera_image* images, uint32_t image_count,
                     const tessera_encode_options* options, tessera_texture** texture) {
  if (texture != nullptr) *texture = nullptr;
  if (context == nullptr) return TESSERA_ERROR_NULL_POINTER;
  return guarded(context, [&] {
    if (tessera_error e = require(context, images, "images"); e != TESSERA_SUCCESS) return e;
    if (tessera_error e = require(context, texture, "texture"); e != TESSERA_SUCCESS) return e;
    return tessera::c_api::encode(context, images, image_count, options, texture);
  });
}

tessera_error pvrtc_level_size(tessera_format format, uint32_t width, uint32_t height,
                               size_t* size) {
  if (size == nullptr) return TESSERA_ERROR_NULL_POINTER;
  return guarded(nullptr, [&] {
    tessera_error e = tessera::c_api::check_level(nullptr, format, width, height);
    if (e == TESSERA_SUCCESS) {
      *size =
          tessera::pvrtc::level_size(tessera::c_api::format_of(format), int(width), int(height));
    }
    return e;
  });
}

tessera_error pvrtc_encode(tessera_context* context, const tessera_image* image,
                           const tessera_encode_options* options, uint8_t* blocks, size_t capacity,
                           size_t* size) {
  if (context == nullptr) return TESSERA_ERROR_NULL_POINTER;
  return guarded(context, [&] {
    if (tessera_error e = require(context, size, "size"); e != TESSERA_SUCCESS) return e;
    return tessera::c_api::pvrtc_encode(context, image, options, blocks, capacity, size);
  });
}

tessera_error pvrtc_decode(tessera_context* context, tessera_format format, uint32_t width,
                           uint32_t height, const uint8_t* blocks, size_t blocks_size,
                           uint8_t* rgba, size_t row_pitch, size_t capacity) {
  if (context == nullptr) return TESSERA_ERROR_NULL_POINTER;
  return guarded(context, [&] {
    return tessera::c_api::pvrtc_decode(context, format, width, height, blocks, blocks_size, rgba,
                                        row_pitch, capacity);
  });
}

tessera_error compare(tessera_context* context, const tessera_image* a, const tessera_image* b,
                      int32_t compute_ssim, tessera_metrics* metrics) {
  if (context == nullptr) return TESSERA_ERROR_NULL_POINTER;
  return guarded(context,
                 [&] { return tessera::c_api::compare(context, a, b, compute_ssim, metrics); });
}

}  // namespace tessera::c_api::entry
