// libFuzzer target, differential: tessera::io::decode_image (libdeflate fast path, falling back to
// libspng) against the libspng path alone, on arbitrary bytes. Both must fail with the same
// message or succeed with the same size, alpha flag and pixels; and whenever the fast path
// accepts a file, libspng must accept it with the same pixels. Each input is checked twice:
// as it is, and with every chunk CRC recomputed, so that mutations inside IHDR and IDAT reach
// the inflaters and filters instead of stopping at a CRC mismatch.
#include <zlib.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <span>
#include <vector>

#include "io/png_fast.h"
#include "tessera/io.h"

namespace {

bool same(const tessera::ImageRGBA8& a, const tessera::ImageRGBA8& b) {
  return a.width == b.width && a.height == b.height && a.has_alpha == b.has_alpha &&
         a.pixels == b.pixels;
}

std::uint32_t be32(const std::uint8_t* p) {
  return (std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) | (std::uint32_t(p[2]) << 8) |
         std::uint32_t(p[3]);
}

std::vector<std::uint8_t> with_fixed_crcs(std::span<const std::uint8_t> in) {
  std::vector<std::uint8_t> b(in.begin(), in.end());
  for (std::size_t pos = 8; b.size() - pos >= 12;) {
    const std::uint32_t len = be32(&b[pos]);
    if (len > b.size() - pos - 12) break;
    const auto crc = std::uint32_t(crc32(0, &b[pos + 4], uInt(len + 4)));
    for (std::size_t k = 0; k < 4; ++k) b[pos + 8 + len + k] = std::uint8_t(crc >> (24 - 8 * k));
    pos += 12 + std::size_t(len);
  }
  return b;
}

void check(std::span<const std::uint8_t> bytes) {
  const std::optional<tessera::ImageRGBA8> fast = tessera::io::detail::decode_png_fast(bytes);
  const tessera::Result<tessera::ImageRGBA8> ref = tessera::io::detail::decode_png_spng(bytes, "f");
  if (fast && (!ref || !same(*fast, *ref))) std::abort();
  const tessera::Result<tessera::ImageRGBA8> got = tessera::io::decode_image(bytes, "f");
  if (got.ok() != ref.ok()) std::abort();
  if (got.ok() ? !same(*got, *ref) : got.status().message != ref.status().message) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> bytes(data, size);
  if (tessera::io::detect_image_format(bytes) != tessera::io::ImageFormat::png) return 0;
  check(bytes);
  check(with_fixed_crcs(bytes));
  return 0;
}
