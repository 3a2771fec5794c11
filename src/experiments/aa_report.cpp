// aa.json and aa.md of a `run_aa` result (tessera/experiments/aa.h): the paper's Table 1 with
// our columns, the Figures 6a, 7 and 8 analogues, per-pass times on GL and the GL-vs-CPU part of
// Backend::both; and the images `tessera aa` writes beside them (aa_rate_images). The key names
// are what users script against.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tessera/experiments/aa.h"
#include "tessera/metrics.h"

namespace tessera::experiments {

namespace {

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

/// GL only: the GPU-timer times and every pass's wall and GPU-timer medians of a method.
void add_gl_times(const AaConfig& c, const AaMethodResult& mr, nlohmann::json& j) {
  j["gpu_shade_ms"] = mr.timing.gpu.median_ms();
  j["gpu_shade_ms_frames"] = mr.timing.gpu.frame_ms;
  if (c.heavy) j["gpu_shade_ms_heavy"] = mr.timing.gpu_heavy.median_ms();
  nlohmann::json jp = nlohmann::json::object();
  for (const AaPassFrames& p : mr.passes) {
    jp[p.pass] = {{"wall_ms", p.wall.median_ms()}, {"gpu_ms", p.gpu.median_ms()}};
  }
  j["passes"] = jp;
}

nlohmann::json rate_json(const AaConfig& c, const AaRateResult& rate, bool gl,
                         nlohmann::json jimages, nlohmann::json jedge_images) {
  const double gms = rate.gbuffer.median_ms();
  auto method_json = [&](AaMethod k, bool with_quality) {
    const AaMethodResult& mr = rate.method(k);
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
    if (gl) add_gl_times(c, mr, j);
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
      {"edge_per_sample", method_json(AaMethod::edge_per_sample, true)},
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
  jr["edge_per_sample"]["images"] = std::move(jedge_images);
  if (gl) {
    jr["gbuffer_gpu_ms"] = rate.gbuffer_gpu.median_ms();
    jr["gbuffer_gpu_ms_frames"] = rate.gbuffer_gpu.frame_ms;
  }
  return jr;
}

/// The Figure 6a/7/8 block of one rate.
std::string figure_md(const AaConfig& c, const AaRateResult& rate, const nlohmann::json& jr) {
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
  md += "Samples map: ![](samples-colourbar-" + r +
        ".svg) Differences: ![](diff-colourbar.svg)"
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

/// A time for the pass tables: "–" where the GPU timer gave no result.
std::string ms_cell(double ms) { return std::isnan(ms) ? std::string("–") : jnum(ms, "%.2f"); }

/// The "images" maps of a rate's JSON: every file `tessera aa` writes for it, named with
/// `prefix` (the colour bars as SVG, the rest as PNG; aa_rate_images).
Status image_maps(const AaConfig& c, const AaRateResult& rate, const std::string& prefix,
                  nlohmann::json& jimages, nlohmann::json& jedge_images) {
  const std::string r = std::to_string(rate.m) + "x" + std::to_string(rate.m);
  jimages[prefix + "samples-colourbar-" + r] = prefix + "samples-colourbar-" + r + ".svg";
  jimages["diff-colourbar"] = "diff-colourbar.svg";
  Result<std::vector<AaRateImage>> names = aa_rate_images(c, rate, false);
  if (!names) return names.status();
  for (const AaRateImage& i : *names) {
    (i.edge_per_sample ? jedge_images : jimages)[prefix + i.name] = prefix + i.name + ".png";
  }
  return Status::success();
}

/// One backend's part of the reports: the table rows, the 1x1 and per-rate JSON, the figure
/// blocks (`figures`) and the rate images (file names prefixed with `prefix`).
struct BackendReport {
  Tables tables;
  nlohmann::json j1, jrates = nlohmann::json::array();
  std::string md_fig, md_passes;
};

Status backend_report(const AaConfig& c, const AaResult& res, const std::string& prefix,
                      bool figures, BackendReport& out) {
  const bool gl = gpu_primary(res.backend);
  Tables& tables = out.tables;
  const double g1 = res.gbuffer_1x1.median_ms();
  tables.row("1×1", "Default", g1, res.default_1x1, "–", "–", "–", "–");
  tables.row("1×1", "FXAA", g1, res.fxaa_1x1, "–", "–", "–", "–");
  out.j1 = {{"gbuffer_ms", g1},
            {"default",
             {{"shade_ms", res.default_1x1.normal.median_ms()},
              {"shade_ms_heavy", res.default_1x1.heavy.median_ms()}}},
            {"fxaa",
             {{"shade_ms", res.fxaa_1x1.normal.median_ms()},
              {"shade_ms_heavy", res.fxaa_1x1.heavy.median_ms()}}}};
  if (gl) {
    out.j1["gbuffer_gpu_ms"] = res.gbuffer_1x1_gpu.median_ms();
    out.j1["default"]["gpu_shade_ms"] = res.default_1x1.gpu.median_ms();
    out.j1["fxaa"]["gpu_shade_ms"] = res.fxaa_1x1.gpu.median_ms();
  }
  for (const AaRateResult& rate : res.rates) {
    nlohmann::json jimages = nlohmann::json::object(), jedge = nlohmann::json::object();
    if (Status s = image_maps(c, rate, prefix, jimages, jedge); !s.ok()) return s;
    const nlohmann::json jr = rate_json(c, rate, gl, std::move(jimages), std::move(jedge));
    out.jrates.push_back(jr);
    const std::string rl = std::to_string(rate.m) + "×" + std::to_string(rate.m);
    const double gms = rate.gbuffer.median_ms();
    const std::string one = jnum(100.0 / (rate.m * rate.m), "%.1f");
    const AaQuality& q_def = rate.method(AaMethod::default_1spp).quality;
    const AaQuality& q_fx = rate.method(AaMethod::fxaa).quality;
    const AaQuality& q_ad = rate.method(AaMethod::adaptive).quality;
    const AaQuality& q_edge = rate.method(AaMethod::edge_per_sample).quality;
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
    tables.row(rl, "Edge per sample (Lauritzen 2010)", gms,
               rate.method(AaMethod::edge_per_sample).timing, qs(q_edge, 0), qs(q_edge, 1),
               qs(q_edge, 2), jnum(rate.method(AaMethod::edge_per_sample).samples_pct, "%.1f"));
    if (figures) out.md_fig += figure_md(c, rate, jr);
    if (gl) {
      out.md_passes += "| " + rl + " | G-buffer | geometry | " + ms_cell(rate.gbuffer.median_ms()) +
                       " | " + ms_cell(rate.gbuffer_gpu.median_ms()) + " |\n";
      for (AaMethod k : kAaMethods) {
        for (const AaPassFrames& p : rate.method(k).passes) {
          out.md_passes += "| " + rl + " | " + aa_method_name(k) + " | " + p.pass + " | " +
                           ms_cell(p.wall.median_ms()) + " | " + ms_cell(p.gpu.median_ms()) +
                           " |\n";
        }
      }
    }
  }
  return Status::success();
}

/// The GPU paragraph of aa.md: the device and which times to read.
std::string gpu_note(const AaResult& res) {
  if (res.backend == Backend::vk) {
    return "Vulkan: `" + res.gpu_renderer + "`, `" + res.gpu_version +
           "`. Vulkan ms are host wall times from each method's submission to its fence "
           "(read-back excluded; passes recorded into one submission share its wall time in "
           "proportion to their GPU timestamps); the GPU timestamps per pass are beside them in "
           "the pass table and in aa.json (`gpu_shade_ms`, `passes`).\n\n";
  }
  std::string md = "OpenGL: `" + res.gpu_renderer + "`, `" + res.gpu_version +
                   "`. GL ms are host wall times from each pass's dispatch to the end of its "
                   "closing glFinish (read-back excluded); GL_TIME_ELAPSED per pass is beside "
                   "them in the pass table and in aa.json (`gpu_shade_ms`, `passes`).";
  if (res.gpu_renderer.find("llvmpipe") != std::string::npos) {
    md +=
        " On llvmpipe the GPU timer reads 0 for compute dispatches: the wall times are the "
        "ones to read.";
  }
  return md + "\n\n";
}

std::string pass_table(const AaResult& res, const std::string& rows) {
  const char* timer = res.backend == Backend::vk ? "GPU timestamps ms" : "GL_TIME_ELAPSED ms";
  return std::string("| rate | method | pass | wall ms | ") + timer +
         " |\n|---|---|---|---|---|\n" + rows;
}

/// aa.json (unserialised) and aa.md of a result.
Status build_report(const AaConfig& c, const AaResult& res, const std::string& scene_label,
                    nlohmann::json& jout, std::string& md) {
  const bool gl = gpu_primary(res.backend);
  BackendReport main{Tables(c.heavy), {}, nlohmann::json::array(), {}, {}};
  if (Status s = backend_report(c, res, "", true, main); !s.ok()) return s;
  nlohmann::json j1 = main.j1, jrates = main.jrates;
  BackendReport side{Tables(c.heavy), {}, nlohmann::json::array(), {}, {}};
  if (res.gl) {
    if (Status s = backend_report(c, *res.gl, "gl-", false, side); !s.ok()) return s;
    j1["gl"] = side.j1;
    for (std::size_t i = 0; i < jrates.size() && i < side.jrates.size(); ++i) {
      jrates[i]["gl"] = side.jrates[i];
      if (const auto& v = res.rates[i].gl_vs_cpu) {
        jrates[i]["gl_vs_cpu"] = {
            {"psnr_db", std::isfinite(v->psnr_db) ? nlohmann::json(v->psnr_db) : nlohmann::json()},
            {"identical", std::isinf(v->psnr_db) && v->psnr_db > 0},
            {"k_mismatch_fraction", v->k_mismatch_fraction}};
      }
    }
  }

  const AdaptiveThresholds& a = c.adaptive;
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
  jout = j;
  if (gl || res.gl) {
    jout["backend"] = backend_name(res.backend);
    jout["gpu_renderer"] = res.gpu_renderer;
    jout["gpu_version"] = res.gpu_version;
  }
  md.clear();
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
  if (gl) md += gpu_note(res);
  md +=
      "| rate | method | ms/frame | heavy ms/frame | shading ms | heavy shading ms | MSE (8-bit) | "
      "MSE (×10⁻⁵) | PSNR dB | samples % |\n|---|---|---|---|---|---|---|---|---|---|\n";
  md += main.tables.rows;
  if (gl) md += "\nPer pass (median ms):\n\n" + pass_table(res, main.md_passes);
  md += main.md_fig;
  if (res.gl) {
    md += "\n## OpenGL beside the CPU (`--backend both`)\n\n" + gpu_note(*res.gl) +
          "The same experiment on GL, against GL's own reference (columns as above):\n\n"
          "| rate | method | ms/frame | heavy ms/frame | shading ms | heavy shading ms | MSE "
          "(8-bit) | MSE (×10⁻⁵) | PSNR dB | samples % |\n|---|---|---|---|---|---|---|---|---|"
          "---|\n" +
          side.tables.rows +
          "\nGL adaptive against CPU adaptive (8-bit sRGB PSNR; pixels whose shaded-sample count "
          "differs):\n\n| rate | PSNR dB | k mismatch |\n|---|---|---|\n";
    for (const AaRateResult& rate : res.rates) {
      if (!rate.gl_vs_cpu) continue;
      const AaQuality q{0.0, rate.gl_vs_cpu->psnr_db, 1.0};
      md += "| " + std::to_string(rate.m) + "×" + std::to_string(rate.m) + " | " + qs(q, 2) +
            " | " + jnum(100.0 * rate.gl_vs_cpu->k_mismatch_fraction, "%.3f") + " % |\n";
    }
    md += "\nGL per pass (median ms):\n\n" + pass_table(*res.gl, side.md_passes);
  }
  return Status::success();
}
}  // namespace

Result<std::vector<AaRateImage>> aa_rate_images(const AaConfig& c, const AaRateResult& rate,
                                                bool pixels) {
  const std::string r = std::to_string(rate.m) + "x" + std::to_string(rate.m);
  const int n = rate.m * rate.m;
  auto samples_map = [&](const std::vector<std::uint8_t>& s) -> Result<ImageRGBA8> {
    if (!pixels) return ImageRGBA8{};
    std::vector<float> v(s.begin(), s.end());
    return metrics::heatmap(v, c.width, c.height, float(n));
  };
  auto diff = [&](const ImageRGBA8& x, const ImageRGBA8& y) -> Result<ImageRGBA8> {
    if (!pixels) return ImageRGBA8{};
    return metrics::difference_heatmap(x, y, 32.0f);
  };
  auto copy = [&](const ImageRGBA8& x) -> Result<ImageRGBA8> { return pixels ? x : ImageRGBA8{}; };
  const ImageRGBA8& ref = rate.method(AaMethod::reference).image;
  const ImageRGBA8& ad = rate.method(AaMethod::adaptive).image;
  const ImageRGBA8& def = rate.method(AaMethod::default_1spp).image;
  const ImageRGBA8& fx = rate.method(AaMethod::fxaa).image;
  const ImageRGBA8& geo = rate.ablation_geometry.image;
  const ImageRGBA8& shd = rate.ablation_shading.image;
  const ImageRGBA8& edge = rate.method(AaMethod::edge_per_sample).image;
  struct Out {
    std::string name;
    bool edge;
    Result<ImageRGBA8> image;
  };
  const std::vector<Out> outs = {
      {"reference-" + r, false, copy(ref)},
      {"adaptive-" + r, false, copy(ad)},
      {"default-" + r, false, copy(def)},
      {"fxaa-" + r, false, copy(fx)},
      {"samples-" + r, false, samples_map(rate.adaptive_samples)},
      {"diff-ref-" + r, false, diff(ref, ad)},
      {"diff-1x-" + r, false, diff(def, ad)},
      {"diff-ref-default-" + r, false, diff(ref, def)},
      {"diff-ref-fxaa-" + r, false, diff(ref, fx)},
      {"ablation-geometry-" + r, false, copy(geo)},
      {"ablation-geometry-samples-" + r, false, samples_map(rate.ablation_geometry.samples)},
      {"ablation-geometry-diff-" + r, false, diff(ref, geo)},
      {"ablation-shading-" + r, false, copy(shd)},
      {"ablation-shading-samples-" + r, false, samples_map(rate.ablation_shading.samples)},
      {"ablation-shading-diff-" + r, false, diff(ref, shd)},
      {"edge_per_sample-" + r, true, copy(edge)},
      {"edge_per_sample-samples-" + r, true, samples_map(rate.edge_samples)},
      {"diff-ref-edge_per_sample-" + r, true, diff(ref, edge)}};
  std::vector<AaRateImage> images;
  for (const Out& o : outs) {
    if (!o.image) return o.image.status();
    images.push_back({o.name, o.edge, *o.image});
  }
  return images;
}

Result<std::string> to_json(const AaConfig& config, const AaResult& result,
                            const AaReportOptions& options) {
  nlohmann::json j;
  std::string md;
  if (Status s = build_report(config, result, options.scene_label, j, md); !s.ok()) return s;
  return j.dump(2);
}

Result<std::string> to_markdown(const AaConfig& config, const AaResult& result,
                                const AaReportOptions& options) {
  nlohmann::json j;
  std::string md;
  if (Status s = build_report(config, result, options.scene_label, j, md); !s.ok()) return s;
  return md;
}

}  // namespace tessera::experiments
