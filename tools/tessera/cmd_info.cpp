// tessera info: describes a PVRTC1 texture file (PVR v3, KTX 1.1 or KTX 2.0): container, format,
// size, shape, colour space and levels, as text or JSON; with -q it only validates the file.
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli.h"
#include "tessera/io.h"
#include "tessera/pvrtc.h"
#include "tessera/texture_file.h"

namespace tessera::cli {

namespace {

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
                        {"bytes", tex->levels[std::size_t(i)].size()},
                        {"image_bytes", tex->image_size(i)}});
    }
    nlohmann::json j = {
        {"file", name},
        {"container", texture_file::container_name(container)},
        {"format", texture_file::texture_format_name(*tex)},
        {"bpp", tex->format == pvrtc::Format::pvrtc1_4bpp ? 4 : 2},
        {"has_alpha", tex->has_alpha},
        {"width", tex->width},
        {"height", tex->height},
        {"shape", texture_file::texture_shape_name(*tex)},
        {"faces", tex->faces},
        {"layers", tex->layers},
        {"array", tex->array},
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
  std::printf("  size          : %dx%d\n", tex->width, tex->height);
  std::printf("  shape         : %s\n", texture_file::texture_shape_name(*tex).c_str());
  std::printf("  faces         : %d\n", tex->faces);
  std::printf("  layers        : %d\n", tex->layers);
  std::printf("  colour space  : %s\n", tex->srgb ? "sRGB" : "linear");
  std::printf("  premultiplied : %s\n", tex->premultiplied ? "yes" : "no");
  std::printf("  file size     : %zu bytes\n", bytes->size());
  std::printf("  levels        : %d\n", tex->level_count());
  for (int i = 0; i < tex->level_count(); ++i) {
    if (tex->image_count() == 1) {
      std::printf("    %2d  %5d x %-5d %9zu bytes\n", i, tex->level_width(i), tex->level_height(i),
                  tex->levels[std::size_t(i)].size());
    } else {
      std::printf("    %2d  %5d x %-5d %9zu bytes (%d images of %zu)\n", i, tex->level_width(i),
                  tex->level_height(i), tex->levels[std::size_t(i)].size(), tex->image_count(),
                  tex->image_size(i));
    }
  }
  return kExitOk;
}

}  // namespace

Command add_info_command(CLI::App& app, const GlobalOptions& /*global*/) {
  auto args = std::make_shared<InfoArgs>();
  CLI::App* sub = app.add_subcommand(
      "info",
      "Describe a .pvr/.ktx/.ktx2 texture: container, format, size, shape (cube map, array), "
      "colour space, premultiplied alpha, levels");
  sub->add_option("FILE", args->input, "Texture file (PVR v3, KTX 1.1 or KTX 2.0; '-' = stdin)")
      ->required();
  sub->add_flag("--json", args->json, "Print one JSON object");
  sub->add_flag("-q,--quiet", args->quiet,
                "Print nothing: only validate the file (exit status 0 = a valid texture, 1 = "
                "not)");
  return {sub, [args] { return run_info(*args); }};
}

}  // namespace tessera::cli
