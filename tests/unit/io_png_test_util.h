// encode_raw_png for the io tests (io_test.cpp, io_png_fast_test.cpp): PNG files made with
// libspng directly, to get 16-bit, grey, palette, filtered and interlaced files.
#pragma once

#include <gtest/gtest.h>
#include <spng.h>

#include <cstdint>
#include <cstdlib>
#include <memory>
#include <vector>

namespace tessera::test {

/// Encodes raw samples as PNG with libspng directly (to make 16-bit, grey and palette files).
/// `filters`: an SPNG_FILTER_CHOICE_* mask (libspng picks per row among those allowed).
inline std::vector<std::uint8_t> encode_raw_png(const void* data, std::size_t size, std::uint32_t w,
                                                std::uint32_t h, std::uint8_t color_type,
                                                std::uint8_t depth, const spng_plte* plte = nullptr,
                                                const spng_trns* trns = nullptr,
                                                int filters = SPNG_FILTER_CHOICE_ALL,
                                                std::uint8_t interlace = 0) {
  std::unique_ptr<spng_ctx, decltype(&spng_ctx_free)> ctx(spng_ctx_new(SPNG_CTX_ENCODER),
                                                          &spng_ctx_free);
  spng_set_option(ctx.get(), SPNG_ENCODE_TO_BUFFER, 1);
  spng_set_option(ctx.get(), SPNG_FILTER_CHOICE, filters);
  spng_ihdr ihdr{};
  ihdr.width = w;
  ihdr.height = h;
  ihdr.bit_depth = depth;
  ihdr.color_type = color_type;
  ihdr.interlace_method = interlace;
  EXPECT_EQ(spng_set_ihdr(ctx.get(), &ihdr), 0);
  if (plte) {
    EXPECT_EQ(spng_set_plte(ctx.get(), const_cast<spng_plte*>(plte)), 0);
  }
  if (trns) {
    EXPECT_EQ(spng_set_trns(ctx.get(), const_cast<spng_trns*>(trns)), 0);
  }
  EXPECT_EQ(spng_encode_image(ctx.get(), data, size, SPNG_FMT_PNG, SPNG_ENCODE_FINALIZE), 0);
  std::size_t n = 0;
  int err = 0;
  void* buf = spng_get_png_buffer(ctx.get(), &n, &err);
  std::vector<std::uint8_t> out(static_cast<std::uint8_t*>(buf),
                                static_cast<std::uint8_t*>(buf) + n);
  std::free(buf);
  return out;
}

}  // namespace tessera::test
