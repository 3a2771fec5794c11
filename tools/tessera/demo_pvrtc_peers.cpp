// Demo section part: PVRTC quality against time, tessera's levels and PVRTexTool's side by
// side from the same run (both as whole processes on the same PNG files), as an SVG plot.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "demo.h"
#include "plot.h"
#include "tessera/io.h"
#include "tessera/metrics.h"
#include "tessera/texture_file.h"

extern char** environ;

namespace tessera::cli {

namespace {

namespace fs = std::filesystem;

/// Runs `argv` with stdout/stderr discarded; returns its wall time in ms, or -1 if it failed.
double run_timed(const std::vector<std::string>& argv) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  const auto t0 = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) return -1;
  int status = 0;
  if (waitpid(pid, &status, 0) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    return -1;
  }
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/// PVRTexToolCLI as scripts/setup.sh caches it ($TESSERA_PVRTEXTOOL overrides); "" if absent.
std::string find_pvrtextool() {
  if (const char* env = std::getenv("TESSERA_PVRTEXTOOL"); env && *env) {
    return ::access(env, X_OK) == 0 ? env : "";
  }
  std::string cache;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) {
    cache = xdg;
  } else if (const char* home = std::getenv("HOME"); home && *home) {
    cache = std::string(home) + "/.cache";
  }
  const std::string path = cache + "/tessera/peers/PVRTexToolCLI";
  return !cache.empty() && ::access(path.c_str(), X_OK) == 0 ? path : "";
}

/// PSNR (RGB) and SSIM of a texture file's level 0 against `original`.
bool measure(const std::string& texture_path, const ImageRGBA8& original, int threads, double& psnr,
             double& ssim) {
  Result<texture_file::CompressedTexture> tex = texture_file::read_texture_file(texture_path);
  if (!tex) return false;
  Result<ImageRGBA8> dec = texture_file::decode_texture_level(*tex, 0, {threads});
  if (!dec) return false;
  metrics::CompareOptions co;
  co.threads = threads;
  Result<metrics::ImageComparison> cmp = metrics::compare_images(original, *dec, co);
  if (!cmp) return false;
  psnr = std::isfinite(cmp->psnr_rgb) ? cmp->psnr_rgb : 99.0;
  ssim = cmp->ssim_gray;
  return true;
}

struct Level {
  const char* label;
  const char* quality;  // tessera --quality or PVRTexTool -q
};

constexpr Level kTessera[] = {{"fast", "fast"}, {"normal", "normal"}, {"high", "high"}};
constexpr Level kPeer[] = {{"fastest", "pvrtcfastest"},
                           {"fast", "pvrtcfast"},
                           {"normal", "pvrtcnormal"},
                           {"high", "pvrtchigh"},
                           {"best", "pvrtcbest"}};

}  // namespace

Status demo_pvrtc_quality_time(Report& report, const DemoOptions& options,
                               const std::vector<PvrtcDemoImage>& images) {
  const std::string self = "/proc/self/exe";
  std::error_code ec;
  const fs::path scratch = fs::path(report.dir()) / "img" / "pvrtc-scratch";
  fs::create_directories(scratch, ec);
  if (ec) return Status::error(ErrorCode::io_error, scratch.string() + ": " + ec.message());
  const std::string peer = find_pvrtextool();

  auto series_for = [&](const Level* levels, std::size_t n, bool is_peer, PlotSeries& s,
                        std::vector<std::vector<std::string>>& rows) {
    for (std::size_t l = 0; l < n; ++l) {
      double ms = 0, psnr = 0, ssim = 0;
      int counted = 0;
      for (const PvrtcDemoImage& img : images) {
        const std::string out = (scratch / (std::string(is_peer ? "p-" : "t-") + levels[l].label +
                                            "-" + img.name + ".pvr"))
                                    .string();
        std::vector<std::string> argv;
        if (is_peer) {
          argv = {peer,
                  "-i",
                  img.png_path,
                  "-o",
                  out,
                  "-f",
                  img.has_alpha ? "PVRTC1_4,UBN,lRGB" : "PVRTC1_4_RGB,UBN,lRGB",
                  "-q",
                  levels[l].quality,
                  "-shh"};
        } else {
          argv = {self, "-j", "1",         "compress",        img.png_path,
                  "-o", out,  "--quality", levels[l].quality, "-q"};
        }
        const double t = run_timed(argv);
        double p = 0, s2 = 0;
        if (t < 0 || !measure(out, img.image, options.threads, p, s2)) continue;
        ms += t;
        psnr += p;
        ssim += s2;
        ++counted;
      }
      if (!counted) continue;
      s.x.push_back(ms / counted);
      s.y.push_back(psnr / counted);
      s.point_labels.push_back(levels[l].label);
      if (options.summary) {
        (*options.summary)["pvrtc"]["quality_time"].push_back(
            {{"tool", is_peer ? "PVRTexTool 4.17" : "tessera"},
             {"level", levels[l].quality},
             {"ms_per_image", ms / counted},
             {"psnr_rgb", psnr / counted},
             {"ssim_gray", ssim / counted}});
      }
      rows.push_back({is_peer ? "PVRTexTool 4.17" : "tessera", levels[l].quality,
                      fmt("%.1f", ms / counted), fmt("%.2f", psnr / counted),
                      fmt("%.4f", ssim / counted)});
    }
  };

  Plot plot;
  plot.title = "PVRTC1 4 bpp: quality against time (procedural images, " +
               std::to_string(images.empty() ? 0 : images.front().image.width) + "²)";
  plot.x_title = "time per image, whole process (ms, log scale)";
  plot.y_title = "mean PSNR RGB (dB)";
  plot.log_x = true;
  std::vector<std::vector<std::string>> rows;
  PlotSeries t;
  t.label = "tessera (-j 1): fast, normal, high";
  t.colour = series_colour(0);
  t.markers = true;
  series_for(kTessera, std::size(kTessera), false, t, rows);
  plot.series.push_back(t);
  if (!peer.empty()) {
    PlotSeries p;
    p.label = "PVRTexTool 4.17 (its own threads): fastest to best";
    p.colour = series_colour(1);
    p.markers = true;
    p.dash = "6 4";
    series_for(kPeer, std::size(kPeer), true, p, rows);
    plot.series.push_back(p);
  }
  fs::remove_all(scratch, ec);
  std::string rel;
  if (Status s = report.save_svg("pvrtc-quality-time", plot_svg(plot), rel); !s.ok()) return s;
  report.paragraph(
      peer.empty()
          ? "Quality against time of tessera's levels (PVRTexToolCLI was not found, so its "
            "levels are missing: `bash scripts/setup.sh` fetches it). Each point is the mean "
            "over the procedural images of one `tessera -j 1 compress --quality Q` process."
          : "Quality against time, both tools measured in this run on the same PNG files: each "
            "point is the mean over the procedural images of one whole process per image "
            "(`tessera -j 1 compress --quality Q`, `PVRTexToolCLI -q pvrtcQ`), PSNR of the "
            "decoded level 0. Up and to the left is better.");
  report.figures({{rel, "PSNR (dB) against time per image (ms, log scale)"}});
  report.table({"tool", "level", "ms per image", "PSNR RGB (dB)", "SSIM grey"}, rows);
  return Status::success();
}

}  // namespace tessera::cli
