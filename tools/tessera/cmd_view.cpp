// tessera view INPUT... [--port N] [--no-open] [--html -o VIEW.html]: original against PVRTC
// in a browser, served locally (view_server.cpp) or exported as one file (view_export.cpp).
#include <cstdio>

#include "view.h"

namespace tessera::cli {

namespace {

struct ViewArgs {
  std::vector<std::string> inputs;
  std::vector<std::vector<std::string>> cubes;   ///< --cube +X -X +Y -Y +Z -Z, each.
  std::vector<std::vector<std::string>> arrays;  ///< --array L0 L1 ..., each.
  int port = 0;
  bool no_open = false;
  bool html = false;
  std::string output;
  bool quiet = false;
  int memory_mib = 512;
  ViewSettings settings;
};

constexpr const char* kSettingOptions[] = {"--format",         "--quality",     "--alpha-bleed",
                                           "--alpha-weighted", "--premultiply", "--normal-map",
                                           "--srgb",           "--mip-levels",  "--mip-filter"};

int run_view(const ViewArgs& args, const CLI::App& sub, const GlobalOptions& global) {
  if (args.html && args.output.empty()) return usage_error("--html needs -o FILE ('-' = stdout)");
  if (!args.html && !args.output.empty()) return usage_error("-o is for --html (the export)");
  if (args.html && sub.count("--port")) {
    return usage_error("--port and --html cannot be used together");
  }
  if (args.html && sub.count("--memory")) {
    return usage_error("--memory is for serving, not --html");
  }
  if (sub.count("--mip-filter") && args.settings.mip_levels == 0) {
    return usage_error("--mip-filter " + args.settings.mip_filter + " needs --mip-levels N");
  }
  bool any_setting = false;
  for (const char* o : kSettingOptions) any_setting = any_setting || sub.count(o) > 0;
  std::vector<ViewSettings> settings;
  if (any_setting) {
    CompressArgs c = compress_args(args.settings, "in", "out.pvr");
    if (std::string p = compress_usage_problem(c, "pvr"); !p.empty()) return usage_error(p);
    settings.push_back(args.settings);
  }
  if (args.inputs.empty() && args.cubes.empty() && args.arrays.empty()) {
    return usage_error("nothing to view: give INPUT files or folders, --cube or --array");
  }
  std::vector<ViewInput> inputs = load_view_inputs(args.inputs);
  for (const auto& faces : args.cubes) inputs.push_back(load_view_group(faces, {6, false}));
  for (const auto& layers : args.arrays) inputs.push_back(load_view_group(layers, {1, true}));
  if (args.html) {
    std::vector<std::string> errors;
    Status s = write_view_export(inputs, settings, global.threads, args.output, &errors,
                                 args.settings.resize_pot);
    if (!s.ok()) return fail(s);
    // The page shows each bad input's error; the terminal gets the same lines.
    for (const std::string& e : errors) std::fprintf(stderr, "tessera: %s\n", e.c_str());
    if (!args.quiet) {
      std::fprintf(text_stream(args.output == "-"), "wrote %s: %zu input(s)\n",
                   args.output == "-" ? "<stdout>" : args.output.c_str(), inputs.size());
    }
    return kExitOk;
  }
  for (const ViewInput& in : inputs) {
    if (!in.error.empty()) std::fprintf(stderr, "tessera: %s\n", in.error.c_str());
  }
  // --resize-pot alone still makes the first encode resample (the page's checkbox set).
  if (settings.empty() && args.settings.resize_pot) settings.push_back(args.settings);
  ViewServeOptions o;
  o.port = args.port;
  o.open = !args.no_open;
  o.quiet = args.quiet;
  o.threads = global.threads;
  o.initial = settings;
  o.memory_budget = std::size_t(args.memory_mib) << 20;
  return serve_view(std::move(inputs), o);
}

}  // namespace

Command add_view_command(CLI::App& app, const GlobalOptions& global) {
  auto args = std::make_shared<ViewArgs>();
  CLI::App* sub = app.add_subcommand(
      "view",
      "See images against their PVRTC encodes in a browser: side by side or as a wipe, zoom to "
      "the texel, channels and alpha, levels and faces, error heatmaps, options tried live; "
      "served on 127.0.0.1 with a token, or exported as one HTML file (--html)");
  sub->add_option("INPUT", args->inputs,
                  "Images (PNG, JPEG, TGA, BMP) to encode, textures (.pvr, .ktx, .ktx2) to "
                  "look at, or folders of them. An input that cannot be read or encoded shows "
                  "its one-line error (also on stderr) and the others go on; --html exits 0 "
                  "when at least one input works");
  sub->add_option(
         "--cube", args->cubes,
         "Six images, the faces +X -X +Y -Y +Z -Z of one cube map (square, one size), "
         "encoded as tessera compress --cube encodes them; repeat for more cube maps (other "
         "inputs go before it)")
      ->expected(6);
  sub->add_option("--array", args->arrays,
                  "Images up to the next option: the layers of one array texture (one size), "
                  "as tessera compress --array; repeat for more arrays")
      ->expected(1, 1 << 16);
  sub->add_option("--port", args->port, "Port on 127.0.0.1 (default: a random free one)")
      ->check(CLI::Range(1, 65535));
  sub->add_flag("--no-open", args->no_open, "Print the URL only; do not start a browser");
  sub->add_option("--memory", args->memory_mib,
                  "MiB of results (images, heatmaps, files) kept while serving; beyond it the "
                  "least recently used results that are not pinned are evicted (default 512)")
      ->check(CLI::Range(16, 1 << 20));
  sub->add_flag("--html", args->html,
                "Write a self-contained static view to -o FILE instead of serving (the given "
                "encoder options, else fast, normal, high and, with alpha, --alpha-bleed and "
                "--alpha-weighted)");
  sub->add_option("-o,--output", args->output, "The --html file ('-' = stdout)");
  ViewSettings& s = args->settings;
  sub->add_option("--format", s.format, "PVRTC1 variant of the first encode")
      ->check(CLI::IsMember({"pvrtc1-4", "pvrtc1-2"}));
  sub->add_option("--quality", s.quality, "Encoder effort of the first encode")
      ->check(CLI::IsMember({"fast", "normal", "high"}));
  sub->add_flag("--alpha-bleed", s.alpha_bleed, "As tessera compress --alpha-bleed");
  sub->add_flag("--alpha-weighted", s.alpha_weighted, "As tessera compress --alpha-weighted");
  sub->add_flag("--premultiply", s.premultiply, "As tessera compress --premultiply");
  sub->add_flag("--normal-map", s.normal_map, "As tessera compress --normal-map");
  sub->add_flag("--srgb", s.srgb, "As tessera compress --srgb");
  sub->add_option("--mip-levels", s.mip_levels, "As tessera compress --mip-levels N")
      ->check(CLI::Range(1, 17));
  sub->add_option("--mip-filter", s.mip_filter, "As tessera compress --mip-filter")
      ->check(CLI::IsMember({"box", "lanczos", "kaiser"}));
  sub->add_flag("--resize-pot", s.resize_pot,
                "As tessera compress --resize-pot: resample a non-power-of-two input to the "
                "nearest power of two (Lanczos-3) and measure against that; without it such an "
                "input shows its original and this fix");
  sub->add_flag("-q,--quiet", args->quiet, "Print only the URL (serving) or nothing (--html)");
  return {sub, [args, sub, &global] { return run_view(*args, *sub, global); }};
}

}  // namespace tessera::cli
