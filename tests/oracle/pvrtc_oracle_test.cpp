// PVRTC conformance against PVRTexToolCLI (label `oracle`): tessera's decoder must equal the
// oracle's decode byte for byte, both on files PVRTexTool encoded and on files tessera encoded.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <string>
#include <vector>

#include "tessera/io.h"
#include "tessera/procedural.h"
#include "tessera/pvrtc.h"
#include "test_support.h"

namespace tessera::pvrtc {
namespace {

namespace fs = std::filesystem;

// Minimal PVR v3 writer/reader (one surface, one level, no metadata) for these tests only.
std::vector<std::uint8_t> make_pvr(Format format, bool alpha, int w, int h,
                                   const std::vector<std::uint8_t>& level, bool srgb = false) {
  std::vector<std::uint8_t> out(52 + level.size());
  std::copy(level.begin(), level.end(), out.begin() + 52);
  auto put32 = [&](std::size_t off, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out[off + std::size_t(i)] = std::uint8_t(v >> (8 * i));
  };
  put32(0, 0x03525650u);
  put32(4, 0);
  const std::uint32_t pf = format == Format::pvrtc1_4bpp ? (alpha ? 3 : 2) : (alpha ? 1 : 0);
  put32(8, pf);
  put32(12, 0);
  put32(16, srgb ? 1 : 0);  // colour space: 0 linear, 1 sRGB
  put32(20, 0);
  put32(24, std::uint32_t(h));
  put32(28, std::uint32_t(w));
  put32(32, 1);
  put32(36, 1);
  put32(40, 1);
  put32(44, 1);
  put32(48, 0);
  return out;
}

std::vector<std::uint8_t> pvr_level(const std::vector<std::uint8_t>& file) {
  if (file.size() < 52) return {};
  std::uint32_t meta = 0;
  for (int i = 0; i < 4; ++i) meta |= std::uint32_t(file[48 + std::size_t(i)]) << (8 * i);
  return {file.begin() + 52 + std::ptrdiff_t(meta), file.end()};
}

// Joins arguments into a shell command, single-quoting each.
std::string shell(std::initializer_list<std::string> args) {
  std::string cmd;
  for (const std::string& a : args) {
    if (!cmd.empty()) cmd += ' ';
    cmd += '\'';
    cmd += a;
    cmd += '\'';
  }
  return cmd;
}

int run(const std::string& cmd) { return std::system((cmd + " >/dev/null 2>&1").c_str()); }

// Decodes `pvr` with the oracle; returns the PNG it wrote.
Result<ImageRGBA8> oracle_decode(const fs::path& tool, const fs::path& pvr, const fs::path& dir) {
  const fs::path scratch = dir / "scratch.pvr", png = dir / "oracle.png";
  const std::string cmd = shell({tool.string(), "-i", pvr.string(), "-o", scratch.string(), "-f",
                                 "r8g8b8a8", "-d", png.string(), "-shh"});
  if (run(cmd) != 0) {
    std::string msg = "oracle failed: ";
    msg += cmd;
    return Status::error(ErrorCode::io_error, msg);
  }
  return io::read_image(png.string());
}

void expect_same(const ImageRGBA8& ours, const ImageRGBA8& oracle, const std::string& what) {
  ASSERT_EQ(ours.width, oracle.width) << what;
  ASSERT_EQ(ours.height, oracle.height) << what;
  std::size_t diffs = 0, first = 0;
  for (std::size_t i = 0; i < ours.pixels.size(); ++i) {
    // The oracle writes an RGB PNG for opaque results: compare alpha only when it has alpha.
    if (i % 4 == 3 && !oracle.has_alpha) continue;
    if (ours.pixels[i] != oracle.pixels[i]) {
      if (diffs++ == 0) first = i;
    }
  }
  EXPECT_EQ(diffs, 0u) << what << ": first difference at texel " << first / 4 << " channel "
                       << first % 4 << " ours " << int(ours.pixels[first]) << " oracle "
                       << int(oracle.pixels[first]);
}

struct Case {
  Procedural kind;
  int w, h;
};

std::vector<Case> decode_cases() {
  std::vector<Case> cases;
  for (Procedural k : all_procedurals()) cases.push_back({k, 256, 256});
  const int sizes[][2] = {{512, 128}, {1024, 256}, {8, 64},    {64, 8}, {16, 32},
                          {8, 8},     {4, 4},      {128, 512}, {32, 16}};
  for (const auto& s : sizes) {
    cases.push_back({Procedural::foliage, s[0], s[1]});
    cases.push_back({Procedural::noise, s[0], s[1]});
  }
  return cases;
}

// Encodes with the oracle, decodes its file with tessera and compares with the oracle's own
// decode.
void check_oracle_encoded(const ImageRGBA8& img, Format format, const std::string& name) {
  auto tool = test::pvrtextool();
  if (!tool) TESSERA_SKIP_OR_FAIL("pvrtextool", "PVRTexToolCLI not available");
  const fs::path dir = test::temp_dir(name);
  ASSERT_TRUE(io::write_png((dir / "in.png").string(), img).ok());
  const bool alpha = img.has_alpha;
  std::string fmt = format == Format::pvrtc1_4bpp ? "PVRTC1_4" : "PVRTC1_2";
  if (!alpha) fmt += "_RGB";
  const fs::path pvr = dir / "enc.pvr", png = dir / "dec.png";
  const std::string cmd =
      shell({tool->string(), "-i", (dir / "in.png").string(), "-o", pvr.string(), "-f",
             fmt + ",UBN,lRGB", "-q", "pvrtcfastest", "-d", png.string()});
  ASSERT_EQ(run(cmd), 0) << cmd;
  auto file = io::read_file(pvr.string());
  ASSERT_TRUE(file.ok());
  const auto level = pvr_level(*file);
  auto ours = decode(level, format, img.width, img.height, {2});
  ASSERT_TRUE(ours.ok()) << ours.status().message;
  auto oracle = io::read_image(png.string());
  ASSERT_TRUE(oracle.ok()) << oracle.status().message;
  expect_same(*ours, *oracle, name);
}

class OracleDecode : public ::testing::TestWithParam<std::tuple<Case, Format>> {};

TEST_P(OracleDecode, DecodesPvrTexToolOutputExactly) {
  const auto& [c, format] = GetParam();
  const ImageRGBA8 img = make_procedural(c.kind, c.w, c.h);
  check_oracle_encoded(img, format,
                       std::string(procedural_name(c.kind)) + std::to_string(c.w) + "x" +
                           std::to_string(c.h) + (format == Format::pvrtc1_4bpp ? "_4" : "_2"));
}

INSTANTIATE_TEST_SUITE_P(All, OracleDecode,
                         ::testing::Combine(::testing::ValuesIn(decode_cases()),
                                            ::testing::Values(Format::pvrtc1_4bpp,
                                                              Format::pvrtc1_2bpp)));

TEST(OracleDecode, RgbInputUsesOpaqueFormat) {
  ImageRGBA8 img = make_procedural(Procedural::bricks, 128, 64);
  img.has_alpha = false;
  check_oracle_encoded(img, Format::pvrtc1_4bpp, "rgb4");
  check_oracle_encoded(img, Format::pvrtc1_2bpp, "rgb2");
}

TEST(OracleDecode, SharedImages) {
  TESSERA_REQUIRE_SHARED_DATA(data);
  int n = 0;
  for (const char* name : {"ldr-rgb-00.png", "ldr-rgb-05.png", "ldr-rgba-00.png", "ldr-rgba-01.png",
                           "ldr-rgb-emissive.png"}) {
    auto img = io::read_image((data / "images" / name).string());
    if (!img.ok()) continue;
    ++n;
    check_oracle_encoded(*img, Format::pvrtc1_4bpp, std::string(name) + "_4");
    check_oracle_encoded(*img, Format::pvrtc1_2bpp, std::string(name) + "_2");
  }
  if (n == 0) TESSERA_SKIP_OR_FAIL("shared", "no shared images");
}

// tessera-encoded files must decode identically in the oracle.
class OracleEncode : public ::testing::TestWithParam<std::tuple<Case, Format, Quality>> {};

TEST_P(OracleEncode, OracleDecodesOurFilesLikeWeDo) {
  auto tool = test::pvrtextool();
  if (!tool) TESSERA_SKIP_OR_FAIL("pvrtextool", "PVRTexToolCLI not available");
  const auto& [c, format, quality] = GetParam();
  const ImageRGBA8 img = make_procedural(c.kind, c.w, c.h);
  EncodeOptions opt;
  opt.format = format;
  opt.quality = quality;
  opt.threads = 2;
  auto enc = encode(img, opt);
  ASSERT_TRUE(enc.ok()) << enc.status().message;
  const std::string name = std::string(procedural_name(c.kind)) + std::to_string(c.w) + "x" +
                           std::to_string(c.h) + "_q" + std::to_string(int(quality)) +
                           (format == Format::pvrtc1_4bpp ? "_4" : "_2");
  const fs::path dir = test::temp_dir(name);
  const auto file = make_pvr(format, img.has_alpha, c.w, c.h, *enc);
  ASSERT_TRUE(io::write_file_atomic((dir / "ours.pvr").string(), file).ok());
  auto oracle = oracle_decode(*tool, dir / "ours.pvr", dir);
  ASSERT_TRUE(oracle.ok()) << oracle.status().message;
  auto ours = decode(*enc, format, c.w, c.h, {1});
  ASSERT_TRUE(ours.ok());
  expect_same(*ours, *oracle, name);
}

std::vector<Case> encode_cases() {
  std::vector<Case> cases;
  for (Procedural k : all_procedurals()) cases.push_back({k, 128, 128});
  const int sizes[][2] = {{512, 128}, {8, 64}, {64, 8}, {16, 32}, {8, 8}, {4, 4}};
  for (const auto& s : sizes) cases.push_back({Procedural::foliage, s[0], s[1]});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(All, OracleEncode,
                         ::testing::Combine(::testing::ValuesIn(encode_cases()),
                                            ::testing::Values(Format::pvrtc1_4bpp,
                                                              Format::pvrtc1_2bpp),
                                            ::testing::Values(Quality::fast, Quality::high)));

// PVRTexTool's -d converts an sRGB-flagged file to linear values; the same blocks flagged
// linear decode exactly as tessera decodes them (tessera writes the stored values either way).
TEST(OracleDecode, SrgbFlagMakesTheOracleWriteLinearValues) {
  auto tool = test::pvrtextool();
  if (!tool) TESSERA_SKIP_OR_FAIL("pvrtextool", "PVRTexToolCLI not available");
  for (Format format : {Format::pvrtc1_4bpp, Format::pvrtc1_2bpp}) {
    const ImageRGBA8 img = make_procedural(Procedural::foliage, 64, 32);
    EncodeOptions opt;
    opt.format = format;
    opt.quality = Quality::fast;
    auto enc = encode(img, opt);
    ASSERT_TRUE(enc.ok()) << enc.status().message;
    auto ours = decode(*enc, format, 64, 32, {1});
    ASSERT_TRUE(ours.ok());
    const fs::path dir = test::temp_dir(format == Format::pvrtc1_4bpp ? "srgb4" : "srgb2");
    for (bool srgb : {false, true}) {
      const fs::path file = dir / (srgb ? "srgb.pvr" : "linear.pvr");
      ASSERT_TRUE(
          io::write_file_atomic(file.string(), make_pvr(format, true, 64, 32, *enc, srgb)).ok());
      auto oracle = oracle_decode(*tool, file, dir);
      ASSERT_TRUE(oracle.ok()) << oracle.status().message;
      if (!srgb) {
        expect_same(*ours, *oracle, "linear-flagged copy");
        continue;
      }
      ASSERT_EQ(oracle->pixels.size(), ours->pixels.size());
      std::size_t changed = 0, off = 0;
      for (std::size_t i = 0; i < ours->pixels.size(); ++i) {
        const int o = oracle->pixels[i], v = ours->pixels[i];
        if (i % 4 == 3) {  // alpha is not converted
          off += o != v;
          continue;
        }
        const int lin = int(255.0f * srgb8_to_linear(std::uint8_t(v)) + 0.5f);
        off += std::abs(o - lin) > 1;
        changed += o != v;
      }
      EXPECT_EQ(off, 0u) << "the oracle's decode of the sRGB file is not the linearised decode";
      EXPECT_GT(changed, ours->pixels.size() / 8) << "the sRGB flag changed nothing";
    }
  }
}

// The smallest and most lopsided sizes, padded to 2x2 blocks or wrapping onto themselves (a
// block's neighbours are the block itself): every quality, both formats, RGBA and RGB.
std::vector<Case> small_cases() {
  std::vector<Case> cases;
  const int sizes[][2] = {{1, 1},  {2, 2},   {1, 16},  {16, 1}, {2, 32},
                          {32, 2}, {1, 256}, {256, 4}, {4, 128}};
  for (const auto& s : sizes) {
    cases.push_back({Procedural::foliage, s[0], s[1]});
    cases.push_back({Procedural::noise, s[0], s[1]});
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(
    Small, OracleEncode,
    ::testing::Combine(::testing::ValuesIn(small_cases()),
                       ::testing::Values(Format::pvrtc1_4bpp, Format::pvrtc1_2bpp),
                       ::testing::Values(Quality::fast, Quality::normal, Quality::high)));

}  // namespace
}  // namespace tessera::pvrtc
