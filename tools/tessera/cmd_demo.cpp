// tessera demo [-o DIR]: runs every system on built-in content and writes DIR/report.html.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli.h"
#include "demo.h"

namespace tessera::cli {

namespace {
struct DemoArgs {
  std::string out = "out";
  int size = 256;
  bool quiet = false;
  bool json = false;
};

/// A number of the summary JSON, or NaN where it is missing or null.
double number(const nlohmann::json& j) { return j.is_number() ? j.get<double>() : std::nan(""); }

std::string cell(const char* format, double v) {
  return std::isfinite(v) ? fmt(format, v) : std::string("–");
}

/// The report's first screen: each paper's headline result of this run, linking down to its
/// section (the numbers are those of the sections' own tables).
std::string summary_html(const nlohmann::json& s) {
  std::vector<std::vector<std::string>> rows;
  // PVRTC: tessera's levels against PVRTexTool's comparable ones (quality-time table).
  if (s.contains("pvrtc") && s["pvrtc"].contains("quality_time")) {
    const nlohmann::json& qt = s["pvrtc"]["quality_time"];
    auto find = [&](const char* level) -> const nlohmann::json* {
      for (const nlohmann::json& r : qt) {
        if (r.value("level", "") == level) return &r;
      }
      return nullptr;
    };
    static constexpr std::pair<const char*, const char*> kPairs[] = {
        {"fast", "pvrtcfast"}, {"normal", "pvrtcnormal"}, {"high", "pvrtcbest"}};
    for (const auto& [ours, theirs] : kPairs) {
      const nlohmann::json* a = find(ours);
      if (!a) continue;
      const nlohmann::json* b = find(theirs);
      const double ta = number((*a)["ms_per_image"]), pa = number((*a)["psnr_rgb"]);
      std::string peer = "PVRTexTool not found";
      if (b) {
        const double tb = number((*b)["ms_per_image"]), pb = number((*b)["psnr_rgb"]);
        peer = std::string(theirs) + ": " + cell("%.2f", pb) + " dB, " + cell("%.1f", tb) +
               " ms (tessera " + cell("%+.2f", pa - pb) + " dB, " + cell("%.1f", tb / ta) +
               "x faster)";
      }
      rows.push_back({"<a href=\"#pvrtc\">PVRTC1</a> (Krajcevski &amp; Manocha 2014)",
                      std::string("tessera ") + ours + ": " + cell("%.2f", pa) + " dB, " +
                          cell("%.1f", ta) + " ms per image",
                      peer});
    }
  }
  // Toth 2013, Table 1: Traverse's time over Discard's per MSAA rate, and the error near seams.
  if (s.contains("seams") && s["seams"].contains("methods")) {
    const nlohmann::json& m = s["seams"]["methods"];
    const nlohmann::json& rates = s["seams"]["msaa"];
    std::string ratio, err;
    for (std::size_t i = 0; i < rates.size(); ++i) {
      const double t = number(m["traverse"]["median_ms"][i]),
                   d = number(m["discard"]["median_ms"][i]);
      ratio += (i ? " / " : "") + cell("%.2f", t / d);
      err += (i ? ", " : "") + cell("%.4f", number(m["discard"]["error_near_seams"][i])) + " vs " +
             cell("%.4f", number(m["traverse"]["error_near_seams"][i]));
    }
    std::string labels;
    for (std::size_t i = 0; i < rates.size(); ++i) {
      labels += (i ? "/" : "") + std::to_string(rates[i].get<int>()) + "x";
    }
    rows.push_back({"<a href=\"#seams\">Seamless per-face texturing</a> (Toth 2013, Table 1)",
                    "Traverse / Discard time at " + labels + ": " + ratio + "x",
                    "mean error near seams, Discard vs Traverse, at " + labels + ": " + err});
  }
  // Holländer et al. 2013, Table 1: adaptive against full supersampling and FXAA.
  if (s.contains("aa") && s["aa"].contains("methods")) {
    const nlohmann::json* ref = nullptr;
    const nlohmann::json* ada = nullptr;
    const nlohmann::json* fxaa = nullptr;
    for (const nlohmann::json& r : s["aa"]["methods"]) {
      const std::string name = r.value("method", "");
      if (name == "reference") ref = &r;
      if (name == "adaptive") ada = &r;
      if (name.find("FXAA") != std::string::npos) fxaa = &r;
    }
    if (ref && ada) {
      const double speed = number((*ref)["shading_ms"]) / number((*ada)["shading_ms"]);
      rows.push_back(
          {"<a href=\"#aa\">Adaptive supersampling</a> (Holl&auml;nder et al. 2013, Table 1)",
           "adaptive: " + cell("%.2f", number((*ada)["psnr_vs_reference"])) +
               " dB against full supersampling, " + cell("%.1f", number((*ada)["samples_pct"])) +
               " % of the samples shaded, " + cell("%.2f", speed) + "x faster shading",
           fxaa ? "1 sample + FXAA: " + cell("%.2f", number((*fxaa)["psnr_vs_reference"])) + " dB"
                : std::string()});
    }
  }
  std::string html =
      "<section id=\"summary\"><p>What this run measured, paper by paper (details in the "
      "sections below; every number was computed in this run, on this machine):</p>\n"
      "<div class=\"scroll\"><table><tr><th>paper</th><th>tessera</th><th>against</th></tr>\n";
  for (const auto& r : rows) {
    html += "<tr><td style=\"text-align:left\">" + r[0] + "</td><td style=\"text-align:left\">" +
            Report::escape(r[1]) + "</td><td style=\"text-align:left\">" + Report::escape(r[2]) +
            "</td></tr>\n";
  }
  return html + "</table></div></section>\n";
}

int run_demo(const DemoArgs& args, const GlobalOptions& global) {
  Report report(args.out, "tessera demo report");
  report.paragraph(
      "tessera implements PVRTC compression by intensity dilation (Krajcevski & Manocha 2014), "
      "seamless per-face texturing by discarding filter taps (Toth 2013) and adaptive "
      "supersampling for deferred shading (Hollander, Boubekeur & Eisemann 2013). This report "
      "is generated by `tessera demo` from procedural content; every figure in it was computed "
      "in this run.");
  DemoOptions options;
  options.threads = global.threads;
  options.size = args.size;
  nlohmann::json summary = nlohmann::json::object();
  options.summary = &summary;  // the report's first screen is made from it too
  const auto t0 = std::chrono::steady_clock::now();
  if (Status s = demo_images_section(report, options); !s.ok()) return fail(s);
  if (Status s = demo_pvrtc_section(report, options); !s.ok()) return fail(s);
  if (Status s = demo_render_section(report, options); !s.ok()) return fail(s);
  if (Status s = demo_seams_section(report, options); !s.ok()) return fail(s);
  if (Status s = demo_aa_section(report, options); !s.ok()) return fail(s);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  char buf[128];
  std::snprintf(buf, sizeof buf, "Generated in %.0f ms with %d worker thread(s).", ms,
                global.threads > 0 ? global.threads : default_thread_count());
  report.paragraph(buf);
  report.top(summary_html(summary));
  report.footer(report_footer());
  if (Status s = report.write(); !s.ok()) return fail(s);
  const std::string path = args.out + "/report.html";
  if (!args.quiet) std::fprintf(text_stream(args.json), "wrote %s\n", path.c_str());
  if (args.json) {
    // The report's headline numbers (its tables), then where it is.
    nlohmann::json j = {{"report", path},
                        {"size", args.size},
                        {"threads", global.threads > 0 ? global.threads : default_thread_count()},
                        {"ms", ms}};
    j.update(summary);
    std::printf("%s\n", j.dump(2).c_str());
  }
  return kExitOk;
}
}  // namespace

Command add_demo_command(CLI::App& app, const GlobalOptions& global) {
  auto args = std::make_shared<DemoArgs>();
  CLI::App* sub = app.add_subcommand(
      "demo", "Run every system on built-in procedural content and write an HTML report");
  sub->add_option("-o,--output,--out", args->out, "Output folder (report.html and img/)")
      ->capture_default_str();
  sub->add_option("--size", args->size,
                  "Edge length of the procedural images (the PVRTC section rounds it to the "
                  "nearest power of two, and says so)")
      ->check(CLI::Range(16, 4096))
      ->capture_default_str();
  sub->add_flag("-q,--quiet", args->quiet, "Print nothing on success (with --json: the JSON only)");
  sub->add_flag("--json", args->json,
                "Print one JSON object: the report's path and the numbers of its tables (keys "
                "images, pvrtc, render, seams, aa); other text goes to stderr");
  return {sub, [args, &global] { return run_demo(*args, global); }};
}

}  // namespace tessera::cli
