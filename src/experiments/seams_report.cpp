// seams.json of a `run_seams` result (tessera/experiments/seams.h): Table 1 (median ms per
// frame) and Figure 5 (CDFs of per-pixel linear-RGB 2-norm errors), with the GL-vs-CPU part of
// Backend::both, and the zoom window; seams.md is seams_report_markdown.cpp. `tessera seams` writes
// them, the plots and the images beside them; the key names are what users script against.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "experiments/seams_report_internal.h"
#include "tessera/experiments/seams.h"

namespace tessera::experiments {

namespace {

using namespace seams_report;  // NOLINT(google-build-using-namespace): the reports' shared helpers

/// {median_ms, frame_ms} (+ wall_median_ms, wall_frame_ms with `wall`).
nlohmann::json times_json(const FrameTimes& t, const FrameTimes* wall) {
  nlohmann::json j = {{"median_ms", t.median_ms()}, {"frame_ms", t.frame_ms}};
  if (wall) j.update({{"wall_median_ms", wall->median_ms()}, {"wall_frame_ms", wall->frame_ms}});
  return j;
}

nlohmann::json summary_json(const ErrorStats& q) {
  return {{"mean", q.mean},
          {"fraction_ge_0.01", q.at(0.01)},
          {"fraction_ge_0.05", q.at(0.05)},
          {"cdf", q.cdf}};
}

/// gpu_samples[rate].positions: [x, y] per sample in 1/16 pixel from the centre, y down; null
/// where the driver's positions are not on that grid.
nlohmann::json positions_json(const SeamsSamplePattern& p) {
  if (p.positions.empty()) return nullptr;
  nlohmann::json a = nlohmann::json::array();
  for (const raster::SampleOffset& o : p.positions) a.push_back(nlohmann::json::array({o.x, o.y}));
  return a;
}

/// gpu_samples[rate].compared_with: the CPU frame the rate's GL frames were compared with; null
/// where they were not (`--backend gl`, or positions no CPU frame can have).
nlohmann::json compared_with_json(const SeamsResult& res, const SeamsSamplePattern& p) {
  const SeamsGlRateResult* g = gl_rate_result(res, p.msaa);
  if (!g) return nullptr;
  switch (g->compared_with) {
    case SeamsGlComparison::cpu_rate:
      return "cpu " + rate_key(p.cpu_msaa);
    case SeamsGlComparison::driver_positions:
      return "cpu, the driver's positions";
    case SeamsGlComparison::none:
      return nullptr;
  }
  return nullptr;
}

/// Why a rate is not compared (SeamsGlComparison::none): gl_vs_cpu[rate][method].not_compared.
constexpr const char* kNotComparedReason =
    "not compared: no CPU pattern has the driver's sample positions, and the CPU cannot draw "
    "at them (not known on its 1/16-pixel grid)";

/// command_config and scene: what was run, on what.
void config_json(const SeamsConfig& c, const SeamsResult& res, nlohmann::json& summary) {
  summary["command_config"] = {{"scene", c.scene},
                               {"ptex", c.ptex},
                               {"msaa", c.msaa},
                               {"frames", c.frames},
                               {"quality_frames", res.quality_frames},
                               {"width", c.width},
                               {"height", c.height},
                               {"reference_factor", c.reference_factor},
                               {"threads", res.threads},
                               {"filter", "anisotropic 16x (trilinear probes)"}};
  // Keys of the options beyond `tessera seams`' only where they are not their defaults, so
  // that the usual report keeps its exact keys.
  if (c.filter == texture::TextureFilter::trilinear) {
    summary["command_config"]["filter"] = "trilinear (the reference: anisotropic 16x)";
  }
  if (c.repetitions != 1) summary["command_config"]["repetitions"] = c.repetitions;
  if (!c.time_cpu) summary["command_config"]["time_cpu"] = false;
  if (c.compare_references) summary["command_config"]["compare_references"] = true;
  summary["scene"] = {{"description", res.scene_description},
                      {"faces", res.faces},
                      {"ground_faces", res.ground_faces},
                      {"texels_level0", res.texels_level0},
                      {"edge_pairings", res.edge_pairings},
                      {"valence4_corner_links", res.linked_corners},
                      {"corners", 4 * res.faces}};
}

/// The GPU device's keys (backend gl, vk or both): renderer, the rates it refuses, its sample
/// positions and how its timings read.
void gpu_device_json(const SeamsResult& res, nlohmann::json& summary) {
  summary["gpu_renderer"] = res.gpu_renderer;
  summary["gpu_version"] = res.gpu_version;
  summary["msaa_unsupported"] = res.msaa_unsupported;
  nlohmann::json samples = nlohmann::json::object();
  for (const SeamsSamplePattern& p : res.gpu_sample_patterns) {
    samples[rate_key(p.msaa)] = {{"samples", p.samples},
                                 {"cpu_msaa", p.cpu_msaa},
                                 {"positions", positions_json(p)},
                                 {"compared_with", compared_with_json(res, p)}};
  }
  summary["gpu_samples"] = samples;
  if (res.backend == Backend::vk) {
    summary["timing_note"] =
        "Vulkan: median_ms/frame_ms are GPU timestamps (draws + resolve), "
        "wall_median_ms/wall_frame_ms the host time from submission to the fence; read the GPU "
        "timer";
    return;
  }
  const std::string read = software_gl(res) ? "the wall times (llvmpipe: the timer is partial)"
                                            : "the GPU timer (a hardware GPU)";
  summary["timing_note"] =
      "GL: median_ms/frame_ms are GL_TIME_ELAPSED (draws + resolve), "
      "wall_median_ms/wall_frame_ms the wall time to glFinish; read " +
      read;
}

/// timing, quality and the NaN counts of every rate `primary` rendered.
void rates_json(const SeamsResult& res, nlohmann::json& summary) {
  const bool gl = gpu_primary(res.backend);
  nlohmann::json timing_j, quality_j, nan_j;
  for (const SeamsRateResult& rate : res.rates) {
    const std::string rk = rate_key(rate.msaa);
    for (const SeamsMethodResult& mr : rate.methods) {
      timing_j[rk][faces::method_name(mr.method)] = times_json(mr.timing, gl ? &mr.wall : nullptr);
    }
    nlohmann::json& so = timing_j[rk]["shading_only"] = times_json(rate.shading_only, nullptr);
    if (rate.shading_only.frame_ms.empty()) {
      so = {{"median_ms", nullptr},
            {"frame_ms", nlohmann::json::array()},
            {"note", "not on this backend"}};
    }
    for (const SeamsMethodResult& mr : rate.methods) {
      quality_j["vs_reference"][faces::method_name(mr.method)][rk] = summary_json(mr.vs_reference);
    }
    if (res.has_character) {
      for (const SeamsMethodResult& mr : rate.methods) {
        const ErrorStats& q = mr.vs_reference_character;
        quality_j["vs_reference_character_only"][faces::method_name(mr.method)][rk] = {
            {"mean", q.mean},
            {"fraction_ge_0.01", q.at(0.01)},
            {"fraction_ge_0.05", q.at(0.05)},
            {"counted_pixels", q.counted}};
      }
    }
    if (res.near_seam_pixels > 0) {
      for (const SeamsMethodResult& mr : rate.methods) {
        nlohmann::json j = summary_json(mr.vs_reference_near_seams);
        j["counted_pixels"] = mr.vs_reference_near_seams.counted;
        quality_j["vs_reference_near_seams"][faces::method_name(mr.method)][rk] = j;
      }
    }
    quality_j["traverse_vs_discard"][rk] = summary_json(rate.traverse_vs_discard);
    quality_j["counted_pixels"][rk] = rate.traverse_vs_discard.counted;
    nan_j[rk] = rate.nan_pixels_without_fallback;
  }
  quality_j["thresholds"] = {{"start", 0.0}, {"step", kStep}, {"count", kBins}};
  if (res.near_seam_pixels > 0) {
    quality_j["near_seams"] = {
        {"pixels", res.near_seam_pixels},
        {"counted", "geometry pixels within this many pixels of a pixel showing another face"},
        {"discard_catches_traverse_at", discard_catches_traverse(res)}};
  }
  quality_j["counted"] =
      "geometry only: pixels whose reference coverage (Mitchell-filtered alpha) exceeds 0.01, "
      "summed over the quality frames";
  summary["timing"] = timing_j;
  summary["quality"] = quality_j;
  summary["nan_pixels_discard_without_fallback_frame0"] = nan_j;
  summary["reference_ms_total"] = res.reference_ms_total;
}

/// Backend both: the GL timings and the GL-vs-CPU agreement of every rate.
void gl_comparison_json(const SeamsResult& res, nlohmann::json& summary) {
  nlohmann::json tg = nlohmann::json::object(), agree = nlohmann::json::object();
  bool standard = true;  // every rate compared with a CPU rate's standard pattern
  for (const SeamsGlRateResult& g : res.gl_rates) {
    const std::string rk = rate_key(g.msaa);
    const bool compared = g.compared_with != SeamsGlComparison::none;
    standard = standard && g.compared_with == SeamsGlComparison::cpu_rate;
    for (const SeamsGlMethodResult& m : g.methods) {
      const char* name = faces::method_name(m.method);
      tg[rk][name] = times_json(m.gpu, &m.wall);
      agree[rk][name] = {{"psnr_db", m.psnr_db}, {"fraction_ge_0.01", m.fraction_ge_001}};
      if (!compared) {
        // Explicit nulls, whatever the result holds: no agreement was measured.
        agree[rk][name] = {{"psnr_db", nullptr},
                           {"fraction_ge_0.01", nullptr},
                           {"not_compared", kNotComparedReason}};
      }
    }
  }
  summary["timing_gl"] = tg;
  summary["gl_vs_cpu"] = agree;
  if (res.gl_reference_vs_cpu.measured) {
    const SeamsReferenceAgreement& r = res.gl_reference_vs_cpu;
    summary["gl_reference_vs_cpu"] = {{"psnr_db", r.psnr_db},
                                      {"fraction_ge_0.01", r.fraction_ge_001},
                                      {"worst_frame_psnr_db", r.worst_psnr_db},
                                      {"worst_frame_fraction_ge_0.01", r.worst_fraction_ge_001}};
  }
  summary["gl_vs_cpu_note"] =
      "GL frame against the CPU frame of the same camera, method and sample positions (the "
      "CPU rate gpu_samples[rate].cpu_msaa: the rate itself unless the driver draws it with "
      "more samples), pooled over the " +
      std::to_string(res.quality_frames) +
      " quality frame(s), all pixels: psnr_db from the mean MSE of the 8-bit sRGB outputs "
      "(null = identical), fraction_ge_0.01 = pixels whose linear-RGB 2-norm difference is >= "
      "0.01 (NaN counts)";
  if (!standard) {
    // Only where a driver's positions are no standard pattern, so that the usual report
    // (every rate matched, as on llvmpipe) keeps its exact text.
    summary["gl_vs_cpu_note"] =
        summary["gl_vs_cpu_note"].get<std::string>() +
        ". Where cpu_msaa is 0 (no CPU pattern has the driver's positions), the CPU frame is "
        "drawn at the driver's own positions (gpu_samples[rate].compared_with \"cpu, the "
        "driver's positions\"), or, where those are not on the CPU's 1/16-pixel grid "
        "(positions null), the rate is not compared (compared_with null, psnr_db and "
        "fraction_ge_0.01 null, not_compared says why)";
  }
}

void fill_json(const SeamsConfig& c, const SeamsResult& res, nlohmann::json& summary) {
  config_json(c, res, summary);
  summary["backend"] = backend_name(res.backend);
  if (uses_gpu(res.backend)) gpu_device_json(res, summary);
  rates_json(res, summary);
  if (res.backend == Backend::both) gl_comparison_json(res, summary);
}

}  // namespace

std::string seams_rate_key(int msaa) { return rate_key(msaa); }

SeamsZoomWindow seams_zoom_window(const SeamsConfig& c, const SeamsResult& res) {
  SeamsZoomWindow z;
  z.w = std::min(40, c.width);
  z.h = std::min(40, c.height);
  if (res.rates.empty()) return z;
  const ImageRGBAF& a = res.rates[0].method(SeamMethod::clamp).frame0;
  const ImageRGBAF& b = res.rates[0].method(SeamMethod::traverse).frame0;
  if (a.width != c.width || a.height != c.height || b.width != c.width || b.height != c.height) {
    return z;  // no frame-0 images (keep_images off)
  }
  double best = -1;
  for (int y = 0; y + z.h <= c.height; y += 4) {
    for (int x = 0; x + z.w <= c.width; x += 4) {
      double s = 0;
      for (int yy = y; yy < y + z.h; yy += 2) {
        for (int xx = x; xx < x + z.w; xx += 2) s += norm_rgb(a.at(xx, yy), b.at(xx, yy));
      }
      if (s > best) {
        best = s;
        z.x = x;
        z.y = y;
      }
    }
  }
  return z;
}

std::string to_json(const SeamsConfig& config, const SeamsResult& result,
                    const SeamsReportOptions& options) {
  nlohmann::json summary;
  if (options.images) {
    const SeamsZoomWindow z = seams_zoom_window(config, result);
    summary["zoom_window"] = {{"x", z.x}, {"y", z.y}, {"w", z.w}, {"h", z.h}, {"scale", z.scale}};
  }
  fill_json(config, result, summary);
  return summary.dump(1);
}

}  // namespace tessera::experiments
