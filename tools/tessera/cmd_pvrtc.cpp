// tessera decompress / info: PVRTC1 textures in PVR v3 and KTX 1.1 files.
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli.h"
#include "tessera/io.h"
#include "tessera/pvrtc.h"
#include "tessera/texture_file.h"

namespace tessera::cli {

namespace {

std::string size_text(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

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
  if (Result<io::ImageFormat> f = io::image_format_for_output(args.output); !f) {
    return usage_error("-o: " + f.status().message);
  }
  if (int rc = refuse_binary_to_terminal(args.output, "an image")) return rc;
  const std::string input_name = io::io_name(args.input);
  Result<texture_file::CompressedTexture> tex = texture_file::read_texture_file(args.input);
  if (!tex) return fail(tex.status());
  if (args.level < 0 || args.level >= tex->level_count()) {
    return fail(Status::error(ErrorCode::invalid_argument,
                              input_name + ": --level " + std::to_string(args.level) +
                                  " is out of range (the file has " +
                                  std::to_string(tex->level_count()) + " level(s), 0 to " +
                                  std::to_string(tex->level_count() - 1) + ")"));
  }
  Result<ImageRGBA8> img = texture_file::decode_texture_level(*tex, args.level, {global.threads});
  if (!img) {
    Status s = img.status();
    s.message = input_name + ": " + s.message;
    return fail(s);
  }
  if (Status s = io::write_image(args.output, *img); !s.ok()) return fail(s);
  std::FILE* out = text_stream(args.output == "-");
  if (args.json) {
    const nlohmann::json j = {{"input", input_name},   {"output", io::io_name(args.output, true)},
                              {"level", args.level},   {"width", img->width},
                              {"height", img->height}, {"has_alpha", img->has_alpha}};
    std::fprintf(out, "%s\n", j.dump(2).c_str());
  } else if (!args.quiet) {
    std::fprintf(out, "wrote %s: level %d, %s\n", io::io_name(args.output, true).c_str(),
                 args.level, size_text(img->width, img->height).c_str());
  }
  return kExitOk;
}

// ---------------------------------------------------------------------------------------------
// info
// ---------------------------------------------------------------------------------------------

struct InfoArgs {
  std::string input;
  bool json = false;
  bool quiet = false;
};

int run_info(const InfoArgs& args) {
  Result<std::vector<std::uint8_t>> bytes = io::read_file(args.input);
  if (!bytes) return fail(bytes.status());
  const std::string name = io::io_name(args.input);
  Result<texture_file::CompressedTexture> tex = texture_file::parse_texture(*bytes, name);
  if (!tex) return fail(tex.status());
  if (args.quiet && !args.json) return kExitOk;  // -q: the file parsed and validated
  const texture_file::ContainerFormat container = texture_file::detect_container(*bytes);
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
        {"container", texture_file::container_name(container)},
        {"format", texture_file::texture_format_name(*tex)},
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
  std::printf("  container     : %s\n", texture_file::container_name(container));
  std::printf("  format        : %s\n", texture_file::texture_format_name(*tex).c_str());
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
  sub->add_flag("-q,--quiet", args->quiet,
                "Print nothing: only validate the file (exit status 0 = a valid texture, 1 = "
                "not)");
  return {sub, [args] { return run_info(*args); }};
}

}  // namespace tessera::cli
