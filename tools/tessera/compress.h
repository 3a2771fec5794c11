// tessera compress: the arguments shared by the single-file and the batch mode.
#pragma once

#include <string>
#include <vector>

#include "cli.h"
#include "tessera/metrics.h"
#include "tessera/texture_file.h"

namespace tessera::cli {

struct CompressArgs {
  std::vector<std::string> inputs;  ///< Files, folders, @lists; "-" = stdin (single mode).
  std::string output;               ///< A file, "-", or (batch) a folder.
  std::string container;            ///< "pvr", "ktx" or "ktx2"; "" = from the output's extension.
  /// The options as typed (`words.container` is `container` once known: `recorded_options`).
  texture_file::RecordedOptions words;
  bool json = false;
  bool quiet = false;
  bool recursive = false;
  bool skip_up_to_date = false;
};

/// The library options of these arguments, with `threads` encoder threads
/// (texture_file::compress_options; a failure names the flags as this CLI spells them).
Result<texture_file::CompressOptions> compress_options(const CompressArgs& args, int threads);

/// The texture shape of --cube / --array.
texture_file::TextureShape texture_shape(const CompressArgs& args);

/// The container the word names ("pvr", "ktx", "ktx2").
texture_file::ContainerFormat container_of(const std::string& word);

/// The one usage problem of these arguments that no single option's check sees (conflicting
/// options, --zstd without KTX 2.0 once the container is known: `container` "" when not yet),
/// or "".
std::string compress_usage_problem(const CompressArgs& args, const std::string& container);

/// The options these arguments record in the up-to-date record of `--skip-up-to-date`
/// (OUTPUT.json: `texture_file::up_to_date_record`, which `tessera.batch` writes too).
texture_file::RecordedOptions recorded_options(const CompressArgs& args,
                                               const std::string& container);

/// True when `output` is up to date for these options and inputs
/// (`texture_file::is_up_to_date`).
bool up_to_date(const CompressArgs& args, const std::string& container,
                const std::vector<std::string>& inputs, const std::string& output);

/// Writes the up-to-date record of `output` (after the output itself, so an interrupted run
/// never leaves an output that looks complete without being so); none for standard input,
/// whose output is never up to date.
Status write_sidecar(const CompressArgs& args, const std::string& container,
                     const std::vector<std::string>& inputs, const std::string& output);

/// A library message with the library's option names ("with resize_pot") as this CLI's flags
/// ("with --resize-pot").
std::string cli_option_names(std::string message);

/// Batch mode: many inputs into the folder `args.output`.
int run_compress_batch(const CompressArgs& args, const GlobalOptions& global);

}  // namespace tessera::cli
