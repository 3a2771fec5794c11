// Cube maps and arrays against PVRTexToolCLI (label `oracle`), both ways: PVRTexTool's own
// cube map and array files (PVR v3 and KTX 1.1) are read by tessera and every face and layer
// decodes to PVRTexTool's own decode of it; tessera's cube maps and arrays are read by
// PVRTexTool and every face and layer it decodes equals tessera's decode.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "tessera/io.h"
#include "tessera/procedural.h"
#include "tessera/texture_file.h"
#include "test_support.h"

namespace tessera::texture_file {
namespace {

namespace fs = std::filesystem;

bool run_tool(const fs::path& tool, const std::string& args) {
  std::string cmd = "'";  // appended, not concatenated: GCC 12 warns (-Wrestrict) on "'" + ...
  cmd.append(tool.string()).append("' ").append(args).append(" >/dev/null 2>&1");
  return std::system(cmd.c_str()) == 0;
}

/// Texels that differ (alpha only where the texture has alpha: PVRTexTool's -d writes what it
/// decodes either way).
int mismatches(const ImageRGBA8& ours, const ImageRGBA8& theirs, bool alpha) {
  if (ours.width != theirs.width || ours.height != theirs.height) return -1;
  int n = 0;
  for (std::size_t i = 0; i < ours.pixels.size(); ++i) {
    if (i % 4 == 3 && !alpha) continue;
    n += ours.pixels[i] != theirs.pixels[i];
  }
  return n;
}

/// PVRTexTool's -d name for image `i` of a cube map (".Face_i") or array (".Array_i").
std::string oracle_image(const std::string& stem, bool cube, int i) {
  return stem + (cube ? ".Face_" : ".Array_") + std::to_string(i) + ".png";
}

std::vector<std::string> write_inputs(const fs::path& dir, int n, int size) {
  std::vector<std::string> paths;
  const Procedural kinds[] = {Procedural::noise,    Procedural::foliage, Procedural::bricks,
                              Procedural::gradient, Procedural::text,    Procedural::noise};
  for (int i = 0; i < n; ++i) {
    paths.push_back((dir / ("in" + std::to_string(i) + ".png")).string());
    EXPECT_TRUE(
        io::write_png(paths.back(), make_procedural(kinds[i % 6], size, size, std::uint32_t(i)))
            .ok());
  }
  return paths;
}

struct Shape {
  bool cube;
  int count;
};

TEST(ShapeOracle, ReadsPvrTexToolCubeMapsAndArrays) {
  const auto tool = test::pvrtextool();
  if (!tool) TESSERA_SKIP_OR_FAIL("pvrtextool", "PVRTexToolCLI not available");
  const fs::path dir = test::temp_dir("shape-oracle-in");
  const std::vector<std::string> inputs = write_inputs(dir, 6, 32);
  for (const Shape shape : {Shape{true, 6}, Shape{false, 4}}) {
    std::string list;
    for (int i = 0; i < shape.count; ++i) list += (i ? "," : "") + inputs[std::size_t(i)];
    for (const char* format : {"PVRTC1_4", "PVRTC1_2"}) {
      const std::string stem =
          (dir / (std::string(shape.cube ? "cube" : "array") + format)).string();
      const std::string common = std::string(" -f ") + format + ",UBN,lRGB -q pvrtcfast -m -shh " +
                                 (shape.cube ? "-cube" : "-array");
      ASSERT_TRUE(
          run_tool(*tool, "-i " + list + " -o " + stem + ".pvr -d " + stem + ".png" + common));
      ASSERT_TRUE(run_tool(*tool, "-i " + list + " -o " + stem + ".ktx" + common));
      Result<CompressedTexture> pvr = read_texture_file(stem + ".pvr");
      ASSERT_TRUE(pvr.ok()) << pvr.status().message;
      Result<CompressedTexture> ktx = read_texture_file(stem + ".ktx");
      ASSERT_TRUE(ktx.ok()) << ktx.status().message;
      EXPECT_EQ(pvr->faces, shape.cube ? 6 : 1);
      EXPECT_EQ(pvr->layers, shape.cube ? 1 : shape.count);
      EXPECT_EQ(ktx->faces, pvr->faces);
      EXPECT_EQ(ktx->layers, pvr->layers);
      EXPECT_EQ(ktx->array, !shape.cube);
      EXPECT_EQ(pvr->level_count(), 6);
      EXPECT_EQ(ktx->levels, pvr->levels);  // the same blocks in both containers
      // Written again by tessera, PVRTexTool's PVR file comes back byte for byte.
      Result<std::vector<std::uint8_t>> original = io::read_file(stem + ".pvr");
      Result<std::vector<std::uint8_t>> again = serialise_pvr3(*pvr);
      ASSERT_TRUE(again.ok());
      EXPECT_EQ(*again, *original);
      for (int i = 0; i < shape.count; ++i) {
        Result<ImageRGBA8> theirs = io::read_image(oracle_image(stem, shape.cube, i));
        ASSERT_TRUE(theirs.ok()) << theirs.status().message;
        Result<ImageRGBA8> ours =
            decode_texture_image(*pvr, 0, shape.cube ? 0 : i, shape.cube ? i : 0, {1});
        ASSERT_TRUE(ours.ok());
        EXPECT_EQ(mismatches(*ours, *theirs, pvr->has_alpha), 0) << stem << " image " << i;
      }
    }
  }
}

TEST(ShapeOracle, PvrTexToolReadsOurCubeMapsAndArrays) {
  const auto tool = test::pvrtextool();
  if (!tool) TESSERA_SKIP_OR_FAIL("pvrtextool", "PVRTexToolCLI not available");
  const fs::path dir = test::temp_dir("shape-oracle-out");
  for (const Shape shape : {Shape{true, 6}, Shape{false, 3}}) {
    for (pvrtc::Format f : {pvrtc::Format::pvrtc1_4bpp, pvrtc::Format::pvrtc1_2bpp}) {
      std::vector<ImageRGBA8> images;
      std::vector<std::string> names;
      for (int i = 0; i < shape.count; ++i) {
        images.push_back(make_procedural(i % 2 ? Procedural::foliage : Procedural::bricks, 32, 32,
                                         std::uint32_t(i + 7)));
        names.push_back("image" + std::to_string(i));
      }
      CompressOptions o;
      o.encode.format = f;
      o.encode.quality = pvrtc::Quality::fast;
      o.mipmaps = true;
      Result<CompressedImage> made =
          compress_images(images, TextureShape{shape.cube ? 6 : 1, !shape.cube}, o, names);
      ASSERT_TRUE(made.ok()) << made.status().message;
      const CompressedTexture& t = made->texture;
      for (const char* ext : {".pvr", ".ktx"}) {
        const std::string stem = (dir / (std::string(shape.cube ? "cube" : "array") +
                                         (f == pvrtc::Format::pvrtc1_4bpp ? "4" : "2") + (ext + 1)))
                                     .string();
        ASSERT_TRUE(write_texture_file(stem + ext, t).ok());
        ASSERT_TRUE(run_tool(*tool, "-i " + stem + ext + " -o " + stem +
                                        "-scratch.pvr -f r8g8b8a8 -d " + stem + ".png -shh"))
            << "PVRTexToolCLI rejected " << stem << ext;
        for (int i = 0; i < shape.count; ++i) {
          Result<ImageRGBA8> theirs = io::read_image(oracle_image(stem, shape.cube, i));
          ASSERT_TRUE(theirs.ok()) << theirs.status().message;
          Result<ImageRGBA8> ours =
              decode_texture_image(t, 0, shape.cube ? 0 : i, shape.cube ? i : 0, {1});
          ASSERT_TRUE(ours.ok());
          EXPECT_EQ(mismatches(*ours, *theirs, t.has_alpha), 0) << stem << ext << " image " << i;
        }
      }
    }
  }
}

}  // namespace
}  // namespace tessera::texture_file
