// Demo section: adaptive supersampling for deferred shading (Hollander, Boubekeur & Eisemann
// 2013) on the built-in scene — the 4x4 reference, the adaptive result, 1 sample per pixel and
// FXAA, with the sample-count heatmap and difference heatmaps (Figures 6a and 7).
#include "demo.h"
#include "plot.h"
#include "tessera/experiments.h"
#include "tessera/metrics.h"

namespace tessera::cli {

Status demo_aa_section(Report& report, const DemoOptions& options) {
  report.heading("Adaptive supersampling for deferred shading", "aa");
  report.paragraph(
      "The built-in scene rendered into a 4x4 enlarged G-buffer (linear depth, normal, material, "
      "UV and UV derivatives per sample; albedo looked up at shading time, anisotropic 16x), "
      "then shaded with Blinn-Phong and 12 point lights: all 16 samples per pixel (the "
      "reference), one sample per pixel (plain deferred) plus FXAA 3.11 (preset 39), and "
      "adaptively: one sample per pixel first, then k more where the depth variance, the normal "
      "cone or the luminance range of the one-sample image asks for them (Hollander et al. "
      "2013). PSNR is against the reference; `tessera aa` runs the full experiment.");
  experiments::AaConfig c;
  c.width = 256;
  c.height = 192;
  c.ssaa = {4};
  c.frames = 1;
  c.lights = 8;
  c.threads = options.threads;
  Result<experiments::AaResult> res = experiments::run_aa(c);
  if (!res) return res.status();
  using experiments::AaMethod;
  const experiments::AaRateResult& rate = res->rates[0];
  const int w = c.width, h = c.height, m = rate.m;
  const ImageRGBA8& ref = rate.method(AaMethod::reference).image;
  const ImageRGBA8& adi = rate.method(AaMethod::adaptive).image;
  const ImageRGBA8& one = rate.method(AaMethod::default_1spp).image;
  const ImageRGBA8& fx = rate.method(AaMethod::fxaa).image;
  std::vector<float> counts(rate.adaptive_samples.begin(), rate.adaptive_samples.end());
  Result<ImageRGBA8> d_ref = metrics::difference_heatmap(ref, adi, 32.0f);
  Result<ImageRGBA8> d_one = metrics::difference_heatmap(one, adi, 32.0f);
  if (!d_ref) return d_ref.status();
  if (!d_one) return d_one.status();
  struct Item {
    const char* name;
    const char* caption;
    const ImageRGBA8* image;
  };
  const ImageRGBA8 heat = metrics::heatmap(counts, w, h, float(m * m));
  const Item items[] = {
      {"aa-reference", "4x4 reference (16 samples/pixel)", &ref},
      {"aa-adaptive", "adaptive", &adi},
      {"aa-samples", "samples per pixel (1..16, Fig. 6a)", &heat},
      {"aa-diff-ref", "|adaptive - reference| (max abs channel difference)", &*d_ref},
      {"aa-default", "1 sample/pixel", &one},
      {"aa-fxaa", "1 sample/pixel + FXAA", &fx},
      {"aa-diff-1x", "|adaptive - 1 sample| (max abs channel difference)", &*d_one}};
  std::vector<Figure> row1, row2, zoom;
  for (std::size_t i = 0; i < std::size(items); ++i) {
    std::string p;
    if (Status s = report.save_image(items[i].name, *items[i].image, p); !s.ok()) return s;
    (i < 4 ? row1 : row2).push_back({p, items[i].caption});
    if (i == 0 || i == 1 || i == 4 || i == 5) {
      // Thin poles and a box edge: 48x36 pixels at 4x.
      if (Status s = report.save_image(std::string(items[i].name) + "-zoom",
                                       crop(*items[i].image, 40, 90, 48, 36), p);
          !s.ok()) {
        return s;
      }
      zoom.push_back({p, std::string(items[i].caption) + " (zoom)"});
    }
  }
  report.figures(row1, 1);
  report.figures(row2, 1);
  {
    std::string kbar, dbar;
    if (Status s = report.save_svg(
            "aa-samples-colourbar",
            colour_bar_svg(metrics::ColourMap::inferno, 0, m * m, m * m / 4 + 1,
                           "samples shaded per pixel (1 + k; " + std::to_string(m * m) +
                               " = every sample of the " + std::to_string(m) + "x" +
                               std::to_string(m) + " window)"),
            kbar);
        !s.ok()) {
      return s;
    }
    if (Status s = report.save_svg("aa-diff-colourbar",
                                   colour_bar_svg(metrics::ColourMap::inferno, 0, 32, 5,
                                                  "max abs channel difference (8-bit levels; "
                                                  "32 and above saturate)"),
                                   dbar);
        !s.ok()) {
      return s;
    }
    report.figures({{kbar, "colour bar of the samples map"}, {dbar, "colour bar of the diffs"}});
  }
  report.figures(zoom, 4);
  std::vector<std::vector<std::string>> rows;
  for (AaMethod k :
       {AaMethod::reference, AaMethod::adaptive, AaMethod::default_1spp, AaMethod::fxaa}) {
    static const char* const labels[] = {"1 sample/pixel", "1 sample/pixel + FXAA", "reference",
                                         "adaptive"};
    const experiments::AaMethodResult& r = rate.method(k);
    if (options.summary) {
      (*options.summary)["aa"]["methods"].push_back(
          {{"method", labels[std::size_t(k)]},
           {"shading_ms", r.timing.normal.median_ms()},
           {"samples_pct", r.samples_pct},
           {"psnr_vs_reference",
            r.quality.identical() ? nlohmann::json(nullptr) : json_number(r.quality.psnr_db)},
           {"ssim_vs_reference", r.quality.ssim}});
    }
    rows.push_back({labels[std::size_t(k)], fmt("%.1f", r.timing.normal.median_ms()),
                    fmt("%.1f", r.samples_pct),
                    r.quality.identical() ? "(reference)" : fmt("%.2f", r.quality.psnr_db),
                    fmt("%.4f", r.quality.ssim)});
  }
  report.table({"method", "shading ms", "samples shaded %", "PSNR vs ref (dB)", "SSIM vs ref"},
               rows);
  if (options.summary) {
    (*options.summary)["aa"]["width"] = w;
    (*options.summary)["aa"]["height"] = h;
    (*options.summary)["aa"]["gbuffer_ms"] = rate.gbuffer.median_ms();
  }
  report.paragraph("G-buffer pass (" + std::to_string(w * m) + "x" + std::to_string(h * m) +
                   ", 11 floats per sample): " + fmt("%.1f", rate.gbuffer.median_ms()) + " ms.");
  return Status::success();
}

}  // namespace tessera::cli
