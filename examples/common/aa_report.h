// aa_report.h — what the two AA example engines (examples/engine_aa on OpenGL,
// examples/engine_aa_vk on Vulkan) share around their frame: the flags both take (--size, --m,
// --budget, --schedule, --json, -o), the component's options both backends' options derive
// from (tessera::AdaptiveCommonOptions: the G-buffer layout, the hook, the resolve), the
// display encoding of the HDR output, the measures of a
// run (samples %, PSNR of the adaptive and the 1 spp image against the component's own full
// supersampling), the -o images and the report (one line, or one JSON object with --json).
// Header-only, like aa_scene.h.
#pragma once

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "engine_args.h"
#include "tessera/adaptive_supersampler.h"
#include "tessera/core.h"
#include "tessera/io.h"
#include "tessera/metrics.h"

namespace engine {

/// The flags both AA engines take.
struct AaArgs {
  int w = 320, h = 240, m = 4;
  long long budget = -1;  // -1: none
  std::string schedule = "frame_list", out;
  tessera::AdaptiveSchedule schedule_kind = tessera::AdaptiveSchedule::frame_list;
  bool json = false;
};

/// Adds --size WxH, --m M, --budget B, --schedule frame_list|tile_list|loop, --json, -o DIR.
inline void add_aa_flags(CommandLine& cl, AaArgs& a) {
  cl.option("--size", [&a](const std::string& v) -> std::string {
    return parse_size(v, a.w, a.h) ? "" : "--size " + v + ": expected WxH";
  });
  cl.option("--m", [&a](const std::string& v) -> std::string {
    a.m = std::atoi(v.c_str());  // the component checks it (2..8)
    return "";
  });
  cl.option("--budget", [&a](const std::string& v) -> std::string {
    a.budget = std::atoll(v.c_str());
    return a.budget < 0 ? "--budget must be >= 0" : "";
  });
  cl.option("--schedule", [&a](const std::string& v) -> std::string {
    a.schedule = v;
    if (v == "frame_list") {
      a.schedule_kind = tessera::AdaptiveSchedule::frame_list;
    } else if (v == "tile_list") {
      a.schedule_kind = tessera::AdaptiveSchedule::tile_list;
    } else if (v == "loop") {
      a.schedule_kind = tessera::AdaptiveSchedule::loop;
    } else {
      return "--schedule " + v + ": frame_list, tile_list or loop";
    }
    return "";
  });
  cl.flag("--json", &a.json);
  cl.option("-o", [&a](const std::string& v) -> std::string {
    a.out = v;
    return "";
  });
}

/// The options both engines give the component (gl:: and vk::AdaptiveSupersamplerOptions add
/// their backend's): the frame size, m and schedule from the flags, the engine's G-buffer layout
/// (RT0 normal xyz + linear depth, RT1 alpha (id + 1) / 255), its shading `hook`, tonemap-weighted
/// resolve (HDR lights) into RGBA16F, the sample counts and the pass times for the report.
inline void set_aa_options(tessera::AdaptiveCommonOptions& o, const AaArgs& a, std::string hook) {
  o.width = a.w;
  o.height = a.h;
  o.m = a.m;
  o.schedule = a.schedule_kind;
  o.layout.normal = {0, "rgb"};
  o.layout.depth = {0, "a"};
  o.layout.id = {1, "a", 255.0f, -1.0f};  // (id + 1) / 255 in unorm8; sky = -1
  o.hook.source = std::move(hook);
  o.hook.name = "engine_shading.glsl";
  o.resolve = tessera::AdaptiveResolve::tonemap_weighted;  // HDR lights
  o.output = tessera::AdaptiveOutputFormat::rgba16f;
  o.sample_count_texture = true;
  o.profile = true;  // pass times for --json (each backend says what it costs)
}

inline double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/// Display encoding: Reinhard c / (1 + c), then sRGB8.
inline tessera::ImageRGBA8 display(const tessera::ImageRGBAF& hdr) {
  tessera::ImageRGBAF ldr = hdr;
  for (std::size_t i = 0; i < ldr.pixel_count(); ++i) {
    for (int c = 0; c < 3; ++c) {
      float& x = ldr.pixels[i * 4 + std::size_t(c)];
      x = x / (1.0f + x);
    }
    ldr.pixels[i * 4 + 3] = 1.0f;
  }
  return tessera::to_srgb8(ldr);
}

inline double psnr(const tessera::ImageRGBA8& a, const tessera::ImageRGBA8& b) {
  tessera::metrics::CompareOptions o;
  o.compute_ssim = false;
  auto r = tessera::metrics::compare_images(a, b, o);
  return r ? r->psnr_rgb : 0.0;
}

/// The three frames of a run, display-encoded: the adaptive one, the component's full
/// supersampling (the reference) and its first sample alone (1 spp).
struct AaImages {
  tessera::ImageRGBA8 adaptive, reference, first;
};

/// What one run measured, for the report (milliseconds: each backend says how it times).
struct AaReport {
  double samples_pct = 0, psnr_adaptive = 0, psnr_one = 0;
  double gbuffer_ms = 0, adaptive_ms = 0, first_ms = 0, reference_ms = 0;
  unsigned long long extra = 0;
  std::vector<std::pair<std::string, double>> passes;  // the adaptive frame's, in order

  /// The adaptive frame's pass times: each pass's `ms` (&PassTime::wall_ms on GL, whose
  /// llvmpipe reads 0 for compute; &PassTime::gpu_ms on Vulkan).
  void set_passes(const std::vector<tessera::PassTime>& times, double tessera::PassTime::*ms) {
    passes.clear();
    for (const tessera::PassTime& t : times) passes.emplace_back(t.pass, t.*ms);
  }
};

/// Display-encodes the three HDR frames and fills the samples % (with `extra` samples beyond
/// one a pixel) and both PSNRs of `r`.
inline AaImages measure(const AaArgs& a, const tessera::ImageRGBAF& adaptive,
                        const tessera::ImageRGBAF& reference, const tessera::ImageRGBAF& first,
                        unsigned long long extra, AaReport& r) {
  AaImages d{display(adaptive), display(reference), display(first)};
  const double pixels = double(a.w) * a.h;
  r.extra = extra;
  r.samples_pct = 100.0 * (pixels + double(extra)) / (pixels * a.m * a.m);
  r.psnr_adaptive = psnr(d.adaptive, d.reference);
  r.psnr_one = psnr(d.first, d.reference);
  return d;
}

/// -o DIR: adaptive.png, reference.png, first.png and samples.png (k + 1 a pixel, grey, from
/// `counts`); "" or the problem.
inline std::string write_aa_outputs(const AaArgs& a, const AaImages& d,
                                    const std::vector<std::uint8_t>& counts) {
  std::error_code ec;
  std::filesystem::create_directories(a.out, ec);
  tessera::ImageRGBA8 k(a.w, a.h);
  for (std::size_t i = 0; i < counts.size(); ++i) {
    const auto g = std::uint8_t(255 * (counts[i] - 1) / (a.m * a.m - 1));
    k.pixels[i * 4] = k.pixels[i * 4 + 1] = k.pixels[i * 4 + 2] = g;
    k.pixels[i * 4 + 3] = 255;
  }
  for (const auto& [name, im] : {std::pair{"adaptive.png", &d.adaptive},
                                 {"reference.png", &d.reference},
                                 {"first.png", &d.first},
                                 {"samples.png", &k}}) {
    const std::string path = (std::filesystem::path(a.out) / name).string();
    if (auto s = tessera::io::write_png(path, *im); !s.ok()) return s.message;
  }
  return "";
}

/// The --json object, one line: {"device", then `after_device` (the backend's own keys, each
/// with its ", "), the size, m and schedule, `after_schedule`, the budget, samples, PSNRs and
/// times, then `at_end` (", "-led keys)}.
inline void print_aa_json(const std::string& device, const AaArgs& a, const AaReport& r,
                          const std::string& after_device, const std::string& after_schedule,
                          const std::string& at_end) {
  std::printf(
      "{\"device\": \"%s\", %s\"width\": %d, \"height\": %d, \"m\": %d, \"schedule\": \"%s\", ",
      device.c_str(), after_device.c_str(), a.w, a.h, a.m, a.schedule.c_str());
  std::printf("%s", after_schedule.c_str());
  if (a.budget >= 0) {
    std::printf("\"budget\": %lld, ", a.budget);
  } else {
    std::printf("\"budget\": null, ");
  }
  std::printf(
      "\"extra_samples\": %llu, \"samples_percent\": %.3f, \"psnr_db\": %.3f, "
      "\"psnr_1spp_db\": %.3f, \"gbuffer_ms\": %.3f, \"passes_ms\": {",
      r.extra, r.samples_pct, r.psnr_adaptive, r.psnr_one, r.gbuffer_ms);
  for (std::size_t i = 0; i < r.passes.size(); ++i) {
    std::printf("%s\"%s\": %.3f", i ? ", " : "", r.passes[i].first.c_str(), r.passes[i].second);
  }
  std::printf("}, \"adaptive_ms\": %.3f, \"first_ms\": %.3f, \"reference_ms\": %.3f%s}\n",
              r.adaptive_ms, r.first_ms, r.reference_ms, at_end.c_str());
}

/// The one-line report: "`engine` WxH m=M`on`: S % samples, PSNR ...".
inline void print_aa_summary(const char* engine, const std::string& on, const AaArgs& a,
                             const AaReport& r) {
  std::printf(
      "%s %dx%d m=%d%s: %.1f %% samples, PSNR %.2f dB (1 spp %.2f dB) against full "
      "supersampling\n",
      engine, a.w, a.h, a.m, on.c_str(), r.samples_pct, r.psnr_adaptive, r.psnr_one);
}

}  // namespace engine
