// tessera compress: one image to one texture (or stdout), or many into a folder (batch mode,
// compress_batch.cpp).
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "compress.h"
#include "progress.h"
#include "tessera/io.h"
#include "tessera/metrics.h"

namespace tessera::cli {

namespace {

namespace fs = std::filesystem;

nlohmann::json db_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

std::string size_text(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

bool is_batch(const CompressArgs& args) {
  if (args.inputs.size() != 1) return true;
  const std::string& in = args.inputs.front();
  std::error_code ec;
  if (in.starts_with('@') || (in != "-" && fs::is_directory(in, ec))) return true;
  if (args.output.ends_with('/')) return true;
  return args.output != "-" && fs::is_directory(args.output, ec);
}

nlohmann::json sidecar_json(const CompressArgs& args, const std::string& container,
                            const std::string& input) {
  struct stat st {};
  if (::stat(input.c_str(), &st) != 0) return nullptr;
  return {{"tessera", TESSERA_VERSION_STRING},
          {"container", container},
          {"options",
           {{"exact_search_rounds", args.exact_search_rounds},
            {"format", args.format},
            {"iterations", args.iterations},
            {"mipmaps", args.mipmaps},
            {"quality", args.quality},
            {"resize_pot", args.resize_pot},
            {"srgb", args.srgb}}},
          {"input_size", std::int64_t(st.st_size)},
          {"input_mtime_ns", std::int64_t(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec}};
}

int run_compress_one(const CompressArgs& args, const GlobalOptions& global) {
  const std::string& input = args.inputs.front();
  texture_file::ContainerFormat container = texture_file::container_from_extension(args.output);
  if (!args.container.empty()) {
    container = args.container == "ktx" ? texture_file::ContainerFormat::ktx1
                                        : texture_file::ContainerFormat::pvr3;
  } else if (args.output == "-") {
    container = texture_file::ContainerFormat::pvr3;
  }
  if (container == texture_file::ContainerFormat::unknown) {
    return usage_error(args.output +
                       ": unknown output extension (use .pvr or .ktx, or --container pvr|ktx)");
  }
  if (int rc = refuse_binary_to_terminal(args.output, "a compressed texture")) return rc;
  const std::string container_word =
      container == texture_file::ContainerFormat::ktx1 ? "ktx" : "pvr";
  if (args.skip_up_to_date && up_to_date(args, container_word, input, args.output)) {
    if (!args.quiet) {
      std::fprintf(text_stream(args.json), "skipped %s: up to date\n", args.output.c_str());
    }
    return kExitOk;
  }
  const std::string input_name = io::io_name(input);
  Result<ImageRGBA8> loaded = io::read_image(input);
  if (!loaded) return fail(loaded.status());
  texture_file::CompressOptions options = compress_options(args, global.threads);
  // A progress bar on a terminal for an encode that takes a while (from 0.5 s on; never with
  // -q or --json): the encoder's progress over the whole mip chain.
  const bool show_progress = !args.quiet && !args.json && ::isatty(STDERR_FILENO);
  ProgressBar bar(show_progress, 0.5);
  if (show_progress) {
    double mpixels = 0;  // of the whole chain, for the rate
    for (int w = loaded->width, h = loaded->height;; w = std::max(1, w / 2),
             h = std::max(1, h / 2)) {
      mpixels += double(w) * double(h) / 1e6;
      if (!args.mipmaps || (w == 1 && h == 1)) break;
    }
    options.encode.progress = [&bar, mpixels](double f) { bar.update(f, "", f * mpixels); };
  }
  Result<texture_file::CompressedImage> made =
      texture_file::compress_image(std::move(loaded).value(), options, input_name);
  bar.clear();
  if (!made) return fail(made.status());
  const texture_file::CompressedTexture& tex = made->texture;

  std::size_t bytes = 0;
  {
    Result<std::vector<std::uint8_t>> file = container == texture_file::ContainerFormat::ktx1
                                                 ? texture_file::serialise_ktx1(tex)
                                                 : texture_file::serialise_pvr3(tex);
    if (!file) return fail(file.status());
    bytes = file->size();
    if (Status s = io::write_file_atomic(args.output, *file); !s.ok()) return fail(s);
  }
  if (args.skip_up_to_date && args.output != "-") {
    if (Status s = write_sidecar(args, container_word, input, args.output); !s.ok()) {
      return fail(s);
    }
  }
  if (args.quiet && !args.json) return kExitOk;

  // Quality of level 0 against the (possibly resized) input, as astcenc's -tl mode reports it.
  Result<ImageRGBA8> decoded = texture_file::decode_texture_level(tex, 0, {global.threads});
  if (!decoded) return fail(decoded.status());
  metrics::CompareOptions co;
  co.threads = global.threads;
  Result<metrics::ImageComparison> cmp = metrics::compare_images(made->sources.front(), *decoded, co);
  if (!cmp) return fail(cmp.status());
  std::FILE* out = text_stream(args.output == "-");
  const std::string output_name = io::io_name(args.output, true);
  if (!args.json) {
    char alpha[48] = "";
    if (tex.has_alpha) std::snprintf(alpha, sizeof alpha, ", alpha %.2f dB", cmp->psnr_alpha);
    std::fprintf(out,
                 "wrote %s: %s %s, %s%s, %d level(s), %zu bytes, encoded in %.1f ms (%s); "
                 "PSNR %.2f dB%s, SSIM %.4f\n",
                 output_name.c_str(), size_text(tex.width, tex.height).c_str(),
                 texture_file::texture_format_name(tex).c_str(), args.srgb ? "sRGB" : "linear",
                 made->resized ? " (resized with Lanczos-3)" : "", tex.level_count(), bytes,
                 made->encode_ms, args.quality.c_str(), cmp->psnr_rgb, alpha, cmp->ssim_gray);
    return kExitOk;
  }
  nlohmann::json j = {
      {"input", input_name},
      {"output", output_name},
      {"container", texture_file::container_name(container)},
      {"width", tex.width},
      {"height", tex.height},
      {"resized", made->resized},
      {"format", args.format},
      {"quality", args.quality},
      {"iterations", args.iterations},
      {"exact_search_rounds", args.exact_search_rounds},
      {"srgb", args.srgb},
      {"has_alpha", tex.has_alpha},
      {"levels", tex.level_count()},
      {"bytes", bytes},
      {"time_ms", made->encode_ms},
      {"threads", global.threads > 0 ? global.threads : default_thread_count()},
      {"psnr_rgb", db_or_null(cmp->psnr_rgb)},
      {"ssim_gray", cmp->ssim_gray},
  };
  if (tex.has_alpha) j["psnr_alpha"] = db_or_null(cmp->psnr_alpha);
  std::fprintf(out, "%s\n", j.dump(2).c_str());
  return kExitOk;
}

}  // namespace

texture_file::CompressOptions compress_options(const CompressArgs& args, int threads) {
  texture_file::CompressOptions o;
  o.encode.format =
      args.format == "pvrtc1-2" ? pvrtc::Format::pvrtc1_2bpp : pvrtc::Format::pvrtc1_4bpp;
  o.encode.quality = args.quality == "fast"   ? pvrtc::Quality::fast
                     : args.quality == "high" ? pvrtc::Quality::high
                                              : pvrtc::Quality::normal;
  o.encode.iterations = args.iterations;
  o.encode.exact_search_rounds = args.exact_search_rounds;
  o.encode.threads = threads;
  o.mipmaps = args.mipmaps;
  o.srgb = args.srgb;
  o.resize_pot = args.resize_pot;
  return o;
}

std::string sidecar_record(const CompressArgs& args, const std::string& container,
                           const std::string& input) {
  return sidecar_json(args, container, input).dump(1) + "\n";
}

bool up_to_date(const CompressArgs& args, const std::string& container, const std::string& input,
                const std::string& output) {
  struct stat in {}, out {};
  if (input == "-" || ::stat(input.c_str(), &in) != 0 || ::stat(output.c_str(), &out) != 0) {
    return false;
  }
  const auto ns = [](const struct stat& s) {
    return std::int64_t(s.st_mtim.tv_sec) * 1000000000 + s.st_mtim.tv_nsec;
  };
  if (ns(out) <= ns(in)) return false;
  Result<std::vector<std::uint8_t>> text = io::read_file(output + ".json", 1 << 20);
  if (!text) return false;
  const nlohmann::json stored = nlohmann::json::parse(text->begin(), text->end(), nullptr, false);
  return !stored.is_discarded() && stored == sidecar_json(args, container, input);
}

Status write_sidecar(const CompressArgs& args, const std::string& container,
                     const std::string& input, const std::string& output) {
  const std::string text = sidecar_record(args, container, input);
  return io::write_file_atomic(output + ".json",
                               {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
}

Command add_compress_command(CLI::App& app, const GlobalOptions& global) {
  auto args = std::make_shared<CompressArgs>();
  CLI::App* sub = app.add_subcommand(
      "compress",
      "Compress images to PVRTC1: one file to one texture (PVR v3 or KTX 1.1 by the output's "
      "extension), or many (files, folders, @lists) into a folder");
  sub->add_option("INPUT", args->inputs,
                  "Input images (PNG, JPEG, TGA, BMP, recognised by their bytes; '-' = stdin), "
                  "folders of them, or @LIST files naming one path a line")
      ->required();
  sub->add_option("-o,--output,--out", args->output,
                  "Output texture (.pvr or .ktx; '-' = stdout, PVR unless --container ktx), or "
                  "with several inputs a folder (created; names follow the inputs')")
      ->required();
  sub->add_option("--container", args->container,
                  "Container, instead of the output's extension: pvr (PVR v3) or ktx (KTX 1.1); "
                  "the batch default is pvr")
      ->check(CLI::IsMember({"pvr", "ktx"}));
  sub->add_option("--format", args->format, "PVRTC1 variant")
      ->check(CLI::IsMember({"pvrtc1-4", "pvrtc1-2"}))
      ->capture_default_str();
  sub->add_option("--quality", args->quality,
                  "fast = intensity dilation only; normal/high add refinement")
      ->check(CLI::IsMember({"fast", "normal", "high"}))
      ->capture_default_str();
  sub->add_option("--iterations", args->iterations,
                  "Least-squares refinement sweeps instead of the quality's own (-1 = the "
                  "quality's: fast 0, normal 3, high 3 at 4 bpp / up to 16 at 2 bpp; with "
                  "--quality fast, N > 0 refines the dilation result). A value other than -1, "
                  "or a non-zero --exact-search-rounds, leaves out high's crossover with a "
                  "second encoding")
      ->check(CLI::Range(-1, 1000))
      ->capture_default_str();
  sub->add_option("--exact-search-rounds", args->exact_search_rounds,
                  "4 bpp: rounds of the exact endpoint search after the refinement, on blocks "
                  "above ~4.5 RMS per channel, instead of the quality's own schedule (0 = the "
                  "quality's)")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  sub->add_flag("--mipmaps", args->mipmaps,
                "Build and encode the full mip chain (2x2 box, alpha-weighted; in linear light "
                "with --srgb)");
  sub->add_flag("--srgb", args->srgb,
                "Mark the texture sRGB (colour space flag / sRGB KTX format) and filter in "
                "linear light");
  sub->add_flag("--resize-pot", args->resize_pot,
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
