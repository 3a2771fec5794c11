// seams.json and seams.md of a `run_seams` result (tessera/experiments/seams.h): Table 1
// (median ms per frame, side by side) and Figure 5 (CDFs of per-pixel linear-RGB 2-norm
// errors), with the GL-vs-CPU part of Backend::both. `tessera seams` writes them, the plots and
// the images beside them; the key names are what users script against.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tessera/experiments/seams.h"

namespace tessera::experiments {

namespace {

using faces::SeamMethod;

constexpr double kStep = kSeamsCdfStep;
constexpr int kBins = kSeamsCdfBins;

std::string rate_key(int r) { return std::to_string(r) + "x"; }

std::string fmt(const char* format, double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, value);
  return buf;
}

float norm_rgb(const float* a, const float* b) {
  const float d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
  return std::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
}

/// The first MSAA rate at which Discard's mean near-seam error is no larger than Traverse's at
/// the same rate, or null when it never is.
nlohmann::json discard_catches_traverse(const SeamsResult& res) {
  for (const SeamsRateResult& rate : res.rates) {
    if (rate.method(SeamMethod::discard).vs_reference_near_seams.mean <=
        rate.method(SeamMethod::traverse).vs_reference_near_seams.mean) {
      return rate.msaa;
    }
  }
  return nullptr;
}

/// Whether GL ran on a software rasteriser (llvmpipe, softpipe): its GPU timer is partial.
bool software_gl(const SeamsResult& res) {
  return res.gl_renderer.find("llvmpipe") != std::string::npos ||
         res.gl_renderer.find("softpipe") != std::string::npos;
}

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

/// The GL-vs-CPU result of a GL rate (`--backend both`), or null.
const SeamsGlRateResult* gl_rate_result(const SeamsResult& res, int msaa) {
  if (res.backend != Backend::both) return nullptr;
  for (const SeamsGlRateResult& g : res.gl_rates) {
    if (g.msaa == msaa) return &g;
  }
  return nullptr;
}

/// gl_samples[rate].positions: [x, y] per sample in 1/16 pixel from the centre, y down; null
/// where the driver's positions are not on that grid.
nlohmann::json positions_json(const SeamsSamplePattern& p) {
  if (p.positions.empty()) return nullptr;
  nlohmann::json a = nlohmann::json::array();
  for (const raster::SampleOffset& o : p.positions) a.push_back(nlohmann::json::array({o.x, o.y}));
  return a;
}

/// gl_samples[rate].compared_with: the CPU frame the rate's GL frames were compared with; null
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

/// The GL device's keys (backend gl or both): renderer, the rates it refuses, its sample
/// positions and how its timings read.
void gl_device_json(const SeamsResult& res, nlohmann::json& summary) {
  summary["gl_renderer"] = res.gl_renderer;
  summary["gl_version"] = res.gl_version;
  summary["msaa_unsupported"] = res.msaa_unsupported;
  nlohmann::json samples = nlohmann::json::object();
  for (const SeamsSamplePattern& p : res.gl_sample_patterns) {
    samples[rate_key(p.msaa)] = {{"samples", p.samples},
                                 {"cpu_msaa", p.cpu_msaa},
                                 {"positions", positions_json(p)},
                                 {"compared_with", compared_with_json(res, p)}};
  }
  summary["gl_samples"] = samples;
  const std::string read = software_gl(res) ? "the wall times (llvmpipe: the timer is partial)"
                                            : "the GPU timer (a hardware GPU)";
  summary["timing_note"] =
      "GL: median_ms/frame_ms are GL_TIME_ELAPSED (draws + resolve), "
      "wall_median_ms/wall_frame_ms the wall time to glFinish; read " +
      read;
}

/// timing, quality and the NaN counts of every rate `primary` rendered.
void rates_json(const SeamsResult& res, nlohmann::json& summary) {
  const bool gl = res.backend == Backend::gl;
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
      "CPU rate gl_samples[rate].cpu_msaa: the rate itself unless the driver draws it with "
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
        "drawn at the driver's own positions (gl_samples[rate].compared_with \"cpu, the "
        "driver's positions\"), or, where those are not on the CPU's 1/16-pixel grid "
        "(positions null), the rate is not compared (compared_with null, psnr_db and "
        "fraction_ge_0.01 null, not_compared says why)";
  }
}

void fill_json(const SeamsConfig& c, const SeamsResult& res, nlohmann::json& summary) {
  config_json(c, res, summary);
  summary["backend"] = backend_name(res.backend);
  if (res.backend == Backend::gl || res.backend == Backend::both) gl_device_json(res, summary);
  rates_json(res, summary);
  if (res.backend == Backend::both) gl_comparison_json(res, summary);
}

std::string error_row(const std::string& label, int msaa, const ErrorStats& q) {
  return "| " + label + " | " + rate_key(msaa) + fmt(" | %.5f", q.mean) +
         fmt(" | %.4f", q.at(0.01)) + fmt(" | %.4f |\n", q.at(0.05));
}

/// Median ms of one variant per rate (`label` in the first column).
struct TimeRow {
  std::string label;
  std::vector<double> ms;
};

/// A Table-1 block: one column per rate, the rows, then Traverse / Discard. Returns whether
/// Discard is at least 2x faster at every rate.
bool time_table(std::ostringstream& md, const std::vector<int>& rates,
                const std::vector<TimeRow>& rows, const char* cell) {
  const auto row = [&](SeamMethod m) {
    return std::find_if(rows.begin(), rows.end(),
                        [&](const TimeRow& r) { return r.label == faces::method_name(m); });
  };
  const auto t = row(SeamMethod::traverse), d = row(SeamMethod::discard);
  md << "| method |";
  for (int r : rates) md << " " << r << "x |";
  md << "\n|---|";
  for (std::size_t ri = 0; ri < rates.size(); ++ri) md << "---:|";
  md << "\n";
  for (const TimeRow& r : rows) {
    md << "| " << r.label << " |";
    for (double v : r.ms) md << fmt(cell, v);
    md << "\n";
  }
  md << "| **traverse / discard** |";
  bool speed_ok = true;
  for (std::size_t ri = 0; ri < rates.size(); ++ri) {
    const double ratio = t->ms[ri] / std::max(d->ms[ri], 1e-9);
    speed_ok = speed_ok && ratio >= 2.0;
    md << fmt(" %.2fx |", ratio);
  }
  md << "\n\n";
  return speed_ok;
}

/// The wall-time and GPU-timer blocks of GL frames; returns the 2x target of the one to read.
template <typename Rate, typename Pick>
bool gl_time_tables(std::ostringstream& md, const SeamsResult& res, const std::vector<Rate>& rates,
                    Pick pick) {
  const std::vector<SeamMethod>& methods = faces::all_methods();
  std::vector<int> keys;
  for (const Rate& r : rates) keys.push_back(r.msaa);
  bool ok[2] = {true, true};
  for (int gpu = 0; gpu < 2; ++gpu) {
    std::vector<TimeRow> rows;
    for (SeamMethod m : methods) {
      TimeRow row{faces::method_name(m), {}};
      for (const Rate& r : rates) row.ms.push_back(pick(r, m, gpu == 1)->median_ms());
      rows.push_back(std::move(row));
    }
    md << (gpu ? "GPU timer (GL_TIME_ELAPSED of the draws and the resolve), median ms:\n\n"
               : "Wall time (first GL call of the frame to glFinish after the resolve, "
                 "read-back excluded), median ms:\n\n");
    ok[gpu] = time_table(md, keys, rows, gpu ? " %.3f |" : " %.2f |");
  }
  md << "**Which to read:** "
     << (software_gl(res)
             ? "the wall times. This is llvmpipe, a software rasteriser: its GL_TIME_ELAPSED "
               "queries are executed per screen tile by the rasteriser threads and cover only "
               "part of the frame (gl_face_renderer.h)."
             : "the GPU timer (a hardware GPU: the timer is the pass time; wall time adds the "
               "driver's submission and the glFinish round trip).")
     << "\n\n";
  return software_gl(res) ? ok[0] : ok[1];
}

/// `--backend both`: the GL times and the GL-vs-CPU agreement.
std::string gl_beside_cpu(const SeamsResult& res) {
  std::ostringstream md;
  md << "\n## OpenGL beside the CPU\n\nThe same frames rendered by GL (" << res.gl_renderer
     << "), methods alternating per frame";
  if (!res.msaa_unsupported.empty()) {
    md << "; refused by the driver and skipped on GL:";
    for (int r : res.msaa_unsupported) md << " " << rate_key(r);
  }
  md << ".\n\n";
  gl_time_tables(md, res, res.gl_rates, [](const SeamsGlRateResult& r, SeamMethod m, bool gpu) {
    return gpu ? &r.method(m).gpu : &r.method(m).wall;
  });
  md << "GL against the CPU, the same camera, method and sample positions (the rate's, unless "
        "the driver draws it with more samples, see above), pooled over the "
     << res.quality_frames
     << " quality frame(s), all pixels: PSNR of the 8-bit sRGB outputs (from the mean MSE) / "
        "fraction of pixels whose linear-RGB 2-norm difference is >= 0.01. Under 16x "
        "anisotropic filtering the drivers' hardware filter is implementation-defined "
        "(llvmpipe's is much blurrier than tessera's exact filter), so the agreement is lower "
        "than under trilinear filtering.\n\n| method |";
  std::string rule = "\n|---|";
  for (const SeamsGlRateResult& g : res.gl_rates) {
    md << " " << rate_key(g.msaa) << " |";
    rule += "---:|";
  }
  md << rule << "\n";
  for (SeamMethod m : faces::all_methods()) {
    md << "| " << faces::method_name(m) << " |";
    for (const SeamsGlRateResult& g : res.gl_rates) {
      const SeamsGlMethodResult& r = g.method(m);
      if (g.compared_with == SeamsGlComparison::none) {
        md << " not compared |";  // see the sample-position note at the top
        continue;
      }
      md << (std::isfinite(r.psnr_db) ? fmt(" %.2f dB", r.psnr_db) : std::string(" identical"))
         << fmt(" / %.4f |", r.fraction_ge_001);
    }
    md << "\n";
  }
  return md.str();
}

/// The note on a GL rate whose sample positions are no CPU pattern (cpu_msaa 0): where they
/// are, and what its GL frames were compared with (`--backend both`).
std::string driver_positions_sentence(const SeamsResult& res, const SeamsSamplePattern& p) {
  std::string s = " The driver draws " + rate_key(p.msaa) + " with " + std::to_string(p.samples) +
                  " sample(s) at positions no CPU pattern has (";
  if (p.positions.empty()) {
    s += "not on the CPU's 1/16-pixel grid)";
  } else {
    for (std::size_t i = 0; i < p.positions.size(); ++i) {
      s += (i ? ", (" : "(") + std::to_string(p.positions[i].x) + ", " +
           std::to_string(p.positions[i].y) + ")";
    }
    s += " /16 px from the pixel centre, y down)";
  }
  if (const SeamsGlRateResult* g = gl_rate_result(res, p.msaa)) {
    s += ": its GL " + rate_key(p.msaa) + " frames are " +
         (g->compared_with == SeamsGlComparison::driver_positions
              ? std::string("compared with CPU frames drawn at those positions")
              : std::string("not compared with the CPU (no CPU frame has those positions)"));
  }
  return s + ".";
}

/// The title, the scene and the backend paragraph.
void md_header(std::ostringstream& md, const SeamsConfig& c, const SeamsResult& res) {
  const bool gl = res.backend == Backend::gl;
  const bool both = res.backend == Backend::both;
  md << "# Seams experiment (Toth 2013, Table 1 and Figure 5)\n\n";
  md << "Scene: " << res.scene_description << "; " << res.faces << " faces, " << res.texels_level0
     << " level-0 texels, " << res.linked_corners << " of " << 4 * res.faces
     << " corners with a valence-4 diagonal face. " << c.width << "x" << c.height << ", "
     << c.frames << " orbit frames (" << res.quality_frames << " with a reference), "
     << (c.filter == texture::TextureFilter::trilinear
             ? "trilinear filtering (the reference: 16x anisotropic)"
             : "16x anisotropic filtering")
     << ", " << res.threads << " thread(s).\n\n";
  if (gl || both) {
    md << "Backend: **" << (gl ? "OpenGL" : "CPU, and OpenGL beside it (`--backend both`)")
       << "**: " << res.gl_renderer << ", " << res.gl_version << ".";
    if (!res.msaa_unsupported.empty()) {
      md << " MSAA rates the driver refuses, skipped" << (gl ? "" : " on GL") << ":";
      for (int r : res.msaa_unsupported) md << " " << rate_key(r);
      md << ".";
    }
    for (const SeamsSamplePattern& p : res.gl_sample_patterns) {
      if (p.cpu_msaa == 0) {
        md << driver_positions_sentence(res, p);
        continue;
      }
      if (p.samples == p.msaa) continue;
      md << " The driver draws " << rate_key(p.msaa) << " with " << p.samples << " samples";
      md << " (the CPU's " << rate_key(p.cpu_msaa) << " positions)";
      md << ": its GL " << rate_key(p.msaa) << " frames are " << p.samples << "-sample frames";
      if (both) {
        md << ", compared with the CPU's " << rate_key(p.cpu_msaa) << " frames";
      }
      md << ".";
    }
    md << (gl ? " The reference is rendered by GL too (Traverse, 16x anisotropic, tiled); face "
                "ids (near-seam pixels) and the character mask come from the CPU renderer, "
                "whose geometry is the same."
              : "")
       << "\n\n";
  }
}

/// Table 1: the median times; whether Discard is at least 2x faster than Traverse everywhere.
bool md_table1(std::ostringstream& md, const SeamsResult& res) {
  const std::vector<SeamMethod>& methods = faces::all_methods();
  const bool gl = res.backend == Backend::gl;
  md << "## Table 1 analogue: median ms per frame\n\n";
  bool speed_ok = true;
  if (gl) {
    md << "Draws + MSAA box resolve on the GPU, all methods rendered side by side in one run, "
          "alternating per frame (no shading-only pass on GL).\n\n";
    speed_ok = gl_time_tables(md, res, res.rates, [](const SeamsRateResult& r, SeamMethod m, bool gpu) {
      return gpu ? &r.method(m).timing : &r.method(m).wall;
    });
  } else {
    md << "Raster + shading + MSAA box resolve, all variants rendered side by side in one run, "
          "alternating per frame; `shading only` is the same pass without the texture "
          "lookup.\n\n";
    std::vector<int> keys;
    std::vector<TimeRow> rows;
    for (const SeamsRateResult& rate : res.rates) keys.push_back(rate.msaa);
    for (std::size_t v = 0; v <= methods.size(); ++v) {
      const bool shading = v == methods.size();
      TimeRow row{shading ? std::string("shading only") : faces::method_name(methods[v]), {}};
      for (const SeamsRateResult& rate : res.rates) {
        row.ms.push_back(
            (shading ? rate.shading_only : rate.method(methods[v]).timing).median_ms());
      }
      rows.push_back(std::move(row));
    }
    speed_ok = time_table(md, keys, rows, " %.1f |");
  }
  return speed_ok;
}

/// Figure 5: the error tables (all pixels, near the seams, the character).
void md_figure5(std::ostringstream& md, const SeamsConfig& c, const SeamsResult& res) {
  const std::vector<SeamMethod>& methods = faces::all_methods();
  md << "## Figure 5 analogue\n\n";
  md << "Pixels counted: **geometry only** — pixels whose reference coverage (the alpha of the "
        "Mitchell-filtered supersampled reference) exceeds 0.01, over the quality frames, the "
        "same set for every method and rate. Error = per-pixel 2-norm of the linear-RGB "
        "difference. Plots: `fig5_left.svg` (Traverse vs Discard), `fig5_right.svg` (each "
        "method vs the reference: Traverse at "
     << c.reference_factor << "x" << c.reference_factor
     << " the resolution, downsampled with Mitchell-Netravali B = C = 1/3), each also as PNG "
        "(`fig5_left.png`, `fig5_right.png`: same curves and legend order, labels in the SVG); "
        "data in `cdf.csv` and `seams.json`.\n\n";
  md << "| comparison | rate | mean error | fraction >= 0.01 | fraction >= 0.05 |\n"
        "|---|---|---:|---:|---:|\n";
  for (const SeamsRateResult& rate : res.rates) {
    md << error_row("traverse vs discard", rate.msaa, rate.traverse_vs_discard);
  }
  for (SeamMethod m : methods) {
    for (const SeamsRateResult& rate : res.rates) {
      md << error_row(std::string(faces::method_name(m)) + " vs reference", rate.msaa,
                      rate.method(m).vs_reference);
    }
  }
  if (res.near_seam_pixels > 0) {
    md << "\nNear the seams: the same comparison counting only the geometry pixels within "
       << res.near_seam_pixels
       << " pixels of a pixel that shows another face, where the methods differ (most of the "
          "error elsewhere is texture filtering, the same for every method). Per-rate plots: "
          "`fig5_<rate>.svg` (solid: all pixels, dashed: near seams).\n\n"
          "| method vs reference, near seams | rate | mean error | fraction >= 0.01 | "
          "fraction >= 0.05 |\n|---|---|---:|---:|---:|\n";
    for (SeamMethod m : methods) {
      for (const SeamsRateResult& rate : res.rates) {
        md << error_row(faces::method_name(m), rate.msaa, rate.method(m).vs_reference_near_seams);
      }
    }
    const nlohmann::json catches = discard_catches_traverse(res);
    md << "\nNear the seams, Discard "
       << (catches.is_null() ? std::string("does not catch Traverse at any rate measured")
                             : "catches Traverse (mean error no larger) from " +
                                   rate_key(catches.get<int>()) + " MSAA")
       << ".\n";
  }
  if (res.has_character) {
    md << "\nBreakdown (not the Figure-5 pixel set): the same comparison counting only the "
          "character's pixels (at least half of 8 MSAA samples on a character face), where the "
          "surface is curved and Traverse's extrapolation across edges is approximate.\n\n"
          "| method vs reference, character only | rate | mean error | fraction >= 0.01 | "
          "fraction >= 0.05 |\n|---|---|---:|---:|---:|\n";
    for (SeamMethod m : methods) {
      for (const SeamsRateResult& rate : res.rates) {
        md << error_row(faces::method_name(m), rate.msaa, rate.method(m).vs_reference_character);
      }
    }
  }
}

/// The targets and the zero-coverage fallback's NaN counts.
void md_targets(std::ostringstream& md, const SeamsResult& res, bool speed_ok) {
  md << "\n## Targets\n\n";
  md << "- Discard at least 2x faster than Traverse at every rate: **"
     << (speed_ok ? "met" : "not met") << "** (ratios in the table).\n";
  for (const SeamsRateResult& rate : res.rates) {
    const double d = rate.method(SeamMethod::discard).vs_reference.mean;
    const double t = rate.method(SeamMethod::traverse).vs_reference.mean;
    md << "- " << rate_key(rate.msaa) << ": mean error vs reference Discard " << fmt("%.5f", d)
       << ", Traverse " << fmt("%.5f", t) << " -> "
       << (d <= t ? "Discard no worse" : "Traverse better") << ".\n";
  }
  md << "\n## Zero-coverage fallback\n\nDiscard without the clamp fallback (frame 0): pixels "
        "with a NaN colour (0/0 where no tap of a pixel-centre lookup outside its face lands "
        "inside it; helper lanes are not shaded here):";
  for (const SeamsRateResult& rate : res.rates) {
    md << " " << rate_key(rate.msaa) << ": " << rate.nan_pixels_without_fallback << ";";
  }
  md << " with the fallback: 0.\n";
}

std::string markdown(const SeamsConfig& c, const SeamsResult& res, bool images) {
  std::ostringstream md;
  md_header(md, c, res);
  const bool speed_ok = md_table1(md, res);
  md_figure5(md, c, res);
  md_targets(md, res, speed_ok);
  if (res.backend == Backend::both) md << gl_beside_cpu(res);
  if (images) {
    md << "\n## Images\n\n`images/<method>_<rate>.png` (frame 0), `images/reference.png`, "
          "`images/zoom_*.png`: a 40x40 window at 4x where Clamp and Traverse differ most, and "
          "`images/clamp_minus_traverse_<rate>.png`: where the seams are, the per-pixel "
          "linear-RGB difference of Clamp and Traverse (inferno, saturating at 0.05; colour bar "
          "`images/clamp_minus_traverse_colourbar.svg`).\n";
  }
  return md.str();
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

std::string to_markdown(const SeamsConfig& config, const SeamsResult& result,
                        const SeamsReportOptions& options) {
  return markdown(config, result, options.images);
}

}  // namespace tessera::experiments
