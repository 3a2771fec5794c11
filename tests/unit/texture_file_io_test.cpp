// Tests of tessera/texture_file.h's detection, validation, file reading and writing, the
// up-to-date record, and — when PVRTexToolCLI is available — files exchanged with the oracle in
// both directions.
// (The PVR v3 and KTX 1.1 containers byte by byte: texture_file_test.cpp.)
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "tessera/image_mipmap.h"
#include "tessera/io.h"
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
  EXPECT_EQ(r.status().message,
            "junk.bin: not a PVR v3, KTX 1.1 or KTX 2.0 texture (unrecognised magic)");
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
    EXPECT_NE(v2.status().message.find("legacy PVR v2"), std::string::npos) << v2.status().message;
  }
}

TEST(Oracle, PvrTexToolReadsOurFiles) {
  const auto tool = test::pvrtextool();
  if (!tool) TESSERA_SKIP_OR_FAIL("pvrtextool", "PVRTexToolCLI not available");
  const fs::path dir = test::temp_dir("oracle-out");
  for (pvrtc::Format f : {pvrtc::Format::pvrtc1_4bpp, pvrtc::Format::pvrtc1_2bpp}) {
    for (bool alpha : {false, true}) {
      const ImageRGBA8 img =
          make_procedural(alpha ? Procedural::foliage : Procedural::noise, 64, 32);
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
        ASSERT_TRUE(run_tool(*tool, "-i " + stem + ext + " -o " + stem +
                                        "-scratch.pvr -f r8g8b8a8 -d " + stem + "-dec.png -shh"))
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

// ---------------------------------------------------------------------------------------------
// The up-to-date record (OUTPUT.json) of `tessera compress --skip-up-to-date` and tessera.batch.

void set_mtime_ns(const std::string& path, std::int64_t ns) {
  const struct timespec t[2] = {{time_t(ns / 1000000000), long(ns % 1000000000)},
                                {time_t(ns / 1000000000), long(ns % 1000000000)}};
  ASSERT_EQ(::utimensat(AT_FDCWD, path.c_str(), t, 0), 0) << path;
}

void write_text_file(const std::string& path, const std::string& text) {
  ASSERT_TRUE(
      io::write_file_atomic(path, {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()})
          .ok());
}

TEST(UpToDateRecord, HoldsTheOptionsAndTheInputsSizeAndTime) {
  const fs::path dir = test::temp_dir("up_to_date_record");
  const std::string in = (dir / "in.png").string(), in2 = (dir / "in2.png").string();
  write_text_file(in, "abc");
  write_text_file(in2, "defg");
  set_mtime_ns(in, 1700000000123456789);
  set_mtime_ns(in2, 1700000000000000001);
  RecordedOptions o;
  o.mip_levels = 3;
  o.zstd = 5;
  o.container = "ktx2";
  Result<std::string> r = up_to_date_record(o, std::vector<std::string>{in});
  ASSERT_TRUE(r.ok()) << r.status().message;
  // Keys sorted, one-space indent; the later options only when set; the version last.
  const std::string expected_head =
      "{\n \"container\": \"ktx2\",\n \"input_mtime_ns\": 1700000000123456789,\n"
      " \"input_size\": 3,\n \"options\": {\n  \"exact_search_rounds\": 0,\n"
      "  \"format\": \"pvrtc1-4\",\n  \"iterations\": -1,\n  \"mip_levels\": 3,\n"
      "  \"mipmaps\": false,\n  \"quality\": \"normal\",\n  \"resize_pot\": false,\n"
      "  \"srgb\": false,\n  \"zstd\": 5\n },\n \"tessera\": \"";
  EXPECT_EQ(r->substr(0, expected_head.size()), expected_head);
  EXPECT_TRUE(r->ends_with("\"\n}\n")) << *r;
  // Several inputs (a cube map or array): each one's path, size and time, in order.
  o.cube = true;
  Result<std::string> several = up_to_date_record(o, std::vector<std::string>{in, in2});
  ASSERT_TRUE(several.ok());
  EXPECT_NE(several->find("\"inputs\": [\n  {\n   \"mtime_ns\": 1700000000123456789,\n   "
                          "\"path\": \"" +
                          in + "\",\n   \"size\": 3\n  },"),
            std::string::npos)
      << *several;
  EXPECT_NE(several->find("\"cube\": true"), std::string::npos);
  // Standard input and a missing file cannot be recorded.
  Result<std::string> stdin_record = up_to_date_record(o, std::vector<std::string>{"-"});
  EXPECT_EQ(stdin_record.status().code, ErrorCode::invalid_argument);
  const std::string gone = (dir / "gone.png").string();
  Result<std::string> missing = up_to_date_record(o, std::vector<std::string>{gone});
  EXPECT_EQ(missing.status().code, ErrorCode::io_error);
  EXPECT_NE(missing.status().message.find(gone), std::string::npos);
}

TEST(UpToDateRecord, AnOutputIsUpToDateUntilItsInputOrOptionsChange) {
  const fs::path dir = test::temp_dir("up_to_date");
  const std::string in = (dir / "in.png").string(), out = (dir / "out.pvr").string();
  const std::vector<std::string> inputs{in};
  write_text_file(in, "abc");
  set_mtime_ns(in, 1700000000000000000);
  RecordedOptions o;
  EXPECT_FALSE(is_up_to_date(o, inputs, out));  // no output
  write_text_file(out, "texture");
  set_mtime_ns(out, 1700000001000000000);
  EXPECT_FALSE(is_up_to_date(o, inputs, out));  // no record
  Result<std::string> r = up_to_date_record(o, inputs);
  ASSERT_TRUE(r.ok());
  ASSERT_TRUE(write_up_to_date_record(out, *r).ok());
  EXPECT_TRUE(fs::exists(out + kRecordSuffix));
  EXPECT_TRUE(is_up_to_date(o, inputs, out));
  RecordedOptions fast = o;
  fast.quality = "fast";
  EXPECT_FALSE(is_up_to_date(fast, inputs, out));  // other options
  EXPECT_FALSE(is_up_to_date(o, std::vector<std::string>{"-"}, out));
  set_mtime_ns(in, 1700000002000000000);  // the input is newer than the output
  EXPECT_FALSE(is_up_to_date(o, inputs, out));
  set_mtime_ns(out, 1700000003000000000);  // newer again, but the record names the old time
  EXPECT_FALSE(is_up_to_date(o, inputs, out));
  write_text_file(out + kRecordSuffix, "{not json");
  EXPECT_FALSE(is_up_to_date(o, inputs, out));
}

}  // namespace
}  // namespace tessera::texture_file
