// Tests of tessera/texture_file.h's detection, validation, file reading and writing, and —
// when PVRTexToolCLI is available — files exchanged with the oracle in both directions.
// (The PVR v3 and KTX 1.1 containers byte by byte: texture_file_test.cpp.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "tessera/io.h"
#include "tessera/mipmap.h"
#include "tessera/procedural.h"
#include "tessera/texture_file.h"
#include "test_support.h"
#include "texture_file_test_util.h"

namespace tessera::texture_file {
namespace {

namespace fs = std::filesystem;
using test::Bytes;
using test::expect_same;
using test::fake_texture;
using test::ktx_bytes;
using test::pvr_bytes;

// ---------------------------------------------------------------------------------------------
// Detection, validation and files
// ---------------------------------------------------------------------------------------------

TEST(TextureFile, DetectsContainers) {
  const CompressedTexture t = fake_texture(pvrtc::Format::pvrtc1_4bpp, 8, 8, 1, false, false);
  EXPECT_EQ(detect_container(pvr_bytes(t)), ContainerFormat::pvr3);
  EXPECT_EQ(detect_container(ktx_bytes(t)), ContainerFormat::ktx1);
  EXPECT_EQ(detect_container(Bytes{1, 2, 3}), ContainerFormat::unknown);
  EXPECT_EQ(container_from_extension("a/b.PVR"), ContainerFormat::pvr3);
  EXPECT_EQ(container_from_extension("x.ktx"), ContainerFormat::ktx1);
  EXPECT_EQ(container_from_extension("x.KTX2"), ContainerFormat::ktx2);
  EXPECT_EQ(container_from_extension("x.dds"), ContainerFormat::unknown);
  EXPECT_EQ(container_from_extension("dir.pvr/x"), ContainerFormat::unknown);
  Result<CompressedTexture> r = parse_texture(Bytes{1, 2, 3, 4, 5}, "junk.bin");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().message, "junk.bin: not a PVR v3, KTX 1.1 or KTX 2.0 texture (unrecognised magic)");
}

TEST(TextureFile, ValidateRejectsInconsistentTextures) {
  CompressedTexture t = fake_texture(pvrtc::Format::pvrtc1_4bpp, 16, 16, 2, false, false);
  EXPECT_TRUE(validate_texture(t, "t").ok());
  t.levels[1].pop_back();
  EXPECT_FALSE(serialise_pvr3(t).ok());
  EXPECT_FALSE(serialise_ktx1(t).ok());
  t = fake_texture(pvrtc::Format::pvrtc1_4bpp, 16, 16, 5, false, false);
  t.levels.push_back(t.levels.back());
  EXPECT_FALSE(validate_texture(t, "t").ok());
  t.levels.clear();
  EXPECT_FALSE(validate_texture(t, "t").ok());
}

TEST(TextureFile, WritesAtomicallyAndReadsBack) {
  const fs::path dir = test::temp_dir("files");
  const CompressedTexture t = fake_texture(pvrtc::Format::pvrtc1_2bpp, 32, 32, 6, true, true);
  for (const char* name : {"t.pvr", "t.ktx"}) {
    const std::string path = (dir / name).string();
    ASSERT_TRUE(write_texture_file(path, t).ok());
    Result<CompressedTexture> back = read_texture_file(path);
    ASSERT_TRUE(back.ok()) << back.status().message;
    expect_same(t, *back);
  }
  // A folder in the way, an unknown extension, a missing file: errors, nothing written.
  fs::create_directories(dir / "sub.pvr");
  EXPECT_FALSE(write_texture_file((dir / "sub.pvr").string(), t).ok());
  Status s = write_texture_file((dir / "t.dds").string(), t);
  EXPECT_EQ(s.code, ErrorCode::invalid_argument);
  EXPECT_FALSE(fs::exists(dir / "t.dds"));
  Result<CompressedTexture> missing = read_texture_file((dir / "none.pvr").string());
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.status().code, ErrorCode::io_error);
}

TEST(TextureFile, DecodeLevelChecksRangeAndForcesOpaqueRgb) {
  CompressedTexture t = fake_texture(pvrtc::Format::pvrtc1_4bpp, 16, 8, 2, false, false);
  Result<ImageRGBA8> img = decode_texture_level(t, 1, {1});
  ASSERT_TRUE(img.ok()) << img.status().message;
  EXPECT_EQ(img->width, 8);
  EXPECT_EQ(img->height, 4);
  EXPECT_FALSE(img->has_alpha);
  for (std::size_t i = 3; i < img->pixels.size(); i += 4) ASSERT_EQ(img->pixels[i], 255);
  Result<ImageRGBA8> bad = decode_texture_level(t, 2, {1});
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message.find("out of range"), std::string::npos);
  EXPECT_FALSE(decode_texture_level(t, -1, {1}).ok());
}

// ---------------------------------------------------------------------------------------------
// Against the oracle (PVRTexToolCLI)
// ---------------------------------------------------------------------------------------------

/// Runs PVRTexToolCLI with `args`; true on exit status 0.
bool run_tool(const fs::path& tool, const std::string& args) {
  std::string cmd = "'";
  cmd.append(tool.string()).append("' ").append(args).append(" >/dev/null 2>&1");
  return std::system(cmd.c_str()) == 0;
}

TEST(Oracle, ReadsPvrTexToolFilesAndMatchesItsDecode) {
  const auto tool = test::pvrtextool();
  if (!tool) TESSERA_SKIP_OR_FAIL("pvrtextool", "PVRTexToolCLI not available");
  const fs::path dir = test::temp_dir("oracle-in");
  struct Case {
    Procedural kind;
    int w, h;
    const char* format;
    bool mips;
  };
  const Case cases[] = {
      {Procedural::noise, 64, 32, "PVRTC1_4,UBN,lRGB", true},
      {Procedural::foliage, 32, 32, "PVRTC1_4,UBN,sRGB", true},
      {Procedural::bricks, 64, 64, "PVRTC1_2,UBN,lRGB", false},
      {Procedural::gradient, 16, 64, "PVRTC1_2_RGB,UBN,sRGB", true},
      {Procedural::text, 32, 32, "PVRTC1_4_RGB,UBN,lRGB", false},
  };
  int n = 0;
  for (const Case& c : cases) {
    const std::string stem = (dir / ("case" + std::to_string(n++))).string();
    ASSERT_TRUE(io::write_png(stem + ".png", make_procedural(c.kind, c.w, c.h)).ok());
    ASSERT_TRUE(run_tool(*tool, "-i " + stem + ".png -o " + stem + ".pvr -f " + c.format +
                                    " -q pvrtcfastest" + (c.mips ? " -m" : "") + " -d " + stem +
                                    "-dec.png -shh"));
    Result<CompressedTexture> tex = read_texture_file(stem + ".pvr");
    ASSERT_TRUE(tex.ok()) << tex.status().message;
    EXPECT_EQ(tex->width, c.w);
    EXPECT_EQ(tex->height, c.h);
    EXPECT_EQ(tex->level_count(), c.mips ? mip_level_count(c.w, c.h) : 1);
    EXPECT_EQ(tex->srgb, std::strstr(c.format, "sRGB") != nullptr);
    EXPECT_EQ(tex->has_alpha, std::strstr(c.format, "_RGB") == nullptr);
    EXPECT_EQ(tex->format, std::strstr(c.format, "PVRTC1_4") ? pvrtc::Format::pvrtc1_4bpp
                                                             : pvrtc::Format::pvrtc1_2bpp);
    // Level 0 decoded by tessera equals PVRTexTool's own decode (RGB exactly; PVRTexTool's
    // -d writes the alpha it decodes even for RGB formats, so compare alpha only for RGBA).
    Result<ImageRGBA8> ours = decode_texture_level(*tex, 0, {1});
    ASSERT_TRUE(ours.ok()) << ours.status().message;
    Result<ImageRGBA8> theirs = io::read_image(stem + "-dec.png");
    ASSERT_TRUE(theirs.ok()) << theirs.status().message;
    ASSERT_EQ(theirs->width, c.w);
    // PVRTexTool's -d converts an sRGB texture to linear 8-bit on output, so for those the
    // reference is srgb_to_linear(our decode), equal within one rounding step.
    int mismatches = 0;
    for (std::size_t i = 0; i < ours->pixels.size(); ++i) {
      const bool is_alpha = i % 4 == 3;
      if (is_alpha && !tex->has_alpha) continue;
      if (tex->srgb && !is_alpha) {
        const int expect = int(std::lround(srgb8_to_linear(ours->pixels[i]) * 255.0f));
        mismatches += std::abs(expect - int(theirs->pixels[i])) > 1;
      } else {
        mismatches += ours->pixels[i] != theirs->pixels[i];
      }
    }
    EXPECT_EQ(mismatches, 0) << stem;
    // And re-serialised, byte for byte the same file.
    Result<std::vector<std::uint8_t>> original = io::read_file(stem + ".pvr");
    Bytes again = pvr_bytes(*tex);
    EXPECT_EQ(again, *original) << stem;
    // Its KTX output of the same encode holds the same blocks (PVRTexTool labels sRGB data
    // with the linear 0x8C0x formats, so the colour space is not compared).
    ASSERT_TRUE(run_tool(*tool, "-i " + stem + ".png -o " + stem + ".ktx -f " + c.format +
                                    " -q pvrtcfastest" + (c.mips ? " -m" : "") + " -shh"));
    Result<CompressedTexture> ktx = read_texture_file(stem + ".ktx");
    ASSERT_TRUE(ktx.ok()) << ktx.status().message;
    EXPECT_EQ(ktx->width, tex->width);
    EXPECT_EQ(ktx->height, tex->height);
    EXPECT_EQ(ktx->format, tex->format);
    EXPECT_EQ(ktx->levels, tex->levels) << stem;
    // Its legacy (v2) output is recognised and rejected with a clear message.
    ASSERT_TRUE(run_tool(*tool, "-i " + stem + ".png -o " + stem + "-v2.pvr -f " + c.format +
                                    " -q pvrtcfastest -legacypvr -shh"));
    Result<CompressedTexture> v2 = read_texture_file(stem + "-v2.pvr");
    ASSERT_FALSE(v2.ok());
    EXPECT_NE(v2.status().message.find("legacy PVR v2"), std::string::npos)
        << v2.status().message;
  }
}

TEST(Oracle, PvrTexToolReadsOurFiles) {
  const auto tool = test::pvrtextool();
  if (!tool) TESSERA_SKIP_OR_FAIL("pvrtextool", "PVRTexToolCLI not available");
  const fs::path dir = test::temp_dir("oracle-out");
  for (pvrtc::Format f : {pvrtc::Format::pvrtc1_4bpp, pvrtc::Format::pvrtc1_2bpp}) {
    for (bool alpha : {false, true}) {
      const ImageRGBA8 img = make_procedural(alpha ? Procedural::foliage : Procedural::noise, 64, 32);
      pvrtc::EncodeOptions eo;
      eo.format = f;
      eo.quality = pvrtc::Quality::fast;
      eo.force_alpha = alpha;
      Result<std::vector<ImageRGBA8>> chain = image::generate_mipmaps(img);
      CompressedTexture t;
      t.format = f;
      t.width = 64;
      t.height = 32;
      t.has_alpha = alpha;
      for (const ImageRGBA8& l : *chain) {
        Result<Bytes> enc = pvrtc::encode(l, eo);
        ASSERT_TRUE(enc.ok()) << enc.status().message;
        t.levels.push_back(*enc);
      }
      for (const char* ext : {".pvr", ".ktx"}) {
        const std::string stem =
            (dir / (std::string(f == pvrtc::Format::pvrtc1_4bpp ? "p4" : "p2") +
                    (alpha ? "a" : "") + (ext[1] == 'p' ? "-pvr" : "-ktx")))
                .string();
        ASSERT_TRUE(write_texture_file(stem + ext, t).ok());
        ASSERT_TRUE(run_tool(*tool, "-i " + stem + ext + " -o " + stem + "-scratch.pvr -f r8g8b8a8 -d " +
                                        stem + "-dec.png -shh"))
            << "PVRTexToolCLI rejected " << stem << ext;
        Result<ImageRGBA8> theirs = io::read_image(stem + "-dec.png");
        ASSERT_TRUE(theirs.ok()) << theirs.status().message;
        Result<ImageRGBA8> ours = decode_texture_level(t, 0, {1});
        ASSERT_TRUE(ours.ok());
        ASSERT_EQ(theirs->width, 64);
        ASSERT_EQ(theirs->height, 32);
        int mismatches = 0;
        for (std::size_t i = 0; i < ours->pixels.size(); ++i) {
          if (i % 4 == 3 && !alpha) continue;
          mismatches += ours->pixels[i] != theirs->pixels[i];
        }
        EXPECT_EQ(mismatches, 0) << stem << ext;
      }
    }
  }
}

}  // namespace
}  // namespace tessera::texture_file
