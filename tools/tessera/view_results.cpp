// tessera view: one result = one texture (encoded here, or opened), every image of it decoded,
// measured against what was encoded, with its heatmaps; the page's JSON and blobs.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <future>
#include <memory>

#include "plot.h"
#include "tessera/image_mipmap.h"
#include "tessera/image_ops.h"
#include "tessera/io.h"
#include "tessera/metrics.h"
#include "view.h"
#include "view_png.h"

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
  std::vector<std::uint8_t> png = encode_view_png(image, blobs.png_level);
  return png.empty() ? std::string() : blobs.put("image/png", std::move(png));
}

std::string hex_key(std::uint64_t h) {
  char key[17];
  std::snprintf(key, sizeof key, "%016llx", static_cast<unsigned long long>(h));
  return key;
}

/// FNV-1a-like hash of `n` bytes, 8 at a time, continuing `h`.
std::uint64_t hash_bytes(const void* data, std::size_t n, std::uint64_t h) {
  const auto* p = static_cast<const std::uint8_t*>(data);
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    std::uint64_t w;
    std::memcpy(&w, p + i, 8);
    h = (h ^ w) * 1099511628211ull;
    h ^= h >> 29;
  }
  for (; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
  return (h ^ n) * 1099511628211ull;
}

/// The PNG blob of an original. The original is the same at every setting, so the blob made for
/// one encode is reused by the next ones (while `blobs` holds it): found by a hash of the texels,
/// which costs a fraction of making the PNG again.
std::string put_original(BlobStore& blobs, const ImageRGBA8& image) {
  static std::mutex mutex;
  static std::map<std::uint64_t, std::string> made;
  const int shape[4] = {image.width, image.height, int(image.has_alpha), blobs.png_level};
  const std::uint64_t h = hash_bytes(image.pixels.data(), image.pixels.size(),
                                     hash_bytes(shape, sizeof shape, 1469598103934665603ull));
  {
    std::lock_guard<std::mutex> lock(mutex);
    if (auto it = made.find(h); it != made.end() && blobs.has(it->second)) return it->second;
  }
  std::string key = put_png(blobs, image);
  std::lock_guard<std::mutex> lock(mutex);
  if (made.size() >= 64) made.clear();  // a bound: the few inputs of one session fit
  made[h] = key;
  return key;
}

/// Where the page reads a decoded image from: the result's .pvr blob `file`, decoded in the page
/// (share/tessera/view/view_pvrtc.js), or (`file` empty) a PNG of its texels.
struct PvrImage {
  std::string file;
  int level = 0, layer = 0, face = 0;
  /// The image's key for the page: "pvrtc:FILE:LEVEL:LAYER:FACE" (view_pvrtc.js reads it).
  std::string key() const {
    return "pvrtc:" + file + ":" + std::to_string(level) + ":" + std::to_string(layer) + ":" +
           std::to_string(face);
  }
};

/// An image's texels kept as its PNG blob `key`, or as image `pvr` of a .pvr blob, read back
/// when needed (exact: view_png.h; the decoder's output).
struct Texels {
  const BlobStore* blobs;
  std::string key;
  bool has_alpha;
  PvrImage pvr;
  Result<ImageRGBA8> read() const {
    const std::string& k = pvr.file.empty() ? key : pvr.file;
    std::shared_ptr<const BlobStore::Blob> b = blobs->get(k);
    if (!b) return Status::error(ErrorCode::io_error, "view: blob " + k + " is gone");
    if (!pvr.file.empty()) {
      Result<texture_file::CompressedTexture> tex =
          texture_file::parse_texture(b->bytes, "view texels");
      if (!tex) return tex.status();
      return texture_file::decode_texture_image(*tex, pvr.level, pvr.layer, pvr.face, {1});
    }
    Result<ImageRGBA8> image = io::decode_image(b->bytes, "view texels");
    if (image) image->has_alpha = has_alpha;  // as measured (the PNG is RGB when opaque)
    return image;
  }
};

/// A heatmap PNG made when the page first asks for it (most are never shown): `what` names it
/// (its kind and the blobs it is made from).
std::string lazy_png(BlobStore& blobs, const std::string& what,
                     std::function<Result<ImageRGBA8>()> make) {
  const std::string key = hex_key(hash_bytes(what.data(), what.size(), 1469598103934665603ull));
  return blobs.put_lazy(key, "image/png", [make = std::move(make), level = blobs.png_level] {
    Result<ImageRGBA8> image = make();
    return image ? encode_view_png(*image, level, true) : std::vector<std::uint8_t>();
  });
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

/// The references of levels 1.. of image `index`'s chain: the input prepared as
/// compress_images prepares it (resampled, premultiplied, mip-filtered, bled), level 0 being
/// `made.sources[index]`.
Result<std::vector<ImageRGBA8>> reference_chain(const ImageRGBA8& input,
                                                const texture_file::CompressOptions& o,
                                                const texture_file::CompressedImage& made,
                                                std::size_t index) {
  const int levels = made.texture.level_count();
  if (levels <= 1) return std::vector<ImageRGBA8>{made.sources[index]};
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
  (*chain)[0] = made.sources[index];
  return chain;
}

/// One image of a result: texels, decoded texels, metrics (also in `comparison` when given) and
/// heatmaps (made when first asked for). The PNGs are made while the metrics are measured;
/// `step` (may be empty) hears 0.5 when the metrics are done. With `pvr_file` (the key of the
/// result's .pvr blob) the page decodes the texels from it: no PNG of `decoded` is made.
Result<nlohmann::json> image_json(const ImageRGBA8* reference, const ImageRGBA8& decoded, int level,
                                  int layer, int face, bool normal_map, bool premultiplied,
                                  int threads, BlobStore& blobs, const std::string& pvr_file,
                                  metrics::ImageComparison* comparison = nullptr,
                                  const std::function<void(double)>& step = {}) {
  const PvrImage pvr{pvr_file, level, layer, face};
  std::future<std::string> dec =
      std::async(pvr_file.empty() ? std::launch::async : std::launch::deferred,
                 [&] { return pvr_file.empty() ? put_png(blobs, decoded) : pvr.key(); });
  nlohmann::json j = {{"level", level},
                      {"layer", layer},
                      {"face", face},
                      {"width", decoded.width},
                      {"height", decoded.height}};
  if (!reference) {
    j["decoded"] = dec.get();
    return j;
  }
  std::future<std::string> orig =
      std::async(std::launch::async, [&] { return put_original(blobs, *reference); });
  metrics::CompareOptions co;
  co.threads = threads;
  co.premultiplied = reference->has_alpha || decoded.has_alpha;
  co.normal = normal_map;
  Result<metrics::ImageComparison> c = metrics::compare_images(*reference, decoded, co);
  if (step) step(0.5);  // measured; the PNGs may still be under way
  const std::string d = dec.get(), o = orig.get();
  if (!c) return c.status();
  if (comparison) *comparison = *c;
  j["decoded"] = d;
  j["original"] = o;
  j["metrics"] = metrics_json(*c);
  j["alpha"] = co.premultiplied;  // whether the difference heatmap counts alpha (the page's)
  // The heatmaps read the two images back from their PNGs (exact), the decoded one from the
  // .pvr when it has one, when asked for: a result holds no image for them meanwhile.
  const Texels ref_texels{&blobs, o, reference->has_alpha, {}};
  const Texels dec_texels{&blobs, d, decoded.has_alpha, pvr};
  j["heatmap"] = lazy_png(blobs, "heatmap " + o + " " + d, [=]() -> Result<ImageRGBA8> {
    Result<ImageRGBA8> a = ref_texels.read(), b = dec_texels.read();
    if (!a || !b) return !a ? a.status() : b.status();
    return metrics::difference_heatmap(*a, *b, kDiffScale);
  });
  if (co.premultiplied && !premultiplied) {
    // What blending shows: the same heatmap over colour x alpha (colour under alpha 0 counts
    // for nothing), where --alpha-weighted's gains are seen.
    j["heatmap_premultiplied"] =
        lazy_png(blobs, "heatmap_premultiplied " + o + " " + d, [=]() -> Result<ImageRGBA8> {
          Result<ImageRGBA8> a = ref_texels.read(), b = dec_texels.read();
          if (!a || !b) return !a ? a.status() : b.status();
          image::premultiply_alpha(*a, false, {threads});
          image::premultiply_alpha(*b, false, {threads});
          return metrics::difference_heatmap(*a, *b, kDiffScale);
        });
  }
  if (normal_map) {
    j["angle_map"] = lazy_png(blobs, "angle_map " + o + " " + d, [=]() -> Result<ImageRGBA8> {
      Result<ImageRGBA8> a = ref_texels.read(), b = dec_texels.read();
      if (!a || !b) return !a ? a.status() : b.status();
      return metrics::heatmap(angle_map(*a, *b), b->width, b->height, kAngleScale);
    });
  }
  return j;
}

/// The share of a view encode's time the encoder itself takes (the rest: decoding, measuring,
/// PNGs), by quality: what the job's fraction gives the encode.
double encode_share(const ViewSettings& s) {
  return s.quality == "fast" ? 0.2 : s.quality == "normal" ? 0.6 : 0.9;
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

}  // namespace

Result<nlohmann::json> encode_view_result(const ViewInput& input, const ViewSettings& settings,
                                          int threads, BlobStore& blobs,
                                          const std::function<void(double)>& progress) {
  if (input.is_texture || !input.error.empty()) {
    return Status::error(ErrorCode::invalid_argument, input.name + ": not an image to encode");
  }
  const std::string output = view_output_name(input);
  const std::vector<std::string> sources = view_sources(input);
  const texture_file::TextureShape shape =
      input.images.empty() ? texture_file::TextureShape{} : input.shape;
  CompressArgs args = compress_args(settings, sources, output, shape);
  if (std::string p = compress_usage_problem(args, "pvr"); !p.empty()) {
    return Status::error(ErrorCode::invalid_argument, p);
  }
  Result<texture_file::CompressOptions> checked = compress_options(args, threads);
  if (!checked) return checked.status();
  texture_file::CompressOptions options = std::move(*checked);
  // The job's fraction covers the whole job: the encode's own fraction scaled to its share,
  // then the steps after it; below 1 (the service says 1 when the job is done).
  const double share = encode_share(settings);
  auto report = [&](double f) {
    if (progress) progress(std::min(0.99, f));
  };
  if (progress) options.encode.progress = [&](double f) { report(share * f); };
  auto after = [&](double f) { report(share + (1.0 - share) * f); };
  const std::vector<ImageRGBA8> inputs = pair_references(input);
  std::vector<std::string> names;
  for (const std::string& p : sources) names.push_back(io::io_name(p));
  if (input.images.empty()) names = {input.name};
  Result<texture_file::CompressedImage> made =
      texture_file::compress_images(inputs, texture_shape(args), options, names);
  if (!made) {
    Status s = made.status();
    s.message = cli_option_names(s.message);
    return s;
  }
  const texture_file::CompressedTexture& tex = made->texture;
  Result<std::vector<std::uint8_t>> file =
      texture_file::serialise_texture(tex, texture_file::ContainerFormat::pvr3);
  if (!file) return file.status();
  const std::size_t file_bytes = file->size();
  const std::string file_key = blobs.put("application/octet-stream", std::move(*file));
  std::vector<std::vector<ImageRGBA8>> chains;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    Result<std::vector<ImageRGBA8>> refs = reference_chain(inputs[i], options, *made, i);
    if (!refs) return refs.status();
    chains.push_back(std::move(refs).value());
  }
  after(0.05);
  // One image (a 2D texture): its level 0 comparison below is measure_level0's; else measured
  // here over every face and layer.
  const bool single = tex.image_count() == 1;
  metrics::ImageComparison total;
  if (!single) {
    Result<metrics::ImageComparison> t = texture_file::measure_level0(tex, made->sources, threads);
    if (!t) return t.status();
    total = *t;
  }
  nlohmann::json images_json = nlohmann::json::array();
  double done = 0, all = 0;
  for (int level = 0; level < tex.level_count(); ++level) {
    all += double(tex.level_width(level)) * tex.level_height(level) * double(inputs.size());
  }
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const int layer = int(i) / tex.faces, face = int(i) % tex.faces;
    for (int level = 0; level < tex.level_count(); ++level) {
      // Within an image: decoded 20 %, measured 60 %, its PNGs done 100 %.
      const double pixels = double(tex.level_width(level)) * tex.level_height(level);
      auto step = [&](double f) { after(0.05 + 0.95 * (done + f * pixels) / all); };
      Result<ImageRGBA8> dec =
          texture_file::decode_texture_image(tex, level, layer, face, {threads});
      if (!dec) return dec.status();
      step(0.2);
      metrics::ImageComparison c;
      Result<nlohmann::json> im = image_json(
          &chains[i][std::size_t(level)], *dec, level, layer, face, settings.normal_map,
          tex.premultiplied, threads, blobs, file_key, &c, [&](double f) { step(0.2 + 0.8 * f); });
      if (!im) return im.status();
      if (level == 0 && single) {
        total.mse_rgb = c.mse_rgb;
        total.mse_alpha = c.mse_alpha;
        total.has_alpha = c.has_alpha;
        total.ssim_gray = c.ssim_gray;
        total.max_abs = c.max_abs;
        total.psnr_rgb = metrics::psnr_from_mse(total.mse_rgb);
        total.psnr_alpha = metrics::psnr_from_mse(total.mse_alpha);
      }
      images_json.push_back(std::move(im).value());
      done += pixels;
      after(0.05 + 0.95 * done / all);
    }
  }
  nlohmann::json j = {
      {"input", input.name},
      {"settings", settings_to_json(settings)},
      {"command", compress_command(settings, sources, output, shape)},  // the paths as typed
      {"texture", texture_json(tex)},
      {"file_name", output},
      {"file", file_key},
      {"bytes", file_bytes},
      {"encode_ms", made->encode_ms},
      {"resized", made->resized},
      {"metrics", metrics_json(total)},
      {"colour_bars", colour_bars(blobs)},
      {"images", std::move(images_json)}};
  if (made->resized) j["resized_from"] = {input.image.width, input.image.height};
  return j;
}

Result<nlohmann::json> texture_view_result(const ViewInput& input, int threads, BlobStore& blobs,
                                           const ImageRGBA8* reference) {
  return texture_view_result(
      input, threads, blobs,
      reference ? std::vector<ImageRGBA8>{*reference} : std::vector<ImageRGBA8>{});
}

Result<nlohmann::json> texture_view_result(const ViewInput& input, int threads, BlobStore& blobs,
                                           const std::vector<ImageRGBA8>& references) {
  if (!input.is_texture || !input.error.empty()) {
    return Status::error(ErrorCode::invalid_argument, input.name + ": not a texture");
  }
  const texture_file::CompressedTexture& tex = input.texture;
  const bool measured = !references.empty() && int(references.size()) == tex.image_count();
  const std::string file_key = blobs.put("application/octet-stream", input.file);
  // A .pvr is decoded in the page; the other containers' texels go as PNGs.
  const bool pvr =
      texture_file::detect_container(input.file) == texture_file::ContainerFormat::pvr3;
  nlohmann::json j = {{"input", input.name},
                      {"label", measured ? "file " + input.name : std::string()},
                      {"texture", texture_json(tex)},
                      {"file_name", input.name},
                      {"file", file_key},
                      {"bytes", input.file.size()},
                      {"colour_bars", colour_bars(blobs)},
                      {"images", nlohmann::json::array()}};
  for (int level = 0; level < tex.level_count(); ++level) {
    for (int layer = 0; layer < tex.layers; ++layer) {
      for (int face = 0; face < tex.faces; ++face) {
        Result<ImageRGBA8> dec =
            texture_file::decode_texture_image(tex, level, layer, face, {threads});
        if (!dec) return dec.status();
        const ImageRGBA8* ref =
            level == 0 && measured ? &references[std::size_t(layer * tex.faces + face)] : nullptr;
        Result<nlohmann::json> im =
            image_json(ref, *dec, level, layer, face, false, tex.premultiplied, threads, blobs,
                       pvr ? file_key : std::string());
        if (!im) return im.status();
        j["images"].push_back(std::move(im).value());
      }
    }
  }
  return j;
}

}  // namespace tessera::cli
