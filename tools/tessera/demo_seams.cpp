// Demo section: seamless per-face texturing (Toth 2013) — the seam experiment run small on the
// built-in Figure-1 scene: Table 1 and Figure 5 analogues, zooms on a seam.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "demo.h"
#include "report_seams.h"

namespace tessera::cli {

namespace {

// The experiment run small: the built-in Figure-1 scene at 128x144, 2 frames, 1x/4x/8x MSAA.
experiments::SeamsConfig demo_seams_config(const DemoOptions& options, const std::string& dir) {
  experiments::SeamsConfig c;
  c.figure1.ground = 16;
  c.figure1.character = 8;
  c.figure1.texels_per_unit = 80.0f;
  c.width = 128;
  c.height = 144;
  c.frames = 2;
  c.msaa = {1, 4, 8};
  c.threads = options.threads;
  c.on_ready = [dir] {
    std::error_code ec;
    std::filesystem::create_directories(std::filesystem::path(dir) / "images", ec);
    if (ec) return Status::error(ErrorCode::io_error, dir + ": cannot create: " + ec.message());
    return Status::success();
  };
  return c;
}

// Per MSAA rate (the order of "msaa"): median ms per frame and the mean linear-RGB errors.
void add_seams_summary(nlohmann::json& seams, const experiments::SeamsConfig& c,
                       const experiments::SeamsResult& res) {
  seams["msaa"] = c.msaa;
  for (const faces::SeamMethod m : faces::all_methods()) {
    nlohmann::json& method = seams["methods"][faces::method_name(m)];
    for (const experiments::SeamsRateResult& rate : res.rates) {
      method["median_ms"].push_back(rate.method(m).timing.median_ms());
      method["error_vs_reference"].push_back(rate.method(m).vs_reference.mean);
      method["error_near_seams"].push_back(rate.method(m).vs_reference_near_seams.mean);
    }
  }
  for (const experiments::SeamsRateResult& rate : res.rates) {
    seams["shading_only_ms"].push_back(rate.shading_only.median_ms());
    seams["traverse_vs_discard"].push_back(rate.traverse_vs_discard.mean);
  }
}

// One table row: `label`, then `value(rate)` printed with `format` for each MSAA rate.
template <class Value>
std::vector<std::string> rate_row(std::string label, const experiments::SeamsResult& res,
                                  const char* format, Value value) {
  std::vector<std::string> row = {std::move(label)};
  for (const experiments::SeamsRateResult& rate : res.rates)
    row.push_back(fmt(format, value(rate)));
  return row;
}

// The tables: median ms per frame, mean error against the reference, the same near seams.
void add_seams_tables(Report& report, const experiments::SeamsConfig& c,
                      const experiments::SeamsResult& res) {
  std::vector<std::vector<std::string>> rows;
  for (const faces::SeamMethod m : faces::all_methods()) {
    rows.push_back(rate_row(faces::method_name(m), res, "%.1f",
                            [m](const auto& rate) { return rate.method(m).timing.median_ms(); }));
  }
  rows.push_back(rate_row("shading_only", res, "%.1f",
                          [](const auto& rate) { return rate.shading_only.median_ms(); }));
  std::vector<std::string> header = {"median ms / frame"};
  for (int r : c.msaa) header.push_back(std::to_string(r) + "x MSAA");
  report.table(header, rows);
  rows.clear();
  for (const faces::SeamMethod m : faces::all_methods()) {
    rows.push_back(rate_row(std::string(faces::method_name(m)) + " vs reference", res, "%.5f",
                            [m](const auto& rate) { return rate.method(m).vs_reference.mean; }));
  }
  rows.push_back(rate_row("traverse vs discard", res, "%.5f",
                          [](const auto& rate) { return rate.traverse_vs_discard.mean; }));
  header[0] = "mean linear-RGB error";
  report.table(header, rows);
  std::vector<Figure> panels;
  for (int r : c.msaa) {
    panels.push_back({"seams/fig5_" + std::to_string(r) + "x.svg",
                      "Figure 5 at " + std::to_string(r) +
                          "x MSAA: fraction of pixels with error >= x against the reference; "
                          "dashed: pixels within 2 of a face edge"});
  }
  report.figures(panels);
  rows.clear();
  for (const faces::SeamMethod m : faces::all_methods()) {
    rows.push_back(
        rate_row(std::string(faces::method_name(m)) + " near seams", res, "%.5f",
                 [m](const auto& rate) { return rate.method(m).vs_reference_near_seams.mean; }));
  }
  header[0] = "mean error within 2 px of a face edge";
  report.table(header, rows);
}

// The images: Figure 5 left, the Clamp - Traverse differences, the zooms on a seam.
void add_seams_images(Report& report) {
  report.figures({{"seams/fig5_left.svg", "Figure 5 left: Traverse vs Discard"}});
  report.figures(
      {{"seams/images/clamp_minus_traverse_1x.png", "|Clamp - Traverse| at 1x: the seams"},
       {"seams/images/clamp_minus_traverse_8x.png", "the same at 8x MSAA"},
       {"seams/images/clamp_minus_traverse_colourbar.svg", "colour bar (linear-RGB 2-norm)"}});
  std::vector<Figure> zooms;
  for (const char* n : {"clamp", "discard", "traverse"}) {
    for (int r : {1, 8}) {
      zooms.push_back({std::string("seams/images/zoom_") + n + "_" + std::to_string(r) + "x.png",
                       std::string(n) + " " + std::to_string(r) + "x"});
    }
  }
  zooms.push_back({"seams/images/zoom_reference.png", "reference"});
  report.figures(zooms);
  report.figures({{"seams/images/discard_4x.png", "Discard, 4x MSAA (frame 0)"},
                  {"seams/images/reference.png", "reference"}},
                 2);
}

}  // namespace

Status demo_seams_section(Report& report, const DemoOptions& options) {
  report.heading("Seamless per-face texturing: Discard vs Traverse (Toth 2013)", "seams");
  report.paragraph(
      "Every face of a quad mesh has its own texture (own resolution and mip chain, no guard "
      "band). Clamp uses the plain clamp-to-edge address mode; Discard drops the filter taps "
      "outside the face and renormalises (border colour 0 plus a constant-one coverage "
      "channel); Traverse (McDonald 2013) also samples the four edge neighbours through the "
      "edge transforms; Traverse+corners adds the diagonal face at valence-4 vertices. The "
      "experiment below is `tessera seams` run small on the built-in scene (ground of 16x16 "
      "faces and a cube-sphere character of 6x8x8 faces, random face orientations, textures "
      "baked from one procedural 3D function), 2 orbit frames, 16x anisotropic filtering. The "
      "reference is Traverse at 8x8 the resolution downsampled with the Mitchell-Netravali "
      "filter. Errors are linear-RGB 2-norms over geometry pixels. docs/benchmarks/seams.md has "
      "the full-size run.");
  const std::string dir = report.dir() + "/seams";
  const experiments::SeamsConfig c = demo_seams_config(options, dir);
  Result<experiments::SeamsResult> res = experiments::run_seams(c);
  if (!res) return res.status();
  std::string json;
  if (Status s = write_seams_report(c, *res, dir, true, json); !s.ok()) return s;
  if (options.summary) add_seams_summary((*options.summary)["seams"], c, *res);
  add_seams_tables(report, c, *res);
  add_seams_images(report);
  return Status::success();
}

}  // namespace tessera::cli
