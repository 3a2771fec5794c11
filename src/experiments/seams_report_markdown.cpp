// seams.md of a `run_seams` result (tessera/experiments/seams.h): Table 1 (median ms per frame,
// side by side), Figure 5 (the CDFs of per-pixel errors) and the targets, with the GL-vs-CPU part
// of Backend::both. seams.json is seams_report.cpp.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "experiments/seams_report_internal.h"
#include "tessera/experiments/seams.h"

namespace tessera::experiments {

namespace {

using namespace seams_report;  // NOLINT(google-build-using-namespace): the reports' shared helpers

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
    const bool vulkan = res.backend == Backend::vk;
    md << (gpu ? (vulkan ? "GPU timer (timestamps around the draws and the resolve), median "
                           "ms:\n\n"
                         : "GPU timer (GL_TIME_ELAPSED of the draws and the resolve), median "
                           "ms:\n\n")
               : (vulkan ? "Wall time (submission to the fence after the resolve, read-back "
                           "excluded), median ms:\n\n"
                         : "Wall time (first GL call of the frame to glFinish after the "
                           "resolve, read-back excluded), median ms:\n\n"));
    ok[gpu] = time_table(md, keys, rows, gpu ? " %.3f |" : " %.2f |");
  }
  md << "**Which to read:** "
     << (software_gl(res)
             ? "the wall times. This is llvmpipe, a software rasteriser: its GL_TIME_ELAPSED "
               "queries are executed per screen tile by the rasteriser threads and cover only "
               "part of the frame (gl_face_renderer.h)."
         : res.backend == Backend::vk
             ? "the GPU timer (timestamps are written as the commands execute, on lavapipe "
               "as on hardware; wall time adds the submission and the fence round trip)."
             : "the GPU timer (a hardware GPU: the timer is the pass time; wall time adds "
               "the driver's submission and the glFinish round trip).")
     << "\n\n";
  return software_gl(res) ? ok[0] : ok[1];
}

/// `--backend both`: the GL times and the GL-vs-CPU agreement.
std::string gl_beside_cpu(const SeamsResult& res) {
  std::ostringstream md;
  md << "\n## OpenGL beside the CPU\n\nThe same frames rendered by GL (" << res.gpu_renderer
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
  const bool gl = gpu_primary(res.backend);
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
    md << "Backend: **" << (gl ? gpu_api_name(res) : "CPU, and OpenGL beside it (`--backend both`)")
       << "**: " << res.gpu_renderer << ", " << res.gpu_version << ".";
    if (!res.msaa_unsupported.empty()) {
      md << " MSAA rates the driver refuses, skipped" << (gl ? "" : " on GL") << ":";
      for (int r : res.msaa_unsupported) md << " " << rate_key(r);
      md << ".";
    }
    for (const SeamsSamplePattern& p : res.gpu_sample_patterns) {
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
    md << (gl ? " The reference is rendered by the GPU too (Traverse, 16x anisotropic, tiled); "
                "face "
                "ids (near-seam pixels) and the character mask come from the CPU renderer, "
                "whose geometry is the same."
              : "")
       << "\n\n";
  }
}

/// Table 1: the median times; whether Discard is at least 2x faster than Traverse everywhere.
bool md_table1(std::ostringstream& md, const SeamsResult& res) {
  const std::vector<SeamMethod>& methods = faces::all_methods();
  const bool gl = gpu_primary(res.backend);
  md << "## Table 1 analogue: median ms per frame\n\n";
  bool speed_ok = true;
  if (gl) {
    md << "Draws + MSAA box resolve on the GPU, all methods rendered side by side in one run, "
          "alternating per frame (no shading-only pass on the GPU).\n\n";
    speed_ok =
        gl_time_tables(md, res, res.rates, [](const SeamsRateResult& r, SeamMethod m, bool gpu) {
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

std::string to_markdown(const SeamsConfig& config, const SeamsResult& result,
                        const SeamsReportOptions& options) {
  return markdown(config, result, options.images);
}

}  // namespace tessera::experiments
