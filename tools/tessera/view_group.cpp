// tessera view: --cube / --array inputs (the faces or layers of one texture, encoded as
// `tessera compress --cube` / `--array` encodes them) and inputs that are not a power of two.
#include <algorithm>
#include <bit>
#include <filesystem>

#include "tessera/image_mipmap.h"
#include "tessera/io.h"
#include "view.h"
#include "view_png.h"

namespace tessera::cli {

namespace {

namespace fs = std::filesystem;

/// The common start of the files' stems without trailing separators ("sky_px", "sky_nx": "sky");
/// `fallback` when they have none.
std::string group_stem(const std::vector<std::string>& paths, const std::string& fallback) {
  if (paths.empty()) return fallback;
  std::string common = fs::path(paths.front()).stem().string();
  for (const std::string& p : paths) {
    const std::string s = fs::path(p).stem().string();
    std::size_t n = 0;
    while (n < common.size() && n < s.size() && common[n] == s[n]) ++n;
    common.resize(n);
  }
  if (paths.size() > 1) {
    while (!common.empty() && std::string("_-. +").find(common.back()) != std::string::npos) {
      common.pop_back();
    }
  }
  return common.empty() ? fallback : common;
}

bool is_cube(const ViewInput& in) { return !in.images.empty() && in.shape.faces == 6; }

}  // namespace

ViewInput load_view_group(const std::vector<std::string>& paths, texture_file::TextureShape shape) {
  ViewInput in;
  in.sources = paths;
  in.shape = shape;
  const bool cube = shape.faces == 6;
  const std::string stem = group_stem(paths, cube ? "cube" : "array");
  in.name = cube ? stem + " (cube map)"
                 : stem + " (array of " + std::to_string(paths.size()) + " layers)";
  in.path = paths.empty() ? stem : paths.front();
  if (cube && paths.size() != 6) {
    in.error = in.name + ": --cube takes 6 faces (+X, -X, +Y, -Y, +Z, -Z), got " +
               std::to_string(paths.size()) + " (other inputs go before --cube)";
    return in;
  }
  if (paths.empty()) {
    in.error = in.name + ": --array takes at least one layer";
    return in;
  }
  for (const std::string& p : paths) {
    Result<ImageRGBA8> im = io::read_image(p);
    if (!im) {
      in.error = im.status().message;
      return in;
    }
    in.images.push_back(std::move(im).value());
  }
  const ImageRGBA8& first = in.images.front();
  for (std::size_t i = 0; i < in.images.size(); ++i) {
    const ImageRGBA8& im = in.images[i];
    if (im.width != first.width || im.height != first.height) {
      in.error = paths[i] + ": " + size_text(im.width, im.height) + ", but " + paths.front() +
                 " is " + size_text(first.width, first.height) +
                 " (every face and layer needs one size)";
      return in;
    }
  }
  if (cube && first.width != first.height) {
    in.error = paths.front() + ": " + size_text(first.width, first.height) +
               " is not square (a cube map's faces are)";
    return in;
  }
  in.image = first;
  return in;
}

std::vector<std::string> view_sources(const ViewInput& input) {
  return input.sources.empty() ? std::vector<std::string>{input.path} : input.sources;
}

std::string view_output_name(const ViewInput& input) {
  if (!input.sources.empty()) {
    return group_stem(input.sources, input.shape.faces == 6 ? "cube" : "array") + ".pvr";
  }
  return fs::path(input.name).stem().string() + ".pvr";
}

bool needs_resize_pot(const ViewInput& input) {
  if (input.is_texture || !input.error.empty() || input.image.width <= 0) return false;
  return !std::has_single_bit(unsigned(input.image.width)) ||
         !std::has_single_bit(unsigned(input.image.height));
}

std::vector<ImageRGBA8> pair_references(const ViewInput& image) {
  return image.images.empty() ? std::vector<ImageRGBA8>{image.image} : image.images;
}

void add_group_json(nlohmann::json& j, const ViewInput& input) {
  if (!input.images.empty()) {
    j["shape"] = is_cube(input) ? "cube map" : "array";
    j["faces"] = input.shape.faces;
    j["layers"] = int(input.images.size()) / std::max(1, input.shape.faces);
    j["sources"] = nlohmann::json::array();
    for (const std::string& p : input.sources) j["sources"].push_back(p);
    bool alpha = false;
    for (const ImageRGBA8& im : input.images) {
      alpha = alpha || (im.has_alpha && !all_opaque(ImageView8::of(im)));
    }
    j["has_alpha"] = alpha;
  }
  if (needs_resize_pot(input)) {
    const int w = input.image.width, h = input.image.height;
    j["needs_resize_pot"] = true;
    j["note"] = size_text(w, h) + " is not a power of two (PVRTC1 needs power-of-two sides): " +
                "--resize-pot resamples it to " +
                size_text(image::nearest_power_of_two(w), image::nearest_power_of_two(h));
  }
}

void add_originals(nlohmann::json& j, const ViewInput& input, BlobStore& blobs) {
  const std::vector<ImageRGBA8> images = pair_references(input);
  const int faces = input.images.empty() ? 1 : std::max(1, input.shape.faces);
  j["originals"] = nlohmann::json::array();
  for (std::size_t i = 0; i < images.size(); ++i) {
    j["originals"].push_back(
        {{"face", int(i) % faces},
         {"layer", int(i) / faces},
         {"level", 0},
         {"width", images[i].width},
         {"height", images[i].height},
         {"original", blobs.put("image/png", encode_view_png(images[i], blobs.png_level))}});
  }
}

}  // namespace tessera::cli
