// tessera — command-line entry point: one program, one subcommand per job.
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "cli.h"
#ifdef TESSERA_HAVE_GL
#include "tessera/gl_experiments.h"
#endif
#ifdef TESSERA_HAVE_VK
#include "tessera/vk_experiments.h"
#endif

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace tessera::cli {

int fail(const Status& status) {
  std::fprintf(stderr, "tessera: %s\n", status.message.c_str());
  return kExitBadInput;
}

namespace {
std::string g_command;  // the subcommand being run, for the prefix of usage errors
}  // namespace

int usage_error(const std::string& message) {
  const std::string who = g_command.empty() ? "tessera" : "tessera " + g_command;
  std::fprintf(stderr, "%s: %s\n", who.c_str(), message.c_str());
  return kExitUsage;
}

int refuse_binary_to_terminal(const std::string& path, const char* what) {
  if (path != "-" || !::isatty(STDOUT_FILENO)) return 0;
  std::fprintf(stderr,
               "tessera: refusing to write %s to a terminal (redirect stdout or give -o FILE)\n",
               what);
  return kExitUsage;
}

std::FILE* text_stream(bool data_on_stdout) { return data_on_stdout ? stderr : stdout; }

nlohmann::json db_or_null(double db) {
  return std::isfinite(db) ? nlohmann::json(db) : nlohmann::json(nullptr);
}

namespace {
std::string g_command_line;
}  // namespace

const std::string& command_line() { return g_command_line; }

std::shared_ptr<const experiments::GpuBackendFactory> gl_backends() {
#ifdef TESSERA_HAVE_GL
  std::string dir = TESSERA_INSTALLED_GLSL_DIR;
  std::error_code ec;
  if (const char* env = std::getenv("TESSERA_GLSL_DIR"); env && *env) {
    dir = env;
  } else if (std::filesystem::is_directory(TESSERA_SOURCE_GLSL_DIR, ec)) {
    dir = TESSERA_SOURCE_GLSL_DIR;
  }
  return gl::experiment_backends(dir);
#else
  return nullptr;
#endif
}

std::shared_ptr<const experiments::GpuBackendFactory> vk_backends() {
#ifdef TESSERA_HAVE_VK
  vk::ExperimentBackendOptions options;
  const char* validation = std::getenv("TESSERA_VK_VALIDATION");
  options.validation = validation != nullptr && std::string_view(validation) == "1";
  return vk::experiment_backends(options);
#else
  return nullptr;
#endif
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

constexpr std::string_view kCommandList =
    "aa, compare, compress, decompress, demo, info, render, seams, view";

bool is_global_option(std::string_view a) {
  return a == "-j" || a == "--threads" || a.rfind("--threads=", 0) == 0 ||
         (a.size() > 2 && a.rfind("-j", 0) == 0);
}

/// The command-line problem found before parsing, if any: an unknown command, an option the
/// program as a whole does not know, or no command at all ("" when the line looks right).
std::string precheck(int argc, char** argv, std::string_view named,
                     std::span<const std::string_view> known) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    if (a == "-j" || a == "--threads") {
      if (++i == argc) return std::string(a) + ": needs a value";
      continue;
    }
    if (is_global_option(a)) continue;
    if (a == "-h" || a == "--help" || a == "--help-all" || a == "--version") return "";
    if (!a.empty() && a[0] == '-' && a != "-") return "unknown option '" + std::string(a) + "'";
    if (std::find(known.begin(), known.end(), named) == known.end()) {
      return "unknown command '" + std::string(a) + "' (commands: " + std::string(kCommandList) +
             ")";
    }
    return "";
  }
  return "no command given (commands: " + std::string(kCommandList) + "; see tessera --help)";
}

std::string after(const std::string& text, const std::string& marker) {
  const std::size_t at = text.find(marker);
  return at == std::string::npos ? std::string() : text.substr(at + marker.size());
}

/// "integer" or "number" for an option whose value did not convert or validate.
std::string value_kind(const CLI::App* sub, const std::string& name) {
  const CLI::Option* opt = nullptr;
  for (const CLI::App* a = sub; a && !opt; a = a->get_parent()) opt = a->get_option_no_throw(name);
  if (!opt) return "valid value";
  const std::string type = opt->get_type_name();
  if (type.rfind("INT", 0) == 0 || type.rfind("UINT", 0) == 0) return "integer";
  if (type.rfind("FLOAT", 0) == 0 || type.rfind("NUMBER", 0) == 0) return "number";
  return "valid value";
}

bool parses_as_number(const std::string& v) {
  if (v.empty()) return false;
  char* end = nullptr;
  std::strtod(v.c_str(), &end);
  return end && *end == '\0';
}

/// The first word of the command line that looks like an option (a dash and a letter) and that
/// neither `sub` nor the global options know; "" when there is none. CLI11 checks required
/// arguments before it reports unknown ones, so `render --bogus` would otherwise read
/// "missing SCENE".
std::string first_unknown_option(int argc, char** argv, const CLI::App* sub) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--") break;
    if (a.size() < 2 || a[0] != '-' ||
        !(std::isalpha(static_cast<unsigned char>(a[1])) || (a[1] == '-' && a.size() > 2))) {
      continue;
    }
    if (is_global_option(a) || a == "-h" || a == "--help") continue;
    std::string name = a.substr(0, a.find('='));
    if (name.size() > 2 && name[1] != '-') name = name.substr(0, 2);  // -ofile, -j4
    if (sub && sub->get_option_no_throw(name)) continue;
    return a;
  }
  return "";
}

/// One line that says what is wrong, from a CLI11 parse error (CLI11 2.1's messages).
std::string describe_parse_error(const CLI::ParseError& e, const CLI::App* sub) {
  const std::string what = e.what();
  const std::string name = e.get_name();
  if (const std::size_t colon = what.find(": ");
      colon != std::string::npos && what.find(" required ", colon) != std::string::npos &&
      what.ends_with(" missing")) {
    return what.substr(0, colon) + ": needs a value";  // "--width: 1 required INT ... missing"
  }
  if (name == "ExtrasError" || what.rfind("The following argument", 0) == 0) {
    std::string rest = after(what, "expected: ");
    const std::string first = rest.substr(0, rest.find(' '));
    if (!first.empty() && first[0] == '-' && first != "-") return "unknown option '" + first + "'";
    return "unexpected argument '" + first + "'";
  }
  if (name == "RequiredError") {
    if (what.rfind("A subcommand", 0) == 0) return "no command given";
    std::string opt = what.substr(0, what.find(" is required"));
    if (!opt.empty() && opt[0] != '-') return "missing " + opt;
    return opt + " is required";
  }
  if (name == "ConversionError") {
    // "Could not convert: --width = abc"
    const std::string rest = after(what, "Could not convert: ");
    const std::size_t eq = rest.find(" = ");
    if (eq != std::string::npos) {
      const std::string opt = rest.substr(0, eq), value = rest.substr(eq + 3);
      const std::string kind = value_kind(sub, opt);
      return opt + ": '" + value + "' is not " + (kind == "integer" ? "an " : "a ") + kind;
    }
  }
  if (name == "ValidationError") {
    // "--width: Value abc not in range 1 to 16384", "--quality: bogus not in {fast,normal}"
    const std::size_t colon = what.find(": ");
    if (colon != std::string::npos) {
      const std::string opt = what.substr(0, colon);
      std::string rest = what.substr(colon + 2);
      if (rest.rfind("Value ", 0) == 0) rest = rest.substr(6);
      const std::size_t range = rest.find(" not in range ");
      if (range != std::string::npos) {
        const std::string value = rest.substr(0, range), bounds = rest.substr(range + 14);
        if (!parses_as_number(value)) {
          const std::string kind = value_kind(sub, opt);
          return opt + ": '" + value + "' is not " + (kind == "integer" ? "an " : "a ") + kind;
        }
        return opt + ": " + value + " is out of range (" + bounds + ")";
      }
      const std::size_t set = rest.find(" not in {");
      if (set != std::string::npos) {
        std::string choices = rest.substr(set + 9);
        if (!choices.empty() && choices.back() == '}') choices.pop_back();
        for (std::size_t c = 0; (c = choices.find(',', c)) != std::string::npos; c += 2) {
          choices.replace(c, 1, ", ");
        }
        return opt + ": '" + rest.substr(0, set) + "' is not one of " + choices;
      }
      return opt + ": " + rest;
    }
  }
  if (name == "ArgumentMismatch") {
    // "Expected exactly 1 arguments to --width, got 0"
    std::string opt = after(what, " arguments to ");
    opt = opt.substr(0, opt.find(','));
    if (!opt.empty()) return opt + ": needs a value";
  }
  if (name == "ExcludesError") {
    // "--camera excludes --orbit"
    const std::size_t at = what.find(" excludes ");
    if (at != std::string::npos) {
      return what.substr(0, at) + " and " + what.substr(at + 10) + " cannot be used together";
    }
  }
  // Anything else: CLI11's own words, on one line.
  std::string line = what;
  for (char& c : line) {
    if (c == '\n') c = ' ';
  }
  return line;
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
  for (int i = 0; i < argc; ++i) {
    std::string word = i == 0 ? std::string("tessera") : std::string(argv[i]);
    if (word.find_first_of(" \t'\"") != std::string::npos) word = "'" + word + "'";
    g_command_line += (i ? " " : "") + word;
  }
  CLI::App app{
      "tessera — real-time texturing and anti-aliasing: PVRTC compression by intensity "
      "dilation, seamless per-face texturing, adaptive supersampling for deferred shading.",
      "tessera"};
  app.require_subcommand(1);
  GlobalOptions global;
  app.add_option("-j,--threads", global.threads, "Worker threads (0 = all hardware threads)")
      ->check(CLI::Range(0, 1024));
  app.set_version_flag("--version", "tessera " TESSERA_VERSION_STRING);
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
      {"view", add_view_command},
  };
  const std::string_view named = subcommand_name(argc, argv);
  std::vector<std::string_view> known;
  for (const auto& [name, add] : kCommands) known.push_back(name);
  if (const std::string problem = precheck(argc, argv, named, known); !problem.empty()) {
    return usage_error(problem);
  }
  std::vector<Command> commands;
  for (const auto& [name, add] : kCommands) {
    if (name == named) commands = {add(app, global)};
  }
  if (commands.empty()) {
    for (const auto& [name, add] : kCommands) commands.push_back(add(app, global));
  }
  for (const Command& c : commands) {
    c.app->footer(
        "Global option, accepted before or after the subcommand: -j,--threads N "
        "(worker threads, 0 = all hardware threads; output is the same for any N)");
  }

  // Options whose value is optional (`--zstd [LEVEL]`): given without a number, they take the
  // default written as `--opt=DEFAULT`, so that CLI11 never swallows the next word (an input
  // path) as the value.
  std::vector<std::string> words(argv, argv + argc);
  static constexpr std::pair<std::string_view, std::string_view> kOptionalValues[] = {
      {"--zstd", "3"}};
  for (std::size_t i = 1; i < words.size(); ++i) {
    for (const auto& [option, fallback] : kOptionalValues) {
      if (words[i] != option) continue;
      const bool number = i + 1 < words.size() && !words[i + 1].empty() &&
                          words[i + 1].find_first_not_of("0123456789") == std::string::npos;
      if (!number) words[i] = std::string(option) + "=" + std::string(fallback);
    }
  }
  std::vector<char*> parse_argv;
  for (std::string& w : words) parse_argv.push_back(w.data());

  try {
    app.parse(int(parse_argv.size()), parse_argv.data());
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    const CLI::App* sub = commands.size() == 1 ? commands.front().app : nullptr;
    g_command = sub ? std::string(named) : std::string();
    const std::string unknown = first_unknown_option(argc, argv, sub);
    return usage_error(unknown.empty() ? describe_parse_error(e, sub ? sub : &app)
                                       : "unknown option '" + unknown + "'");
  }
  for (const Command& c : commands) {
    if (c.app->parsed()) {
      g_command = c.app->get_name();
      return c.run();
    }
  }
  return usage_error("no command given (see tessera --help)");
}
