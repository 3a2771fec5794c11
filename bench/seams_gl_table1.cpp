// Toth 2013, Table 1 on the GPU: GL_TIME_ELAPSED per frame (draw + MSAA resolve) of Traverse and
// Discard on the Figure-1 scene at each MSAA rate the driver allows, medians over an orbit,
// the Traverse/Discard ratios against the paper's (Iris Pro: 2.90, 2.19, 2.20, 1.65; GTX 680:
// 2.06, 1.68, 1.61, 1.38), and whether Discard at 4x beats Traverse at 1x. Then the GL frames
// against the CPU renderer (faces::FaceRenderer) at the same size, per method and rate: PSNR of
// the 8-bit sRGB outputs and the fraction of pixels with linear-RGB 2-norm difference >= 0.01,
// of the worst frame. All of it is one experiments::run_seams on the GL backend
// (gl::experiment_backends): `Backend::both` with the CPU side untimed (`time_cpu = false`),
// or `Backend::gl` when nothing is compared. The CPU frame has the GL frame's sample positions
// (printed per rate): llvmpipe draws 2x with its 4x samples, so its 2x is compared with the
// CPU's 4x; a pattern that is no standard one is drawn by the CPU at the driver's own positions,
// or, off the CPU's 1/16-pixel grid, not compared ("-").
//
//   seams_gl_table1 [--width 480] [--height 540] [--frames 8] [--reps 5] [--msaa 1,2,4,8]
//                   [--filter aniso16|trilinear] [--agreement-frames 1] [--cpu-threads 2]
//                   [--reference]   # also GL-vs-CPU of the 8x8 Mitchell-Netravali reference
//
// run_seams times all four methods (the table shows Traverse and Discard), the order of the
// methods rotating per frame and repetition; timed frames skip the read-back. The agreement
// frames are run_seams' quality frames, spread over the orbit. The bench reads none of
// run_seams' statistics against the reference, so without --reference it asks for the cheapest
// reference (factor 1). Set LP_NUM_THREADS for llvmpipe to the cores the run may use
// (docs/benchmarks/seams_gl.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "tessera/experiments/seams.h"
#include "tessera/gl_experiments.h"

using namespace tessera;
using experiments::FrameTimes;

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
  return a.width > 0 && a.height > 0 && a.frames > 0 && a.reps > 0 && a.agreement_frames >= 0 &&
         !a.msaa.empty();
}

int fail(const std::string& m) {
  std::fprintf(stderr, "seams_gl_table1: %s\n", m.c_str());
  return 1;
}

/// The GL times of one method at the i-th GL rate: GPU timer and wall.
struct GlTimes {
  const FrameTimes* gpu;
  const FrameTimes* wall;
};

/// The GL times of `m` at the ri-th GL rate (from the GL side of a `Backend::both` run).
GlTimes gl_times(const experiments::SeamsResult& res, std::size_t ri, faces::SeamMethod m) {
  if (res.backend == experiments::Backend::both) {
    const experiments::SeamsGlMethodResult& g = res.gl_rates[ri].method(m);
    return {&g.gpu, &g.wall};
  }
  const experiments::SeamsMethodResult& g = res.rates[ri].method(m);
  return {&g.timing, &g.wall};
}

/// The Figure-1 scene exactly as `tessera seams` builds it (default options, pattern scale 1).
experiments::SeamsConfig seams_config(const Args& a) {
  const bool compare = a.agreement_frames > 0 || a.reference;
  experiments::SeamsConfig c;
  c.msaa = a.msaa;
  c.frames = a.frames;
  c.quality_frames = std::max(1, a.agreement_frames);
  c.width = a.width;
  c.height = a.height;
  c.reference_factor = a.reference ? 8 : 1;
  c.threads = a.cpu_threads;
  c.filter = a.filter;
  c.repetitions = a.reps;
  c.backend = compare ? experiments::Backend::both : experiments::Backend::gl;
  c.time_cpu = !compare;  // with both: the CPU renders only what the comparison needs
  c.compare_references = a.reference;
  c.gl_factory = gl::experiment_backends(TESSERA_GLSL_DIR);
  c.keep_images = false;
  c.near_seam_pixels = 0;
  c.progress = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
  return c;
}

/// The header lines: driver, scene, refused rates, and what the driver draws each rate with (it
/// may round a rate up: llvmpipe draws 2x with its 4x samples) and what run_seams compared it
/// with (SeamsGlComparison). Returns the GL rates.
std::vector<int> print_setup(const Args& a, const experiments::SeamsResult& res,
                             const char* filter_name) {
  const char* lp = std::getenv("LP_NUM_THREADS");
  std::printf("# %s, %s; LP_NUM_THREADS=%s\n", res.gpu_renderer.c_str(), res.gpu_version.c_str(),
              lp ? lp : "(unset)");
  std::printf("# Figure-1 scene: %d faces, %dx%d, %s, %d orbit frames x %d reps\n", res.faces,
              a.width, a.height, filter_name, a.frames, a.reps);
  std::string refused_text;
  for (int m : res.msaa_unsupported)
    refused_text += (refused_text.empty() ? "" : ", ") + std::to_string(m) + "x";
  std::printf("# MSAA rates refused by the driver: %s\n",
              refused_text.empty() ? "none" : refused_text.c_str());
  std::vector<int> rates;
  for (const experiments::SeamsSamplePattern& p : res.gpu_sample_patterns) {
    rates.push_back(p.msaa);
    const experiments::SeamsGlComparison cmp = experiments::seams_gl_comparison(p);
    std::printf("# %dx: %d sample(s) at", p.msaa, p.samples);
    for (const raster::SampleOffset& q : p.positions) std::printf(" (%+d, %+d)", q.x, q.y);
    std::printf(" /16 px from the centre, y down: %s\n",
                cmp == experiments::SeamsGlComparison::cpu_rate
                    ? ("the CPU's " + std::to_string(p.cpu_msaa) + "x").c_str()
                : cmp == experiments::SeamsGlComparison::driver_positions
                    ? "no CPU pattern (compared with the CPU drawn at these positions)"
                    : "no CPU pattern, off the CPU's 1/16-pixel grid (not compared)");
  }
  return rates;
}

/// Table 1: GPU timer and wall medians of Traverse and Discard per rate, their ratios against
/// the paper's, and whether Discard at 4x beats Traverse at 1x.
void print_table1(const experiments::SeamsResult& res, const std::vector<int>& rates) {
  const auto times = [&](std::size_t ri, faces::SeamMethod m) { return gl_times(res, ri, m); };
  const faces::SeamMethod methods[2] = {faces::SeamMethod::traverse, faces::SeamMethod::discard};
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
      std::printf(" %.3f |", times(ri, methods[m]).gpu->median_ms());
    std::printf("\n");
  }
  for (int m = 0; m < 2; ++m) {
    std::printf("| wall (to glFinish) | %s |", names[m]);
    for (std::size_t ri = 0; ri < rates.size(); ++ri)
      std::printf(" %.3f |", times(ri, methods[m]).wall->median_ms());
    std::printf("\n");
  }
  std::printf("| ratio Traverse/Discard (GPU timer) | |");
  for (std::size_t ri = 0; ri < rates.size(); ++ri)
    std::printf(" %.2f |",
                times(ri, methods[0]).gpu->median_ms() / times(ri, methods[1]).gpu->median_ms());
  std::printf("\n| ratio Traverse/Discard (wall) | |");
  for (std::size_t ri = 0; ri < rates.size(); ++ri)
    std::printf(" %.2f |",
                times(ri, methods[0]).wall->median_ms() / times(ri, methods[1]).wall->median_ms());
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
    const double t1 = times(std::size_t(i1 - rates.begin()), methods[0]).gpu->median_ms();
    const double d4 = times(std::size_t(i4 - rates.begin()), methods[1]).gpu->median_ms();
    std::printf(
        "Discard 4x (%.3f ms) %s Traverse 1x (%.3f ms) on the GPU timer (paper: beats on "
        "both devices)\n",
        d4, d4 < t1 ? "beats" : "does not beat", t1);
  }
  std::printf("samples per cell: %zu\n",
              rates.empty() ? std::size_t(0) : times(0, methods[0]).gpu->frame_ms.size());
}

/// GL vs CPU at the benchmark size (run_seams' quality frames, worst frame), per method and rate.
void print_agreement(const experiments::SeamsResult& res, const std::vector<int>& rates,
                     const char* filter_name) {
  std::printf(
      "\nGL vs CPU (%s, %d orbit frame(s)): PSNR dB (8-bit sRGB) / fraction of pixels "
      "with ||GL - CPU||_2 >= 0.01 (linear RGB), worst frame\n\n| method |",
      filter_name, res.quality_frames);
  for (std::size_t ri = 0; ri < rates.size(); ++ri) {
    const experiments::SeamsSamplePattern& p = res.gpu_sample_patterns[ri];
    const experiments::SeamsGlComparison cmp = res.gl_rates[ri].compared_with;
    if (cmp == experiments::SeamsGlComparison::none) {
      std::printf(" %dx (GL; not compared) |", rates[ri]);
    } else if (cmp == experiments::SeamsGlComparison::driver_positions) {
      std::printf(" %dx (GL) vs the CPU at its positions |", rates[ri]);
    } else if (p.cpu_msaa == rates[ri]) {
      std::printf(" %dx |", rates[ri]);
    } else {
      std::printf(" %dx (GL) vs %dx (CPU) |", rates[ri], p.cpu_msaa);
    }
  }
  std::printf("\n|---|");
  for (std::size_t i = 0; i < rates.size(); ++i) std::printf("---|");
  std::printf("\n");
  for (faces::SeamMethod m : faces::all_methods()) {
    std::printf("| %s |", faces::method_name(m));
    for (std::size_t ri = 0; ri < rates.size(); ++ri) {
      const experiments::SeamsGlMethodResult& g = res.gl_rates[ri].method(m);
      if (res.gl_rates[ri].compared_with == experiments::SeamsGlComparison::none) {
        std::printf(" - |");  // no CPU frame has the driver's positions
        continue;
      }
      std::printf(" %.2f / %.4f |", g.worst_psnr_db, g.worst_fraction_ge_001);
    }
    std::printf("\n");
  }
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
  Result<experiments::SeamsResult> run = experiments::run_seams(seams_config(a));
  if (!run) return fail(run.status().message);
  const experiments::SeamsResult& res = *run;
  const char* filter_name =
      a.filter == tessera::texture::TextureFilter::trilinear ? "trilinear" : "16x anisotropic";
  const std::vector<int> rates = print_setup(a, res, filter_name);
  print_table1(res, rates);
  if (a.agreement_frames <= 0) std::printf("\nGL vs CPU: skipped (--agreement-frames 0)\n");
  if (a.agreement_frames > 0) print_agreement(res, rates, filter_name);
  if (a.reference) {
    const experiments::SeamsReferenceAgreement& r = res.gl_reference_vs_cpu;
    const std::string frames = res.quality_frames == 1
                                   ? std::string("frame 0")
                                   : "worst of " + std::to_string(res.quality_frames) + " frames";
    std::printf(
        "\nreference (Traverse 8x8, Mitchell-Netravali; GL 16x anisotropic vs CPU 16x "
        "anisotropic), %s: %.2f dB, %.4f of pixels >= 0.01\n",
        frames.c_str(), r.worst_psnr_db, r.worst_fraction_ge_001);
  }
  return 0;
}
