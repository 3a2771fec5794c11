// tessera view: one result = one texture (encoded here, or opened), every image of it decoded,
// measured against what was encoded, with its heatmaps; the page's JSON and blobs.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "plot.h"
#include "tessera/image_mipmap.h"
#include "tessera/image_ops.h"
#include "tessera/io.h"
#include "tessera/metrics.h"
#include "view.h"

namespace tessera::cli {

namespace {

/// Saturation of the difference heatmap: `tessera compare --heatmap`'s (metrics default).
constexpr float kDiffScale = 64.0f;
/// Saturation of the angular error heatmap, degrees.
constexpr float kAngleScale = 10.0f;

nlohmann::json num(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

std::string put_png(BlobStore& blobs, const ImageRGBA8& image) {
  Result<std::vector<std::uint8_t>> png = io::encode_png(image);
  return png ? blobs.put("image/png", std::move(png).value()) : std::string();
}

std::string put_rgba(BlobStore& blobs, const ImageRGBA8& image) {
  return blobs.put("application/x-tessera-rgba-deflate", deflate_rgba(image));
}

/// Per-texel angle (degrees) between the normalised vectors 2 c / 255 - 1 of `a` and `b`, as
/// metrics::compare_images measures it (a zero vector counts as +Z).
std::vector<float> angle_map(const ImageRGBA8& a, const ImageRGBA8& b) {
  std::vector<float> out(a.pixel_count());
  auto unit = [](const std::uint8_t* p, double v[3]) {
    double n = 0;
    for (int c = 0; c < 3; ++c) {
      v[c] = 2.0 * p[c] / 255.0 - 1.0;
      n += v[c] * v[c];
    }
    if (n <= 0) {
      v[0] = v[1] = 0;
      v[2] = 1;
      return;
    }
    n = std::sqrt(n);
    for (int c = 0; c < 3; ++c) v[c] /= n;
  };
  for (std::size_t i = 0; i < out.size(); ++i) {
    double u[3], w[3];
    unit(&a.pixels[i * 4], u);
    unit(&b.pixels[i * 4], w);
    const double d = std::clamp(u[0] * w[0] + u[1] * w[1] + u[2] * w[2], -1.0, 1.0);
    out[i] = float(std::acos(d) * 180.0 / 3.14159265358979323846);
  }
  return out;
}

nlohmann::json metrics_json(const metrics::ImageComparison& c) {
  nlohmann::json m = {{"psnr_rgb", num(c.psnr_rgb)},
                      {"ssim_gray", c.ssim_gray},
                      {"mse_rgb", c.mse_rgb},
                      {"max_abs", c.max_abs}};
  if (c.has_alpha) m["psnr_alpha"] = num(c.psnr_alpha);
  if (c.has_premultiplied) m["psnr_premultiplied"] = num(c.psnr_premultiplied);
  if (c.has_normal) {
    m["angular_error_mean_deg"] = c.angular_error_mean_deg;
    m["angular_error_p99_deg"] = c.angular_error_p99_deg;
    m["angular_error_max_deg"] = c.angular_error_max_deg;
  }
  return m;
}

/// The references of levels 1.. of a chain: the input prepared as compress_images prepares it
/// (resampled, premultiplied, mip-filtered, bled), level 0 being `made.sources[0]`.
Result<std::vector<ImageRGBA8>> reference_chain(const ImageRGBA8& input,
                                                const texture_file::CompressOptions& o,
                                                const texture_file::CompressedImage& made) {
  const int levels = made.texture.level_count();
  if (levels <= 1) return std::vector<ImageRGBA8>{made.sources[0]};
  ImageRGBA8 image = input;
  if (image.has_alpha) image.has_alpha = !all_opaque(ImageView8::of(image));
  image::MipmapOptions filter;
  filter.srgb = o.srgb;
  filter.normal_map = o.normal_map;
  filter.threads = o.encode.threads;
  if (made.resized) {
    Result<ImageRGBA8> r =
        image::resize_image(image, made.texture.width, made.texture.height, filter);
    if (!r) return r.status();
    image = std::move(r).value();
  }
  if (o.premultiply && image.has_alpha) {
    image::premultiply_alpha(image, o.srgb, {o.encode.threads});
    filter.premultiply = false;
  }
  filter.max_levels = levels;
  filter.filter = o.mip_filter;
  Result<std::vector<ImageRGBA8>> chain = image::generate_mipmaps(image, filter);
  if (!chain) return chain.status();
  if (o.alpha_bleed) {
    for (ImageRGBA8& level : *chain) image::bleed_alpha(level, {o.encode.threads});
  }
  (*chain)[0] = made.sources[0];
  return chain;
}

/// One image of a result: texels, decoded texels, heatmaps and metrics.
Result<nlohmann::json> image_json(const ImageRGBA8* reference, const ImageRGBA8& decoded, int level,
                                  int layer, int face, bool normal_map, bool premultiplied,
                                  int threads, BlobStore& blobs) {
  nlohmann::json j = {
      {"level", level},         {"layer", layer},           {"face", face},
      {"width", decoded.width}, {"height", decoded.height}, {"decoded", put_rgba(blobs, decoded)}};
  if (!reference) return j;
  j["original"] = put_rgba(blobs, *reference);
  metrics::CompareOptions co;
  co.threads = threads;
  co.premultiplied = reference->has_alpha || decoded.has_alpha;
  co.normal = normal_map;
  Result<metrics::ImageComparison> c = metrics::compare_images(*reference, decoded, co);
  if (!c) return c.status();
  j["metrics"] = metrics_json(*c);
  Result<ImageRGBA8> heat = metrics::difference_heatmap(*reference, decoded, kDiffScale);
  if (!heat) return heat.status();
  j["heatmap"] = put_png(blobs, *heat);
  if (co.premultiplied && !premultiplied) {
    // What blending shows: the same heatmap over colour x alpha (colour under alpha 0 counts
    // for nothing), where --alpha-weighted's gains are seen.
    ImageRGBA8 a = *reference, b = decoded;
    image::premultiply_alpha(a, false, {threads});
    image::premultiply_alpha(b, false, {threads});
    Result<ImageRGBA8> pm = metrics::difference_heatmap(a, b, kDiffScale);
    if (!pm) return pm.status();
    j["heatmap_premultiplied"] = put_png(blobs, *pm);
  }
  if (normal_map) {
    j["angle_map"] = put_png(blobs, metrics::heatmap(angle_map(*reference, decoded), decoded.width,
                                                     decoded.height, kAngleScale));
  }
  return j;
}

nlohmann::json texture_json(const texture_file::CompressedTexture& tex) {
  return {{"width", tex.width},
          {"height", tex.height},
          {"format", texture_file::texture_format_name(tex)},
          {"shape", texture_file::texture_shape_name(tex)},
          {"faces", tex.faces},
          {"layers", tex.layers},
          {"levels", tex.level_count()},
          {"has_alpha", tex.has_alpha},
          {"premultiplied", tex.premultiplied},
          {"srgb", tex.srgb}};
}

nlohmann::json colour_bars(BlobStore& blobs) {
  auto svg = [&](const std::string& text) {
    return blobs.put("image/svg+xml", std::vector<std::uint8_t>(text.begin(), text.end()));
  };
  const std::string diff = svg(colour_bar_svg(metrics::ColourMap::inferno, 0, kDiffScale, 5,
                                              "max abs channel difference (8-bit levels; 64 "
                                              "and above saturate)"));
  return {{"heatmap", diff},
          {"heatmap_premultiplied", diff},
          {"angle_map", svg(colour_bar_svg(metrics::ColourMap::inferno, 0, kAngleScale, 6,
                                           "angle between normals (degrees; 10 and above "
                                           "saturate)"))}};
}

std::string stem_of(const std::string& name) { return std::filesystem::path(name).stem().string(); }

}  // namespace

Result<nlohmann::json> encode_view_result(const ViewInput& input, const ViewSettings& settings,
                                          int threads, BlobStore& blobs,
                                          const std::function<void(double)>& progress) {
  if (input.is_texture || !input.error.empty()) {
    return Status::error(ErrorCode::invalid_argument, input.name + ": not an image to encode");
  }
  const std::string output = stem_of(input.name) + ".pvr";
  CompressArgs args = compress_args(settings, input.path, output);
  if (std::string p = compress_usage_problem(args, "pvr"); !p.empty()) {
    return Status::error(ErrorCode::invalid_argument, p);
  }
  Result<texture_file::CompressOptions> checked = compress_options(args, threads);
  if (!checked) return checked.status();
  texture_file::CompressOptions options = std::move(*checked);
  options.encode.progress = progress;
  std::vector<ImageRGBA8> images{input.image};
  const std::vector<std::string> names{input.name};
  Result<texture_file::CompressedImage> made =
      texture_file::compress_images(std::move(images), texture_shape(args), options, names);
  if (!made) return made.status();
  const texture_file::CompressedTexture& tex = made->texture;
  Result<std::vector<std::uint8_t>> file =
      texture_file::serialise_texture(tex, texture_file::ContainerFormat::pvr3);
  if (!file) return file.status();
  Result<std::vector<ImageRGBA8>> refs = reference_chain(input.image, options, *made);
  if (!refs) return refs.status();
  Result<metrics::ImageComparison> total =
      texture_file::measure_level0(made->texture, made->sources, threads);
  if (!total) return total.status();

  nlohmann::json j = {
      {"input", input.name},
      {"settings", settings_to_json(settings)},
      {"command", compress_command(settings, input.path, output)},  // the path as typed
      {"texture", texture_json(tex)},
      {"file_name", output},
      {"file", blobs.put("application/octet-stream", *file)},
      {"bytes", file->size()},
      {"encode_ms", made->encode_ms},
      {"resized", made->resized},
      {"metrics", metrics_json(*total)},
      {"colour_bars", colour_bars(blobs)},
      {"images", nlohmann::json::array()}};
  for (int level = 0; level < tex.level_count(); ++level) {
    Result<ImageRGBA8> dec = texture_file::decode_texture_image(tex, level, 0, 0, {threads});
    if (!dec) return dec.status();
    Result<nlohmann::json> im = image_json(&(*refs)[std::size_t(level)], *dec, level, 0, 0,
                                           settings.normal_map, tex.premultiplied, threads, blobs);
    if (!im) return im.status();
    j["images"].push_back(std::move(im).value());
  }
  return j;
}

Result<nlohmann::json> texture_view_result(const ViewInput& input, int threads, BlobStore& blobs,
                                           const ImageRGBA8* reference) {
  if (!input.is_texture || !input.error.empty()) {
    return Status::error(ErrorCode::invalid_argument, input.name + ": not a texture");
  }
  const texture_file::CompressedTexture& tex = input.texture;
  nlohmann::json j = {{"input", input.name},
                      {"label", reference ? "file " + input.name : std::string()},
                      {"texture", texture_json(tex)},
                      {"file_name", input.name},
                      {"file", blobs.put("application/octet-stream", input.file)},
                      {"bytes", input.file.size()},
                      {"colour_bars", colour_bars(blobs)},
                      {"images", nlohmann::json::array()}};
  for (int level = 0; level < tex.level_count(); ++level) {
    for (int layer = 0; layer < tex.layers; ++layer) {
      for (int face = 0; face < tex.faces; ++face) {
        Result<ImageRGBA8> dec =
            texture_file::decode_texture_image(tex, level, layer, face, {threads});
        if (!dec) return dec.status();
        Result<nlohmann::json> im = image_json(level == 0 ? reference : nullptr, *dec, level, layer,
                                               face, false, tex.premultiplied, threads, blobs);
        if (!im) return im.status();
        j["images"].push_back(std::move(im).value());
      }
    }
  }
  return j;
}

}  // namespace tessera::cli
