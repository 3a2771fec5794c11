// tessera — command-line entry point: one program, one subcommand per job.
#include <cstdio>
#include <iostream>
#include <vector>

#include "cli.h"

namespace tessera::cli {

int fail(const Status& status) {
  std::fprintf(stderr, "tessera: %s\n", status.message.c_str());
  return kExitBadInput;
}

int usage_error(const std::string& message) {
  std::fprintf(stderr, "tessera: %s\n", message.c_str());
  return kExitUsage;
}

}  // namespace tessera::cli

int main(int argc, char** argv) {
  using namespace tessera::cli;
  CLI::App app{
      "tessera — real-time texturing and anti-aliasing: PVRTC compression by intensity "
      "dilation, seamless per-face texturing, adaptive supersampling for deferred shading.",
      "tessera"};
  app.require_subcommand(1);
  GlobalOptions global;
  app.add_option("-j,--threads", global.threads, "Worker threads (0 = all hardware threads)")
      ->check(CLI::Range(0, 1024));
  app.set_version_flag("--version", "tessera 0.1.0");

  std::vector<Command> commands = {
      add_aa_command(app, global),
      add_compare_command(app, global),
      add_demo_command(app, global),
      add_compress_command(app, global),
      add_decompress_command(app, global),
      add_info_command(app, global),
      add_render_command(app, global),
      add_seams_command(app, global),
  };

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
