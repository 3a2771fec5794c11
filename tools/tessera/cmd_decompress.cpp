// tessera decompress: decodes PVRTC1 textures in PVR v3, KTX 1.1 and KTX 2.0 files (2D textures,
// cube maps and arrays with their mip chains) to images, one or every image of the texture.
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli.h"
#include "tessera/io.h"
#include "tessera/pvrtc.h"
#include "tessera/texture_file.h"

namespace tessera::cli {

namespace {

struct DecompressArgs {
  std::string input, output;
  int level = 0;  ///< Meaningful when given (`level_given`): else level 0 for a single output,
                  ///< every level for a folder.
  int layer = 0;
  int face = 0;
  bool level_given = false, layer_given = false, face_given = false;
  bool quiet = false;
  bool json = false;
};

/// Short names of the cube faces, in KTX / PVRTexTool order, for output file names.
constexpr const char* kFaceNames[6] = {"px", "nx", "py", "ny", "pz", "nz"};

/// One image of the texture to write.
struct Selected {
  int level, layer, face;
  std::string path;
};

bool is_folder_output(const std::string& output) {
  std::error_code ec;
  return output != "-" && (output.ends_with('/') || std::filesystem::is_directory(output, ec));
}

/// "sky_layer2_face0-px_level1.png": the layer only for arrays, the face only for cube maps.
std::string image_file_name(const std::string& stem, const texture_file::CompressedTexture& tex,
                            int level, int layer, int face) {
  std::string n = stem;
  if (tex.array) n += "_layer" + std::to_string(layer);
  if (tex.is_cube()) n += "_face" + std::to_string(face) + "-" + kFaceNames[face];
  return n + "_level" + std::to_string(level) + ".png";
}

int run_decompress(const DecompressArgs& args, const GlobalOptions& global) {
  const bool to_folder = is_folder_output(args.output);
  if (!to_folder) {
    if (Result<io::ImageFormat> f = io::image_format_for_output(args.output); !f) {
      return usage_error("-o: " + f.status().message);
    }
    if (int rc = refuse_binary_to_terminal(args.output, "an image")) return rc;
  }
  const std::string input_name = io::io_name(args.input);
  Result<texture_file::CompressedTexture> tex = texture_file::read_texture_file(args.input);
  if (!tex) return fail(tex.status());
  // Range checks name the option and the file's own range.
  auto out_of_range = [&](const char* option, int value, int count, const char* what) {
    return fail(Status::error(ErrorCode::invalid_argument,
                              input_name + ": " + option + " " + std::to_string(value) +
                                  " is out of range (the file has " + std::to_string(count) + " " +
                                  what + "(s), 0 to " + std::to_string(count - 1) + ")"));
  };
  if (args.level_given && (args.level < 0 || args.level >= tex->level_count())) {
    return out_of_range("--level", args.level, tex->level_count(), "level");
  }
  if (args.layer_given && (args.layer < 0 || args.layer >= tex->layers)) {
    if (!tex->array) {
      return fail(Status::error(ErrorCode::invalid_argument,
                                input_name + ": --layer " + std::to_string(args.layer) +
                                    " is out of range (the texture is not an array: layer 0)"));
    }
    return out_of_range("--layer", args.layer, tex->layers, "layer");
  }
  if (args.face_given && (args.face < 0 || args.face >= tex->faces)) {
    if (!tex->is_cube()) {
      return fail(Status::error(ErrorCode::invalid_argument,
                                input_name + ": --face " + std::to_string(args.face) +
                                    " is out of range (the texture is not a cube map: face 0)"));
    }
    return out_of_range("--face", args.face, tex->faces, "face");
  }
  if (!to_folder) {
    std::string missing;
    if (tex->array && !args.layer_given) missing += " --layer N";
    if (tex->is_cube() && !args.face_given) missing += " --face N";
    if (!missing.empty()) {
      return usage_error(input_name + " is a " + texture_file::texture_shape_name(*tex) +
                         ": choose one image with" + missing +
                         " (and --level N), or write every image into a folder with -o DIR/");
    }
  }

  std::vector<Selected> selected;
  const std::string stem =
      args.input == "-" ? std::string("stdin") : std::filesystem::path(args.input).stem().string();
  for (int level = 0; level < tex->level_count(); ++level) {
    if (args.level_given ? level != args.level : (!to_folder && level != 0)) continue;
    for (int layer = 0; layer < tex->layers; ++layer) {
      if (args.layer_given && layer != args.layer) continue;
      for (int face = 0; face < tex->faces; ++face) {
        if (args.face_given && face != args.face) continue;
        selected.push_back({level, layer, face,
                            to_folder ? (std::filesystem::path(args.output) /
                                         image_file_name(stem, *tex, level, layer, face))
                                            .string()
                                      : args.output});
      }
    }
  }
  if (to_folder) {
    std::error_code ec;
    std::filesystem::create_directories(args.output, ec);
    if (ec || !std::filesystem::is_directory(args.output)) {
      return fail(Status::error(ErrorCode::io_error, args.output +
                                                         ": cannot create the output folder: " +
                                                         (ec ? ec.message() : "not a directory")));
    }
  }
  nlohmann::json outputs = nlohmann::json::array();
  std::FILE* out = text_stream(args.output == "-");
  for (const Selected& sel : selected) {
    Result<ImageRGBA8> img =
        texture_file::decode_texture_image(*tex, sel.level, sel.layer, sel.face, {global.threads});
    if (!img) {
      Status s = img.status();
      s.message = input_name + ": " + s.message;
      return fail(s);
    }
    if (Status s = io::write_image(sel.path, *img); !s.ok()) return fail(s);
    const std::string shown = io::io_name(sel.path, true);
    nlohmann::json j = {{"output", shown},
                        {"level", sel.level},
                        {"width", img->width},
                        {"height", img->height},
                        {"has_alpha", img->has_alpha}};
    if (tex->array) j["layer"] = sel.layer;
    if (tex->is_cube()) j["face"] = sel.face;
    outputs.push_back(j);
    if (!args.json && !args.quiet) {
      std::string where = "level " + std::to_string(sel.level);
      if (tex->array) where += ", layer " + std::to_string(sel.layer);
      if (tex->is_cube()) {
        where += ", face " + std::to_string(sel.face) + " (" + kFaceNames[sel.face] + ")";
      }
      std::fprintf(out, "wrote %s: %s, %s\n", shown.c_str(), where.c_str(),
                   size_text(img->width, img->height).c_str());
    }
  }
  if (args.json) {
    nlohmann::json j;
    if (to_folder) {
      j = {{"input", input_name}, {"output", args.output}, {"images", outputs}};
    } else {
      j = outputs.front();
      j["input"] = input_name;
    }
    std::fprintf(out, "%s\n", j.dump(2).c_str());
  }
  return kExitOk;
}

}  // namespace

Command add_decompress_command(CLI::App& app, const GlobalOptions& global) {
  auto args = std::make_shared<DecompressArgs>();
  CLI::App* sub = app.add_subcommand(
      "decompress",
      "Decode a PVRTC .pvr/.ktx/.ktx2 texture to images: one image (a level, layer and face) to a "
      "file, or every image into a folder");
  sub->add_option("INPUT", args->input,
                  "Input texture (PVR v3, KTX 1.1 or KTX 2.0, recognised by its bytes; '-' = "
                  "stdin)")
      ->required();
  sub->add_option("-o,--output,--out", args->output,
                  "Output image: .png, .bmp, .tga or .jpg by extension ('-' = PNG on stdout); or "
                  "a folder (DIR/, created) that gets every image as NAME[_layerL][_faceF-px]"
                  "_levelN.png")
      ->required();
  CLI::Option* level =
      sub->add_option("--level", args->level,
                      "Mip level to decode (0 = largest; default 0, or every level into a folder)");
  CLI::Option* layer = sub->add_option(
      "--layer", args->layer, "Array layer to decode (needed for an array unless -o DIR/)");
  CLI::Option* face = sub->add_option(
      "--face", args->face,
      "Cube map face to decode: 0..5 = +X, -X, +Y, -Y, +Z, -Z (needed for a cube map unless -o "
      "DIR/)");
  sub->add_flag("--json", args->json,
                "Print one JSON object (input, output, level, size; for a folder, the list of "
                "images)");
  sub->add_flag("-q,--quiet", args->quiet, "Print nothing on success");
  return {sub, [args, &global, level, layer, face] {
            args->level_given = level->count() > 0;
            args->layer_given = layer->count() > 0;
            args->face_given = face->count() > 0;
            return run_decompress(*args, global);
          }};
}

}  // namespace tessera::cli
