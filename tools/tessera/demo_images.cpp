// Demo section: procedural content and the quality metrics every later section uses.
#include <cmath>
#include <cstdio>

#include "demo.h"
#include "plot.h"
#include "tessera/metrics.h"
#include "tessera/procedural.h"

namespace tessera::cli {

namespace {

/// 2x2 box downsample in linear light followed by nearest upsampling: a known, visible loss
/// to show what the metrics report.
ImageRGBA8 half_resolution(const ImageRGBA8& img, int threads) {
  const ImageRGBAF lin = to_linear(img, {threads});
  ImageRGBAF out(img.width, img.height);
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const int x0 = x & ~1, y0 = y & ~1;
      for (int c = 0; c < 4; ++c) {
        float s = 0.0f;
        for (int dy = 0; dy < 2; ++dy) {
          for (int dx = 0; dx < 2; ++dx) {
            s += lin.at(std::min(x0 + dx, img.width - 1), std::min(y0 + dy, img.height - 1))[c];
          }
        }
        out.at(x, y)[c] = s * 0.25f;
      }
    }
  }
  ImageRGBA8 r = to_srgb8(out, {threads});
  r.has_alpha = img.has_alpha;
  return r;
}
}  // namespace

Status demo_images_section(Report& report, const DemoOptions& options) {
  report.heading("Images and metrics");
  report.paragraph(
      "Built-in procedural content (deterministic, generated in code). Each image is reduced to "
      "half resolution (2x2 box filter in linear light, nearest upsampling) to show the metrics "
      "every later section uses: PSNR over RGB (peak 255), SSIM on Rec.709 grey (Wang et al. "
      "2004, 11x11 Gaussian window, sigma 1.5, valid region), a difference heatmap (max "
      "absolute channel difference, inferno colour map, saturating at 64) and the local SSIM "
      "loss behind the SSIM score (1 - SSIM of each 11x11 window, viridis; the map is 10 "
      "pixels smaller than the image, the valid region). Colour bars with units are below the "
      "images.");
  std::vector<std::vector<std::string>> rows;
  for (Procedural kind : all_procedurals()) {
    const std::string name = procedural_name(kind);
    const ImageRGBA8 img = make_procedural(kind, options.size, options.size);
    const ImageRGBA8 half = half_resolution(img, options.threads);
    metrics::CompareOptions co;
    co.threads = options.threads;
    Result<metrics::ImageComparison> cmp = metrics::compare_images(img, half, co);
    if (!cmp) return cmp.status();
    Result<ImageRGBA8> heat = metrics::difference_heatmap(img, half);
    if (!heat) return heat.status();
    std::string p0, p1, p2;
    if (Status s = report.save_image("images-" + name, img, p0); !s.ok()) return s;
    if (Status s = report.save_image("images-" + name + "-half", half, p1); !s.ok()) return s;
    if (Status s = report.save_image("images-" + name + "-diff", *heat, p2); !s.ok()) return s;
    std::vector<Figure> row = {{p0, name + (img.has_alpha ? " (RGBA)" : " (RGB)")},
                               {p1, "half resolution"},
                               {p2, "difference: colour bar below"}};
    if (img.width > 10 && img.height > 10) {
      // The local SSIM loss: where the SSIM score loses (the valid region of the windows).
      metrics::SsimOptions so;
      so.threads = options.threads;
      std::vector<float> loss = metrics::ssim_map(metrics::luma709(img), metrics::luma709(half),
                                                  img.width, img.height, so);
      for (float& v : loss) v = 1.0f - v;
      std::string p3;
      if (Status s = report.save_image("images-" + name + "-ssim",
                                       metrics::heatmap(loss, img.width - 10, img.height - 10, 1.0f,
                                                        metrics::ColourMap::viridis),
                                       p3);
          !s.ok()) {
        return s;
      }
      row.push_back({p3, "1 - local SSIM: colour bar below"});
    }
    report.figures(row);
    if (options.summary) {
      nlohmann::json j = {{"image", name},
                          {"psnr_rgb", json_number(cmp->psnr_rgb)},
                          {"ssim_gray", cmp->ssim_gray},
                          {"max_abs", cmp->max_abs}};
      if (cmp->has_alpha) j["psnr_alpha"] = json_number(cmp->psnr_alpha);
      (*options.summary)["images"].push_back(j);
    }
    rows.push_back({name, fmt("%.2f", cmp->psnr_rgb),
                    cmp->has_alpha ? fmt("%.2f", cmp->psnr_alpha) : "-",
                    fmt("%.4f", cmp->ssim_gray), std::to_string(cmp->max_abs)});
  }
  {
    std::string diff_bar, ssim_bar;
    if (Status s = report.save_svg("images-diff-colourbar",
                                   colour_bar_svg(metrics::ColourMap::inferno, 0, 64, 5,
                                                  "max abs channel difference (8-bit levels; "
                                                  "64 and above saturate)"),
                                   diff_bar);
        !s.ok()) {
      return s;
    }
    if (Status s = report.save_svg("images-ssim-colourbar",
                                   colour_bar_svg(metrics::ColourMap::viridis, 0, 1, 5,
                                                  "1 - local SSIM (Rec.709 grey, 11x11 window; "
                                                  "unitless: 0 = identical, 1 and above "
                                                  "saturate)"),
                                   ssim_bar);
        !s.ok()) {
      return s;
    }
    report.figures({{diff_bar, "Colour bar of the difference heatmaps"},
                    {ssim_bar, "Colour bar of the local SSIM maps"}});
  }
  report.table({"image", "PSNR RGB (dB)", "PSNR alpha (dB)", "SSIM grey", "max abs"}, rows);
  return Status::success();
}

}  // namespace tessera::cli
