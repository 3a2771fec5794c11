// Hollander et al. 2013, Table 1, on the GPU: the dungeon at 1024x768, m = 4, heavy shading,
// through experiments::run_aa on its GL backend (gl::experiment_backends, tessera/gl_deferred.h
// underneath); per method the samples shaded (% of m^2 per pixel), PSNR against the full
// reference (8-bit sRGB, RGB), the host time per frame (dispatch to the end of glFinish) and
// GL_TIME_ELAPSED (sum of the method's passes), medians over the frames, methods interleaved
// per frame and each called once untimed first (run_aa's warm-up). Plus the engine baseline
// (per-sample shading of edge pixels, Lauritzen 2010). With the heavy term the table is the
// heavy run's; run_aa shades every frame without it too, and the per-pass times are of that run.
//
// Usage: aa_gl_table1 [--scene FILE.gltf] [--width 1024 --height 768] [--m 4] [--frames 5]
//                     [--light-terms 256] [--normal]   (--normal: no heavy term)
//                     [--schedule tile|loop|frame] [--force-k K] [--glsl DIR]
// --schedule: how the adaptive and edge-per-sample extra samples are scheduled
// (gl::ExtraSchedule); --force-k: every adaptive pixel shades K extra samples (the pass's cost
// at a known load); --glsl: the shader folder (default: the source tree's share/tessera/glsl).
// Sets LP_NUM_THREADS=2 unless already set (llvmpipe's worker threads).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "tessera/experiments.h"
#include "tessera/gl_experiments.h"
#include "tessera/metrics.h"
#include "tessera/scene.h"

using namespace tessera;
using experiments::AaMethod;

namespace {

double psnr(const ImageRGBA8& a, const ImageRGBA8& b) {
  metrics::CompareOptions o;
  o.compute_ssim = false;
  Result<metrics::ImageComparison> c = metrics::compare_images(a, b, o);
  return c ? c->psnr_rgb : std::nan("");
}

int fail(const Status& s) {
  std::fprintf(stderr, "aa_gl_table1: %s\n", s.message.c_str());
  return 1;
}

const char* schedule_name(gl::ExtraSchedule s) {
  return s == gl::ExtraSchedule::loop         ? "loop (paper 4.2)"
         : s == gl::ExtraSchedule::frame_list ? "frame list"
                                              : "tile list";
}

}  // namespace

int main(int argc, char** argv) {
  setenv("LP_NUM_THREADS", "2", 0);
  std::string scene_path = TESSERA_SOURCE_DIR "/../shared/data/scenes/dungeon/level-dungeon.gltf";
  if (const char* s = std::getenv("TESSERA_SHARED"))
    scene_path = std::string(s) + "/data/scenes/dungeon/level-dungeon.gltf";
  int m = 4, terms = 256;
  bool heavy = true;
  gl::ExperimentBackendOptions go;
  go.glsl_dir = TESSERA_GLSL_DIR;
  experiments::AaConfig c;
  c.width = 1024;
  c.height = 768;
  c.frames = 5;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> const char* { return i + 1 < argc ? argv[++i] : ""; };
    if (a == "--scene") {
      scene_path = next();
    } else if (a == "--width") {
      c.width = std::atoi(next());
    } else if (a == "--height") {
      c.height = std::atoi(next());
    } else if (a == "--m") {
      m = std::atoi(next());
    } else if (a == "--frames") {
      c.frames = std::max(1, std::atoi(next()));
    } else if (a == "--light-terms") {
      terms = std::atoi(next());
    } else if (a == "--normal") {
      heavy = false;
    } else if (a == "--force-k") {
      c.adaptive.force_k = std::atoi(next());
    } else if (a == "--glsl") {
      go.glsl_dir = next();
    } else if (a == "--schedule") {
      const std::string v = next();
      if (v != "tile" && v != "loop" && v != "frame") {
        std::fprintf(stderr, "aa_gl_table1: --schedule takes tile, loop or frame, not '%s'\n",
                     v.c_str());
        return 2;
      }
      go.schedule = v == "loop"    ? gl::ExtraSchedule::loop
                    : v == "frame" ? gl::ExtraSchedule::frame_list
                                   : gl::ExtraSchedule::tile_list;
    } else {
      std::fprintf(stderr, "aa_gl_table1: unknown option '%s'\n", a.c_str());
      return 2;
    }
  }
  Result<scene::Scene> sc = scene::load_scene(scene_path);
  if (!sc) return fail(sc.status());
  Result<scene::Camera> cam = scene::camera_from_text(*sc, "", "");
  if (!cam) return fail(cam.status());
  c.scene = std::make_shared<const scene::Scene>(std::move(*sc));
  c.camera = *cam;
  c.ssaa = {m};
  c.lights = 8;
  c.heavy = heavy;
  c.heavy_terms = terms;
  c.backend = experiments::Backend::gl;
  c.gl_factory = gl::experiment_backends(go);
  Result<experiments::AaResult> res = experiments::run_aa(c);
  if (!res) return fail(res.status());
  const experiments::AaRateResult& rate = res->rates.at(0);

  const AaMethod methods[] = {AaMethod::default_1spp, AaMethod::fxaa, AaMethod::adaptive,
                              AaMethod::edge_per_sample, AaMethod::reference};
  const char* names[] = {"1 spp", "FXAA", "adaptive", "edge_per_sample", "reference"};
  const auto wall = [&](AaMethod k) {
    const experiments::AaTiming& t = rate.method(k).timing;
    return (heavy ? t.heavy : t.normal).median_ms();
  };
  const auto image = [&](AaMethod k) -> const ImageRGBA8& {
    return heavy ? rate.method(k).image_heavy : rate.method(k).image;
  };
  std::printf(
      "# %s, %dx%d, m = %d, %s shading (%d terms), %zu lights; GL: %s; %d frames "
      "(medians; every method once untimed first)\n",
      scene_path.c_str(), c.width, c.height, m, heavy ? "heavy" : "normal", res->heavy_terms,
      res->lights, res->gpu_renderer.c_str(), c.frames);
  const std::string forced =
      c.adaptive.force_k >= 0 ? ", adaptive k forced to " + std::to_string(c.adaptive.force_k) : "";
  std::printf("# extra samples: %s schedule%s\n", schedule_name(go.schedule), forced.c_str());
  std::printf(
      "# ms = host time per pass, dispatch to the end of glFinish (llvmpipe's "
      "GL_TIME_ELAPSED reads 0 for compute; its median is the last column)\n");
  std::printf("# G-buffer pass: %.2f ms (median)\n\n", rate.gbuffer.median_ms());
  std::printf(
      "| method | samples %% | PSNR vs reference (dB) | ms | speed-up vs reference | "
      "GL_TIME_ELAPSED ms |\n");
  std::printf("|---|---:|---:|---:|---:|---:|\n");
  const double ref_ms = wall(AaMethod::reference);
  for (int i = 0; i < 5; ++i) {
    const AaMethod k = methods[i];
    const experiments::AaTiming& t = rate.method(k).timing;
    const double pct = heavy && k == AaMethod::adaptive ? rate.adaptive_heavy_samples_pct
                                                        : rate.method(k).samples_pct;
    const double p =
        k == AaMethod::reference ? std::nan("") : psnr(image(AaMethod::reference), image(k));
    const std::string cell = k == AaMethod::reference ? "-"
                             : std::isinf(p)          ? "inf"
                                                      : std::to_string(p).substr(0, 5);
    std::printf("| %s | %.1f | %s | %.1f | %.2fx | %.2f |\n", names[i], pct, cell.c_str(), wall(k),
                ref_ms / wall(k), (heavy ? t.gpu_heavy : t.gpu).median_ms());
  }
  std::printf("\nper pass (median ms%s):\n", heavy ? ", without the heavy term" : "");
  for (int i = 0; i < 5; ++i) {
    for (const experiments::AaPassFrames& p : rate.method(methods[i]).passes) {
      const std::string name = std::string(names[i]) + "/" + p.pass;
      std::printf("  %-28s %9.2f\n", name.c_str(), p.wall.median_ms());
    }
  }
  return 0;
}
