// tessera aa: the experiment of Hollander, Boubekeur & Eisemann 2013 (Table 1, Figures 6a, 7
// and 8) — adaptive supersampling of an enlarged G-buffer against full supersampling, plain 1x
// deferred shading and FXAA 3.11, measured side by side in one run.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli.h"
#include "tessera/deferred.h"
#include "tessera/io.h"
#include "tessera/metrics.h"

namespace tessera::cli {

namespace {

struct AaArgs {
  std::string scene = "builtin", out, camera, orbit, ssaa = "2,3,4";
  int width = 1024, height = 768, frames = 3, lights = 8, heavy_terms = -1, fxaa_preset = 39;
  bool heavy = false;
  deferred::AdaptiveOptions adaptive;
};

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// Parses "2,3,4" into window sizes in [1, 8]; empty on error.
std::vector<int> parse_rates(const std::string& text) {
  std::vector<int> rates;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    const long v = std::strtol(item.c_str(), &end, 10);
    if (item.empty() || *end != '\0' || v < 1 || v > 8) return {};
    if (std::find(rates.begin(), rates.end(), int(v)) == rates.end()) rates.push_back(int(v));
  }
  return rates;
}

std::string jnum(double v, const char* f = "%.3f") {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

/// Timings of one method: per-frame shading times (ms), normal and heavy.
struct Timing {
  std::vector<double> normal, heavy;
};

/// Quality of one image against the same-rate reference.
struct Quality {
  double mse = 0, psnr = 0;  // 8-bit RGB
  bool identical = false;
};

Quality quality(const ImageRGBA8& ref, const ImageRGBA8& img, int threads) {
  CompareOptions co;
  co.compute_ssim = false;
  co.threads = threads;
  const Result<ImageComparison> c = compare_images(ref, img, co);
  Quality q;
  if (c) {
    q.mse = c->mse_rgb;
    q.identical = !std::isfinite(c->psnr_rgb);
    q.psnr = q.identical ? 999.0 : c->psnr_rgb;
  }
  return q;
}

nlohmann::json quality_json(const Quality& q) {
  return {{"mse_8bit", q.mse},
          {"mse_unit_e5", q.mse / (255.0 * 255.0) * 1e5},
          {"psnr_db", q.identical ? nlohmann::json(nullptr) : nlohmann::json(q.psnr)}};
}

int run_aa(const AaArgs& args, const GlobalOptions& global) {
  const std::vector<int> rates = parse_rates(args.ssaa);
  if (rates.empty()) {
    return usage_error("--ssaa: expected a comma-separated list of window sizes in [1, 8], got '" +
                       args.ssaa + "'");
  }
  Result<scene::Scene> sc = args.scene == "builtin" ? Result<scene::Scene>(scene::builtin_scene())
                                                    : scene::load_scene(args.scene);
  if (!sc) return fail(sc.status());
  Result<scene::Camera> camera = scene::camera_from_text(
      *sc, args.camera,
      args.orbit.empty() && args.camera.empty() && args.scene == "builtin" ? std::string("1/8")
                                                                           : args.orbit);
  if (!camera) return usage_error(camera.status().message);
  // Output folder before the expensive part (after the inputs: no folder for a bad scene).
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(args.out, ec);
  {
    const std::string probe = (fs::path(args.out) / ".tessera-aa-probe").string();
    std::ofstream f(probe);
    if (ec || !f) {
      return fail(Status::error(ErrorCode::io_error,
                                args.out + ": cannot create or write the output folder"));
    }
    f.close();
    fs::remove(probe, ec);
  }
  Result<std::unique_ptr<deferred::DeferredRenderer>> rr =
      deferred::DeferredRenderer::create(*sc, global.threads);
  if (!rr) return fail(rr.status());
  deferred::DeferredRenderer& renderer = **rr;
  const int threads = global.threads > 0 ? global.threads : default_thread_count();

  deferred::ShadingOptions normal = deferred::scene_shading(*sc, args.lights, &*camera);
  normal.threads = global.threads;
  deferred::ShadingOptions heavy = normal;
  heavy.heavy = true;
  if (args.heavy_terms >= 0) heavy.heavy_terms = args.heavy_terms;
  deferred::FxaaOptions fxo;
  fxo.preset = args.fxaa_preset;
  fxo.threads = global.threads;

  auto save = [&](const std::string& name, const ImageRGBA8& img) {
    return write_png((fs::path(args.out) / name).string(), img);
  };

  nlohmann::json jrates = nlohmann::json::array();
  std::string md_rows, md_fig;
  const std::uint64_t pixels = std::uint64_t(args.width) * std::uint64_t(args.height);

  // The paper's 1x1 rows: a w x h G-buffer, one sample per pixel, and FXAA on it.
  double ms_1x_gbuffer = 0;
  Timing t1_default, t1_fxaa;
  {
    deferred::GBuffer gb;
    std::vector<double> g;
    for (int f = 0; f < args.frames; ++f) {
      auto t0 = std::chrono::steady_clock::now();
      if (Status s = renderer.render_gbuffer(*camera, args.width, args.height, 1, gb); !s.ok()) {
        return fail(s);
      }
      g.push_back(ms_since(t0));
      for (int mode = 0; mode < (args.heavy ? 2 : 1); ++mode) {
        const deferred::ShadingOptions& so = mode ? heavy : normal;
        for (int k = 0; k < 2; ++k) {
          const int method = (k + f) % 2;
          t0 = std::chrono::steady_clock::now();
          ImageRGBA8 img = to_srgb8(renderer.shade_default(gb, so), global.threads);
          if (method == 1) img = std::move(*deferred::fxaa(img, fxo));
          Timing& tt = method ? t1_fxaa : t1_default;
          (mode ? tt.heavy : tt.normal).push_back(ms_since(t0));
        }
      }
    }
    ms_1x_gbuffer = median(g);
  }
  auto row = [&](const std::string& rate, const std::string& method, double gbuf, const Timing& t,
                 const std::string& mse, const std::string& mse5, const std::string& psnr,
                 const std::string& pct) {
    const bool timed = !t.normal.empty(), timed_heavy = args.heavy && !t.heavy.empty();
    const std::string dash = "—";
    md_rows += "| " + rate + " | " + method + " | " +
               (timed ? jnum(gbuf + median(t.normal), "%.1f") : dash) + " | " +
               (timed_heavy ? jnum(gbuf + median(t.heavy), "%.1f") : dash) + " | " +
               (timed ? jnum(median(t.normal), "%.1f") : dash) + " | " +
               (timed_heavy ? jnum(median(t.heavy), "%.1f") : dash) + " | " + mse + " | " + mse5 +
               " | " + psnr + " | " + pct + " |\n";
  };
  row("1×1", "Default", ms_1x_gbuffer, t1_default, "–", "–", "–", "–");
  row("1×1", "FXAA", ms_1x_gbuffer, t1_fxaa, "–", "–", "–", "–");
  nlohmann::json j1 = {
      {"gbuffer_ms", ms_1x_gbuffer},
      {"default",
       {{"shade_ms", median(t1_default.normal)}, {"shade_ms_heavy", median(t1_default.heavy)}}},
      {"fxaa", {{"shade_ms", median(t1_fxaa.normal)}, {"shade_ms_heavy", median(t1_fxaa.heavy)}}}};

  for (int m : rates) {
    deferred::GBuffer gb;
    std::vector<double> gtimes;
    // Methods: 0 default, 1 FXAA, 2 reference, 3 adaptive; alternated per frame.
    Timing t[4];
    ImageRGBA8 img[4], img_heavy[4];
    deferred::AdaptiveResult ad, ad_heavy;
    std::vector<double> ad_first, ad_metric, ad_rest;
    for (int f = 0; f < args.frames; ++f) {
      auto t0 = std::chrono::steady_clock::now();
      if (Status s = renderer.render_gbuffer(*camera, args.width, args.height, m, gb); !s.ok()) {
        return fail(s);
      }
      gtimes.push_back(ms_since(t0));
      for (int mode = 0; mode < (args.heavy ? 2 : 1); ++mode) {
        const deferred::ShadingOptions& so = mode ? heavy : normal;
        ImageRGBA8* out = mode ? img_heavy : img;
        for (int k = 0; k < 4; ++k) {
          const int method = (k + f) % 4;
          t0 = std::chrono::steady_clock::now();
          if (method == 0 || method == 1) {
            out[method] = to_srgb8(renderer.shade_default(gb, so), global.threads);
            if (method == 1) out[method] = std::move(*deferred::fxaa(out[method], fxo));
          } else if (method == 2) {
            out[method] = to_srgb8(renderer.shade_reference(gb, so), global.threads);
          } else {
            deferred::AdaptiveResult r = renderer.shade_adaptive(gb, so, args.adaptive);
            out[method] = to_srgb8(r.image, global.threads);
            if (mode == 0) {
              ad_first.push_back(r.ms_first);
              ad_metric.push_back(r.ms_metric);
              ad_rest.push_back(r.ms_rest);
            }
            (mode ? ad_heavy : ad) = std::move(r);
          }
          (mode ? t[method].heavy : t[method].normal).push_back(ms_since(t0));
        }
      }
    }
    const double gms = median(gtimes);
    // Ablations (Figure 8): one metric at a time.
    deferred::AdaptiveOptions geo = args.adaptive, shd = args.adaptive;
    geo.use_shading = false;
    shd.use_geometry = false;
    const deferred::AdaptiveResult ab_geo = renderer.shade_adaptive(gb, normal, geo);
    const deferred::AdaptiveResult ab_shd = renderer.shade_adaptive(gb, normal, shd);
    const ImageRGBA8 geo_img = to_srgb8(ab_geo.image, global.threads);
    const ImageRGBA8 shd_img = to_srgb8(ab_shd.image, global.threads);

    const double total = double(pixels) * double(m * m);
    auto pct = [&](std::uint64_t s) { return 100.0 * double(s) / total; };
    const Quality q_def = quality(img[2], img[0], threads), q_fx = quality(img[2], img[1], threads),
                  q_ad = quality(img[2], img[3], threads),
                  q_geo = quality(img[2], geo_img, threads),
                  q_shd = quality(img[2], shd_img, threads);
    Quality q_ad_heavy;
    if (args.heavy) q_ad_heavy = quality(img_heavy[2], img_heavy[3], threads);

    // Images.
    const std::string r = std::to_string(m) + "x" + std::to_string(m);
    const int n = m * m;
    auto samples_map = [&](const std::vector<std::uint8_t>& s) {
      std::vector<float> v(s.begin(), s.end());
      return heatmap(v, args.width, args.height, float(n));
    };
    struct Out {
      std::string name;
      ImageRGBA8 image;
    };
    std::vector<Out> outs;
    outs.push_back({"reference-" + r, img[2]});
    outs.push_back({"adaptive-" + r, img[3]});
    outs.push_back({"default-" + r, img[0]});
    outs.push_back({"fxaa-" + r, img[1]});
    outs.push_back({"samples-" + r, samples_map(ad.samples)});
    outs.push_back({"diff-ref-" + r, *difference_heatmap(img[2], img[3], 32.0f)});
    outs.push_back({"diff-1x-" + r, *difference_heatmap(img[0], img[3], 32.0f)});
    outs.push_back({"diff-ref-default-" + r, *difference_heatmap(img[2], img[0], 32.0f)});
    outs.push_back({"diff-ref-fxaa-" + r, *difference_heatmap(img[2], img[1], 32.0f)});
    outs.push_back({"ablation-geometry-" + r, geo_img});
    outs.push_back({"ablation-geometry-samples-" + r, samples_map(ab_geo.samples)});
    outs.push_back({"ablation-geometry-diff-" + r, *difference_heatmap(img[2], geo_img, 32.0f)});
    outs.push_back({"ablation-shading-" + r, shd_img});
    outs.push_back({"ablation-shading-samples-" + r, samples_map(ab_shd.samples)});
    outs.push_back({"ablation-shading-diff-" + r, *difference_heatmap(img[2], shd_img, 32.0f)});
    nlohmann::json jimages = nlohmann::json::object();
    for (const Out& o : outs) {
      if (Status s = save(o.name + ".png", o.image); !s.ok()) return fail(s);
      jimages[o.name] = o.name + ".png";
    }

    auto method_json = [&](int k, const Quality* q, double samples_pct) {
      nlohmann::json j = {{"shade_ms", median(t[k].normal)},
                          {"frame_ms", gms + median(t[k].normal)},
                          {"shade_ms_frames", t[k].normal},
                          {"samples_pct", samples_pct}};
      if (args.heavy) {
        j["shade_ms_heavy"] = median(t[k].heavy);
        j["frame_ms_heavy"] = gms + median(t[k].heavy);
        j["shade_ms_heavy_frames"] = t[k].heavy;
      }
      if (q) j["quality"] = quality_json(*q);
      return j;
    };
    nlohmann::json jr = {
        {"m", m},
        {"gbuffer_ms", gms},
        {"gbuffer_ms_frames", gtimes},
        {"default", method_json(0, &q_def, 100.0 / n)},
        {"fxaa", method_json(1, &q_fx, 100.0 / n)},
        {"reference", method_json(2, nullptr, 100.0)},
        {"adaptive", method_json(3, &q_ad, pct(ad.samples_shaded))},
        {"adaptive_passes_ms",
         {{"first", median(ad_first)}, {"metric", median(ad_metric)}, {"rest", median(ad_rest)}}},
        {"adaptive_extra_albedo_lookups_pct", 100.0 * double(ad.extra_lookups) / double(pixels)},
        {"speedup_frame", (gms + median(t[2].normal)) / (gms + median(t[3].normal))},
        {"speedup_shading", median(t[2].normal) / median(t[3].normal)},
        {"ablation_geometry",
         {{"samples_pct", pct(ab_geo.samples_shaded)}, {"quality", quality_json(q_geo)}}},
        {"ablation_shading",
         {{"samples_pct", pct(ab_shd.samples_shaded)}, {"quality", quality_json(q_shd)}}},
        {"images", jimages}};
    if (args.heavy) {
      jr["speedup_frame_heavy"] = (gms + median(t[2].heavy)) / (gms + median(t[3].heavy));
      jr["speedup_shading_heavy"] = median(t[2].heavy) / median(t[3].heavy);
      jr["adaptive_heavy_quality"] = quality_json(q_ad_heavy);
      jr["adaptive_heavy_samples_pct"] = pct(ad_heavy.samples_shaded);
    }
    jrates.push_back(jr);

    auto qs = [](const Quality& q, int what) {
      if (what == 0) return jnum(q.mse, "%.3f");
      if (what == 1) return jnum(q.mse / (255.0 * 255.0) * 1e5, "%.2f");
      return q.identical ? std::string("∞") : jnum(q.psnr, "%.2f");
    };
    const std::string rl = std::to_string(m) + "×" + std::to_string(m);
    row(rl, "Default (1 spp)", gms, t[0], qs(q_def, 0), qs(q_def, 1), qs(q_def, 2),
        jnum(100.0 / n, "%.1f"));
    row(rl, "FXAA", gms, t[1], qs(q_fx, 0), qs(q_fx, 1), qs(q_fx, 2), jnum(100.0 / n, "%.1f"));
    row(rl, "Reference", gms, t[2], "–", "–", "–", "100");
    row(rl, "Adaptive", gms, t[3], qs(q_ad, 0), qs(q_ad, 1), qs(q_ad, 2),
        jnum(pct(ad.samples_shaded), "%.1f"));
    row(rl, "Adaptive, geometry only", gms, {}, qs(q_geo, 0), qs(q_geo, 1), qs(q_geo, 2),
        jnum(pct(ab_geo.samples_shaded), "%.1f"));
    row(rl, "Adaptive, shading only", gms, {}, qs(q_shd, 0), qs(q_shd, 1), qs(q_shd, 2),
        jnum(pct(ab_shd.samples_shaded), "%.1f"));
    md_fig += "\n### " + rl + "\n\n";
    md_fig += "Speed-up of adaptive over the reference: frame " +
              jnum(jr["speedup_frame"].get<double>(), "%.2f") + "×, shading pass " +
              jnum(jr["speedup_shading"].get<double>(), "%.2f") + "×";
    if (args.heavy) {
      md_fig += "; heavy: frame " + jnum(jr["speedup_frame_heavy"].get<double>(), "%.2f") +
                "×, shading pass " + jnum(jr["speedup_shading_heavy"].get<double>(), "%.2f") +
                "× (heavy adaptive vs heavy reference: PSNR " + qs(q_ad_heavy, 2) + " dB)";
    }
    md_fig += ".\n\n";
    md_fig +=
        "| reference | adaptive | samples (Fig. 6a) | diff vs reference | diff vs 1× |\n"
        "|---|---|---|---|---|\n";
    md_fig += "| ![](reference-" + r + ".png) | ![](adaptive-" + r + ".png) | ![](samples-" + r +
              ".png) | ![](diff-ref-" + r + ".png) | ![](diff-1x-" + r + ".png) |\n\n";
    md_fig +=
        "Figure 8 analogue: | 1 spp | FXAA | geometry only: samples, diff | shading only: "
        "samples, diff |\n\n";
    md_fig += "| ![](default-" + r + ".png) ![](diff-ref-default-" + r + ".png) | ![](fxaa-" + r +
              ".png) ![](diff-ref-fxaa-" + r + ".png) | ![](ablation-geometry-samples-" + r +
              ".png) ![](ablation-geometry-diff-" + r + ".png) | ![](ablation-shading-samples-" +
              r + ".png) ![](ablation-shading-diff-" + r + ".png) |\n|---|---|---|---|\n";
    std::fprintf(stderr,
                 "aa: %s: gbuffer %.0f ms; shading default %.0f, fxaa %.0f, reference %.0f, "
                 "adaptive %.0f ms; adaptive %.1f%% samples, PSNR %s dB\n",
                 r.c_str(), gms, median(t[0].normal), median(t[1].normal), median(t[2].normal),
                 median(t[3].normal), pct(ad.samples_shaded), qs(q_ad, 2).c_str());
  }

  const deferred::AdaptiveOptions& a = args.adaptive;
  nlohmann::json j = {{"scene", args.scene},
                      {"width", args.width},
                      {"height", args.height},
                      {"threads", threads},
                      {"frames", args.frames},
                      {"heavy", args.heavy},
                      {"heavy_terms", heavy.heavy_terms},
                      {"lights", normal.lights.size()},
                      {"fxaa_preset", fxo.preset},
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
  md += "Scene `" + args.scene + "`, " + std::to_string(args.width) + "×" +
        std::to_string(args.height) + ", " + std::to_string(normal.lights.size()) +
        " point lights, " + std::to_string(threads) + " thread(s), median of " +
        std::to_string(args.frames) + " frame(s), methods alternated per frame. FXAA 3.11 preset " +
        std::to_string(fxo.preset) + ". Heavy mode: " +
        (args.heavy ? std::to_string(heavy.heavy_terms) + " sinusoid terms per shaded sample"
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
  md += md_rows;
  md += md_fig;
  const std::string js = j.dump(2) + "\n";
  if (Status s = write_file_atomic((fs::path(args.out) / "aa.json").string(),
                                   {reinterpret_cast<const std::uint8_t*>(js.data()), js.size()});
      !s.ok()) {
    return fail(s);
  }
  if (Status s = write_file_atomic((fs::path(args.out) / "aa.md").string(),
                                   {reinterpret_cast<const std::uint8_t*>(md.data()), md.size()});
      !s.ok()) {
    return fail(s);
  }
  std::printf("%s", md.substr(0, md.find("\n### ")).c_str());
  std::printf("\nwrote %s/aa.json, aa.md and PNGs\n", args.out.c_str());
  return kExitOk;
}

}  // namespace

Command add_aa_command(CLI::App& app, const GlobalOptions& global) {
  auto args = std::make_shared<AaArgs>();
  CLI::App* sub = app.add_subcommand(
      "aa",
      "Adaptive supersampling for deferred shading (Hollander et al. 2013) vs full SSAA, 1x "
      "and FXAA: timings, quality, heatmaps");
  sub->add_option("--scene", args->scene, "Scene file (.obj, .gltf, .glb) or 'builtin'")
      ->capture_default_str();
  sub->add_option("--ssaa", args->ssaa, "Comma-separated window sizes m (m x m samples per pixel)")
      ->capture_default_str();
  sub->add_option("--width", args->width)->check(CLI::Range(1, 8192))->capture_default_str();
  sub->add_option("--height", args->height)->check(CLI::Range(1, 8192))->capture_default_str();
  sub->add_flag("--heavy", args->heavy,
                "Also time a heavy per-sample shader (the paper's 'stalled' column)");
  sub->add_option("--heavy-terms", args->heavy_terms,
                  "Sinusoids evaluated per shaded sample in heavy mode (default 256)")
      ->check(CLI::Range(0, 100000));
  sub->add_option("--frames", args->frames, "Timed frames per method (medians reported)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  auto* cam =
      sub->add_option("--camera", args->camera,
                      "Camera eye,target,up,fov: 10 comma-separated numbers (default: orbit "
                      "1/8 for 'builtin', 0/1 for files)");
  sub->add_option("--orbit", args->orbit, "FRAME/N: camera on the scene's orbit")->excludes(cam);
  sub->add_option("--lights", args->lights,
                  "Extra point lights on a ring above the camera target (besides the scene's)")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();
  sub->add_option("--fxaa-preset", args->fxaa_preset, "FXAA 3.11 quality preset")
      ->check([](const std::string& s) {
        try {
          return deferred::valid_fxaa_preset(std::stoi(s)) ? std::string()
                                                           : std::string("10..15, 20..29 or 39");
        } catch (...) {
          return std::string("an integer preset");
        }
      })
      ->capture_default_str();
  sub->add_option("--c-depth", args->adaptive.c_depth, "Depth-variance constant")
      ->capture_default_str();
  sub->add_option("--c-normal", args->adaptive.c_normal, "Normal-cone constant")
      ->capture_default_str();
  sub->add_option("--c-shade", args->adaptive.c_shade, "Luminance-range constant")
      ->capture_default_str();
  sub->add_option("--t-min", args->adaptive.t_min, "Shading metric: minimum threshold")
      ->capture_default_str();
  sub->add_option("--t-edge", args->adaptive.t_edge, "Shading metric: relative edge threshold")
      ->capture_default_str();
  sub->add_option("-o,--output,--out", args->out, "Output folder (aa.json, aa.md, PNGs)")
      ->required();
  return {sub, [args, &global] { return run_aa(*args, global); }};
}

}  // namespace tessera::cli
