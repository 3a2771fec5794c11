// libFuzzer target: pvrtc::encode on arbitrary content, sizes and options, checked for what the
// encoder promises whatever the input. Input layout:
//   byte 0   width = 2^(byte % 7)  (1 .. 64)
//   byte 1   height = 2^(byte % 7) (1 .. 64)
//   byte 2   bit 0: 2 bpp; bits 1-2: quality (0 fast, 1 normal, 2 high, 3 fast + 1 refinement
//            sweep); bit 3: the image has alpha; bit 4: no punch-through; bit 5: force alpha;
//            bits 6-7: how the rest fills the texels (0: RGBA bytes as they come; 1: palette of
//            the first 4 colours, indices from the following bytes, 2 bits each, so flat areas
//            and uniform blocks occur; 2: grey ramps with one alpha byte; 3: one colour)
//   byte 3   bits 0-3: exact-search rounds (4 bpp normal / high only)
//   rest     the texel source, repeated to fill the image
// High quality runs only up to 32x32 texels (larger inputs fall back to normal) to keep each
// input fast under the sanitizers.
// Checks: the encode succeeds with exactly level_size bytes; two threads write the same bytes
// as one; the bytes decode; an image without alpha decodes fully opaque (RGB input writes only
// opaque endpoints).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "tessera/pvrtc.h"

namespace {

void fill(tessera::ImageRGBA8& img, int how, const std::uint8_t* src, std::size_t n) {
  std::vector<std::uint8_t>& px = img.pixels;
  if (n == 0) return;  // zero-filled
  const std::size_t texels = img.pixel_count();
  switch (how) {
    case 0:
      for (std::size_t i = 0; i < px.size(); ++i) px[i] = src[i % n];
      break;
    case 1: {
      std::uint8_t pal[4][4] = {};
      for (std::size_t i = 0; i < 16; ++i) pal[i / 4][i % 4] = src[i % n];
      const std::uint8_t* idx = n > 16 ? src + 16 : src;
      const std::size_t m = n > 16 ? n - 16 : n;
      for (std::size_t t = 0; t < texels; ++t) {
        const int k = (idx[(t / 4) % m] >> (2 * (t % 4))) & 3;
        std::memcpy(&px[t * 4], pal[k], 4);
      }
      break;
    }
    case 2:
      for (std::size_t t = 0; t < texels; ++t) {
        const std::uint8_t v = std::uint8_t(src[(t / 8) % n] + t % 8 * (n > 1 ? src[1] : 1));
        px[t * 4] = px[t * 4 + 1] = px[t * 4 + 2] = v;
        px[t * 4 + 3] = src[0];
      }
      break;
    default:
      for (std::size_t t = 0; t < texels; ++t) {
        for (std::size_t c = 0; c < 4; ++c) px[t * 4 + c] = src[c % n];
      }
      break;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tessera;
  if (size < 4) return 0;
  const int width = 1 << (data[0] % 7), height = 1 << (data[1] % 7);
  const std::uint8_t flags = data[2];
  pvrtc::EncodeOptions opt;
  opt.format = (flags & 1) ? pvrtc::Format::pvrtc1_2bpp : pvrtc::Format::pvrtc1_4bpp;
  switch ((flags >> 1) & 3) {
    case 0:
      opt.quality = pvrtc::Quality::fast;
      break;
    case 1:
      opt.quality = pvrtc::Quality::normal;
      break;
    case 2:
      opt.quality = width * height <= 1024 ? pvrtc::Quality::high : pvrtc::Quality::normal;
      break;
    default:
      opt.quality = pvrtc::Quality::fast;
      opt.iterations = 1;
      break;
  }
  opt.punch_through = !(flags & 16);
  opt.force_alpha = (flags & 32) != 0;
  if (opt.quality != pvrtc::Quality::fast) opt.exact_search_rounds = data[3] & 15;
  ImageRGBA8 img(width, height);
  img.has_alpha = (flags & 8) != 0;
  fill(img, flags >> 6, data + 4, size - 4);

  opt.threads = 1;
  Result<std::vector<std::uint8_t>> one = pvrtc::encode(img, opt);
  if (!one || one->size() != pvrtc::level_size(opt.format, width, height)) std::abort();
  opt.threads = 2;
  Result<std::vector<std::uint8_t>> two = pvrtc::encode(img, opt);
  if (!two || *two != *one) std::abort();  // output must not depend on the thread count

  Result<ImageRGBA8> dec = pvrtc::decode(*one, opt.format, width, height, {1});
  if (!dec || dec->width != width || dec->height != height) std::abort();
  if (!img.has_alpha && !opt.force_alpha) {
    for (std::size_t t = 0; t < dec->pixel_count(); ++t) {
      if (dec->pixels[t * 4 + 3] != 255) std::abort();  // RGB input stays opaque
    }
  }
  return 0;
}
