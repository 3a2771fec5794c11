// Demo section: PVRTC1 compression of the procedural images at every quality, with metrics,
// encode times, difference heatmaps, zoomed crops and a gamma-correct mip chain.
#include <chrono>
#include <cmath>
#include <cstdio>

#include "demo.h"
#include "plot.h"
#include "tessera/image_mipmap.h"
#include "tessera/metrics.h"
#include "tessera/procedural.h"
#include "tessera/pvrtc.h"
#include "tessera/texture_file.h"

namespace tessera::cli {

namespace {

std::string db(double v) { return std::isfinite(v) ? fmt("%.2f", v) : "inf"; }

struct Variant {
  const char* label;
  const char* key;
  pvrtc::Format format;
  pvrtc::Quality quality;
};

constexpr Variant kVariants[] = {
    {"4bpp fast", "4-fast", pvrtc::Format::pvrtc1_4bpp, pvrtc::Quality::fast},
    {"4bpp normal", "4-normal", pvrtc::Format::pvrtc1_4bpp, pvrtc::Quality::normal},
    {"4bpp high", "4-high", pvrtc::Format::pvrtc1_4bpp, pvrtc::Quality::high},
    {"2bpp normal", "2-normal", pvrtc::Format::pvrtc1_2bpp, pvrtc::Quality::normal},
};

struct Encoded {
  ImageRGBA8 decoded;
  double ms = 0;
};

Result<Encoded> encode_decode(const ImageRGBA8& img, const Variant& v, int threads) {
  pvrtc::EncodeOptions eo;
  eo.format = v.format;
  eo.quality = v.quality;
  eo.threads = threads;
  const auto t0 = std::chrono::steady_clock::now();
  Result<std::vector<std::uint8_t>> data = pvrtc::encode(img, eo);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (!data) return data.status();
  Result<ImageRGBA8> dec = pvrtc::decode(*data, v.format, img.width, img.height, {threads});
  if (!dec) return dec.status();
  if (!img.has_alpha) {
    for (std::size_t i = 3; i < dec->pixels.size(); i += 4) dec->pixels[i] = 255;
  }
  dec->has_alpha = img.has_alpha;
  return Encoded{std::move(dec).value(), ms};
}

/// A gamma-correct, alpha-weighted mip chain of the RGBA image (n x n), each level
/// PVRTC-compressed.
Status demo_pvrtc_mips(Report& report, const DemoOptions& options, int n) {
  const ImageRGBA8 foliage = make_procedural(Procedural::foliage, n, n);
  image::MipmapOptions mo;
  mo.srgb = true;
  mo.max_levels = 5;
  mo.threads = options.threads;
  Result<std::vector<ImageRGBA8>> chain = image::generate_mipmaps(foliage, mo);
  if (!chain) return chain.status();
  std::vector<Figure> levels;
  for (std::size_t i = 1; i < chain->size(); ++i) {
    Result<Encoded> e = encode_decode((*chain)[i], kVariants[1], options.threads);
    if (!e) return e.status();
    std::string p;
    if (Status s = report.save_image("pvrtc-mip" + std::to_string(i), e->decoded, p); !s.ok()) {
      return s;
    }
    levels.push_back({p, "level " + std::to_string(i) + " (" + std::to_string((*chain)[i].width) +
                             "x" + std::to_string((*chain)[i].height) + ")"});
  }
  report.paragraph(
      "Mip levels 1-4 of the foliage texture (2x2 box filter in linear light, colour weighted "
      "by alpha so transparent texels do not darken the edges), each compressed at 4bpp normal "
      "as `tessera compress --mipmaps --srgb` does.");
  report.figures(levels);
  return Status::success();
}

}  // namespace

Status demo_pvrtc_section(Report& report, const DemoOptions& options) {
  report.heading("PVRTC1 compression", "pvrtc");
  report.paragraph(
      "Each procedural image is compressed to PVRTC1 at 4 bpp with the three encoder settings "
      "(fast = intensity dilation only, Krajcevski & Manocha 2014; normal and high add "
      "least-squares refinement of the block colours with brute-force modulation) and at 2 bpp, "
      "then decoded with tessera's PVRTexTool-exact decoder. PSNR is over RGB (peak 255), SSIM "
      "on Rec.709 grey; the heatmap shows the 4bpp-normal error (max absolute channel "
      "difference, saturating at 64). Crops are a 32x32 window from the centre at 4x zoom. "
      "Encode times are in-process wall times of this run.");
  std::vector<std::vector<std::string>> rows;
  // PVRTC needs power-of-two sides: a non-power-of-two --size is rounded to the nearest one,
  // and the report says so.
  const int n = image::nearest_power_of_two(options.size);
  if (n != options.size) {
    report.paragraph("The images of this section are " + std::to_string(n) + "x" +
                     std::to_string(n) + ", not " + std::to_string(options.size) + "x" +
                     std::to_string(options.size) +
                     " as --size asked: PVRTC needs power-of-two "
                     "sides, and " +
                     std::to_string(n) + " is the nearest power of two.");
  }
  std::vector<PvrtcDemoImage> saved;
  for (Procedural kind : all_procedurals()) {
    const std::string name = procedural_name(kind);
    const ImageRGBA8 img = make_procedural(kind, n, n);
    std::vector<Encoded> results;
    for (const Variant& v : kVariants) {
      Result<Encoded> e = encode_decode(img, v, options.threads);
      if (!e) return e.status();
      metrics::CompareOptions co;
      co.threads = options.threads;
      Result<metrics::ImageComparison> cmp = metrics::compare_images(img, e->decoded, co);
      if (!cmp) return cmp.status();
      if (options.summary) {
        nlohmann::json j = {{"image", name},
                            {"variant", v.label},
                            {"size", n},
                            {"psnr_rgb", json_number(cmp->psnr_rgb)},
                            {"ssim_gray", cmp->ssim_gray},
                            {"encode_ms", e->ms}};
        if (cmp->has_alpha) j["psnr_alpha"] = json_number(cmp->psnr_alpha);
        (*options.summary)["pvrtc"]["variants"].push_back(j);
      }
      rows.push_back({name, v.label, db(cmp->psnr_rgb), cmp->has_alpha ? db(cmp->psnr_alpha) : "-",
                      fmt("%.4f", cmp->ssim_gray), fmt("%.1f", e->ms)});
      results.push_back(std::move(e).value());
    }
    const ImageRGBA8& normal = results[1].decoded;
    Result<ImageRGBA8> heat = metrics::difference_heatmap(img, normal);
    if (!heat) return heat.status();
    std::string p_orig, p_norm, p_heat, p_2bpp;
    const std::string stem = "pvrtc-" + name;
    if (Status s = report.save_image(stem, img, p_orig); !s.ok()) return s;
    saved.push_back({name, report.dir() + "/" + p_orig, img, img.has_alpha});
    if (Status s = report.save_image(stem + "-4-normal", normal, p_norm); !s.ok()) return s;
    if (Status s = report.save_image(stem + "-4-normal-diff", *heat, p_heat); !s.ok()) return s;
    if (Status s = report.save_image(stem + "-2-normal", results[3].decoded, p_2bpp); !s.ok()) {
      return s;
    }
    report.figures({{p_orig, name + (img.has_alpha ? " (RGBA)" : " (RGB)")},
                    {p_norm, "PVRTC1 4bpp normal"},
                    {p_heat, "difference (4bpp normal): colour bar below"},
                    {p_2bpp, "PVRTC1 2bpp normal"}});
    const int c = std::min(32, n), x0 = (n - c) / 2, y0 = (n - c) / 2;
    std::vector<Figure> crops;
    std::string p;
    if (Status s = report.save_image(stem + "-crop", crop(img, x0, y0, c, c), p); !s.ok()) return s;
    crops.push_back({p, "original"});
    for (std::size_t i = 0; i < results.size(); ++i) {
      const std::string key = stem + "-crop-" + kVariants[i].key;
      if (Status s = report.save_image(key, crop(results[i].decoded, x0, y0, c, c), p); !s.ok()) {
        return s;
      }
      crops.push_back({p, kVariants[i].label});
    }
    report.figures(crops, 4);
  }
  {
    std::string bar;
    if (Status s = report.save_svg("pvrtc-diff-colourbar",
                                   colour_bar_svg(metrics::ColourMap::inferno, 0, 64, 5,
                                                  "max abs channel difference (8-bit levels; "
                                                  "64 and above saturate)"),
                                   bar);
        !s.ok()) {
      return s;
    }
    report.figures({{bar, "Colour bar of the difference heatmaps"}});
  }
  report.table({"image", "variant", "PSNR RGB (dB)", "PSNR alpha (dB)", "SSIM grey", "encode (ms)"},
               rows);
  if (Status s = demo_pvrtc_quality_time(report, options, saved); !s.ok()) return s;
  if (Status s = demo_pvrtc_view(report, options, saved); !s.ok()) return s;

  return demo_pvrtc_mips(report, options, n);
}

}  // namespace tessera::cli
