// Toth 2013, Table 1 on the GPU: GL_TIME_ELAPSED per frame (draw + MSAA resolve) of Traverse and
// Discard on the Figure-1 scene at each MSAA rate the driver allows, medians over an orbit,
// the Traverse/Discard ratios against the paper's (Iris Pro: 2.90, 2.19, 2.20, 1.65; GTX 680:
// 2.06, 1.68, 1.61, 1.38), and whether Discard at 4x beats Traverse at 1x. Then the GL frames
// against the CPU renderer (faces::FaceRenderer) at the same size, per method and rate: PSNR of
// the 8-bit sRGB outputs and the fraction of pixels with linear-RGB 2-norm difference >= 0.01.
// The CPU frame has the GL frame's sample positions (SeamsRenderer::sample_pattern, printed per
// rate): llvmpipe draws 2x with its 4x samples, so its 2x is compared with the CPU's 4x; a
// pattern that is no standard one is drawn by the CPU at the driver's own positions
// (gl::cpu_sample_offsets), or, off the CPU's 1/16-pixel grid, not compared ("-").
//
//   seams_gl_table1 [--width 480] [--height 540] [--frames 8] [--reps 5] [--msaa 1,2,4,8]
//                   [--filter aniso16|trilinear] [--agreement-frames 1] [--cpu-threads 2]
//                   [--reference]   # also GL-vs-CPU of the 8x8 Mitchell-Netravali reference
//
// Timed frames skip the read-back; the order of the two methods alternates per repetition.
// Set LP_NUM_THREADS for llvmpipe to the cores the run may use (docs/benchmarks/seams_gl.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "tessera/faces.h"
#include "tessera/gl.h"
#include "tessera/gl_seams.h"
#include "tessera/metrics.h"

using namespace tessera;

namespace {

struct Args {
  int width = 480, height = 540, frames = 8, reps = 5, agreement_frames = 1, cpu_threads = 2;
  std::vector<int> msaa = {1, 2, 4, 8};
  tessera::texture::TextureFilter filter = tessera::texture::TextureFilter::anisotropic;
  bool reference = false;
};

bool parse(int argc, char** argv, Args& a) {
  for (int i = 1; i < argc; ++i) {
    const std::string k = argv[i];
    auto next = [&](int& out) {
      if (i + 1 >= argc) return false;
      out = std::atoi(argv[++i]);
      return true;
    };
    bool ok = true;
    if (k == "--width")
      ok = next(a.width);
    else if (k == "--height")
      ok = next(a.height);
    else if (k == "--frames")
      ok = next(a.frames);
    else if (k == "--reps")
      ok = next(a.reps);
    else if (k == "--agreement-frames")
      ok = next(a.agreement_frames);
    else if (k == "--cpu-threads")
      ok = next(a.cpu_threads);
    else if (k == "--reference")
      a.reference = true;
    else if (k == "--filter" && i + 1 < argc) {
      const std::string f = argv[++i];
      if (f != "aniso16" && f != "trilinear") return false;
      a.filter = f == "trilinear" ? tessera::texture::TextureFilter::trilinear
                                  : tessera::texture::TextureFilter::anisotropic;
    } else if (k == "--msaa" && i + 1 < argc) {
      a.msaa.clear();
      for (const char* p = argv[++i]; *p;) {
        a.msaa.push_back(std::atoi(p));
        while (*p && *p != ',') ++p;
        if (*p == ',') ++p;
      }
    } else {
      return false;
    }
    if (!ok) return false;
  }
  return a.width > 0 && a.height > 0 && a.frames > 0 && a.reps > 0 && !a.msaa.empty();
}

struct Agreement {
  double psnr = 0, frac = 0;
};

Agreement agree(const ImageRGBAF& a, const ImageRGBAF& b) {
  Agreement r;
  Result<metrics::ImageComparison> c =
      metrics::compare_images(to_srgb8(a), to_srgb8(b), metrics::CompareOptions{false, 1});
  if (c) r.psnr = c->psnr_rgb;
  Result<std::vector<float>> n = metrics::error_norms(a, b);
  if (n) {
    std::size_t over = 0;
    for (float e : *n) over += !(e < 0.01f);  // NaN counts as different
    r.frac = double(over) / double(n->size());
  }
  return r;
}

int fail(const std::string& m) {
  std::fprintf(stderr, "seams_gl_table1: %s\n", m.c_str());
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  Args a;
  if (!parse(argc, argv, a)) {
    std::fprintf(stderr,
                 "usage: seams_gl_table1 [--width W] [--height H] [--frames N] [--reps R] "
                 "[--msaa 1,2,4,8] [--filter aniso16|trilinear] [--agreement-frames K] "
                 "[--cpu-threads T] [--reference]\n");
    return 2;
  }
  // The Figure-1 scene exactly as `tessera seams` builds it (default options, pattern scale 1).
  const faces::FaceScene scene = faces::figure1_scene();
  Result<std::vector<faces::FaceAdjacency>> adj = faces::build_adjacency(scene.mesh);
  if (!adj) return fail(adj.status().message);
  Result<faces::FaceTextureSet> set =
      faces::FaceTextureSet::create(faces::bake_faces(scene, {.scale = 1.0f}), std::move(*adj));
  if (!set) return fail(set.status().message);

  Result<std::unique_ptr<gl::Context>> ctx = gl::Context::create();
  if (!ctx) return fail(ctx.status().message);
  gl::SeamsRendererOptions ro;
  ro.glsl_dir = TESSERA_GLSL_DIR;
  Result<std::unique_ptr<gl::SeamsRenderer>> rr = gl::SeamsRenderer::create(scene, *set, ro);
  if (!rr) return fail(rr.status().message);
  gl::SeamsRenderer& r = **rr;
  const char* lp = std::getenv("LP_NUM_THREADS");
  std::printf("# %s, %s; LP_NUM_THREADS=%s\n", (*ctx)->renderer().c_str(),
              (*ctx)->version().c_str(), lp ? lp : "(unset)");
  std::printf(
      "# Figure-1 scene: %d faces in %d classes, %dx%d, %s, %d orbit frames x %d reps\n",
      set->face_count(), r.textures().class_count(), a.width, a.height,
      a.filter == tessera::texture::TextureFilter::trilinear ? "trilinear" : "16x anisotropic",
      a.frames, a.reps);
  std::vector<int> rates;
  const std::vector<int> refused = r.refused_msaa(a.msaa);
  for (int m : a.msaa) {
    if (std::find(refused.begin(), refused.end(), m) == refused.end()) rates.push_back(m);
  }
  std::string refused_text;
  for (int m : refused)
    refused_text += (refused_text.empty() ? "" : ", ") + std::to_string(m) + "x";
  std::printf("# MSAA rates refused by the driver: %s\n",
              refused_text.empty() ? "none" : refused_text.c_str());
  // What the driver draws each rate with (it may round a rate up: llvmpipe draws 2x with its 4x
  // samples); the GL-vs-CPU comparison renders the CPU with the same positions: the CPU rate
  // with that standard pattern, else the driver's own positions on the CPU's 1/16-pixel grid
  // (cpu_pattern), else none (cpu_rate 0: the rate is not compared).
  std::vector<int> cpu_rate(rates.size());
  std::vector<std::vector<raster::SampleOffset>> cpu_pattern(rates.size());
  for (std::size_t ri = 0; ri < rates.size(); ++ri) {
    Result<gl::SamplePattern> p = r.sample_pattern(rates[ri]);
    if (!p) return fail(p.status().message);
    if (p->cpu_msaa == 0) cpu_pattern[ri] = gl::cpu_sample_offsets(p->positions);
    cpu_rate[ri] = p->cpu_msaa > 0 ? p->cpu_msaa : int(cpu_pattern[ri].size());
    std::printf("# %dx: %d sample(s) at", rates[ri], p->samples);
    for (const gl::SamplePosition& q : p->positions) {
      std::printf(" (%+g, %+g)", double(q.x) * 16.0, double(q.y) * 16.0);
    }
    std::printf(" /16 px from the centre, y down: %s\n",
                p->cpu_msaa > 0 ? ("the CPU's " + std::to_string(p->cpu_msaa) + "x").c_str()
                : cpu_rate[ri] > 0
                    ? "no CPU pattern (compared with the CPU drawn at these positions)"
                    : "no CPU pattern, off the CPU's 1/16-pixel grid (not compared)");
  }

  const faces::Method methods[2] = {faces::Method::traverse, faces::Method::discard};
  // gpu[m][ri], wall[m][ri]
  std::vector<std::vector<std::vector<double>>> gpu(2,
                                                    std::vector<std::vector<double>>(rates.size()));
  auto wall = gpu;
  gl::SeamsFrameOptions o;
  o.width = a.width;
  o.height = a.height;
  o.filter = a.filter;
  o.read_back = false;
  // Warm-up: compile every program and create every target once.
  for (std::size_t ri = 0; ri < rates.size(); ++ri) {
    for (faces::Method m : methods) {
      o.msaa = rates[ri];
      o.method = m;
      if (Result<gl::SeamsFrame> f = r.render(faces::face_orbit_camera(scene, 0, a.frames), o); !f)
        return fail(f.status().message);
    }
  }
  for (int f = 0; f < a.frames; ++f) {
    const scene::Camera cam = faces::face_orbit_camera(scene, f, a.frames);
    for (std::size_t ri = 0; ri < rates.size(); ++ri) {
      o.msaa = rates[ri];
      for (int rep = 0; rep < a.reps; ++rep) {
        for (int k = 0; k < 2; ++k) {
          const int m = (k + rep + f) % 2;
          o.method = methods[m];
          Result<gl::SeamsFrame> fr = r.render(cam, o);
          if (!fr) return fail(fr.status().message);
          gpu[std::size_t(m)][ri].push_back(fr->gpu_ms());
          wall[std::size_t(m)][ri].push_back(fr->wall_ms);
        }
      }
      std::fprintf(stderr, "frame %d/%d %dx: traverse %.1f ms, discard %.1f ms (wall, last)\n",
                   f + 1, a.frames, rates[ri], wall[0][ri].back(), wall[1][ri].back());
    }
  }
  const double paper_gtx[4] = {0.344 / 0.167, 0.446 / 0.265, 0.485 / 0.301, 0.568 / 0.412};
  const double paper_iris[4] = {2.36 / 0.815, 2.94 / 1.34, 3.25 / 1.48, 4.02 / 2.43};
  auto rate_index = [](int m) { return m == 1 ? 0 : m == 2 ? 1 : m == 4 ? 2 : m == 8 ? 3 : -1; };
  std::printf("\n| GL_TIME_ELAPSED median, ms | Method |");
  for (int m : rates) std::printf(" %dx |", m);
  std::printf("\n|---|---|");
  for (std::size_t i = 0; i < rates.size(); ++i) std::printf("---|");
  std::printf("\n");
  const char* names[2] = {"*Traverse*", "*Discard*"};
  for (int m = 0; m < 2; ++m) {
    std::printf("| GPU timer (draw + resolve) | %s |", names[m]);
    for (std::size_t ri = 0; ri < rates.size(); ++ri)
      std::printf(" %.3f |", median(gpu[std::size_t(m)][ri]));
    std::printf("\n");
  }
  for (int m = 0; m < 2; ++m) {
    std::printf("| wall (to glFinish) | %s |", names[m]);
    for (std::size_t ri = 0; ri < rates.size(); ++ri)
      std::printf(" %.3f |", median(wall[std::size_t(m)][ri]));
    std::printf("\n");
  }
  std::printf("| ratio Traverse/Discard (GPU timer) | |");
  for (std::size_t ri = 0; ri < rates.size(); ++ri)
    std::printf(" %.2f |", median(gpu[0][ri]) / median(gpu[1][ri]));
  std::printf("\n| ratio Traverse/Discard (wall) | |");
  for (std::size_t ri = 0; ri < rates.size(); ++ri)
    std::printf(" %.2f |", median(wall[0][ri]) / median(wall[1][ri]));
  std::printf("\n| paper: GTX 680 / Iris Pro 5200 | |");
  for (int m : rates) {
    const int i = rate_index(m);
    if (i < 0)
      std::printf(" - |");
    else
      std::printf(" %.2f / %.2f |", paper_gtx[i], paper_iris[i]);
  }
  std::printf("\n\n");
  const auto i1 = std::find(rates.begin(), rates.end(), 1),
             i4 = std::find(rates.begin(), rates.end(), 4);
  if (i1 != rates.end() && i4 != rates.end()) {
    const double t1 = median(gpu[0][std::size_t(i1 - rates.begin())]);
    const double d4 = median(gpu[1][std::size_t(i4 - rates.begin())]);
    std::printf(
        "Discard 4x (%.3f ms) %s Traverse 1x (%.3f ms) on the GPU timer (paper: beats on "
        "both devices)\n",
        d4, d4 < t1 ? "beats" : "does not beat", t1);
  }
  std::printf("samples per cell: %zu\n", gpu[0].empty() ? std::size_t(0) : gpu[0][0].size());

  // ---- GL vs CPU at the benchmark size.
  Result<std::unique_ptr<faces::FaceRenderer>> cpu = faces::FaceRenderer::create(scene, *set);
  if (!cpu) return fail(cpu.status().message);
  if (a.agreement_frames <= 0) std::printf("\nGL vs CPU: skipped (--agreement-frames 0)\n");
  if (a.agreement_frames > 0) {
    std::printf(
        "\nGL vs CPU (%s, %d orbit frame(s)): PSNR dB (8-bit sRGB) / fraction of pixels "
        "with ||GL - CPU||_2 >= 0.01 (linear RGB), worst frame\n\n| method |",
        a.filter == tessera::texture::TextureFilter::trilinear ? "trilinear" : "16x anisotropic",
        a.agreement_frames);
    for (std::size_t ri = 0; ri < rates.size(); ++ri) {
      if (cpu_rate[ri] == 0) {
        std::printf(" %dx (GL; not compared) |", rates[ri]);
      } else if (!cpu_pattern[ri].empty()) {
        std::printf(" %dx (GL) vs the CPU at its positions |", rates[ri]);
      } else if (cpu_rate[ri] == rates[ri]) {
        std::printf(" %dx |", rates[ri]);
      } else {
        std::printf(" %dx (GL) vs %dx (CPU) |", rates[ri], cpu_rate[ri]);
      }
    }
    std::printf("\n|---|");
    for (std::size_t i = 0; i < rates.size(); ++i) std::printf("---|");
    std::printf("\n");
    o.read_back = true;
    for (faces::Method m : faces::all_methods()) {
      std::printf("| %s |", faces::method_name(m));
      for (std::size_t ri = 0; ri < rates.size(); ++ri) {
        const int rate = rates[ri];
        if (cpu_rate[ri] == 0) {
          std::printf(" - |");  // no CPU frame has the driver's positions
          continue;
        }
        double psnr = 1e9, frac = 0;
        for (int f = 0; f < a.agreement_frames; ++f) {
          const scene::Camera cam =
              faces::face_orbit_camera(scene, f * a.frames / a.agreement_frames, a.frames);
          o.msaa = rate;
          o.method = m;
          Result<gl::SeamsFrame> g = r.render(cam, o);
          if (!g) return fail(g.status().message);
          faces::FaceRenderOptions co;
          co.width = a.width;
          co.height = a.height;
          co.msaa = cpu_rate[ri];               // the driver's sample positions
          co.sample_pattern = cpu_pattern[ri];  // empty: the standard pattern of cpu_rate
          co.sampling.method = m;
          co.sampling.filter = a.filter;
          co.sampling.max_aniso = 16;
          co.threads = a.cpu_threads;
          Result<faces::FaceFrame> c = (*cpu)->render(cam, co);
          if (!c) return fail(c.status().message);
          const Agreement ag = agree(g->image, c->image);
          psnr = std::min(psnr, ag.psnr);
          frac = std::max(frac, ag.frac);
        }
        std::printf(" %.2f / %.4f |", psnr, frac);
      }
      std::printf("\n");
    }
  }
  if (a.reference) {
    const scene::Camera cam = faces::face_orbit_camera(scene, 0, a.frames);
    Result<ImageRGBAF> gref =
        r.render_reference(cam, a.width, a.height, {.factor = 8, .filter = a.filter});
    if (!gref) return fail(gref.status().message);
    Result<ImageRGBAF> cref =
        (*cpu)->render_reference(cam, a.width, a.height,
                                 {.factor = 8,
                                  .filter = tessera::texture::TextureFilter::anisotropic,
                                  .threads = a.cpu_threads});
    if (!cref) return fail(cref.status().message);
    const Agreement ag = agree(*gref, *cref);
    std::printf(
        "\nreference (Traverse 8x8, Mitchell-Netravali; GL %s vs CPU 16x anisotropic), "
        "frame 0: %.2f dB, %.4f of pixels >= 0.01\n",
        a.filter == tessera::texture::TextureFilter::trilinear ? "trilinear" : "16x anisotropic",
        ag.psnr, ag.frac);
  }
  return 0;
}
