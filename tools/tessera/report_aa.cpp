// The reports of `tessera aa`: aa.json, aa.md (the paper's Table 1 with our columns, Figures
// 6a, 7 and 8 analogues) and every image and heatmap as PNG.
#include "report_aa.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "plot.h"
#include "tessera/io.h"
#include "tessera/metrics.h"

namespace tessera::cli {

namespace {

namespace fs = std::filesystem;
using experiments::AaMethod;
using experiments::AaQuality;
using experiments::AaRateResult;
using experiments::AaTiming;

std::string jnum(double v, const char* f = "%.3f") {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

nlohmann::json quality_json(const AaQuality& q) {
  return {{"mse_8bit", q.mse},
          {"mse_unit_e5", q.mse / (255.0 * 255.0) * 1e5},
          {"psnr_db", q.identical() ? nlohmann::json(nullptr) : nlohmann::json(q.psnr_db)}};
}

/// MSE (8-bit), MSE x 1e-5 on [0, 1], PSNR ("∞" when identical).
std::string qs(const AaQuality& q, int what) {
  if (what == 0) return jnum(q.mse, "%.3f");
  if (what == 1) return jnum(q.mse / (255.0 * 255.0) * 1e5, "%.2f");
  return q.identical() ? std::string("∞") : jnum(q.psnr_db, "%.2f");
}

Status write_text(const fs::path& path, const std::string& text) {
  return write_file_atomic(path.string(),
                           {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
}

/// The images of one rate (reference, adaptive, 1 spp, FXAA, sample counts, difference
/// heatmaps, ablations) as DIR/NAME-mxm.png; `jimages` maps each name to its file.
Status write_rate_images(const experiments::AaConfig& c, const AaRateResult& rate,
                         const std::string& dir, nlohmann::json& jimages) {
  const std::string r = std::to_string(rate.m) + "x" + std::to_string(rate.m);
  const int n = rate.m * rate.m;
  auto samples_map = [&](const std::vector<std::uint8_t>& s) {
    std::vector<float> v(s.begin(), s.end());
    return heatmap(v, c.width, c.height, float(n));
  };
  const ImageRGBA8& ref = rate.method(AaMethod::reference).image;
  const ImageRGBA8& ad = rate.method(AaMethod::adaptive).image;
  const ImageRGBA8& def = rate.method(AaMethod::default_1spp).image;
  const ImageRGBA8& fx = rate.method(AaMethod::fxaa).image;
  const ImageRGBA8& geo = rate.ablation_geometry.image;
  const ImageRGBA8& shd = rate.ablation_shading.image;
  struct Out {
    std::string name;
    Result<ImageRGBA8> image;
  };
  std::vector<Out> outs;
  outs.push_back({"reference-" + r, ref});
  outs.push_back({"adaptive-" + r, ad});
  outs.push_back({"default-" + r, def});
  outs.push_back({"fxaa-" + r, fx});
  outs.push_back({"samples-" + r, samples_map(rate.adaptive_samples)});
  outs.push_back({"diff-ref-" + r, difference_heatmap(ref, ad, 32.0f)});
  outs.push_back({"diff-1x-" + r, difference_heatmap(def, ad, 32.0f)});
  outs.push_back({"diff-ref-default-" + r, difference_heatmap(ref, def, 32.0f)});
  outs.push_back({"diff-ref-fxaa-" + r, difference_heatmap(ref, fx, 32.0f)});
  outs.push_back({"ablation-geometry-" + r, geo});
  outs.push_back({"ablation-geometry-samples-" + r, samples_map(rate.ablation_geometry.samples)});
  outs.push_back({"ablation-geometry-diff-" + r, difference_heatmap(ref, geo, 32.0f)});
  outs.push_back({"ablation-shading-" + r, shd});
  outs.push_back({"ablation-shading-samples-" + r, samples_map(rate.ablation_shading.samples)});
  outs.push_back({"ablation-shading-diff-" + r, difference_heatmap(ref, shd, 32.0f)});
  // Colour bars: the samples maps (1 + k of m*m) and the difference heatmaps.
  const std::string kbar = "samples-colourbar-" + r + ".svg";
  if (Status s = write_text(fs::path(dir) / kbar,
                            colour_bar_svg(ColorMap::inferno, 0, n, n / 4 + 1,
                                           "samples shaded per pixel (1 + k of " +
                                               std::to_string(n) + ")"));
      !s.ok()) {
    return s;
  }
  jimages["samples-colourbar-" + r] = kbar;
  if (Status s = write_text(fs::path(dir) / "diff-colourbar.svg",
                            colour_bar_svg(ColorMap::inferno, 0, 32, 5,
                                           "max abs channel difference (8-bit levels; 32 and "
                                           "above saturate)"));
      !s.ok()) {
    return s;
  }
  jimages["diff-colourbar"] = "diff-colourbar.svg";
  for (const Out& o : outs) {
    if (!o.image) return o.image.status();
    if (Status s = write_png((fs::path(dir) / (o.name + ".png")).string(), *o.image); !s.ok()) {
      return s;
    }
    jimages[o.name] = o.name + ".png";
  }
  return Status::success();
}

/// Markdown table rows and JSON of the rates; `row` formats one table row.
class Tables {
 public:
  explicit Tables(bool heavy) : heavy_(heavy) {}

  void row(const std::string& rate, const std::string& method, double gbuf, const AaTiming& t,
           const std::string& mse, const std::string& mse5, const std::string& psnr,
           const std::string& pct) {
    const bool timed = !t.normal.frame_ms.empty();
    const bool timed_heavy = heavy_ && !t.heavy.frame_ms.empty();
    const std::string dash = "—";
    const double sn = t.normal.median_ms(), sh = t.heavy.median_ms();
    rows += "| " + rate + " | " + method + " | " + (timed ? jnum(gbuf + sn, "%.1f") : dash) +
            " | " + (timed_heavy ? jnum(gbuf + sh, "%.1f") : dash) + " | " +
            (timed ? jnum(sn, "%.1f") : dash) + " | " + (timed_heavy ? jnum(sh, "%.1f") : dash) +
            " | " + mse + " | " + mse5 + " | " + psnr + " | " + pct + " |\n";
  }

  std::string rows;

 private:
  bool heavy_;
};

nlohmann::json rate_json(const experiments::AaConfig& c, const AaRateResult& rate,
                         nlohmann::json jimages) {
  const double gms = rate.gbuffer.median_ms();
  auto method_json = [&](AaMethod k, bool with_quality) {
    const experiments::AaMethodResult& mr = rate.method(k);
    nlohmann::json j = {{"shade_ms", mr.timing.normal.median_ms()},
                        {"frame_ms", gms + mr.timing.normal.median_ms()},
                        {"shade_ms_frames", mr.timing.normal.frame_ms},
                        {"samples_pct", mr.samples_pct}};
    if (c.heavy) {
      j["shade_ms_heavy"] = mr.timing.heavy.median_ms();
      j["frame_ms_heavy"] = gms + mr.timing.heavy.median_ms();
      j["shade_ms_heavy_frames"] = mr.timing.heavy.frame_ms;
    }
    if (with_quality) j["quality"] = quality_json(mr.quality);
    return j;
  };
  const AaTiming& tr = rate.method(AaMethod::reference).timing;
  const AaTiming& ta = rate.method(AaMethod::adaptive).timing;
  nlohmann::json jr = {
      {"m", rate.m},
      {"gbuffer_ms", gms},
      {"gbuffer_ms_frames", rate.gbuffer.frame_ms},
      {"default", method_json(AaMethod::default_1spp, true)},
      {"fxaa", method_json(AaMethod::fxaa, true)},
      {"reference", method_json(AaMethod::reference, false)},
      {"adaptive", method_json(AaMethod::adaptive, true)},
      {"adaptive_passes_ms",
       {{"first", rate.adaptive_first.median_ms()},
        {"metric", rate.adaptive_metric.median_ms()},
        {"rest", rate.adaptive_rest.median_ms()}}},
      {"adaptive_extra_albedo_lookups_pct", rate.adaptive_extra_albedo_lookups_pct},
      {"speedup_frame", (gms + tr.normal.median_ms()) / (gms + ta.normal.median_ms())},
      {"speedup_shading", tr.normal.median_ms() / ta.normal.median_ms()},
      {"ablation_geometry",
       {{"samples_pct", rate.ablation_geometry.samples_pct},
        {"quality", quality_json(rate.ablation_geometry.quality)}}},
      {"ablation_shading",
       {{"samples_pct", rate.ablation_shading.samples_pct},
        {"quality", quality_json(rate.ablation_shading.quality)}}},
      {"images", std::move(jimages)}};
  if (c.heavy) {
    jr["speedup_frame_heavy"] = (gms + tr.heavy.median_ms()) / (gms + ta.heavy.median_ms());
    jr["speedup_shading_heavy"] = tr.heavy.median_ms() / ta.heavy.median_ms();
    jr["adaptive_heavy_quality"] = quality_json(rate.adaptive_heavy_quality);
    jr["adaptive_heavy_samples_pct"] = rate.adaptive_heavy_samples_pct;
  }
  return jr;
}

/// The Figure 6a/7/8 block of one rate.
std::string figure_md(const experiments::AaConfig& c, const AaRateResult& rate,
                      const nlohmann::json& jr) {
  const std::string r = std::to_string(rate.m) + "x" + std::to_string(rate.m);
  const std::string rl = std::to_string(rate.m) + "×" + std::to_string(rate.m);
  std::string md = "\n### " + rl + "\n\n";
  md += "Speed-up of adaptive over the reference: frame " +
        jnum(jr["speedup_frame"].get<double>(), "%.2f") + "×, shading pass " +
        jnum(jr["speedup_shading"].get<double>(), "%.2f") + "×";
  if (c.heavy) {
    md += "; heavy: frame " + jnum(jr["speedup_frame_heavy"].get<double>(), "%.2f") +
          "×, shading pass " + jnum(jr["speedup_shading_heavy"].get<double>(), "%.2f") +
          "× (heavy adaptive vs heavy reference: PSNR " + qs(rate.adaptive_heavy_quality, 2) +
          " dB)";
  }
  md += ".\n\n";
  md +=
      "| reference | adaptive | samples (Fig. 6a) | diff vs reference | diff vs 1× |\n"
      "|---|---|---|---|---|\n";
  md += "| ![](reference-" + r + ".png) | ![](adaptive-" + r + ".png) | ![](samples-" + r +
        ".png) | ![](diff-ref-" + r + ".png) | ![](diff-1x-" + r + ".png) |\n\n";
  md += "Samples map: ![](samples-colourbar-" + r + ".svg) Differences: ![](diff-colourbar.svg)"
        "\n\n";
  md +=
      "Figure 8 analogue: | 1 spp | FXAA | geometry only: samples, diff | shading only: "
      "samples, diff |\n\n";
  md += "| ![](default-" + r + ".png) ![](diff-ref-default-" + r + ".png) | ![](fxaa-" + r +
        ".png) ![](diff-ref-fxaa-" + r + ".png) | ![](ablation-geometry-samples-" + r +
        ".png) ![](ablation-geometry-diff-" + r + ".png) | ![](ablation-shading-samples-" + r +
        ".png) ![](ablation-shading-diff-" + r + ".png) |\n|---|---|---|---|\n";
  return md;
}

}  // namespace

Status write_aa_report(const experiments::AaConfig& c, const experiments::AaResult& res,
                       const std::string& scene_label, const std::string& dir,
                       std::string* markdown) {
  Tables tables(c.heavy);
  const double g1 = res.gbuffer_1x1.median_ms();
  tables.row("1×1", "Default", g1, res.default_1x1, "–", "–", "–", "–");
  tables.row("1×1", "FXAA", g1, res.fxaa_1x1, "–", "–", "–", "–");
  const nlohmann::json j1 = {{"gbuffer_ms", g1},
                             {"default",
                              {{"shade_ms", res.default_1x1.normal.median_ms()},
                               {"shade_ms_heavy", res.default_1x1.heavy.median_ms()}}},
                             {"fxaa",
                              {{"shade_ms", res.fxaa_1x1.normal.median_ms()},
                               {"shade_ms_heavy", res.fxaa_1x1.heavy.median_ms()}}}};
  nlohmann::json jrates = nlohmann::json::array();
  std::string md_fig;
  for (const AaRateResult& rate : res.rates) {
    nlohmann::json jimages = nlohmann::json::object();
    if (Status s = write_rate_images(c, rate, dir, jimages); !s.ok()) return s;
    const nlohmann::json jr = rate_json(c, rate, std::move(jimages));
    jrates.push_back(jr);
    const std::string rl = std::to_string(rate.m) + "×" + std::to_string(rate.m);
    const double gms = rate.gbuffer.median_ms();
    const std::string one = jnum(100.0 / (rate.m * rate.m), "%.1f");
    const AaQuality& q_def = rate.method(AaMethod::default_1spp).quality;
    const AaQuality& q_fx = rate.method(AaMethod::fxaa).quality;
    const AaQuality& q_ad = rate.method(AaMethod::adaptive).quality;
    const AaQuality& q_geo = rate.ablation_geometry.quality;
    const AaQuality& q_shd = rate.ablation_shading.quality;
    tables.row(rl, "Default (1 spp)", gms, rate.method(AaMethod::default_1spp).timing, qs(q_def, 0),
               qs(q_def, 1), qs(q_def, 2), one);
    tables.row(rl, "FXAA", gms, rate.method(AaMethod::fxaa).timing, qs(q_fx, 0), qs(q_fx, 1),
               qs(q_fx, 2), one);
    tables.row(rl, "Reference", gms, rate.method(AaMethod::reference).timing, "–", "–", "–", "100");
    tables.row(rl, "Adaptive", gms, rate.method(AaMethod::adaptive).timing, qs(q_ad, 0),
               qs(q_ad, 1), qs(q_ad, 2), jnum(rate.method(AaMethod::adaptive).samples_pct, "%.1f"));
    tables.row(rl, "Adaptive, geometry only", gms, {}, qs(q_geo, 0), qs(q_geo, 1), qs(q_geo, 2),
               jnum(rate.ablation_geometry.samples_pct, "%.1f"));
    tables.row(rl, "Adaptive, shading only", gms, {}, qs(q_shd, 0), qs(q_shd, 1), qs(q_shd, 2),
               jnum(rate.ablation_shading.samples_pct, "%.1f"));
    md_fig += figure_md(c, rate, jr);
  }

  const deferred::AdaptiveOptions& a = c.adaptive;
  const nlohmann::json j = {
      {"scene", scene_label},
      {"width", c.width},
      {"height", c.height},
      {"threads", res.threads},
      {"frames", c.frames},
      {"heavy", c.heavy},
      {"heavy_terms", res.heavy_terms},
      {"lights", res.lights},
      {"fxaa_preset", c.fxaa_preset},
      {"adaptive_options",
       {{"c_depth", a.c_depth},
        {"c_normal", a.c_normal},
        {"c_shade", a.c_shade},
        {"t_min", a.t_min},
        {"t_edge", a.t_edge},
        {"seam_factor", a.seam_factor}}},
      {"gbuffer_depth", "linear view depth"},
      {"one_sample_per_pixel", "first sample of the window in index-matrix order"},
      {"rate_1x1", j1},
      {"rates", jrates}};
  std::string md;
  md += "# Adaptive supersampling for deferred shading — `tessera aa`\n\n";
  md += "Scene `" + scene_label + "`, " + std::to_string(c.width) + "×" + std::to_string(c.height) +
        ", " + std::to_string(res.lights) + " point lights, " + std::to_string(res.threads) +
        " thread(s), median of " + std::to_string(c.frames) +
        " frame(s), methods alternated per frame. FXAA 3.11 preset " +
        std::to_string(c.fxaa_preset) + ". Heavy mode: " +
        (c.heavy ? std::to_string(res.heavy_terms) + " sinusoid terms per shaded sample"
                 : std::string("not run")) +
        ".\n\n";
  md +=
      "ms/frame = G-buffer pass + shading pass (+ FXAA); the G-buffer pass is shared by all "
      "methods of a rate and timed once per frame. MSE on 8-bit RGB and, like the paper, "
      "×10⁻⁵ on [0, 1]; PSNR against the reference at the same rate. Samples % of the "
      "reference's shaded samples.\n\n";
  md +=
      "| rate | method | ms/frame | heavy ms/frame | shading ms | heavy shading ms | MSE (8-bit) | "
      "MSE (×10⁻⁵) | PSNR dB | samples % |\n|---|---|---|---|---|---|---|---|---|---|\n";
  md += tables.rows;
  md += md_fig;
  if (Status s = write_text(fs::path(dir) / "aa.json", j.dump(2) + "\n"); !s.ok()) return s;
  if (Status s = write_text(fs::path(dir) / "aa.md", md); !s.ok()) return s;
  if (markdown) *markdown = std::move(md);
  return Status::success();
}

}  // namespace tessera::cli
