// tessera aa: the experiment of Hollander, Boubekeur & Eisemann 2013 (Table 1, Figures 6a, 7
// and 8) — adaptive supersampling of an enlarged G-buffer against full supersampling, plain 1x
// deferred shading and FXAA 3.11, measured side by side in one run. The experiment is
// `experiments::run_aa`; the files are written by `write_aa_report`.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli.h"
#include "report_aa.h"
#include "tessera/experiments.h"
#include "tessera/io.h"

namespace tessera::cli {

namespace {

struct AaArgs {
  std::string scene = "builtin", out, camera, orbit, ssaa = "2,3,4", backend = "cpu";
  int width = 1024, height = 768, frames = 3, lights = 8, heavy_terms = -1, fxaa_preset = 39;
  bool heavy = false;
  bool quiet = false, json = false, markdown = false;
  AdaptiveThresholds adaptive;
};

/// One line per rate: what a reader wants from a run (the tables are in aa.md).
void print_summary(std::FILE* out, const experiments::AaResult& res, const char* label = "") {
  using experiments::AaMethod;
  if (res.backend == experiments::Backend::gl) label = " (GL, wall ms)";
  if (res.backend == experiments::Backend::vk) label = " (Vulkan, wall ms)";
  for (const experiments::AaRateResult& rate : res.rates) {
    const auto frame_ms = [&](AaMethod m) {
      return rate.gbuffer.median_ms() + rate.method(m).timing.normal.median_ms();
    };
    const auto psnr = [&](AaMethod m) { return rate.method(m).quality.psnr_db; };
    std::fprintf(out,
                 "aa %dx%d%s: adaptive shades %.1f%% of the samples, %.2f dB against the "
                 "reference (1 spp %.2f dB, FXAA %.2f dB, edge per sample %.1f%% %.2f dB), "
                 "%.1f ms/frame (reference %.1f ms, edge per sample %.1f ms)",
                 rate.m, rate.m, label, rate.method(AaMethod::adaptive).samples_pct,
                 psnr(AaMethod::adaptive), psnr(AaMethod::default_1spp), psnr(AaMethod::fxaa),
                 rate.method(AaMethod::edge_per_sample).samples_pct,
                 psnr(AaMethod::edge_per_sample), frame_ms(AaMethod::adaptive),
                 frame_ms(AaMethod::reference), frame_ms(AaMethod::edge_per_sample));
    if (rate.gl_vs_cpu) {
      std::fprintf(out, "; GL vs CPU adaptive %.2f dB, k differs at %.3f%% of the pixels",
                   rate.gl_vs_cpu->psnr_db, 100.0 * rate.gl_vs_cpu->k_mismatch_fraction);
    }
    std::fprintf(out, "\n");
  }
  if (res.gl) print_summary(out, *res.gl, " (GL, wall ms)");
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

int run_aa(const AaArgs& args, const GlobalOptions& global) {
  experiments::AaConfig c;
  c.ssaa = parse_rates(args.ssaa);
  if (c.ssaa.empty()) {
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
  c.scene = std::make_shared<const scene::Scene>(std::move(*sc));
  c.camera = *camera;
  c.width = args.width;
  c.height = args.height;
  c.frames = args.frames;
  c.lights = args.lights;
  c.heavy = args.heavy;
  c.heavy_terms = args.heavy_terms;
  c.fxaa_preset = args.fxaa_preset;
  c.adaptive = args.adaptive;
  c.threads = global.threads;
  Result<experiments::Backend> backend = experiments::parse_backend(args.backend);
  if (!backend) return usage_error(backend.status().message);
  c.backend = *backend;
  c.gl_factory = gl_backends();
  c.vk_factory = vk_backends();
  if (!args.quiet) {
    c.progress = [](const std::string& line) { std::fprintf(stderr, "aa: %s\n", line.c_str()); };
  }
  // Output folder before the expensive part (after the inputs: no folder for a bad scene).
  const std::string out = args.out;
  c.on_ready = [out] {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::create_directories(out, ec);
    const std::string probe = (fs::path(out) / ".tessera-aa-probe").string();
    std::ofstream f(probe);
    if (ec || !f) {
      return Status::error(ErrorCode::io_error, out + ": cannot create or write the output folder");
    }
    f.close();
    fs::remove(probe, ec);
    return Status::success();
  };
  Result<experiments::AaResult> res = experiments::run_aa(c);
  if (!res) return fail(res.status());
  std::string md, json;
  if (Status s = write_aa_report(c, *res, args.scene, out, &md, &json); !s.ok()) return fail(s);
  if (args.json) {
    std::printf("%s\n\n", json.c_str());  // aa.json's final newline, then the line's
  } else if (args.markdown) {
    std::printf("%s", md.c_str());
  }
  if (!args.quiet) {
    std::FILE* text = text_stream(args.json || args.markdown);
    print_summary(text, *res);
    std::fprintf(text, "wrote %s/aa.json, aa.md and images\n", out.c_str());
  }
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
  sub->add_option("--backend", args->backend,
                  "Who renders: cpu, gl (OpenGL; wall and GPU-timer times, GL reference), vk "
                  "(Vulkan; wall times and GPU timestamps, Vulkan reference) or both (the CPU "
                  "report plus GL's under 'gl' and GL-vs-CPU agreement)")
      ->check(CLI::IsMember({"cpu", "gl", "vk", "both"}))
      ->capture_default_str();
  sub->add_option("-o,--output,--out", args->out, "Output folder (aa.json, aa.md, PNGs)")
      ->required();
  sub->add_flag("-q,--quiet", args->quiet, "No progress and no summary");
  sub->add_flag("--json", args->json, "Print aa.json on stdout (the summary goes to stderr)");
  sub->add_flag("--markdown", args->markdown,
                "Print aa.md's tables on stdout (the summary goes to stderr)");
  return {sub, [args, &global] { return run_aa(*args, global); }};
}

}  // namespace tessera::cli
