// tessera/glsl.h: the shipped GLSL embedded at build time (byte-identical to share/tessera/glsl,
// the one source of truth), the development override folder, `#include` expansion that falls
// back to the shipped files, and compiler logs turned into "FILE:LINE: message". No GL.
#include "tessera/glsl.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "test_support.h"

namespace {

using namespace tessera;

void write_text(const std::filesystem::path& p, const std::string& text) {
  std::ofstream f(p, std::ios::binary);
  f << text;
}

std::string read_text(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

bool one_line(const std::string& s) { return !s.empty() && s.find('\n') == std::string::npos; }

// Unset $TESSERA_GLSL_DIR for a test (the embedded copies are what is tested).
class Glsl : public ::testing::Test {
 protected:
  void SetUp() override { unsetenv("TESSERA_GLSL_DIR"); }
};

TEST_F(Glsl, EmbeddedFilesAreTheShippedFolderByteForByte) {
  const std::filesystem::path folder = TESSERA_SOURCE_GLSL_DIR;
  std::vector<std::string> on_disk;
  for (const auto& e : std::filesystem::directory_iterator(folder)) {
    on_disk.push_back(e.path().filename().string());
  }
  std::sort(on_disk.begin(), on_disk.end());
  const std::vector<std::string> shipped = glsl::shipped_files();
  EXPECT_EQ(shipped, on_disk);
  ASSERT_FALSE(shipped.empty());
  for (const std::string& name : shipped) {
    Result<std::string> text = glsl::shipped_source(name);
    ASSERT_TRUE(text.ok()) << text.status().message;
    EXPECT_EQ(*text, read_text(folder / name)) << name;
  }
}

TEST_F(Glsl, UnknownShippedFileIsOneLineError) {
  Result<std::string> none = glsl::shipped_source("no_such.glsl");
  ASSERT_FALSE(none.ok());
  EXPECT_TRUE(one_line(none.status().message));
  EXPECT_NE(none.status().message.find("no_such.glsl"), std::string::npos);
}

TEST_F(Glsl, OverrideFolderIsReadInsteadOfTheEmbeddedCopy) {
  const auto dir = test::temp_dir("glsl_override");
  write_text(dir / "seams.glsl", "// development copy\n");
  Result<std::string> text = glsl::shipped_source("seams.glsl", dir);
  ASSERT_TRUE(text.ok()) << text.status().message;
  EXPECT_EQ(*text, "// development copy\n");
  // The environment variable does the same; a file missing there is an error naming the
  // folder, not a silent fall-back to the embedded copy.
  setenv("TESSERA_GLSL_DIR", dir.c_str(), 1);
  EXPECT_EQ(*glsl::shipped_source("seams.glsl"), "// development copy\n");
  Result<std::string> missing = glsl::shipped_source("fxaa.glsl");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.status().message.find(dir.string()), std::string::npos);
  unsetenv("TESSERA_GLSL_DIR");
  EXPECT_NE(glsl::shipped_source("seams.glsl")->find("tessera_seams_sample_discard"),
            std::string::npos);
}

TEST_F(Glsl, EngineShaderIncludesResolveToTheShippedFiles) {
  // What an engine does with its own fragment shader: expand, then compile the string itself.
  glsl::Source src{glsl::Stage::fragment,
                   "#version 450 core\n#include \"seams.glsl\"\nvoid main() {}\n", "engine.frag"};
  glsl::ExpandOptions o;
  o.preamble = {"#define TESSERA_SEAMS_CLASSES 2"};
  Result<glsl::Expanded> e = glsl::expand_includes(src, o);
  ASSERT_TRUE(e.ok()) << e.status().message;
  ASSERT_EQ(e->files.size(), 2u);
  EXPECT_EQ(e->files[1], "seams.glsl");
  EXPECT_NE(e->text.find("#define TESSERA_SEAMS_CLASSES 2"), std::string::npos);
  EXPECT_NE(e->text.find("tessera_seams_sample_discard"), std::string::npos);
  EXPECT_EQ(e->text.find("\n#include \"seams.glsl\""), std::string::npos);
  // Negative control: without the shipped fall-back the include is not found.
  o.shipped_includes = false;
  Result<glsl::Expanded> bad = glsl::expand_includes(src, o);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message.rfind("engine.frag:2: cannot find include file", 0), 0u)
      << bad.status().message;
}

TEST_F(Glsl, FormatsShadercLogs) {
  EXPECT_EQ(glsl::format_log("hook.comp:12: error: 'x' : undeclared identifier\n", {"hook"}),
            "hook:12: error: 'x' : undeclared identifier");
  EXPECT_EQ(glsl::format_log("hook.comp:100004: error: 'y' : undeclared identifier\n",
                             {"hook", "adaptive_component.glsl"}),
            "adaptive_component.glsl:4: error: 'y' : undeclared identifier");
}

TEST_F(Glsl, FormatsDriverLogsAsFileAndLine) {
  // With includes, the line number tells the file (glsl::kIncludeLineStride per file).
  const std::vector<std::string> files = {"main.frag", "lib/seams.glsl"};
  EXPECT_EQ(glsl::format_log("0:12(5): error: `x' undeclared\n", files),
            "main.frag:12: error: `x' undeclared");
  EXPECT_EQ(glsl::format_log("0:3(1): warning: w\n0:100007(10): error: syntax error\n", files),
            "lib/seams.glsl:7: error: syntax error");
  EXPECT_EQ(glsl::format_log("1:100007(10): error: e\n", files), "lib/seams.glsl:7: error: e");
  EXPECT_EQ(glsl::format_log("1(100041) : error C1008: undefined variable \"y\"", files),
            "lib/seams.glsl:41: error C1008: undefined variable \"y\"");
  EXPECT_EQ(glsl::format_log("ERROR: 0:9: 'z' : undeclared identifier", files),
            "main.frag:9: 'z' : undeclared identifier");
  EXPECT_EQ(glsl::format_log("0:400002(1): error: e", files), "source 4:2: error: e");
  // One file: the source-string number as reported.
  EXPECT_EQ(glsl::format_log("0:5(1): error: e", {"one.frag"}), "one.frag:5: error: e");
  EXPECT_EQ(glsl::format_log("3:5(1): error: e", {"one.frag"}), "source 3:5: error: e");
  EXPECT_EQ(glsl::format_log("something odd\n", files), "something odd");
  EXPECT_EQ(glsl::format_log("", files), "unknown shader error (empty info log)");
}

TEST_F(Glsl, ExpandsIncludesWithLineDirectives) {
  const auto dir = test::temp_dir("includes");
  write_text(dir / "a.glsl", "float a() { return 1.0; }\n#include \"b.glsl\"\n");
  write_text(dir / "b.glsl", "float b() { return 2.0; }\n");
  glsl::Source src{glsl::Stage::fragment,
                   "#version 450 core\n#include \"a.glsl\"\n#include \"b.glsl\"\nvoid main() {}\n",
                   "main.frag"};
  glsl::ExpandOptions o;
  o.include_paths = {dir};
  o.preamble = {"#define N 4"};
  Result<glsl::Expanded> e = glsl::expand_includes(src, o);
  ASSERT_TRUE(e.ok()) << e.status().message;
  ASSERT_EQ(e->files.size(), 3u);
  EXPECT_EQ(e->files[0], "main.frag");
  EXPECT_NE(e->text.find("#version 450 core\n#define N 4\n#line 2 0\n#line 100001 1\n"),
            std::string::npos)
      << e->text;
  EXPECT_NE(e->text.find("#line 200001 2\nfloat b() { return 2.0; }\n"
                         "#line 100003 1\n#line 3 0\n\n"),
            std::string::npos)
      << e->text;
  EXPECT_EQ(glsl::format_log("0:200001(3): error: x", e->files),
            (dir / "b.glsl").string() + ":1: error: x");
  src.text = "#version 450 core\n\n#include \"missing.glsl\"\n";
  Result<glsl::Expanded> bad = glsl::expand_includes(src, o);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().code, ErrorCode::io_error);
  EXPECT_TRUE(one_line(bad.status().message));
  EXPECT_EQ(bad.status().message.rfind("main.frag:3: cannot find include file \"missing.glsl\"", 0),
            0u)
      << bad.status().message;
}

TEST_F(Glsl, FloatLiteralsReadBackExactly) {
  for (float v : {0.0f, 1.0f, 0.1f, 1e-7f, 3.4e38f, -2.5f}) {
    const std::string s = glsl::float_literal(v);
    EXPECT_NE(s.find('.'), std::string::npos) << s;
    EXPECT_EQ(std::strtof(s.c_str(), nullptr), v) << s;
  }
}

}  // namespace
