// The reports of `tessera seams`: Table 1 (median ms per frame, side by side) and Figure 5
// (CDFs of per-pixel linear-RGB 2-norm errors) as JSON, Markdown, CSV and SVG/PNG, plus the
// frame-0 images and zooms on the worst seam.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "plot.h"
#include "report.h"
#include "report_plot.h"
#include "seams.h"
#include "tessera/io.h"
#include "tessera/metrics.h"

namespace tessera::cli {

namespace {

using experiments::ErrorStats;
using experiments::SeamsRateResult;
using faces::Method;

constexpr double kStep = experiments::kSeamsCdfStep;
constexpr int kBins = experiments::kSeamsCdfBins;
constexpr float kDiffScale = 0.05f;  // heatmap saturation of the clamp-minus-traverse images

float norm_rgb(const float* a, const float* b) {
  const float d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
  return std::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
}

ImageRGBA8 to_png_image(const ImageRGBAF& img, int threads) {
  ImageRGBAF c = img;
  for (std::size_t i = 0; i < c.pixel_count(); ++i) c.pixels[i * 4 + 3] = 1.0f;
  ImageRGBA8 out = to_srgb8(c, threads);
  out.has_alpha = false;
  return out;
}

ImageRGBA8 zoom(const ImageRGBA8& img, int x0, int y0, int w, int h, int s) {
  ImageRGBA8 out(w * s, h * s);
  for (int y = 0; y < h * s; ++y) {
    for (int x = 0; x < w * s; ++x) {
      const std::uint8_t* p = img.at(x0 + x / s, y0 + y / s);
      std::copy(p, p + 4, out.at(x, y));
    }
  }
  return out;
}

Status write_text(const std::string& path, const std::string& text) {
  return write_file_atomic(
      path, std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()),
                                          text.size()));
}

const char* rate_color(std::size_t i) {
  static const char* c[] = {"#d62728", "#ff7f0e", "#2ca02c", "#1f77b4", "#9467bd"};
  return c[std::min<std::size_t>(i, 4)];
}

const char* method_dash(Method m) {
  switch (m) {
    case Method::clamp:
      return "2,3";
    case Method::discard:
      return "";
    case Method::traverse:
      return "8,4";
    case Method::traverse_corners:
      return "12,3,2,3";
  }
  return "";
}

std::string rate_key(int r) { return std::to_string(r) + "x"; }

/// Frame 0 of every method and rate, the reference, and a zoom on the worst seam: the window
/// where Clamp and Traverse differ most at the first rate.
Status write_images(const experiments::SeamsConfig& c, const experiments::SeamsResult& res,
                    const std::string& dir, nlohmann::json& summary) {
  const ImageRGBA8 ref8 = to_png_image(res.reference_frame0, c.threads);
  if (Status s = write_png(dir + "/images/reference.png", ref8); !s.ok()) return s;
  const int zw = std::min(40, c.width), zh = std::min(40, c.height);
  int bx = 0, by = 0;
  double best = -1;
  const ImageRGBAF& a = res.rates[0].method(Method::clamp).frame0;
  const ImageRGBAF& b = res.rates[0].method(Method::traverse).frame0;
  for (int y = 0; y + zh <= c.height; y += 4) {
    for (int x = 0; x + zw <= c.width; x += 4) {
      double s = 0;
      for (int yy = y; yy < y + zh; yy += 2) {
        for (int xx = x; xx < x + zw; xx += 2) s += norm_rgb(a.at(xx, yy), b.at(xx, yy));
      }
      if (s > best) {
        best = s;
        bx = x;
        by = y;
      }
    }
  }
  const int zs = 4;
  if (Status s = write_png(dir + "/images/zoom_reference.png", zoom(ref8, bx, by, zw, zh, zs));
      !s.ok()) {
    return s;
  }
  for (const SeamsRateResult& rate : res.rates) {
    for (const experiments::SeamsMethodResult& mr : rate.methods) {
      const std::string stem =
          std::string(faces::method_name(mr.method)) + "_" + rate_key(rate.msaa);
      const ImageRGBA8 img = to_png_image(mr.frame0, c.threads);
      if (Status s = write_png(dir + "/images/" + stem + ".png", img); !s.ok()) return s;
      if (Status s =
              write_png(dir + "/images/zoom_" + stem + ".png", zoom(img, bx, by, zw, zh, zs));
          !s.ok()) {
        return s;
      }
    }
  }
  summary["zoom_window"] = {{"x", bx}, {"y", by}, {"w", zw}, {"h", zh}, {"scale", zs}};
  // Clamp minus Traverse (frame 0): the seam artefact, per-pixel linear-RGB 2-norm.
  for (const SeamsRateResult* rate : {&res.rates.front(), &res.rates.back()}) {
    const ImageRGBAF& ca = rate->method(Method::clamp).frame0;
    const ImageRGBAF& tr = rate->method(Method::traverse).frame0;
    std::vector<float> d(ca.pixel_count());
    for (std::size_t i = 0; i < d.size(); ++i) {
      d[i] = norm_rgb(&ca.pixels[i * 4], &tr.pixels[i * 4]);
    }
    const std::string name = "clamp_minus_traverse_" + rate_key(rate->msaa);
    if (Status s = write_png(dir + "/images/" + name + ".png",
                             heatmap(d, ca.width, ca.height, kDiffScale));
        !s.ok()) {
      return s;
    }
  }
  return write_text(dir + "/images/clamp_minus_traverse_colourbar.svg",
                    colour_bar_svg(ColorMap::inferno, 0, kDiffScale, 6,
                                   "|Clamp - Traverse|: linear-RGB 2-norm (0.05 and above "
                                   "saturate)"));
}

/// The first MSAA rate at which Discard's mean near-seam error is no larger than Traverse's at
/// the same rate, or null when it never is.
nlohmann::json discard_catches_traverse(const experiments::SeamsResult& res) {
  for (const SeamsRateResult& rate : res.rates) {
    if (rate.method(Method::discard).vs_reference_near_seams.mean <=
        rate.method(Method::traverse).vs_reference_near_seams.mean) {
      return rate.msaa;
    }
  }
  return nullptr;
}

/// Whether GL ran on a software rasterizer (llvmpipe, softpipe): its GPU timer is partial.
bool software_gl(const experiments::SeamsResult& res) {
  return res.gl_renderer.find("llvmpipe") != std::string::npos ||
         res.gl_renderer.find("softpipe") != std::string::npos;
}

/// {median_ms, frame_ms} (+ wall_median_ms, wall_frame_ms with `wall`).
nlohmann::json times_json(const experiments::FrameTimes& t, const experiments::FrameTimes* wall) {
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

void fill_json(const experiments::SeamsConfig& c, const experiments::SeamsResult& res,
               nlohmann::json& summary) {
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
  summary["scene"] = {{"description", res.scene_description},
                      {"faces", res.faces},
                      {"ground_faces", res.ground_faces},
                      {"texels_level0", res.texels_level0},
                      {"edge_pairings", res.edge_pairings},
                      {"valence4_corner_links", res.linked_corners},
                      {"corners", 4 * res.faces}};
  const bool gl = res.backend == experiments::Backend::gl;
  summary["backend"] = res.compared_gl ? "both" : experiments::backend_name(res.backend);
  if (gl || res.compared_gl) {
    summary["gl_renderer"] = res.gl_renderer;
    summary["gl_version"] = res.gl_version;
    summary["msaa_unsupported"] = res.msaa_unsupported;
    const std::string read = software_gl(res) ? "the wall times (llvmpipe: the timer is partial)"
                                              : "the GPU timer (a hardware GPU)";
    summary["timing_note"] =
        "GL: median_ms/frame_ms are GL_TIME_ELAPSED (draws + resolve), "
        "wall_median_ms/wall_frame_ms the wall time to glFinish; read " +
        read;
  }
  nlohmann::json timing_j, quality_j, nan_j;
  for (const SeamsRateResult& rate : res.rates) {
    const std::string rk = rate_key(rate.msaa);
    for (const experiments::SeamsMethodResult& mr : rate.methods) {
      timing_j[rk][faces::method_name(mr.method)] = times_json(mr.timing, gl ? &mr.wall : nullptr);
    }
    nlohmann::json& so = timing_j[rk]["shading_only"] = times_json(rate.shading_only, nullptr);
    if (rate.shading_only.frame_ms.empty()) {
      so = {{"median_ms", nullptr},
            {"frame_ms", nlohmann::json::array()},
            {"note", "not on this backend"}};
    }
    for (const experiments::SeamsMethodResult& mr : rate.methods) {
      quality_j["vs_reference"][faces::method_name(mr.method)][rk] = summary_json(mr.vs_reference);
    }
    if (res.has_character) {
      for (const experiments::SeamsMethodResult& mr : rate.methods) {
        const ErrorStats& q = mr.vs_reference_character;
        quality_j["vs_reference_character_only"][faces::method_name(mr.method)][rk] = {
            {"mean", q.mean},
            {"fraction_ge_0.01", q.at(0.01)},
            {"fraction_ge_0.05", q.at(0.05)},
            {"counted_pixels", q.counted}};
      }
    }
    if (res.near_seam_pixels > 0) {
      for (const experiments::SeamsMethodResult& mr : rate.methods) {
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
  if (res.compared_gl) {
    nlohmann::json tg = nlohmann::json::object(), agree = nlohmann::json::object();
    for (const experiments::SeamsGlRateResult& g : res.gl_rates) {
      const std::string rk = rate_key(g.msaa);
      for (const experiments::SeamsGlMethodResult& m : g.methods) {
        const char* name = faces::method_name(m.method);
        tg[rk][name] = times_json(m.gpu, &m.wall);
        agree[rk][name] = {{"psnr_db", m.psnr_db}, {"fraction_ge_0.01", m.fraction_ge_001}};
      }
    }
    summary["timing_gl"] = tg;
    summary["gl_vs_cpu"] = agree;
    summary["gl_vs_cpu_note"] =
        "GL frame against the CPU frame of the same camera, rate and method, pooled over the " +
        std::to_string(res.quality_frames) +
        " quality frame(s), all pixels: psnr_db from the mean MSE of the 8-bit sRGB outputs "
        "(null = identical), fraction_ge_0.01 = pixels whose linear-RGB 2-norm difference is >= "
        "0.01 (NaN counts)";
  }
}

/// cdf.csv and the Figure-5 plots.
Status write_plots(const experiments::SeamsResult& res, const std::string& dir) {
  std::ostringstream csv;
  csv << "threshold";
  for (const SeamsRateResult& rate : res.rates) {
    csv << ",traverse_vs_discard_" << rate_key(rate.msaa);
  }
  const std::vector<Method>& methods = faces::all_methods();
  for (Method m : methods) {
    for (const SeamsRateResult& rate : res.rates) {
      csv << "," << faces::method_name(m) << "_vs_ref_" << rate_key(rate.msaa);
    }
  }
  csv << "\n";
  std::vector<const std::vector<double>*> cols;
  for (const SeamsRateResult& rate : res.rates) cols.push_back(&rate.traverse_vs_discard.cdf);
  for (Method m : methods) {
    for (const SeamsRateResult& rate : res.rates) cols.push_back(&rate.method(m).vs_reference.cdf);
  }
  for (int i = 0; i < kBins; ++i) {
    csv << double(i) * kStep;
    for (const std::vector<double>* col : cols) csv << "," << (*col)[std::size_t(i)];
    csv << "\n";
  }
  if (Status s = write_text(dir + "/cdf.csv", csv.str()); !s.ok()) return s;
  std::vector<Curve> left, right;
  for (std::size_t ri = 0; ri < res.rates.size(); ++ri) {
    left.push_back(
        {rate_key(res.rates[ri].msaa), rate_color(ri), "", res.rates[ri].traverse_vs_discard.cdf});
  }
  for (Method m : methods) {
    if (m == Method::traverse_corners) continue;  // in the CSV/JSON
    for (std::size_t ri = 0; ri < res.rates.size(); ++ri) {
      right.push_back({std::string(faces::method_name(m)) + " " + rate_key(res.rates[ri].msaa),
                       rate_color(ri), method_dash(m), res.rates[ri].method(m).vs_reference.cdf});
    }
  }
  // One readable panel per rate: Clamp, Discard and Traverse against the reference over all
  // geometry pixels (solid) and near the seams (dashed).
  for (std::size_t ri = 0; ri < res.rates.size(); ++ri) {
    const SeamsRateResult& rate = res.rates[ri];
    Plot plot;
    plot.title = "Figure 5, " + rate_key(rate.msaa) + " MSAA: error against the reference";
    plot.x_title = "x: per-pixel linear-RGB error (2-norm)";
    plot.y_title = "fraction of pixels with error >= x";
    plot.log_y = true;
    plot.x_min = 0;
    plot.x_max = 0.15;
    plot.y_min = 1e-4;
    plot.y_max = 1;
    std::size_t colour = 0;
    for (Method m : {Method::clamp, Method::discard, Method::traverse}) {
      for (bool near : {false, true}) {
        if (near && res.near_seam_pixels == 0) continue;
        const ErrorStats& q =
            near ? rate.method(m).vs_reference_near_seams : rate.method(m).vs_reference;
        PlotSeries ser;
        ser.label = std::string(faces::method_name(m)) +
                    (near ? ", near seams" : ", all pixels") + fmt(" (mean %.4f)", q.mean);
        ser.colour = series_colour(colour);
        ser.dashed = near;
        for (int i = 0; i < kBins && i < int(q.cdf.size()); ++i) {
          ser.x.push_back(double(i) * kStep);
          ser.y.push_back(q.cdf[std::size_t(i)]);
        }
        plot.series.push_back(std::move(ser));
      }
      ++colour;
    }
    if (Status s = write_text(dir + "/fig5_" + rate_key(rate.msaa) + ".svg", plot_svg(plot));
        !s.ok()) {
      return s;
    }
  }
  if (Status s = write_text(dir + "/fig5_left.svg", cdf_svg("Traverse vs Discard", left, 0.15));
      !s.ok()) {
    return s;
  }
  if (Status s = write_png(dir + "/fig5_left.png", cdf_png(left, 0.15)); !s.ok()) return s;
  if (Status s = write_png(dir + "/fig5_right.png", cdf_png(right, 0.15)); !s.ok()) return s;
  return write_text(dir + "/fig5_right.svg",
                    cdf_svg("Deviation from the reference (solid Discard, dashed "
                            "Traverse, dotted Clamp)",
                            right, 0.15));
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
  const auto row = [&](Method m) {
    return std::find_if(rows.begin(), rows.end(),
                        [&](const TimeRow& r) { return r.label == faces::method_name(m); });
  };
  const auto t = row(Method::traverse), d = row(Method::discard);
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
bool gl_time_tables(std::ostringstream& md, const experiments::SeamsResult& res,
                    const std::vector<Rate>& rates, Pick pick) {
  const std::vector<Method>& methods = faces::all_methods();
  std::vector<int> keys;
  for (const Rate& r : rates) keys.push_back(r.msaa);
  bool ok[2] = {true, true};
  for (int gpu = 0; gpu < 2; ++gpu) {
    std::vector<TimeRow> rows;
    for (Method m : methods) {
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
             ? "the wall times. This is llvmpipe, a software rasterizer: its GL_TIME_ELAPSED "
               "queries are executed per screen tile by the rasterizer threads and cover only "
               "part of the frame (gl_seams.h)."
             : "the GPU timer (a hardware GPU: the timer is the pass time; wall time adds the "
               "driver's submission and the glFinish round trip).")
     << "\n\n";
  return software_gl(res) ? ok[0] : ok[1];
}

/// `--backend both`: the GL times and the GL-vs-CPU agreement.
std::string gl_beside_cpu(const experiments::SeamsResult& res) {
  std::ostringstream md;
  md << "\n## OpenGL beside the CPU\n\nThe same frames rendered by GL (" << res.gl_renderer
     << "), methods alternating per frame";
  if (!res.msaa_unsupported.empty()) {
    md << "; refused by the driver and skipped on GL:";
    for (int r : res.msaa_unsupported) md << " " << rate_key(r);
  }
  md << ".\n\n";
  gl_time_tables(md, res, res.gl_rates,
                 [](const experiments::SeamsGlRateResult& r, Method m, bool gpu) {
                   return gpu ? &r.method(m).gpu : &r.method(m).wall;
                 });
  md << "GL against the CPU, the same camera, rate and method, pooled over the "
     << res.quality_frames
     << " quality frame(s), all pixels: PSNR of the 8-bit sRGB outputs (from the mean MSE) / "
        "fraction of pixels whose linear-RGB 2-norm difference is >= 0.01. Under 16x "
        "anisotropic filtering the drivers' hardware filter is implementation-defined "
        "(llvmpipe's is much blurrier than tessera's exact filter), so the agreement is lower "
        "than under trilinear filtering.\n\n| method |";
  std::string rule = "\n|---|";
  for (const experiments::SeamsGlRateResult& g : res.gl_rates) {
    md << " " << rate_key(g.msaa) << " |";
    rule += "---:|";
  }
  md << rule << "\n";
  for (Method m : faces::all_methods()) {
    md << "| " << faces::method_name(m) << " |";
    for (const experiments::SeamsGlRateResult& g : res.gl_rates) {
      const experiments::SeamsGlMethodResult& r = g.method(m);
      md << (std::isfinite(r.psnr_db) ? fmt(" %.2f dB", r.psnr_db) : std::string(" identical"))
         << fmt(" / %.4f |", r.fraction_ge_001);
    }
    md << "\n";
  }
  return md.str();
}

std::string markdown(const experiments::SeamsConfig& c, const experiments::SeamsResult& res,
                     bool images) {
  const std::vector<Method>& methods = faces::all_methods();
  std::ostringstream md;
  md << "# Seams experiment (Toth 2013, Table 1 and Figure 5)\n\n";
  md << "Scene: " << res.scene_description << "; " << res.faces << " faces, " << res.texels_level0
     << " level-0 texels, " << res.linked_corners << " of " << 4 * res.faces
     << " corners with a valence-4 diagonal face. " << c.width << "x" << c.height << ", "
     << c.frames << " orbit frames (" << res.quality_frames
     << " with a reference), 16x anisotropic filtering, " << res.threads << " thread(s).\n\n";
  const bool gl = res.backend == experiments::Backend::gl;
  if (gl || res.compared_gl) {
    md << "Backend: **" << (gl ? "OpenGL" : "CPU, and OpenGL beside it (`--backend both`)")
       << "**: " << res.gl_renderer << ", " << res.gl_version << ".";
    if (!res.msaa_unsupported.empty()) {
      md << " MSAA rates the driver refuses, skipped" << (gl ? "" : " on GL") << ":";
      for (int r : res.msaa_unsupported) md << " " << rate_key(r);
      md << ".";
    }
    md << (gl ? " The reference is rendered by GL too (Traverse, 16x anisotropic, tiled); face "
                "ids (near-seam pixels) and the character mask come from the CPU renderer, "
                "whose geometry is the same."
              : "")
       << "\n\n";
  }
  md << "## Table 1 analogue: median ms per frame\n\n";
  bool speed_ok = true;
  if (gl) {
    md << "Draws + MSAA box resolve on the GPU, all methods rendered side by side in one run, "
          "alternating per frame (no shading-only pass on GL).\n\n";
    speed_ok = gl_time_tables(md, res, res.rates, [](const SeamsRateResult& r, Method m, bool gpu) {
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
  for (Method m : methods) {
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
    for (Method m : methods) {
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
    for (Method m : methods) {
      for (const SeamsRateResult& rate : res.rates) {
        md << error_row(faces::method_name(m), rate.msaa, rate.method(m).vs_reference_character);
      }
    }
  }
  md << "\n## Targets\n\n";
  md << "- Discard at least 2x faster than Traverse at every rate: **"
     << (speed_ok ? "met" : "not met") << "** (ratios in the table).\n";
  for (const SeamsRateResult& rate : res.rates) {
    const double d = rate.method(Method::discard).vs_reference.mean;
    const double t = rate.method(Method::traverse).vs_reference.mean;
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
  if (res.compared_gl) md << gl_beside_cpu(res);
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

Status write_seams_report(const experiments::SeamsConfig& config,
                          const experiments::SeamsResult& result, const std::string& dir,
                          bool images, nlohmann::json& summary) {
  if (result.rates.empty()) {
    return Status::error(ErrorCode::invalid_argument, "seams report: empty result");
  }
  if (images) {
    if (Status s = write_images(config, result, dir, summary); !s.ok()) return s;
  }
  fill_json(config, result, summary);
  if (Status s = write_plots(result, dir); !s.ok()) return s;
  if (Status s = write_text(dir + "/seams.md", markdown(config, result, images)); !s.ok()) {
    return s;
  }
  return write_text(dir + "/seams.json", summary.dump(1));
}

}  // namespace tessera::cli
