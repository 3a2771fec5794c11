// Tests of the PNG fast path (src/io/png_fast.cpp) against libspng: every filter, width,
// colour type and sequence of row filters; ancillary chunks; what it declines; corrupt files
// giving the same result as libspng. (The rest of tessera/io.h: io_test.cpp.)
#include <gtest/gtest.h>
#include <spng.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/png_fast.h"
#include "io_png_test_util.h"
#include "tessera/io.h"
#include "test_support.h"

namespace tessera::io {
namespace {

namespace fs = std::filesystem;
using test::encode_raw_png;

std::uint32_t crc32_of(const std::uint8_t* p, std::size_t n) {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < n; ++i) {
    crc ^= p[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void put_be32(std::vector<std::uint8_t>& b, std::size_t off, std::uint32_t v) {
  b[off] = std::uint8_t(v >> 24);
  b[off + 1] = std::uint8_t(v >> 16);
  b[off + 2] = std::uint8_t(v >> 8);
  b[off + 3] = std::uint8_t(v);
}

std::uint32_t get_be32(const std::vector<std::uint8_t>& b, std::size_t off) {
  return (std::uint32_t(b[off]) << 24) | (std::uint32_t(b[off + 1]) << 16) |
         (std::uint32_t(b[off + 2]) << 8) | std::uint32_t(b[off + 3]);
}

/// Offset of the first chunk of `type` (its length field), or 0.
std::size_t find_chunk(const std::vector<std::uint8_t>& png, const char* type) {
  for (std::size_t pos = 8; pos + 12 <= png.size(); pos += 12 + get_be32(png, pos)) {
    if (std::memcmp(&png[pos + 4], type, 4) == 0) return pos;
  }
  return 0;
}

/// Recomputes the CRC of the chunk at `pos`, so only the deliberate damage remains.
void fix_crc(std::vector<std::uint8_t>& png, std::size_t pos) {
  const std::uint32_t len = get_be32(png, pos);
  put_be32(png, pos + 8 + len, crc32_of(&png[pos + 4], len + 4));
}

/// Inserts a chunk before the one at `pos`.
void insert_chunk(std::vector<std::uint8_t>& png, std::size_t pos, const char* type,
                  const std::vector<std::uint8_t>& body) {
  std::vector<std::uint8_t> c(12 + body.size());
  put_be32(c, 0, std::uint32_t(body.size()));
  std::memcpy(&c[4], type, 4);
  std::copy(body.begin(), body.end(), c.begin() + 8);
  put_be32(c, 8 + body.size(), crc32_of(&c[4], body.size() + 4));
  png.insert(png.begin() + std::ptrdiff_t(pos), c.begin(), c.end());
}

/// Samples with smooth runs, edges and noise, so every filter and Paeth branch gets used.
std::vector<std::uint8_t> test_samples(std::uint32_t w, std::uint32_t h, int channels) {
  std::vector<std::uint8_t> s(std::size_t(w) * h * std::size_t(channels));
  std::uint32_t rng = 12345;
  for (std::uint32_t y = 0; y < h; ++y) {
    for (std::uint32_t x = 0; x < w; ++x) {
      for (int c = 0; c < channels; ++c) {
        rng = rng * 1664525u + 1013904223u;
        const std::uint32_t smooth = x * (3 + std::uint32_t(c)) + y * 5;
        const std::uint32_t v = ((x / 4 + y / 3) % 3 == 0) ? smooth : (rng >> 24);
        s[(std::size_t(y) * w + x) * std::size_t(channels) + std::size_t(c)] = std::uint8_t(v);
      }
    }
  }
  return s;
}

/// decode_image must give exactly what libspng gives: the same pixels, or the same error.
void expect_same_as_spng(const std::vector<std::uint8_t>& png, const std::string& what) {
  Result<ImageRGBA8> got = decode_image(png, "x.png");
  Result<ImageRGBA8> want = detail::decode_png_spng(png, "x.png");
  ASSERT_EQ(got.ok(), want.ok()) << what << ": " << (got.ok() ? want : got).status().message;
  if (!want.ok()) {
    EXPECT_EQ(got.status().message, want.status().message) << what;
    EXPECT_EQ(got.status().message.rfind("x.png: ", 0), 0u) << got.status().message;
    EXPECT_EQ(got.status().message.find('\n'), std::string::npos);
    return;
  }
  EXPECT_EQ(got->width, want->width) << what;
  EXPECT_EQ(got->height, want->height) << what;
  EXPECT_EQ(got->has_alpha, want->has_alpha) << what;
  EXPECT_TRUE(got->pixels == want->pixels) << what;
}

TEST(PngFastPath, MatchesLibspngForEveryFilterWidthAndColourType) {
  const int choices[] = {SPNG_FILTER_CHOICE_NONE, SPNG_FILTER_CHOICE_SUB,   SPNG_FILTER_CHOICE_UP,
                         SPNG_FILTER_CHOICE_AVG,  SPNG_FILTER_CHOICE_PAETH, SPNG_FILTER_CHOICE_ALL};
  const std::pair<std::uint8_t, int> types[] = {{0, 1}, {2, 3}, {4, 2}, {6, 4}};
  for (auto [color_type, channels] : types) {
    for (std::uint32_t w : {1u, 3u, 17u, 257u}) {
      for (int filters : choices) {
        const std::uint32_t h = 7;
        const std::vector<std::uint8_t> samples = test_samples(w, h, channels);
        const std::vector<std::uint8_t> png = encode_raw_png(
            samples.data(), samples.size(), w, h, color_type, 8, nullptr, nullptr, filters);
        const std::string what = "type " + std::to_string(color_type) + " width " +
                                 std::to_string(w) + " filters " + std::to_string(filters);
        std::optional<ImageRGBA8> fast = detail::decode_png_fast(png);
        ASSERT_TRUE(fast.has_value()) << what << ": the fast path should take this file";
        Result<ImageRGBA8> ref = detail::decode_png_spng(png, "ref");
        ASSERT_TRUE(ref.ok()) << ref.status().message;
        EXPECT_EQ(fast->width, ref->width);
        EXPECT_EQ(fast->height, ref->height);
        EXPECT_EQ(fast->has_alpha, ref->has_alpha) << what;
        EXPECT_TRUE(fast->pixels == ref->pixels) << what;
      }
    }
  }
}

TEST(PngFastPath, IgnoresTheSameAncillaryChunksAsLibspng) {
  const std::vector<std::uint8_t> samples = test_samples(17, 5, 3);
  const std::vector<std::uint8_t> base =
      encode_raw_png(samples.data(), samples.size(), 17, 5, 2, 8);
  const std::size_t idat = find_chunk(base, "IDAT");
  // Well-formed and malformed (libspng discards those) ancillary chunks before and after IDAT.
  const std::vector<std::pair<const char*, std::vector<std::uint8_t>>> chunks = {
      {"pHYs", {0, 0, 0x0B, 0x13, 0, 0, 0x0B, 0x13, 1}},
      {"gAMA", {0, 0, 0xB1, 0x8F}},
      {"gAMA", {0, 0, 0, 0}},  // a duplicate, and an invalid value
      {"sRGB", {9}},           // invalid rendering intent
      {"cHRM", {1, 2, 3}},     // wrong size
      {"tEXt", {'C', 'o', 'm', 'm', 'e', 'n', 't', 0, 'h', 'i'}},
      {"zTXt", {'k', 0, 0, 1, 2, 3}},                       // corrupt zlib stream
      {"iCCP", {'p', 0, 0, 0x78, 0x9C, 3, 0, 0, 0, 0, 1}},  // empty profile
      {"iCCP", {'p', 'r', 'o'}},                            // no name terminator
      {"tEXt", {0, 'x'}},                                   // empty keyword
      {"tIME", {0x07, 0xE6, 13, 40, 25, 61, 61}},           // impossible date
      {"pHYs", {0, 0, 0, 1, 0, 0, 0, 1, 7}},                // unknown unit
      {"bKGD", {0, 1}},                                     // wrong size for RGB
      {"sBIT", {0, 9, 8}},                                  // out of range
      {"hIST", {0, 1, 0, 2}},                               // no PLTE
      {"oFFs", {0, 0, 0, 1, 0, 0, 0, 1, 2}},                // unknown unit
      {"prVt", {1, 2, 3}},                                  // unknown, safe to copy
  };
  for (const auto& [type, body] : chunks) {
    std::vector<std::uint8_t> before = base;
    insert_chunk(before, idat, type, body);
    ASSERT_TRUE(detail::decode_png_fast(before).has_value()) << type;
    expect_same_as_spng(before, std::string(type) + " before IDAT");
    std::vector<std::uint8_t> after = base;
    insert_chunk(after, find_chunk(after, "IEND"), type, body);
    expect_same_as_spng(after, std::string(type) + " after IDAT");
  }
}

TEST(PngFastPath, DeclinesWhatItDoesNotHandle) {
  const std::vector<std::uint8_t> rgb = test_samples(9, 6, 3);
  // tRNS changes alpha: libspng decides.
  spng_trns trns{};
  trns.red = rgb[0];
  trns.green = rgb[1];
  trns.blue = rgb[2];
  const std::vector<std::uint8_t> keyed =
      encode_raw_png(rgb.data(), rgb.size(), 9, 6, 2, 8, nullptr, &trns);
  EXPECT_FALSE(detail::decode_png_fast(keyed).has_value());
  Result<ImageRGBA8> k = decode_image(keyed, "keyed.png");
  ASSERT_TRUE(k.ok());
  EXPECT_TRUE(k->has_alpha);
  EXPECT_EQ(k->pixels[3], 0);
  // 16-bit samples and Adam7 interlacing.
  std::vector<std::uint16_t> wide(9 * 6 * 3, 0x1234);
  const std::vector<std::uint8_t> sixteen =
      encode_raw_png(wide.data(), wide.size() * 2, 9, 6, 2, 16);
  EXPECT_FALSE(detail::decode_png_fast(sixteen).has_value());
  EXPECT_TRUE(decode_image(sixteen, "16.png").ok());
  const std::vector<std::uint8_t> interlaced = encode_raw_png(
      rgb.data(), rgb.size(), 9, 6, 2, 8, nullptr, nullptr, SPNG_FILTER_CHOICE_ALL, 1);
  EXPECT_FALSE(detail::decode_png_fast(interlaced).has_value());
  expect_same_as_spng(interlaced, "interlaced");
}

TEST(PngFastPath, CorruptFilesGiveTheSameResultAsLibspng) {
  const std::vector<std::uint8_t> samples = test_samples(33, 17, 4);
  const std::vector<std::uint8_t> png =
      encode_raw_png(samples.data(), samples.size(), 33, 17, 6, 8);
  ASSERT_TRUE(detail::decode_png_fast(png).has_value());
  const std::size_t ihdr = find_chunk(png, "IHDR"), idat = find_chunk(png, "IDAT");
  const std::uint32_t idat_len = get_be32(png, idat);

  // A flipped bit inside the zlib data, CRC fixed up: inflate or Adler-32 must catch it.
  for (std::size_t at : {std::size_t(2), std::size_t(idat_len / 2), std::size_t(idat_len - 2)}) {
    std::vector<std::uint8_t> bad = png;
    bad[idat + 8 + at] ^= 0x10;
    fix_crc(bad, idat);
    EXPECT_FALSE(detail::decode_png_fast(bad).has_value()) << "flip at " << at;
    expect_same_as_spng(bad, "flip at " + std::to_string(at));
  }
  // A bad CRC anywhere is an error.
  for (std::size_t pos : {ihdr, idat, find_chunk(png, "IEND")}) {
    std::vector<std::uint8_t> bad = png;
    bad[pos + 8 + get_be32(png, pos)] ^= 1;
    EXPECT_FALSE(detail::decode_png_fast(bad).has_value());
    Result<ImageRGBA8> r = decode_image(bad, "crc.png");
    ASSERT_FALSE(r.ok()) << "CRC at " << pos;
    EXPECT_EQ(r.status().message.rfind("crc.png: ", 0), 0u) << r.status().message;
  }
  // Truncated anywhere is an error.
  for (std::size_t cut : {std::size_t(8), std::size_t(30), idat + 4, idat + 20, idat + 8 + idat_len,
                          png.size() - 12, png.size() - 1}) {
    std::vector<std::uint8_t> part(png.begin(), png.begin() + std::ptrdiff_t(cut));
    EXPECT_FALSE(detail::decode_png_fast(part).has_value()) << "cut at " << cut;
    Result<ImageRGBA8> r = decode_image(part, "cut.png");
    ASSERT_FALSE(r.ok()) << "cut at " << cut;
    EXPECT_EQ(r.status().message.rfind("cut.png: ", 0), 0u) << r.status().message;
    EXPECT_EQ(r.status().message.find('\n'), std::string::npos);
  }
  // IHDR lying about the size (CRC fixed up): larger, smaller, another colour type.
  struct Lie {
    std::uint32_t w, h;
    std::uint8_t color_type;
  };
  for (Lie lie : {Lie{33, 18, 6}, Lie{34, 17, 6}, Lie{33, 16, 6}, Lie{32, 17, 6}, Lie{33, 17, 2},
                  Lie{60000, 60000, 6}, Lie{4096, 4096, 6}}) {
    std::vector<std::uint8_t> bad = png;
    put_be32(bad, ihdr + 8, lie.w);
    put_be32(bad, ihdr + 12, lie.h);
    bad[ihdr + 17] = lie.color_type;
    fix_crc(bad, ihdr);
    const std::string what = std::to_string(lie.w) + "x" + std::to_string(lie.h);
    EXPECT_FALSE(detail::decode_png_fast(bad).has_value()) << what;
    expect_same_as_spng(bad, "IHDR says " + what);
  }
}

/// Applies PNG filter `filter` (0-4) to one row of samples (`prev`: the row above, or zeros).
void filter_row(int filter, const std::uint8_t* row, const std::uint8_t* prev, std::size_t n,
                std::size_t bpp, std::uint8_t* out) {
  for (std::size_t i = 0; i < n; ++i) {
    const int a = i >= bpp ? row[i - bpp] : 0, b = prev[i], c = i >= bpp ? prev[i - bpp] : 0;
    int pred = 0;
    if (filter == 1) pred = a;
    if (filter == 2) pred = b;
    if (filter == 3) pred = (a + b) / 2;
    if (filter == 4) {
      const int pa = std::abs(b - c), pb = std::abs(a - c), pc = std::abs(a + b - 2 * c);
      pred = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
    }
    out[i] = std::uint8_t(row[i] - pred);
  }
}

/// An 8-bit PNG of `samples` whose row y uses filter filters[y] exactly (encoders choose their
/// own), stored in uncompressed DEFLATE blocks: IHDR, one IDAT, IEND.
std::vector<std::uint8_t> png_with_filters(const std::vector<std::uint8_t>& samples,
                                           std::uint32_t w, std::uint8_t color_type,
                                           std::size_t channels, const std::vector<int>& filters) {
  const std::size_t row_bytes = w * channels, h = filters.size();
  std::vector<std::uint8_t> raw(h * (1 + row_bytes));
  const std::vector<std::uint8_t> zeros(row_bytes, 0);
  for (std::size_t y = 0; y < h; ++y) {
    raw[y * (1 + row_bytes)] = std::uint8_t(filters[y]);
    filter_row(filters[y], &samples[y * row_bytes],
               y ? &samples[(y - 1) * row_bytes] : zeros.data(), row_bytes, channels,
               &raw[y * (1 + row_bytes) + 1]);
  }
  std::vector<std::uint8_t> z = {0x78, 0x01};  // zlib header, then stored blocks
  for (std::size_t at = 0; at == 0 || at < raw.size();) {
    const std::size_t n = std::min<std::size_t>(raw.size() - at, 65535);
    const bool last = at + n == raw.size();
    z.insert(z.end(), {std::uint8_t(last), std::uint8_t(n), std::uint8_t(n >> 8), std::uint8_t(~n),
                       std::uint8_t(~n >> 8)});
    z.insert(z.end(), raw.begin() + std::ptrdiff_t(at), raw.begin() + std::ptrdiff_t(at + n));
    at += n;
  }
  std::uint32_t s1 = 1, s2 = 0;
  for (std::uint8_t v : raw) {
    s1 = (s1 + v) % 65521;
    s2 = (s2 + s1) % 65521;
  }
  z.resize(z.size() + 4);
  put_be32(z, z.size() - 4, (s2 << 16) | s1);
  std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  std::vector<std::uint8_t> ihdr(13, 0);
  put_be32(ihdr, 0, w);
  put_be32(ihdr, 4, std::uint32_t(h));
  ihdr[8] = 8;
  ihdr[9] = color_type;
  const std::size_t end = png.size();
  insert_chunk(png, end, "IEND", {});
  insert_chunk(png, end, "IDAT", z);
  insert_chunk(png, end, "IHDR", ihdr);
  return png;
}

/// The fast path takes `png` and gives exactly libspng's pixels.
void expect_fast_matches_spng(const std::vector<std::uint8_t>& png, const std::string& what) {
  std::optional<ImageRGBA8> fast = detail::decode_png_fast(png);
  ASSERT_TRUE(fast.has_value()) << what << ": the fast path should take this file";
  Result<ImageRGBA8> ref = detail::decode_png_spng(png, "ref");
  ASSERT_TRUE(ref.ok()) << what << ": " << ref.status().message;
  EXPECT_EQ(fast->width, ref->width) << what;
  EXPECT_EQ(fast->height, ref->height) << what;
  EXPECT_EQ(fast->has_alpha, ref->has_alpha) << what;
  EXPECT_EQ(fast->pixels.size(), std::size_t(ref->width) * std::size_t(ref->height) * 4) << what;
  EXPECT_TRUE(fast->pixels == ref->pixels) << what;
}

TEST(PngFastPath, MatchesLibspngForEverySequenceOfRowFilters) {
  // Rows are unfiltered in pairs (y, y + 1), y even, plus a single last row when the height is
  // odd: heights 1-3 take every sequence of filters; height 51 has all 25 ordered pairs at
  // even rows and then each filter alone as the last row.
  std::vector<std::vector<int>> sequences;
  for (int n = 1; n <= 3; ++n) {
    for (int code = 0; code < (n == 1 ? 5 : n == 2 ? 25 : 125); ++code) {
      std::vector<int> f;
      for (int k = 0, c = code; k < n; ++k, c /= 5) f.push_back(c % 5);
      sequences.push_back(f);
    }
  }
  for (int last = 0; last < 5; ++last) {
    std::vector<int> f;
    for (int pair = 0; pair < 25; ++pair) f.insert(f.end(), {pair / 5, pair % 5});
    f.push_back(last);
    sequences.push_back(f);
  }
  const std::pair<std::uint8_t, std::size_t> types[] = {{0, 1}, {2, 3}, {4, 2}, {6, 4}};
  for (auto [color_type, channels] : types) {
    for (std::uint32_t w : {1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u, 9u, 31u, 33u}) {
      for (const std::vector<int>& filters : sequences) {
        const std::uint32_t h = std::uint32_t(filters.size());
        const std::vector<std::uint8_t> samples = test_samples(w, h, int(channels));
        std::string what =
            "type " + std::to_string(color_type) + " width " + std::to_string(w) + " filters";
        for (int f : filters) what.append(1, ' ').append(std::to_string(f));
        expect_fast_matches_spng(png_with_filters(samples, w, color_type, channels, filters), what);
        if (HasFailure()) return;  // one report is enough
      }
    }
  }
}

TEST(PngFastPath, ExtremeSamplesWrapAroundLikeLibspng) {
  // All-0 and all-255 runs next to each other: every prediction and sum wraps modulo 256.
  for (auto [color_type, channels] : {std::pair<std::uint8_t, std::size_t>{2, 3}, {6, 4}}) {
    const std::uint32_t w = 19, h = 10;
    std::vector<std::uint8_t> samples(w * h * channels);
    for (std::size_t i = 0; i < samples.size(); ++i) samples[i] = ((i / 5) % 3 == 1) ? 0 : 255;
    for (int f = 0; f < 5; ++f) {
      const std::vector<int> filters = {f, 4, f, 3, 1, f, 2, f, f, 4};
      expect_fast_matches_spng(
          png_with_filters(samples, w, color_type, channels, filters),
          "extremes type " + std::to_string(color_type) + " filter " + std::to_string(f));
    }
  }
}

TEST(PngFastPath, BadFilterByteInAnyRowIsDeclined) {
  const std::vector<std::uint8_t> samples = test_samples(5, 3, 3);
  for (std::size_t bad_row = 0; bad_row < 3; ++bad_row) {
    std::vector<int> filters = {4, 3, 1};
    filters[bad_row] = 5;  // filter_row treats it as None; the decoders must reject it
    const std::vector<std::uint8_t> png = png_with_filters(samples, 5, 2, 3, filters);
    EXPECT_FALSE(detail::decode_png_fast(png).has_value()) << "row " << bad_row;
    expect_same_as_spng(png, "filter 5 in row " + std::to_string(bad_row));
  }
}

TEST(SharedData, PngFastPathMatchesLibspngOnRealImages) {
  TESSERA_REQUIRE_SHARED_DATA(data);
  int taken = 0;
  for (const auto& e : fs::directory_iterator(data / "images")) {
    if (e.path().extension() != ".png") continue;
    Result<std::vector<std::uint8_t>> bytes = read_file(e.path().string());
    ASSERT_TRUE(bytes.ok());
    taken += detail::decode_png_fast(*bytes).has_value() ? 1 : 0;
    expect_same_as_spng(*bytes, e.path().filename().string());
  }
  EXPECT_GT(taken, 0);
}

}  // namespace
}  // namespace tessera::io
