// tessera compress: one image to one texture (or stdout), or many into a folder (batch mode,
// compress_batch.cpp).
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string_view>

#include "compress.h"
#include "progress.h"
#include "tessera/io.h"
#include "tessera/metrics.h"

namespace tessera::cli {

namespace {

namespace fs = std::filesystem;

bool is_folder(const std::string& output) {
  std::error_code ec;
  return output != "-" && (output.ends_with('/') || fs::is_directory(output, ec));
}

bool is_batch(const CompressArgs& args) {
  // --cube / --array: the inputs are one texture unless -o names a folder.
  if (args.words.cube || args.words.array) return is_folder(args.output);
  if (args.inputs.size() != 1) return true;
  const std::string& in = args.inputs.front();
  std::error_code ec;
  if (in.starts_with('@') || (in != "-" && fs::is_directory(in, ec))) return true;
  return is_folder(args.output);
}

/// The output's container and its --container word ("pvr", "ktx", "ktx2"), and the usage
/// checks of one texture; returns -1 to go on, else the exit code.
int check_compress_one(const CompressArgs& args, texture_file::ContainerFormat& container,
                       std::string& word) {
  container = texture_file::container_from_extension(args.output);
  if (!args.container.empty()) {
    container = container_of(args.container);
  } else if (args.output == "-") {
    container = texture_file::ContainerFormat::pvr3;
  }
  if (container == texture_file::ContainerFormat::unknown) {
    return usage_error(args.output +
                       ": unknown output extension (use .pvr, .ktx or .ktx2, or --container "
                       "pvr|ktx|ktx2)");
  }
  word = container == texture_file::ContainerFormat::ktx1   ? "ktx"
         : container == texture_file::ContainerFormat::ktx2 ? "ktx2"
                                                            : "pvr";
  if (std::string problem = compress_usage_problem(args, word); !problem.empty()) {
    return usage_error(problem);
  }
  if (std::count(args.inputs.begin(), args.inputs.end(), "-") > 1) {
    return usage_error("'-' (stdin) can be only one of the inputs");
  }
  if (int rc = refuse_binary_to_terminal(args.output, "a compressed texture")) return rc;
  if (args.words.premultiply && container == texture_file::ContainerFormat::ktx1 && !args.quiet) {
    std::fprintf(stderr,
                 "tessera: warning: KTX 1.1 has no premultiplied-alpha flag: loaders of "
                 "%s cannot tell (.pvr and .ktx2 say it)\n",
                 io::io_name(args.output, true).c_str());
  }
  return -1;
}

/// The input images and their names for messages; returns -1 to go on, else the exit code.
int read_inputs(const CompressArgs& args, std::vector<std::string>& names,
                std::vector<ImageRGBA8>& images) {
  for (const std::string& input : args.inputs) {
    names.push_back(io::io_name(input));
    Result<ImageRGBA8> loaded = io::read_image(input);
    if (!loaded) return fail(loaded.status());
    if (args.words.premultiply && !args.quiet && !loaded->has_alpha) {
      std::fprintf(stderr,
                   "tessera: warning: %s has no alpha channel: --premultiply leaves it "
                   "as it is\n",
                   names.back().c_str());
    }
    images.push_back(std::move(loaded).value());
  }
  return -1;
}

/// Feeds the encoder's progress over every image and level to `bar`.
void show_progress_on(ProgressBar& bar, const CompressArgs& args,
                      const std::vector<ImageRGBA8>& images,
                      texture_file::CompressOptions& options) {
  double mpixels = 0;  // of every chain, for the rate
  const int cap = args.words.mip_levels > 0 ? args.words.mip_levels : 1 << 30;
  for (const ImageRGBA8& im : images) {
    int level = 0;
    for (int w = im.width, h = im.height;; w = std::max(1, w / 2), h = std::max(1, h / 2)) {
      mpixels += double(w) * double(h) / 1e6;
      if (!args.words.mipmaps || (w == 1 && h == 1) || ++level >= cap) break;
    }
  }
  options.encode.progress = [&bar, mpixels](double f) { bar.update(f, "", f * mpixels); };
}

/// The one-line summary of what was written.
void print_summary(std::FILE* out, const CompressArgs& args, const std::string& output_name,
                   const texture_file::CompressedImage& made, std::size_t bytes,
                   const metrics::ImageComparison& cmp) {
  const texture_file::CompressedTexture& tex = made.texture;
  const std::string shape = tex.image_count() > 1 || tex.array
                                ? " " + texture_file::texture_shape_name(tex) + ","
                                : std::string();
  char alpha[48] = "";
  if (tex.has_alpha) std::snprintf(alpha, sizeof alpha, ", alpha %.2f dB", cmp.psnr_alpha);
  std::fprintf(out,
               "wrote %s: %s%s %s, %s%s%s, %d level(s), %zu bytes, encoded in %.1f ms (%s); "
               "PSNR %.2f dB%s, SSIM %.4f\n",
               output_name.c_str(), size_text(tex.width, tex.height).c_str(), shape.c_str(),
               texture_file::texture_format_name(tex).c_str(), args.words.srgb ? "sRGB" : "linear",
               tex.premultiplied ? ", premultiplied" : "",
               made.resized ? " (resized with Lanczos-3)" : "", tex.level_count(), bytes,
               made.encode_ms, args.words.quality.c_str(), cmp.psnr_rgb, alpha, cmp.ssim_gray);
}

/// The --json report of what was written.
void print_json(std::FILE* out, const CompressArgs& args, const GlobalOptions& global,
                const std::vector<std::string>& names, const std::string& output_name,
                texture_file::ContainerFormat container, const texture_file::CompressedImage& made,
                std::size_t bytes, const metrics::ImageComparison& cmp) {
  const texture_file::CompressedTexture& tex = made.texture;
  nlohmann::json j = {
      {"input", names.size() == 1 ? nlohmann::json(names.front()) : nlohmann::json(names)},
      {"output", output_name},
      {"container", texture_file::container_name(container)},
      {"width", tex.width},
      {"height", tex.height},
      {"resized", made.resized},
      {"format", args.words.format},
      {"quality", args.words.quality},
      {"iterations", args.words.iterations},
      {"exact_search_rounds", args.words.exact_search_rounds},
      {"srgb", args.words.srgb},
      {"has_alpha", tex.has_alpha},
      {"premultiplied", tex.premultiplied},
      {"shape", texture_file::texture_shape_name(tex)},
      {"faces", tex.faces},
      {"layers", tex.layers},
      {"levels", tex.level_count()},
      {"bytes", bytes},
      {"time_ms", made.encode_ms},
      {"threads", global.threads > 0 ? global.threads : default_thread_count()},
      {"psnr_rgb", db_or_null(cmp.psnr_rgb)},
      {"ssim_gray", cmp.ssim_gray},
  };
  if (tex.has_alpha) j["psnr_alpha"] = db_or_null(cmp.psnr_alpha);
  std::fprintf(out, "%s\n", j.dump(2).c_str());
}

int run_compress_one(const CompressArgs& args, const GlobalOptions& global) {
  texture_file::ContainerFormat container = texture_file::ContainerFormat::unknown;
  std::string container_word;
  if (int rc = check_compress_one(args, container, container_word); rc >= 0) return rc;
  if (args.skip_up_to_date && up_to_date(args, container_word, args.inputs, args.output)) {
    if (!args.quiet) {
      std::fprintf(text_stream(args.json), "skipped %s: up to date\n", args.output.c_str());
    }
    return kExitOk;
  }
  std::vector<std::string> names;
  std::vector<ImageRGBA8> images;
  if (int rc = read_inputs(args, names, images); rc >= 0) return rc;
  Result<texture_file::CompressOptions> checked = compress_options(args, global.threads);
  if (!checked) return fail(checked.status());
  texture_file::CompressOptions options = std::move(*checked);
  // A progress bar on a terminal for an encode that takes a while (from 0.5 s on; never with
  // -q or --json): the encoder's progress over every image and level.
  const bool show_progress = !args.quiet && !args.json && ::isatty(STDERR_FILENO);
  ProgressBar bar(show_progress, 0.5);
  if (show_progress) show_progress_on(bar, args, images, options);
  Result<texture_file::CompressedImage> made =
      texture_file::compress_images(std::move(images), texture_shape(args), options, names);
  bar.clear();
  if (!made) {
    Status s = made.status();
    s.message = cli_option_names(s.message);
    return fail(s);
  }
  const texture_file::CompressedTexture& tex = made->texture;

  std::size_t bytes = 0;
  {
    texture_file::Ktx2Options ktx2;
    ktx2.zstd_level = args.words.zstd;
    Result<std::vector<std::uint8_t>> file = texture_file::serialise_texture(tex, container, ktx2);
    if (!file) return fail(file.status());
    bytes = file->size();
    if (Status s = io::write_file_atomic(args.output, *file); !s.ok()) return fail(s);
  }
  if (args.skip_up_to_date && args.output != "-") {
    if (Status s = write_sidecar(args, container_word, args.inputs, args.output); !s.ok()) {
      return fail(s);
    }
  }
  if (args.quiet && !args.json) return kExitOk;

  // Quality of level 0 against the (possibly resized and prepared) input, as astcenc's -tl
  // mode reports it.
  Result<metrics::ImageComparison> cmp =
      texture_file::measure_level0(made->texture, made->sources, global.threads);
  if (!cmp) return fail(cmp.status());
  std::FILE* out = text_stream(args.output == "-");
  const std::string output_name = io::io_name(args.output, true);
  if (!args.json) {
    print_summary(out, args, output_name, *made, bytes, *cmp);
  } else {
    print_json(out, args, global, names, output_name, container, *made, bytes, *cmp);
  }
  return kExitOk;
}

}  // namespace

namespace {

/// This CLI's spelling of an option in messages: "--mip-filter lanczos", "--mipmaps".
std::string flag_spelling(std::string_view field, std::string_view value) {
  std::string flag = "--" + std::string(field);
  std::replace(flag.begin(), flag.end(), '_', '-');
  if (value.empty() || value == "True") return flag;
  return flag + " " + std::string(value);
}

}  // namespace

Result<texture_file::CompressOptions> compress_options(const CompressArgs& args, int threads) {
  return texture_file::compress_options(args.words, threads, flag_spelling);
}

std::string cli_option_names(std::string message) {
  static constexpr std::pair<std::string_view, std::string_view> kNames[] = {
      {"with resize_pot", "with --resize-pot"}};
  for (const auto& [library, cli] : kNames) {
    if (const std::size_t at = message.find(library); at != std::string::npos) {
      message.replace(at, library.size(), cli);
    }
  }
  return message;
}

texture_file::TextureShape texture_shape(const CompressArgs& args) {
  return {args.words.cube ? 6 : 1, args.words.array};
}

texture_file::ContainerFormat container_of(const std::string& word) {
  if (word == "ktx") return texture_file::ContainerFormat::ktx1;
  if (word == "ktx2") return texture_file::ContainerFormat::ktx2;
  if (word == "pvr") return texture_file::ContainerFormat::pvr3;
  return texture_file::ContainerFormat::unknown;
}

std::string compress_usage_problem(const CompressArgs& args, const std::string& container) {
  if (Result<texture_file::CompressOptions> o = compress_options(args, 0); !o) {
    return o.status().message;
  }
  if (args.words.zstd && !container.empty() && container != "ktx2") {
    return "--zstd needs a KTX 2.0 output (.ktx2 or --container ktx2)";
  }
  return "";
}

texture_file::RecordedOptions recorded_options(const CompressArgs& args,
                                               const std::string& container) {
  texture_file::RecordedOptions r = args.words;
  r.container = container;
  return r;
}

bool up_to_date(const CompressArgs& args, const std::string& container,
                const std::vector<std::string>& inputs, const std::string& output) {
  return texture_file::is_up_to_date(recorded_options(args, container), inputs, output);
}

Status write_sidecar(const CompressArgs& args, const std::string& container,
                     const std::vector<std::string>& inputs, const std::string& output) {
  // Standard input has no size or time to compare with: its output is never up to date.
  if (std::count(inputs.begin(), inputs.end(), "-") > 0) return Status::success();
  Result<std::string> record =
      texture_file::up_to_date_record(recorded_options(args, container), inputs);
  if (!record) return record.status();
  return texture_file::write_up_to_date_record(output, *record);
}

Command add_compress_command(CLI::App& app, const GlobalOptions& global) {
  auto args = std::make_shared<CompressArgs>();
  CLI::App* sub = app.add_subcommand(
      "compress",
      "Compress images to PVRTC1: one file to one texture (PVR v3, KTX 1.1 or KTX 2.0 by the "
      "output's extension), the faces of a cube map or the layers of an array to one texture, or "
      "many (files, folders, @lists) into a folder");
  sub->add_option("INPUT", args->inputs,
                  "Input images (PNG, JPEG, TGA, BMP, recognised by their bytes; '-' = stdin), "
                  "folders of them, or @LIST files naming one path a line")
      ->required();
  sub->add_option("-o,--output,--out", args->output,
                  "Output texture (.pvr, .ktx or .ktx2; '-' = stdout, PVR unless --container), "
                  "or with several inputs a folder (created; names follow the inputs')")
      ->required();
  sub->add_option("--container", args->container,
                  "Container, instead of the output's extension: pvr (PVR v3), ktx (KTX 1.1) or "
                  "ktx2 (KTX 2.0); the batch default is pvr")
      ->check(CLI::IsMember({"pvr", "ktx", "ktx2"}));
  sub->add_flag("--cube", args->words.cube,
                "The inputs are the 6 faces of a cube map, in the order +X, -X, +Y, -Y, +Z, -Z "
                "(square, one size); with --array, 6 per layer. In a batch (-o DIR/), each input "
                "folder is one cube map");
  sub->add_flag("--array", args->words.array,
                "The inputs are the layers of an array texture (one size). In a batch (-o DIR/), "
                "each input folder is one array, its images in name order");
  sub->add_option("--format", args->words.format, "PVRTC1 variant")
      ->check(CLI::IsMember({"pvrtc1-4", "pvrtc1-2"}))
      ->capture_default_str();
  sub->add_option("--quality", args->words.quality,
                  "fast = intensity dilation only; normal/high add refinement")
      ->check(CLI::IsMember({"fast", "normal", "high"}))
      ->capture_default_str();
  sub->add_option("--iterations", args->words.iterations,
                  "Least-squares refinement sweeps instead of the quality's own (-1 = the "
                  "quality's: fast 0, normal 3, high 3 at 4 bpp / 4 at 2 bpp; with "
                  "--quality fast, N > 0 refines the dilation result). A value other than -1, "
                  "or a non-zero --exact-search-rounds, leaves out high's crossover with a "
                  "second encoding")
      ->check(CLI::Range(-1, 1000))
      ->capture_default_str();
  sub->add_option("--exact-search-rounds", args->words.exact_search_rounds,
                  "4 bpp: rounds of the exact endpoint search after the refinement, on blocks "
                  "above ~4.5 RMS per channel, instead of the quality's own schedule (0 = the "
                  "quality's)")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  sub->add_flag("--mipmaps", args->words.mipmaps,
                "Build and encode the mip chain (alpha-weighted; in linear light with --srgb; "
                "as vectors with --normal-map)");
  sub->add_option("--mip-levels", args->words.mip_levels,
                  "Encode at most N levels, level 0 included (implies --mipmaps)")
      ->check(CLI::Range(1, 17));
  sub->add_option("--mip-filter", args->words.mip_filter,
                  "How each mip level is made: box (2x2), lanczos (Lanczos-3) or kaiser "
                  "(Kaiser-windowed sinc)")
      ->check(CLI::IsMember({"box", "lanczos", "kaiser"}))
      ->capture_default_str();
  sub->add_flag("--flip-y", args->words.flip_y,
                "Flip the images upside down first (for pipelines whose origin is bottom-left)");
  sub->add_flag("--premultiply", args->words.premultiply,
                "Multiply colour by alpha (in linear light with --srgb) and mark the texture "
                "premultiplied (PVR v3 flag, KTX 2.0 DFD flag)");
  sub->add_flag("--alpha-bleed", args->words.alpha_bleed,
                "Give fully transparent texels the colour of the nearest visible texel, so that "
                "filtering and PVRTC's block interpolation pull no invisible colour into edges");
  sub->add_flag("--alpha-weighted", args->words.alpha_weighted,
                "4 bpp, straight alpha: weight each texel's colour error by its alpha (what a "
                "blending renderer shows), so no bits go to the colour of invisible texels");
  sub->add_flag("--normal-map", args->words.normal_map,
                "The input is a normal map (RGB = x, y, z in [-1, 1]): renormalised, mips "
                "averaged as vectors; never sRGB");
  sub->add_option("--zstd", args->words.zstd,
                  "KTX 2.0: Zstandard supercompression at LEVEL (1-22; 3 when no level follows)")
      ->check(CLI::Range(1, 22));
  sub->add_flag("--srgb", args->words.srgb,
                "Mark the texture sRGB (colour space flag / sRGB KTX format) and filter in "
                "linear light");
  sub->add_flag("--resize-pot", args->words.resize_pot,
                "Resample non-power-of-two input to the nearest power of two (separable "
                "Lanczos-3)");
  sub->add_flag("-r,--recursive", args->recursive,
                "Batch: take the images in the folders' subfolders too (output tree mirrors it)");
  sub->add_flag("--skip-up-to-date", args->skip_up_to_date,
                "Skip an input whose output is newer and was made with the same options (kept "
                "in OUTPUT.json beside it, written after the output): an interrupted run "
                "resumes");
  sub->add_flag("--json", args->json,
                "Print JSON: one object (single file: time_ms, size, format, quality, levels, "
                "bytes, psnr_rgb, ssim_gray, psnr_alpha of level 0 vs the input); batch: one "
                "line per file, then a summary line");
  sub->add_flag("-q,--quiet", args->quiet,
                "Print nothing on success (no progress bar, no PSNR/SSIM measurement)");
  return {sub, [args, &global] {
            return is_batch(*args) ? run_compress_batch(*args, global)
                                   : run_compress_one(*args, global);
          }};
}

}  // namespace tessera::cli
