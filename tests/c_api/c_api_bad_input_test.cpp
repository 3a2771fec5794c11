// The C API (tessera/tessera_c.h) on bad input: NULL pointers, short output buffers (the needed
// size returned, nothing written), pitches below a row, sizes PVRTC cannot hold, truncated and
// corrupt containers, options structs of unknown size, conflicting options. Each gives its
// error code and a message, never a crash, and leaves the caller's outputs untouched.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "c_api_test_util.h"
#include "tessera/texture_file.h"

namespace tessera::c_api_test {
namespace {

/// The context's message is a non-empty line.
void expect_message(tessera_context* context) {
  const std::string m = tessera_context_last_error(context);
  EXPECT_FALSE(m.empty());
  EXPECT_EQ(m.find('\n'), std::string::npos) << m;
}

class CApiBadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    context_ = make_context(1);
    image_ = test_image(16, 16, 0, true);
    view_ = c_image(image_);
    tessera_encode_options_init(&options_);
    tessera_texture* raw = nullptr;
    ASSERT_EQ(tessera_encode(context_.get(), &view_, 1, &options_, &raw), TESSERA_SUCCESS);
    texture_.reset(raw);
    file_ = c_file(context_.get(), raw, TESSERA_CONTAINER_KTX2, 1);
  }
  tessera_context* context() { return context_.get(); }

  Context context_;
  ImageRGBA8 image_;
  tessera_image view_{};
  tessera_encode_options options_{};
  Texture texture_;
  std::vector<std::uint8_t> file_;
};

TEST_F(CApiBadInput, NullPointers) {
  tessera_texture* out = reinterpret_cast<tessera_texture*>(this);
  EXPECT_EQ(tessera_encode(nullptr, &view_, 1, nullptr, &out), TESSERA_ERROR_NULL_POINTER);
  EXPECT_EQ(out, nullptr);
  EXPECT_EQ(tessera_encode(context(), nullptr, 1, nullptr, &out), TESSERA_ERROR_NULL_POINTER);
  expect_message(context());
  EXPECT_EQ(tessera_encode(context(), &view_, 1, nullptr, nullptr), TESSERA_ERROR_NULL_POINTER);
  tessera_image no_pixels = view_;
  no_pixels.pixels = nullptr;
  EXPECT_EQ(tessera_encode(context(), &no_pixels, 1, nullptr, &out), TESSERA_ERROR_NULL_POINTER);
  EXPECT_EQ(tessera_context_create(nullptr, nullptr), TESSERA_ERROR_NULL_POINTER);
  EXPECT_EQ(tessera_context_config_init(nullptr), TESSERA_ERROR_NULL_POINTER);
  EXPECT_EQ(tessera_encode_options_init(nullptr), TESSERA_ERROR_NULL_POINTER);
  EXPECT_EQ(tessera_texture_read_memory(context(), nullptr, 10, &out), TESSERA_ERROR_NULL_POINTER);
  EXPECT_EQ(tessera_texture_read_file(context(), nullptr, &out), TESSERA_ERROR_NULL_POINTER);
  std::size_t size = 0;
  EXPECT_EQ(tessera_texture_write_memory(context(), nullptr, TESSERA_CONTAINER_PVR3, 0, nullptr, 0,
                                         &size),
            TESSERA_ERROR_NULL_POINTER);
  EXPECT_EQ(tessera_texture_write_memory(context(), texture_.get(), TESSERA_CONTAINER_PVR3, 0,
                                         nullptr, 0, nullptr),
            TESSERA_ERROR_NULL_POINTER);
  EXPECT_EQ(tessera_texture_write_alloc(context(), texture_.get(), TESSERA_CONTAINER_PVR3, 0,
                                        nullptr, &size),
            TESSERA_ERROR_NULL_POINTER);
  EXPECT_EQ(tessera_texture_write_file(context(), texture_.get(), nullptr, 0),
            TESSERA_ERROR_NULL_POINTER);
  EXPECT_EQ(tessera_texture_get_info(nullptr, nullptr), TESSERA_ERROR_NULL_POINTER);
  const std::uint8_t* blocks = nullptr;
  EXPECT_EQ(tessera_texture_get_blocks(texture_.get(), 0, 0, 0, &blocks, nullptr),
            TESSERA_ERROR_NULL_POINTER);
  EXPECT_EQ(tessera_texture_decode(context(), texture_.get(), 0, 0, 0, nullptr, 0, 1 << 20),
            TESSERA_ERROR_NULL_POINTER);
  EXPECT_EQ(tessera_pvrtc_decode(context(), TESSERA_FORMAT_PVRTC1_4BPP, 16, 16, nullptr, 128,
                                 nullptr, 0, 0),
            TESSERA_ERROR_NULL_POINTER);
  EXPECT_EQ(tessera_pvrtc_level_size(TESSERA_FORMAT_PVRTC1_4BPP, 16, 16, nullptr),
            TESSERA_ERROR_NULL_POINTER);
  EXPECT_EQ(tessera_compare(context(), &view_, nullptr, 1, nullptr), TESSERA_ERROR_NULL_POINTER);
  tessera_metrics m{};
  m.struct_size = sizeof m;
  EXPECT_EQ(tessera_compare(context(), &view_, nullptr, 1, &m), TESSERA_ERROR_NULL_POINTER);
  // The frees and the message take NULL.
  tessera_texture_free(nullptr);
  tessera_context_free(nullptr);
  tessera_free(nullptr);
  EXPECT_STREQ(tessera_context_last_error(nullptr), "");
}

TEST_F(CApiBadInput, ShortBuffersReturnTheSizeAndWriteNothing) {
  std::size_t size = 0;
  std::vector<std::uint8_t> out(file_.size() - 1, 0xcd);
  EXPECT_EQ(tessera_texture_write_memory(context(), texture_.get(), TESSERA_CONTAINER_KTX2, 1,
                                         out.data(), out.size(), &size),
            TESSERA_ERROR_BUFFER_TOO_SMALL);
  EXPECT_EQ(size, file_.size());
  EXPECT_EQ(out, std::vector<std::uint8_t>(file_.size() - 1, 0xcd));
  expect_message(context());

  std::size_t level = 0;
  ASSERT_EQ(tessera_pvrtc_level_size(TESSERA_FORMAT_PVRTC1_4BPP, 16, 16, &level), TESSERA_SUCCESS);
  std::vector<std::uint8_t> blocks(level - 8, 0xcd);
  size = 0;
  EXPECT_EQ(tessera_pvrtc_encode(context(), &view_, nullptr, blocks.data(), blocks.size(), &size),
            TESSERA_ERROR_BUFFER_TOO_SMALL);
  EXPECT_EQ(size, level);
  EXPECT_EQ(blocks, std::vector<std::uint8_t>(level - 8, 0xcd));

  std::vector<std::uint8_t> rgba(16 * 16 * 4 - 1, 0xcd);
  EXPECT_EQ(tessera_texture_decode(context(), texture_.get(), 0, 0, 0, rgba.data(), 0, rgba.size()),
            TESSERA_ERROR_BUFFER_TOO_SMALL);
  EXPECT_EQ(rgba, std::vector<std::uint8_t>(16 * 16 * 4 - 1, 0xcd));
  // A pitch of 80 needs 15 * 80 + 64 bytes, one less is short.
  rgba.assign(15 * 80 + 63, 0xcd);
  EXPECT_EQ(
      tessera_texture_decode(context(), texture_.get(), 0, 0, 0, rgba.data(), 80, rgba.size()),
      TESSERA_ERROR_BUFFER_TOO_SMALL);
  rgba.push_back(0xcd);
  EXPECT_EQ(
      tessera_texture_decode(context(), texture_.get(), 0, 0, 0, rgba.data(), 80, rgba.size()),
      TESSERA_SUCCESS);
  const std::uint8_t* b = nullptr;
  ASSERT_EQ(tessera_texture_get_blocks(texture_.get(), 0, 0, 0, &b, &size), TESSERA_SUCCESS);
  EXPECT_EQ(tessera_pvrtc_decode(context(), TESSERA_FORMAT_PVRTC1_4BPP, 16, 16, b, size - 1,
                                 rgba.data(), 80, rgba.size()),
            TESSERA_ERROR_INVALID_ARGUMENT);  // short input blocks
}

TEST_F(CApiBadInput, PitchBelowARow) {
  tessera_image narrow = view_;
  narrow.row_pitch = 16 * 4 - 1;
  tessera_texture* out = nullptr;
  EXPECT_EQ(tessera_encode(context(), &narrow, 1, nullptr, &out), TESSERA_ERROR_INVALID_ARGUMENT);
  expect_message(context());
  tessera_metrics m{};
  m.struct_size = sizeof m;
  EXPECT_EQ(tessera_compare(context(), &view_, &narrow, 1, &m), TESSERA_ERROR_INVALID_ARGUMENT);
  std::vector<std::uint8_t> rgba(16 * 16 * 4, 0xcd);
  EXPECT_EQ(
      tessera_texture_decode(context(), texture_.get(), 0, 0, 0, rgba.data(), 60, rgba.size()),
      TESSERA_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(rgba, std::vector<std::uint8_t>(16 * 16 * 4, 0xcd));
}

TEST_F(CApiBadInput, SizesPvrtcCannotHold) {
  const ImageRGBA8 odd = test_image(24, 16, 0, true);
  tessera_image v = c_image(odd);
  tessera_texture* out = nullptr;
  EXPECT_EQ(tessera_encode(context(), &v, 1, nullptr, &out), TESSERA_ERROR_INVALID_ARGUMENT);
  expect_message(context());
  EXPECT_NE(std::string(tessera_context_last_error(context())).find("24x16"), std::string::npos)
      << tessera_context_last_error(context());
  std::size_t size = 0;
  EXPECT_EQ(tessera_pvrtc_level_size(TESSERA_FORMAT_PVRTC1_4BPP, 24, 16, &size),
            TESSERA_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(tessera_pvrtc_level_size(TESSERA_FORMAT_PVRTC1_4BPP, 1u << 17, 16, &size),
            TESSERA_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(tessera_pvrtc_level_size(TESSERA_FORMAT_PVRTC1_4BPP, 0, 16, &size),
            TESSERA_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(size, 0u);
  v.width = 0;
  EXPECT_EQ(tessera_encode(context(), &v, 1, nullptr, &out), TESSERA_ERROR_INVALID_ARGUMENT);
  v = view_;
  v.width = 1u << 20;  // more than tessera takes, checked before any texel is read
  EXPECT_EQ(tessera_encode(context(), &v, 1, nullptr, &out), TESSERA_ERROR_INVALID_ARGUMENT);
  std::vector<std::uint8_t> blocks(1024);
  const tessera_image odd_view = c_image(odd);
  EXPECT_EQ(
      tessera_pvrtc_encode(context(), &odd_view, nullptr, blocks.data(), blocks.size(), &size),
      TESSERA_ERROR_INVALID_ARGUMENT);
  // A cube map's faces must be six of one square size.
  tessera_encode_options cube = options_;
  cube.faces = 6;
  std::vector<tessera_image> five(5, view_);
  EXPECT_EQ(tessera_encode(context(), five.data(), 5, &cube, &out), TESSERA_ERROR_INVALID_ARGUMENT);
  expect_message(context());
  EXPECT_EQ(out, nullptr);
}

TEST_F(CApiBadInput, TruncatedAndCorruptContainers) {
  tessera_texture* out = nullptr;
  for (std::size_t n = 0; n < file_.size(); n += n < 96 ? 1 : 17) {
    std::vector<std::uint8_t> cut(file_.begin(), file_.begin() + std::ptrdiff_t(n));
    cut.push_back(0);  // a readable byte for n == 0, outside the size given
    const tessera_error e = tessera_texture_read_memory(context(), cut.data(), n, &out);
    ASSERT_NE(e, TESSERA_SUCCESS) << n << " bytes";
    ASSERT_EQ(out, nullptr);
    expect_message(context());
  }
  std::vector<std::uint8_t> corrupt = file_;
  corrupt[20] ^= 0xff;  // pixelWidth
  corrupt[21] ^= 0x7f;
  EXPECT_NE(tessera_texture_read_memory(context(), corrupt.data(), corrupt.size(), &out),
            TESSERA_SUCCESS);
  EXPECT_EQ(out, nullptr);
  const char junk[] = "not a texture at all";
  EXPECT_EQ(tessera_texture_read_memory(context(), junk, sizeof junk, &out),
            TESSERA_ERROR_CORRUPT_DATA);
  EXPECT_EQ(tessera_texture_read_file(context(), "/nonexistent/x.ktx2", &out), TESSERA_ERROR_IO);
  expect_message(context());
  // The whole file still reads (the control).
  ASSERT_EQ(tessera_texture_read_memory(context(), file_.data(), file_.size(), &out),
            TESSERA_SUCCESS);
  tessera_texture_free(out);
}

TEST_F(CApiBadInput, StructsOfUnknownSize) {
  tessera_encode_options o = options_;
  o.struct_size = sizeof o + 8;
  tessera_texture* out = nullptr;
  EXPECT_EQ(tessera_encode(context(), &view_, 1, &o, &out), TESSERA_ERROR_BAD_STRUCT_SIZE);
  expect_message(context());
  o.struct_size = 0;  // a struct the init never saw
  EXPECT_EQ(tessera_encode(context(), &view_, 1, &o, &out), TESSERA_ERROR_BAD_STRUCT_SIZE);
  tessera_context_config config;
  tessera_context_config_init(&config);
  config.struct_size = 4;
  tessera_context* c = reinterpret_cast<tessera_context*>(this);
  EXPECT_EQ(tessera_context_create(&config, &c), TESSERA_ERROR_BAD_STRUCT_SIZE);
  EXPECT_EQ(c, nullptr);
  tessera_texture_info info{};
  info.struct_size = sizeof info - 4;
  EXPECT_EQ(tessera_texture_get_info(texture_.get(), &info), TESSERA_ERROR_BAD_STRUCT_SIZE);
  EXPECT_EQ(info.width, 0u);
  tessera_metrics m{};
  m.struct_size = 1;
  EXPECT_EQ(tessera_compare(context(), &view_, &view_, 1, &m), TESSERA_ERROR_BAD_STRUCT_SIZE);
  EXPECT_EQ(m.psnr_rgb, 0.0);
}

TEST_F(CApiBadInput, OptionsOutOfRangeOrInConflict) {
  const auto refused = [&](auto&& change) {
    tessera_encode_options o = options_;
    change(o);
    tessera_texture* out = nullptr;
    const tessera_error e = tessera_encode(context(), &view_, 1, &o, &out);
    EXPECT_EQ(out == nullptr, e != TESSERA_SUCCESS);
    tessera_texture_free(out);
    if (e == TESSERA_ERROR_INVALID_ARGUMENT) expect_message(context());
    return e;
  };
  const tessera_error bad = TESSERA_ERROR_INVALID_ARGUMENT;
  EXPECT_EQ(refused([](auto& o) { o.format = static_cast<tessera_format>(7); }), bad);
  EXPECT_EQ(refused([](auto& o) { o.quality = static_cast<tessera_quality>(-1); }), bad);
  EXPECT_EQ(refused([](auto& o) { o.mip_filter = static_cast<tessera_mip_filter>(3); }), bad);
  EXPECT_EQ(refused([](auto& o) { o.iterations = -2; }), bad);
  EXPECT_EQ(refused([](auto& o) { o.mip_levels = 18; }), bad);
  EXPECT_EQ(refused([](auto& o) { o.faces = 2; }), bad);
  EXPECT_EQ(refused([](auto& o) { o.flags = 0x100; }), bad);
  EXPECT_EQ(refused([](auto& o) { o.flags = TESSERA_FLAG_NORMAL_MAP | TESSERA_FLAG_SRGB; }), bad);
  EXPECT_EQ(refused([](auto& o) { o.flags = TESSERA_FLAG_PREMULTIPLY | TESSERA_FLAG_ALPHA_BLEED; }),
            bad);
  EXPECT_EQ(refused([](auto& o) {
              o.flags = TESSERA_FLAG_ALPHA_WEIGHTED;
              o.format = TESSERA_FORMAT_PVRTC1_2BPP;
            }),
            bad);
  EXPECT_EQ(refused([](auto& o) { o.mip_filter = TESSERA_MIP_FILTER_LANCZOS; }), bad);
  EXPECT_EQ(refused([](auto&) {}), TESSERA_SUCCESS);  // the control: the options as they were
  std::size_t size = 0;
  EXPECT_EQ(tessera_texture_write_memory(context(), texture_.get(), TESSERA_CONTAINER_PVR3, 3,
                                         nullptr, 0, &size),
            bad);  // zstd outside KTX 2.0
  EXPECT_EQ(tessera_texture_write_memory(context(), texture_.get(), TESSERA_CONTAINER_KTX2, 23,
                                         nullptr, 0, &size),
            bad);
  EXPECT_EQ(tessera_texture_write_memory(context(), texture_.get(),
                                         static_cast<tessera_container>(5), 0, nullptr, 0, &size),
            bad);
  EXPECT_EQ(tessera_texture_write_file(context(), texture_.get(), "/tmp/x.png", 0), bad);
  EXPECT_EQ(tessera_texture_decode(context(), texture_.get(), 9, 0, 0, nullptr, 0, 0), bad);
  const std::uint8_t* blocks = nullptr;
  EXPECT_EQ(tessera_texture_get_blocks(texture_.get(), 0, 1, 0, &blocks, &size), bad);
  EXPECT_EQ(blocks, nullptr);
  tessera_context_config config;
  tessera_context_config_init(&config);
  config.threads = -1;
  tessera_context* c = nullptr;
  EXPECT_EQ(tessera_context_create(&config, &c), bad);
}

}  // namespace
}  // namespace tessera::c_api_test
