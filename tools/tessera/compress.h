// tessera compress: the arguments shared by the single-file and the batch mode.
#pragma once

#include <string>
#include <vector>

#include "cli.h"
#include "tessera/texture_file.h"

namespace tessera::cli {

struct CompressArgs {
  std::vector<std::string> inputs;  ///< Files, folders, @lists; "-" = stdin (single mode).
  std::string output;               ///< A file, "-", or (batch) a folder.
  std::string container;            ///< "pvr" or "ktx"; "" = from the output's extension.
  std::string format = "pvrtc1-4";
  std::string quality = "normal";
  bool mipmaps = false;
  bool srgb = false;
  bool resize_pot = false;
  bool json = false;
  bool quiet = false;
  bool recursive = false;
  bool skip_up_to_date = false;
  int iterations = -1;          ///< -1: the quality preset's schedule.
  int exact_search_rounds = 0;  ///< 0: the quality preset's schedule.
};

/// The library options of these arguments, with `threads` encoder threads.
texture_file::CompressOptions compress_options(const CompressArgs& args, int threads);

/// The record `--skip-up-to-date` keeps beside each output (OUTPUT.json, the sidecar): tessera's
/// version, the container, the encode options and the input's size and modification time. The
/// Python `tessera.batch` writes and reads the same record.
std::string sidecar_record(const CompressArgs& args, const std::string& container,
                           const std::string& input);

/// True when `output` exists, is newer than `input`, and its sidecar holds the record of these
/// options and this input.
bool up_to_date(const CompressArgs& args, const std::string& container, const std::string& input,
                const std::string& output);

/// Writes the sidecar of `output` (after the output itself, so an interrupted run never leaves
/// an output that looks complete without being so).
Status write_sidecar(const CompressArgs& args, const std::string& container,
                     const std::string& input, const std::string& output);

/// Batch mode: many inputs into the folder `args.output`.
int run_compress_batch(const CompressArgs& args, const GlobalOptions& global);

}  // namespace tessera::cli
