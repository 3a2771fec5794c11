// tessera compress / decompress / info: PVRTC1 textures in PVR v3 and KTX 1.1 files.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>

#include "cli.h"
#include "tessera/io.h"
#include "tessera/metrics.h"
#include "tessera/mipmap.h"
#include "tessera/pvrtc.h"
#include "tessera/texture_file.h"

namespace tessera::cli {

namespace {

nlohmann::json db_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

std::string size_text(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

// ---------------------------------------------------------------------------------------------
// compress
// ---------------------------------------------------------------------------------------------

struct CompressArgs {
  std::string input, output;
  std::string format = "pvrtc1-4";
  std::string quality = "normal";
  bool mipmaps = false;
  bool srgb = false;
  bool resize_pot = false;
  std::string container;  // "pvr" or "ktx"; "" = from the output's extension
  bool json = false;
  bool quiet = false;
  int iterations = -1;          // -1: the quality preset's schedule
  int exact_search_rounds = 0;  // 0: the quality preset's schedule
};

int run_compress(const CompressArgs& args, const GlobalOptions& global) {
  ContainerFormat container = container_from_extension(args.output);
  if (!args.container.empty()) {
    container = args.container == "ktx" ? ContainerFormat::ktx1 : ContainerFormat::pvr3;
  } else if (args.output == "-") {
    container = ContainerFormat::pvr3;
  }
  if (container == ContainerFormat::unknown) {
    return usage_error(args.output +
                       ": unknown output extension (use .pvr or .ktx, or --container pvr|ktx)");
  }
  if (int rc = refuse_binary_to_terminal(args.output, "a compressed texture")) return rc;
  const std::string input_name = io_name(args.input);
  Result<ImageRGBA8> loaded = read_image(args.input);
  if (!loaded) return fail(loaded.status());
  ImageRGBA8 image = std::move(loaded).value();
  // An alpha channel that is opaque everywhere (common in RGBA PNGs) gives an RGB texture.
  if (image.has_alpha) {
    // Two texels a step: their alpha bytes are the top bytes of each little-endian half.
    constexpr std::uint64_t kAlpha2 = 0xff000000ff000000ull;
    const std::uint8_t* p = image.pixels.data();
    const std::size_t n = image.pixels.size();
    std::uint64_t all = kAlpha2;
    std::size_t i = 0;
    for (; i + 8 <= n && all == kAlpha2; i += 8) {
      std::uint64_t v;
      std::memcpy(&v, p + i, 8);
      all &= v | ~kAlpha2;
    }
    bool translucent = all != kAlpha2;
    for (i += 3; i < n && !translucent; i += 4) translucent = p[i] != 255;
    image.has_alpha = translucent;
  }

  MipmapOptions filter;
  filter.srgb = args.srgb;
  filter.threads = global.threads;
  const bool pot = pvrtc::check_dimensions(image.width, image.height, input_name).ok();
  if (!pot) {
    const int pw = nearest_power_of_two(image.width), ph = nearest_power_of_two(image.height);
    if (!args.resize_pot) {
      return fail(Status::error(
          ErrorCode::invalid_argument,
          input_name + ": size " + size_text(image.width, image.height) +
              " is not a power of two (PVRTC needs power-of-two sides); use --resize-pot to "
              "resample to " + size_text(pw, ph)));
    }
    Result<ImageRGBA8> resized = resize_image(image, pw, ph, filter);
    if (!resized) return fail(resized.status());
    image = std::move(resized).value();
  }
  if (Status s = pvrtc::check_dimensions(image.width, image.height, input_name); !s.ok()) {
    return fail(s);
  }

  pvrtc::EncodeOptions eo;
  eo.format = args.format == "pvrtc1-2" ? pvrtc::Format::pvrtc1_2bpp : pvrtc::Format::pvrtc1_4bpp;
  eo.quality = args.quality == "fast"   ? pvrtc::Quality::fast
               : args.quality == "high" ? pvrtc::Quality::high
                                        : pvrtc::Quality::normal;
  eo.iterations = args.iterations;
  eo.exact_search_rounds = args.exact_search_rounds;
  eo.threads = global.threads;

  // Level 0 is `image` itself (no copy); the smaller levels come from generate_mipmaps.
  std::vector<ImageRGBA8> mips;
  std::vector<const ImageRGBA8*> chain = {&image};
  if (args.mipmaps) {
    Result<std::vector<ImageRGBA8>> c = generate_mipmaps(image, filter);
    if (!c) return fail(c.status());
    mips = std::move(c).value();
    chain.clear();
    for (const ImageRGBA8& m : mips) chain.push_back(&m);
  }

  CompressedTexture tex;
  tex.format = eo.format;
  tex.width = image.width;
  tex.height = image.height;
  tex.has_alpha = image.has_alpha;
  tex.srgb = args.srgb;
  const auto t0 = std::chrono::steady_clock::now();
  for (const ImageRGBA8* level : chain) {
    Result<std::vector<std::uint8_t>> enc = pvrtc::encode(*level, eo);
    if (!enc) {
      Status s = enc.status();
      s.message = input_name + ": " + s.message;
      return fail(s);
    }
    tex.levels.push_back(std::move(enc).value());
  }
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();

  std::size_t bytes = 0;
  {
    Result<std::vector<std::uint8_t>> file =
        container == ContainerFormat::ktx1 ? serialize_ktx1(tex) : serialize_pvr3(tex);
    if (!file) return fail(file.status());
    bytes = file->size();
    if (Status s = write_file_atomic(args.output, *file); !s.ok()) return fail(s);
  }
  if (args.quiet && !args.json) return kExitOk;

  // Quality of level 0 against the (possibly resized) input, as astcenc's -tl mode reports it.
  Result<ImageRGBA8> decoded = decode_texture_level(tex, 0, global.threads);
  if (!decoded) return fail(decoded.status());
  CompareOptions co;
  co.threads = global.threads;
  Result<ImageComparison> cmp = compare_images(image, *decoded, co);
  if (!cmp) return fail(cmp.status());
  std::FILE* out = text_stream(args.output == "-");
  const std::string output_name = io_name(args.output, true);
  if (!args.json) {
    char alpha[48] = "";
    if (tex.has_alpha) {
      std::snprintf(alpha, sizeof alpha, ", alpha %.2f dB", cmp->psnr_alpha);
    }
    std::fprintf(out,
                 "wrote %s: %s %s, %s%s, %d level(s), %zu bytes, encoded in %.1f ms (%s); "
                 "PSNR %.2f dB%s, SSIM %.4f\n",
                 output_name.c_str(), size_text(tex.width, tex.height).c_str(),
                 texture_format_name(tex).c_str(), args.srgb ? "sRGB" : "linear",
                 pot ? "" : " (resized with Lanczos-3)", tex.level_count(), bytes, ms,
                 args.quality.c_str(), cmp->psnr_rgb, alpha, cmp->ssim_gray);
    return kExitOk;
  }
  nlohmann::json j = {
      {"input", input_name},
      {"output", output_name},
      {"container", container_name(container)},
      {"width", tex.width},
      {"height", tex.height},
      {"resized", !pot},
      {"format", args.format},
      {"quality", args.quality},
      {"iterations", args.iterations},
      {"exact_search_rounds", args.exact_search_rounds},
      {"srgb", args.srgb},
      {"has_alpha", tex.has_alpha},
      {"levels", tex.level_count()},
      {"bytes", bytes},
      {"time_ms", ms},
      {"threads", global.threads > 0 ? global.threads : default_thread_count()},
      {"psnr_rgb", db_or_null(cmp->psnr_rgb)},
      {"ssim_gray", cmp->ssim_gray},
  };
  if (tex.has_alpha) j["psnr_alpha"] = db_or_null(cmp->psnr_alpha);
  std::fprintf(out, "%s\n", j.dump(2).c_str());
  return kExitOk;
}

// ---------------------------------------------------------------------------------------------
// decompress
// ---------------------------------------------------------------------------------------------

struct DecompressArgs {
  std::string input, output;
  int level = 0;
  bool quiet = false;
  bool json = false;
};

int run_decompress(const DecompressArgs& args, const GlobalOptions& global) {
  if (Result<ImageFormat> f = image_format_for_output(args.output); !f) {
    return usage_error("-o: " + f.status().message);
  }
  if (int rc = refuse_binary_to_terminal(args.output, "an image")) return rc;
  const std::string input_name = io_name(args.input);
  Result<CompressedTexture> tex = read_texture_file(args.input);
  if (!tex) return fail(tex.status());
  if (args.level < 0 || args.level >= tex->level_count()) {
    return fail(Status::error(ErrorCode::invalid_argument,
                              input_name + ": --level " + std::to_string(args.level) +
                                  " is out of range (the file has " +
                                  std::to_string(tex->level_count()) + " level(s), 0 to " +
                                  std::to_string(tex->level_count() - 1) + ")"));
  }
  Result<ImageRGBA8> img = decode_texture_level(*tex, args.level, global.threads);
  if (!img) {
    Status s = img.status();
    s.message = input_name + ": " + s.message;
    return fail(s);
  }
  if (Status s = write_image(args.output, *img); !s.ok()) return fail(s);
  std::FILE* out = text_stream(args.output == "-");
  if (args.json) {
    const nlohmann::json j = {{"input", input_name},
                              {"output", io_name(args.output, true)},
                              {"level", args.level},
                              {"width", img->width},
                              {"height", img->height},
                              {"has_alpha", img->has_alpha}};
    std::fprintf(out, "%s\n", j.dump(2).c_str());
  } else if (!args.quiet) {
    std::fprintf(out, "wrote %s: level %d, %s\n", io_name(args.output, true).c_str(), args.level,
                 size_text(img->width, img->height).c_str());
  }
  return kExitOk;
}

// ---------------------------------------------------------------------------------------------
// info
// ---------------------------------------------------------------------------------------------

struct InfoArgs {
  std::string input;
  bool json = false;
};

int run_info(const InfoArgs& args) {
  Result<std::vector<std::uint8_t>> bytes = read_file(args.input);
  if (!bytes) return fail(bytes.status());
  const std::string name = io_name(args.input);
  Result<CompressedTexture> tex = parse_texture(*bytes, name);
  if (!tex) return fail(tex.status());
  const ContainerFormat container = detect_container(*bytes);
  if (args.json) {
    nlohmann::json levels = nlohmann::json::array();
    for (int i = 0; i < tex->level_count(); ++i) {
      levels.push_back({{"level", i},
                        {"width", tex->level_width(i)},
                        {"height", tex->level_height(i)},
                        {"bytes", tex->levels[std::size_t(i)].size()}});
    }
    nlohmann::json j = {
        {"file", name},
        {"container", container_name(container)},
        {"format", texture_format_name(*tex)},
        {"bpp", tex->format == pvrtc::Format::pvrtc1_4bpp ? 4 : 2},
        {"has_alpha", tex->has_alpha},
        {"width", tex->width},
        {"height", tex->height},
        {"colour_space", tex->srgb ? "sRGB" : "linear"},
        {"premultiplied", tex->premultiplied},
        {"file_bytes", bytes->size()},
        {"levels", levels},
    };
    std::printf("%s\n", j.dump(2).c_str());
    return kExitOk;
  }
  std::printf("%s\n", name.c_str());
  std::printf("  container     : %s\n", container_name(container));
  std::printf("  format        : %s\n", texture_format_name(*tex).c_str());
  std::printf("  size          : %s\n", size_text(tex->width, tex->height).c_str());
  std::printf("  colour space  : %s\n", tex->srgb ? "sRGB" : "linear");
  std::printf("  premultiplied : %s\n", tex->premultiplied ? "yes" : "no");
  std::printf("  file size     : %zu bytes\n", bytes->size());
  std::printf("  levels        : %d\n", tex->level_count());
  for (int i = 0; i < tex->level_count(); ++i) {
    std::printf("    %2d  %5d x %-5d %9zu bytes\n", i, tex->level_width(i), tex->level_height(i),
                tex->levels[std::size_t(i)].size());
  }
  return kExitOk;
}

}  // namespace

Command add_compress_command(CLI::App& app, const GlobalOptions& global) {
  auto args = std::make_shared<CompressArgs>();
  CLI::App* sub = app.add_subcommand(
      "compress", "Compress an image to PVRTC1 (PVR v3 or KTX 1.1 by output extension)");
  sub->add_option("INPUT", args->input,
                  "Input image (PNG, JPEG, TGA, BMP; recognised by its bytes; '-' = stdin)")
      ->required();
  sub->add_option("-o,--output,--out", args->output,
                  "Output texture: .pvr or .ktx ('-' = stdout, PVR unless --container ktx)")
      ->required();
  sub->add_option("--container", args->container,
                  "Container, instead of the output's extension: pvr (PVR v3) or ktx (KTX 1.1)")
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
  sub->add_flag("--json", args->json,
                "Print one JSON object: time_ms (encode), width, height, format, quality, levels, "
                "bytes, psnr_rgb, ssim_gray (and psnr_alpha) of level 0 vs the input");
  sub->add_flag("-q,--quiet", args->quiet,
                "Print nothing on success (and skip measuring the result's PSNR and SSIM)");
  return {sub, [args, &global] { return run_compress(*args, global); }};
}

Command add_decompress_command(CLI::App& app, const GlobalOptions& global) {
  auto args = std::make_shared<DecompressArgs>();
  CLI::App* sub =
      app.add_subcommand("decompress", "Decode one level of a PVRTC .pvr/.ktx file to an image");
  sub->add_option("INPUT", args->input,
                  "Input texture (PVR v3 or KTX 1.1, recognised by its bytes; '-' = stdin)")
      ->required();
  sub->add_option("-o,--output,--out", args->output,
                  "Output image: .png, .bmp, .tga or .jpg by extension ('-' = PNG on stdout)")
      ->required();
  sub->add_option("--level", args->level, "Mip level to decode (0 = largest)")
      ->capture_default_str();
  sub->add_flag("--json", args->json, "Print one JSON object (input, output, level, size)");
  sub->add_flag("-q,--quiet", args->quiet, "Print nothing on success");
  return {sub, [args, &global] { return run_decompress(*args, global); }};
}

Command add_info_command(CLI::App& app, const GlobalOptions& /*global*/) {
  auto args = std::make_shared<InfoArgs>();
  CLI::App* sub = app.add_subcommand(
      "info", "Describe a .pvr/.ktx texture: container, format, size, colour space, levels");
  sub->add_option("FILE", args->input, "Texture file (PVR v3 or KTX 1.1; '-' = stdin)")
      ->required();
  sub->add_flag("--json", args->json, "Print one JSON object");
  return {sub, [args] { return run_info(*args); }};
}

}  // namespace tessera::cli
