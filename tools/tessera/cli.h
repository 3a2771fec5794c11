// Shared plumbing of the tessera command-line tool: exit codes, error printing and the
// registration interface every subcommand implements.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdio>
#include <functional>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "tessera/core.h"
#include "tessera/experiments/common.h"

namespace tessera::cli {

/// Process exit codes of every subcommand.
enum ExitCode : int {
  kExitOk = 0,        ///< Success.
  kExitBadInput = 1,  ///< A file is missing, unreadable, corrupt, or an output cannot be written.
  kExitUsage = 2,     ///< The command line itself is wrong.
};

/// Options shared by every subcommand.
struct GlobalOptions {
  int threads = 0;  ///< -j N; 0 = all hardware threads.
};

/// Prints "tessera: <message>" on one line to stderr and returns kExitBadInput.
int fail(const Status& status);
/// Prints "tessera: <message>" on one line to stderr and returns kExitUsage.
int usage_error(const std::string& message);

/// Refuses binary output to a terminal, as zstd does: when `path` is "-" and standard output is
/// a terminal, prints a one-line hint naming `what` and returns kExitUsage; else returns 0.
int refuse_binary_to_terminal(const std::string& path, const char* what);

/// Where human-readable text goes: stderr when stdout carries data (`data_on_stdout`) or JSON,
/// else stdout.
std::FILE* text_stream(bool data_on_stdout);

/// A value in dB for --json output: the number, or null where it is not finite (the PSNR of
/// identical images is infinite, and JSON has no infinity).
nlohmann::json db_or_null(double db);

/// The command line this process was started with, words joined by spaces (quoted where they
/// hold a space), for reports.
const std::string& command_line();

/// The OpenGL backends of `tessera seams` and `tessera aa` (gl::experiment_backends) with the
/// shipped GLSL folder: $TESSERA_GLSL_DIR, else the source tree's share/tessera/glsl (a build
/// tree), else the installed one; null when tessera is built without the GL runtime.
std::shared_ptr<const experiments::GpuBackendFactory> gl_backends();

/// The Vulkan backends of `tessera seams` and `tessera aa` (vk::experiment_backends) on the
/// loader libvulkan.so.1, under VK_LAYER_KHRONOS_validation when $TESSERA_VK_VALIDATION is 1 (a
/// validation message then fails the command), on the device $TESSERA_VK_DEVICE numbers; null
/// when tessera is built without the Vulkan runtime.
std::shared_ptr<const experiments::GpuBackendFactory> vk_backends();

/// A registered subcommand: the CLI11 sub-app and the action run when it was selected.
struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
};

Command add_aa_command(CLI::App& app, const GlobalOptions& global);
Command add_compare_command(CLI::App& app, const GlobalOptions& global);
Command add_demo_command(CLI::App& app, const GlobalOptions& global);
Command add_compress_command(CLI::App& app, const GlobalOptions& global);
Command add_decompress_command(CLI::App& app, const GlobalOptions& global);
Command add_info_command(CLI::App& app, const GlobalOptions& global);
Command add_render_command(CLI::App& app, const GlobalOptions& global);
Command add_seams_command(CLI::App& app, const GlobalOptions& global);
Command add_view_command(CLI::App& app, const GlobalOptions& global);

}  // namespace tessera::cli
