// Demo section: adaptive supersampling for deferred shading (Hollander, Boubekeur & Eisemann
// 2013) on the built-in scene — the 4x4 reference, the adaptive result, 1 sample per pixel and
// FXAA, with the sample-count heatmap and difference heatmaps (Figures 6a and 7).
#include <chrono>
#include <cmath>

#include "demo.h"
#include "tessera/deferred.h"
#include "tessera/metrics.h"

namespace tessera::cli {

Status demo_aa_section(Report& report, const DemoOptions& options) {
  report.heading("Adaptive supersampling for deferred shading");
  report.paragraph(
      "The built-in scene rendered into a 4x4 enlarged G-buffer (linear depth, normal, material, "
      "UV and UV derivatives per sample; albedo looked up at shading time, anisotropic 16x), "
      "then shaded with Blinn-Phong and 12 point lights: all 16 samples per pixel (the "
      "reference), one sample per pixel (plain deferred) plus FXAA 3.11 (preset 39), and "
      "adaptively: one sample per pixel first, then k more where the depth variance, the normal "
      "cone or the luminance range of the one-sample image asks for them (Hollander et al. "
      "2013). PSNR is against the reference; `tessera aa` runs the full experiment.");
  const scene::Scene sc = scene::builtin_scene();
  Result<std::unique_ptr<deferred::DeferredRenderer>> rr =
      deferred::DeferredRenderer::create(sc, options.threads);
  if (!rr) return rr.status();
  deferred::DeferredRenderer& renderer = **rr;
  const scene::Camera camera = scene::orbit_camera(sc, 1, 8);
  deferred::ShadingOptions shading = deferred::scene_shading(sc, 8, &camera);
  shading.threads = options.threads;
  const int w = 256, h = 192, m = 4;
  deferred::GBuffer gb;
  auto t0 = std::chrono::steady_clock::now();
  if (Status s = renderer.render_gbuffer(camera, w, h, m, gb); !s.ok()) return s;
  auto since = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
  };
  const double ms_gbuffer = since(t0);
  t0 = std::chrono::steady_clock::now();
  const ImageRGBA8 ref = to_srgb8(renderer.shade_reference(gb, shading), options.threads);
  const double ms_ref = since(t0);
  t0 = std::chrono::steady_clock::now();
  const ImageRGBA8 one = to_srgb8(renderer.shade_default(gb, shading), options.threads);
  const double ms_one = since(t0);
  deferred::FxaaOptions fo;
  fo.threads = options.threads;
  t0 = std::chrono::steady_clock::now();
  Result<ImageRGBA8> fx = deferred::fxaa(one, fo);
  if (!fx) return fx.status();
  const double ms_fx = ms_one + since(t0);
  t0 = std::chrono::steady_clock::now();
  const deferred::AdaptiveResult ad = renderer.shade_adaptive(gb, shading, {});
  const double ms_ad = since(t0);
  const ImageRGBA8 adi = to_srgb8(ad.image, options.threads);

  std::vector<float> counts(ad.samples.begin(), ad.samples.end());
  Result<ImageRGBA8> d_ref = difference_heatmap(ref, adi, 32.0f);
  Result<ImageRGBA8> d_one = difference_heatmap(one, adi, 32.0f);
  if (!d_ref) return d_ref.status();
  if (!d_one) return d_one.status();
  struct Item {
    const char* name;
    const char* caption;
    const ImageRGBA8* image;
  };
  const ImageRGBA8 heat = heatmap(counts, w, h, float(m * m));
  const Item items[] = {{"aa-reference", "4x4 reference (16 samples/pixel)", &ref},
                        {"aa-adaptive", "adaptive", &adi},
                        {"aa-samples", "samples per pixel (1..16, Fig. 6a)", &heat},
                        {"aa-diff-ref", "|adaptive - reference| (x8)", &*d_ref},
                        {"aa-default", "1 sample/pixel", &one},
                        {"aa-fxaa", "1 sample/pixel + FXAA", &*fx},
                        {"aa-diff-1x", "|adaptive - 1 sample| (x8)", &*d_one}};
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
  report.figures(zoom, 4);
  CompareOptions co;
  co.threads = options.threads;
  std::vector<std::vector<std::string>> rows;
  auto add = [&](const char* label, const ImageRGBA8& img, double ms, double pct) -> Status {
    Result<ImageComparison> c = compare_images(ref, img, co);
    if (!c) return c.status();
    rows.push_back({label, fmt("%.1f", ms), fmt("%.1f", pct),
                    std::isfinite(c->psnr_rgb) ? fmt("%.2f", c->psnr_rgb) : "(reference)",
                    fmt("%.4f", c->ssim_gray)});
    return Status::success();
  };
  const double total = double(w) * h * m * m;
  if (Status s = add("reference", ref, ms_ref, 100.0); !s.ok()) return s;
  if (Status s = add("adaptive", adi, ms_ad, 100.0 * double(ad.samples_shaded) / total); !s.ok()) {
    return s;
  }
  if (Status s = add("1 sample/pixel", one, ms_one, 100.0 / (m * m)); !s.ok()) return s;
  if (Status s = add("1 sample/pixel + FXAA", *fx, ms_fx, 100.0 / (m * m)); !s.ok()) return s;
  report.table({"method", "shading ms", "samples shaded %", "PSNR vs ref (dB)", "SSIM vs ref"},
               rows);
  report.paragraph("G-buffer pass (" + std::to_string(w * m) + "x" + std::to_string(h * m) +
                   ", 11 floats per sample): " + fmt("%.1f", ms_gbuffer) + " ms.");
  return Status::success();
}

}  // namespace tessera::cli
