// Hollander et al. 2013, Table 1, on the GPU (tessera/gl_deferred.h): the dungeon at 1024x768,
// m = 4, heavy shading; per method the samples shaded (% of m^2 per pixel), PSNR against the
// full reference (8-bit sRGB, RGB) and the GPU time (GL_TIME_ELAPSED, sum of the method's
// passes, median over the frames; methods interleaved per frame). Plus the engine baseline
// (per-sample shading of edge pixels, Lauritzen 2010).
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
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "tessera/deferred.h"
#include "tessera/gl.h"
#include "tessera/gl_deferred.h"
#include "tessera/metrics.h"
#include "tessera/scene.h"

using namespace tessera;

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

}  // namespace

int main(int argc, char** argv) {
  setenv("LP_NUM_THREADS", "2", 0);
  std::string scene_path = TESSERA_SOURCE_DIR "/../shared/data/scenes/dungeon/level-dungeon.gltf";
  if (const char* s = std::getenv("TESSERA_SHARED"))
    scene_path = std::string(s) + "/data/scenes/dungeon/level-dungeon.gltf";
  int width = 1024, height = 768, m = 4, frames = 5, terms = 256;
  bool heavy = true;
  gl::DeferredGlOptions go;
  go.glsl_dir = TESSERA_GLSL_DIR;
  deferred::AdaptiveOptions adaptive;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> const char* { return i + 1 < argc ? argv[++i] : ""; };
    if (a == "--scene") scene_path = next();
    else if (a == "--width") width = std::atoi(next());
    else if (a == "--height") height = std::atoi(next());
    else if (a == "--m") m = std::atoi(next());
    else if (a == "--frames") frames = std::max(1, std::atoi(next()));
    else if (a == "--light-terms") terms = std::atoi(next());
    else if (a == "--normal") heavy = false;
    else if (a == "--force-k") adaptive.force_k = std::atoi(next());
    else if (a == "--glsl") go.glsl_dir = next();
    else if (a == "--schedule") {
      const std::string v = next();
      if (v != "tile" && v != "loop" && v != "frame") {
        std::fprintf(stderr, "aa_gl_table1: --schedule takes tile, loop or frame, not '%s'\n",
                     v.c_str());
        return 2;
      }
      go.schedule = v == "loop"    ? gl::ExtraSchedule::loop
                    : v == "frame" ? gl::ExtraSchedule::frame_list
                                   : gl::ExtraSchedule::tile_list;
    }
    else {
      std::fprintf(stderr, "aa_gl_table1: unknown option '%s'\n", a.c_str());
      return 2;
    }
  }
  Result<scene::Scene> sc = scene::load_scene(scene_path);
  if (!sc) return fail(sc.status());
  Result<scene::Camera> cam = scene::camera_from_text(*sc, "", "");
  if (!cam) return fail(cam.status());
  Result<std::unique_ptr<gl::Context>> ctx = gl::Context::create();
  if (!ctx) return fail(ctx.status());
  Result<std::unique_ptr<gl::DeferredGlRenderer>> rr = gl::DeferredGlRenderer::create(*sc, go);
  if (!rr) return fail(rr.status());
  gl::DeferredGlRenderer& r = **rr;
  deferred::ShadingOptions so = deferred::scene_shading(*sc, 8, &*cam);
  so.heavy = heavy;
  so.heavy_terms = terms;
  if (Status s = r.render_gbuffer(*cam, width, height, m); !s.ok()) return fail(s);

  const char* names[] = {"1 spp", "FXAA", "adaptive", "edge_per_sample", "reference"};
  constexpr int kMethods = 5;
  std::map<int, std::vector<double>> ms, gpu_ms;
  std::vector<double> gbuffer_ms;
  std::map<std::string, std::vector<double>> pass_ms;
  ImageRGBA8 img[kMethods];
  double pct[kMethods] = {0, 0, 0, 0, 100.0};
  const double total = double(width) * height * m * m;
  pct[0] = pct[1] = 100.0 / (m * m);
  for (int f = 0; f < frames + 1; ++f) {  // frame 0 warms up (shader compilation) and is dropped
    if (Status s = r.render_gbuffer(*cam, width, height, m); !s.ok()) return fail(s);
    if (f > 0) gbuffer_ms.push_back(r.last_gbuffer_wall_ms());
    for (int k = 0; k < kMethods; ++k) {
      const int method = (k + f) % kMethods;
      double t = 0, gpu = 0;
      std::vector<gl::PassTime> passes;
      if (method == 1) {
        Result<gl::GlFxaaResult> x = r.shade_default_fxaa(so);
        if (!x) return fail(x.status());
        t = x->total_wall_ms();
        gpu = x->total_ms();
        passes = x->wall_passes;
        img[method] = std::move(x->image);
      } else {
        Result<gl::GlShadeResult> x = method == 0   ? r.shade_default(so)
                                      : method == 2 ? r.shade_adaptive(so, adaptive)
                                      : method == 3 ? r.shade_edge_per_sample(so)
                                                    : r.shade_reference(so);
        if (!x) return fail(x.status());
        t = x->total_wall_ms();
        gpu = x->total_ms();
        passes = x->wall_passes;
        if (method == 2 || method == 3) pct[method] = 100.0 * double(x->samples_shaded) / total;
        img[method] = to_srgb8(x->image);
      }
      if (f > 0) {
        ms[method].push_back(t);
        gpu_ms[method].push_back(gpu);
        for (const gl::PassTime& p : passes) pass_ms[std::string(names[method]) + "/" + p.pass].push_back(p.ms);
      }
    }
  }
  const double ref_ms = median(ms[4]);
  std::printf("# %s, %dx%d, m = %d, %s shading (%d terms), %zu lights; GL: %s; %d frames "
              "(medians; 1 warm-up frame dropped)\n",
              scene_path.c_str(), width, height, m, heavy ? "heavy" : "normal", terms,
              so.lights.size(), (*ctx)->renderer().c_str(), frames);
  std::printf("# extra samples: %s schedule%s\n",
              go.schedule == gl::ExtraSchedule::loop         ? "loop (paper 4.2)"
              : go.schedule == gl::ExtraSchedule::frame_list ? "frame list"
                                                             : "tile list",
              adaptive.force_k >= 0 ? (", adaptive k forced to " + std::to_string(adaptive.force_k)).c_str()
                                    : "");
  std::printf("# ms = host time per pass, dispatch to the end of glFinish (llvmpipe's GL_TIME_ELAPSED "
              "reads 0 for compute; its median is the last column)\n");
  std::printf("# G-buffer pass: %.2f ms (median)\n\n", median(gbuffer_ms));
  std::printf("| method | samples %% | PSNR vs reference (dB) | ms | speed-up vs reference | GL_TIME_ELAPSED ms |\n");
  std::printf("|---|---:|---:|---:|---:|---:|\n");
  for (int k = 0; k < kMethods; ++k) {
    const double t = median(ms[k]);
    const double p = k == 4 ? std::nan("") : psnr(img[4], img[k]);
    std::printf("| %s | %.1f | %s | %.1f | %.2fx | %.2f |\n", names[k], pct[k],
                k == 4 ? "-" : (std::isinf(p) ? "inf" : std::to_string(p).substr(0, 5)).c_str(),
                t, ref_ms / t, median(gpu_ms[k]));
  }
  std::printf("\nper pass (median ms):\n");
  for (const auto& [name, v] : pass_ms) std::printf("  %-28s %9.2f\n", name.c_str(), median(v));
  return 0;
}
