// tessera — command-line entry point: one program, one subcommand per job.
#include <cstdio>
#include <iostream>
#include <string_view>
#include <utility>
#include <vector>

#include "cli.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace tessera::cli {

int fail(const Status& status) {
  std::fprintf(stderr, "tessera: %s\n", status.message.c_str());
  return kExitBadInput;
}

int usage_error(const std::string& message) {
  std::fprintf(stderr, "tessera: %s\n", message.c_str());
  return kExitUsage;
}

namespace {

/// The first argument that is not a global option (-j N, --threads N, -jN, --threads=N), or
/// "" when there is none or a help/version flag comes first (those need every subcommand).
std::string_view subcommand_name(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    if (a == "-j" || a == "--threads") {
      ++i;
    } else if (a.rfind("--threads=", 0) == 0 || (a.size() > 2 && a.rfind("-j", 0) == 0)) {
      continue;
    } else {
      return a.empty() || a[0] == '-' ? std::string_view() : a;
    }
  }
  return {};
}

/// A tessera run is one short job over a few image-sized buffers, freed and allocated again
/// stage after stage (PNG bytes, inflated rows, pixels, encoder planes, output). glibc would
/// map each buffer of 128 KiB or more afresh and unmap it when freed, so every stage pays a page
/// fault per 4 KiB touched; keeping such buffers in the heap (up to glibc's 32 MiB cap) and not
/// trimming it lets later stages reuse pages already mapped. 1024^2 `compress --quality fast`
/// (ldr-rgb-metalrough): 3530 -> 2616 page faults (`perf stat -r 15`).
void tune_allocator() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

}  // namespace

}  // namespace tessera::cli

int main(int argc, char** argv) {
  using namespace tessera::cli;
  tune_allocator();
  CLI::App app{
      "tessera — real-time texturing and anti-aliasing: PVRTC compression by intensity "
      "dilation, seamless per-face texturing, adaptive supersampling for deferred shading.",
      "tessera"};
  app.require_subcommand(1);
  GlobalOptions global;
  app.add_option("-j,--threads", global.threads, "Worker threads (0 = all hardware threads)")
      ->check(CLI::Range(0, 1024));
  app.set_version_flag("--version", "tessera 0.1.0");
  // -j may also follow the subcommand (`tessera compress IN -o OUT -j 4`): options a
  // subcommand does not know fall through to this parser. Set before the subcommands are
  // added, which inherit it.
  app.fallthrough();

  // Registering a subcommand builds all of its CLI11 options: for all eight that is about a
  // fifth of the start-up instructions of a short run. When the command line names one, only
  // that one is registered (its help, errors and parsing are the same); otherwise all are.
  using AddCommand = Command (*)(CLI::App&, const GlobalOptions&);
  static constexpr std::pair<std::string_view, AddCommand> kCommands[] = {
      {"aa", add_aa_command},
      {"compare", add_compare_command},
      {"demo", add_demo_command},
      {"compress", add_compress_command},
      {"decompress", add_decompress_command},
      {"info", add_info_command},
      {"render", add_render_command},
      {"seams", add_seams_command},
  };
  const std::string_view named = subcommand_name(argc, argv);
  std::vector<Command> commands;
  for (const auto& [name, add] : kCommands) {
    if (name == named) commands = {add(app, global)};
  }
  if (commands.empty()) {
    for (const auto& [name, add] : kCommands) commands.push_back(add(app, global));
  }
  for (const Command& c : commands) {
    c.app->footer("Global option, accepted before or after the subcommand: -j,--threads N "
                  "(worker threads, 0 = all hardware threads; output is the same for any N)");
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitUsage;
  }
  for (const Command& c : commands) {
    if (c.app->parsed()) return c.run();
  }
  return usage_error("no subcommand given (see tessera --help)");
}
