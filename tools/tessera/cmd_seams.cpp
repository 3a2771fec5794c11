// tessera seams: the experiment of Toth 2013 — Clamp, Discard, Traverse and Traverse+corners
// at every MSAA rate along a camera orbit; Table 1 (median ms per frame, side by side) and
// Figure 5 (CDFs of per-pixel linear-RGB 2-norm errors) as JSON, Markdown, CSV and SVG. The
// experiment is `experiments::run_seams`; the files are written by `write_seams_report`.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "cli.h"
#include "report_seams.h"
#include "tessera/io.h"

namespace tessera::cli {

namespace {
struct SeamsArgs {
  experiments::SeamsConfig config;
  std::string out;
  std::string backend = "cpu";
  bool quiet = false, json = false, markdown = false;
};

/// One line per rate: the Table-1 ratio and the Figure-5 means (the tables are in seams.md).
void print_summary(std::FILE* out, const experiments::SeamsResult& res) {
  using faces::SeamMethod;
  const bool gl = experiments::gpu_primary(res.backend);
  const char* wall_label =
      res.backend == experiments::Backend::vk ? " (Vulkan, wall)" : " (GL, wall)";
  for (const experiments::SeamsRateResult& rate : res.rates) {
    const auto& t = rate.method(SeamMethod::traverse);
    const auto& d = rate.method(SeamMethod::discard);
    const auto& c = rate.method(SeamMethod::clamp);
    // GL: wall time to glFinish first (the GPU timer is partial on llvmpipe), then the timer.
    const experiments::FrameTimes& tt = gl ? t.wall : t.timing;
    const experiments::FrameTimes& dt = gl ? d.wall : d.timing;
    std::fprintf(out, "seams %dx%s: traverse %.1f ms, discard %.1f ms (%.2fx)", rate.msaa,
                 gl ? wall_label : "", tt.median_ms(), dt.median_ms(),
                 tt.median_ms() / std::max(dt.median_ms(), 1e-9));
    if (gl) {
      std::fprintf(out, ", GPU timer %.2f / %.2f ms", t.timing.median_ms(), d.timing.median_ms());
    }
    std::fprintf(out, "; mean error vs reference clamp %.5f, discard %.5f, traverse %.5f",
                 c.vs_reference.mean, d.vs_reference.mean, t.vs_reference.mean);
    if (res.near_seam_pixels > 0) {
      std::fprintf(out, "; near seams %.5f, %.5f, %.5f", c.vs_reference_near_seams.mean,
                   d.vs_reference_near_seams.mean, t.vs_reference_near_seams.mean);
    }
    std::fprintf(out, "\n");
  }
  for (const experiments::SeamsGlRateResult& g : res.gl_rates) {
    const auto& t = g.method(SeamMethod::traverse);
    const auto& d = g.method(SeamMethod::discard);
    std::fprintf(out,
                 "seams %dx GL: traverse %.1f ms, discard %.1f ms wall (GPU timer %.2f / %.2f "
                 "ms); GL vs CPU PSNR discard %.1f dB, traverse %.1f dB\n",
                 g.msaa, t.wall.median_ms(), d.wall.median_ms(), t.gpu.median_ms(),
                 d.gpu.median_ms(), d.psnr_db, t.psnr_db);
  }
  for (int r : res.msaa_unsupported) {
    std::fprintf(out, "seams %dx: refused by the OpenGL driver, skipped on GL\n", r);
  }
}
}  // namespace

Command add_seams_command(CLI::App& app, const GlobalOptions& global) {
  auto args = std::make_shared<SeamsArgs>();
  CLI::App* sub = app.add_subcommand(
      "seams",
      "Toth 2013 experiment: Clamp/Discard/Traverse per-face texturing at every MSAA rate "
      "(Table 1 timings, Figure 5 error CDFs)");
  experiments::SeamsConfig& c = args->config;
  sub->add_option("--scene", c.scene, "'figure1' (built in) or an all-quad .obj")
      ->capture_default_str();
  sub->add_option("--ptex", c.ptex, "Ptex file with the textures of the .obj scene");
  sub->add_option("--character", c.character,
                  "figure1: .obj to use as the character instead of the cube-sphere (non-quad "
                  "faces are split into quads)");
  sub->add_option("--subdivide", c.subdivide, "Linear subdivision steps of --character")
      ->check(CLI::Range(0, 4))
      ->capture_default_str();
  sub->add_option("--msaa", c.msaa, "MSAA rates, comma-separated")
      ->delimiter(',')
      ->check(CLI::IsMember({1, 2, 4, 8, 16}));
  sub->add_option("--frames", c.frames, "Orbit frames")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  sub->add_option("--quality-frames", c.quality_frames,
                  "Frames compared against a reference, spread over the orbit (0 = all)")
      ->check(CLI::Range(0, 100000));
  sub->add_option("--width", c.width)->check(CLI::Range(8, 8192))->capture_default_str();
  sub->add_option("--height", c.height)->check(CLI::Range(8, 8192))->capture_default_str();
  sub->add_option("--reference-factor", c.reference_factor, "Reference supersampling per axis")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  sub->add_flag("-q,--quiet", args->quiet, "No progress and no summary");
  sub->add_flag("--json", args->json, "Print seams.json on stdout (the summary goes to stderr)");
  sub->add_flag("--markdown", args->markdown,
                "Print seams.md on stdout (the summary goes to stderr)");
  sub->add_option("--near-seam-pixels", c.near_seam_pixels,
                  "Near-seam errors count pixels within this many pixels of another face (0 = "
                  "off)")
      ->check(CLI::Range(0, 64))
      ->capture_default_str();
  sub->add_option("--backend", args->backend,
                  "Who renders: cpu, gl (OpenGL; GPU-timer and wall times), vk (Vulkan; GPU "
                  "timestamps and wall times) or both (CPU report plus GL times and GL-vs-CPU "
                  "agreement)")
      ->check(CLI::IsMember({"cpu", "gl", "vk", "both"}))
      ->capture_default_str();
  sub->add_option("-o,--output,--out", args->out, "Output folder")->required();
  return {sub, [args, &global] {
            experiments::SeamsConfig cfg = args->config;
            if (!cfg.ptex.empty() && cfg.scene == "figure1") {
              return usage_error("--ptex needs --scene MESH.obj (the mesh of the Ptex file)");
            }
            cfg.threads = global.threads;
            Result<experiments::Backend> backend = experiments::parse_backend(args->backend);
            if (!backend) return usage_error(backend.status().message);
            cfg.backend = *backend;
            cfg.gl_factory = gl_backends();
            cfg.vk_factory = vk_backends();
            const std::string out = args->out;
            if (!args->quiet) {
              cfg.progress = [](const std::string& line) {
                std::fprintf(stderr, "seams: %s\n", line.c_str());
              };
            }
            // The output folder is created only once the inputs are known to be good.
            cfg.on_ready = [out] {
              std::error_code ec;
              std::filesystem::create_directories(std::filesystem::path(out) / "images", ec);
              if (ec) {
                return Status::error(ErrorCode::io_error, out + ": cannot create: " + ec.message());
              }
              return Status::success();
            };
            Result<experiments::SeamsResult> result = experiments::run_seams(cfg);
            if (!result) return fail(result.status());
            std::string json;
            if (Status s = write_seams_report(cfg, *result, out, true, json); !s.ok()) {
              return fail(s);
            }
            if (args->json) {
              std::printf("%s\n", json.c_str());
            } else if (args->markdown) {
              Result<std::vector<std::uint8_t>> md = io::read_file(out + "/seams.md");
              if (!md) return fail(md.status());
              std::fwrite(md->data(), 1, md->size(), stdout);
            }
            if (!args->quiet) {
              std::FILE* text = text_stream(args->json || args->markdown);
              print_summary(text, *result);
              std::fprintf(text, "wrote %s/seams.md, seams.json, plots and images\n", out.c_str());
            }
            return int(kExitOk);
          }};
}

}  // namespace tessera::cli
