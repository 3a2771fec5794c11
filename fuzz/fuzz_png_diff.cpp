// libFuzzer target, differential: tessera::decode_image (libdeflate fast path, falling back to
// libspng) against the libspng path alone, on arbitrary bytes. Both must fail with the same
// message or succeed with the same size, alpha flag and pixels; and whenever the fast path
// accepts a file, libspng must accept it with the same pixels.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <span>

#include "io/png_fast.h"
#include "tessera/io.h"

namespace {

bool same(const tessera::ImageRGBA8& a, const tessera::ImageRGBA8& b) {
  return a.width == b.width && a.height == b.height && a.has_alpha == b.has_alpha &&
         a.pixels == b.pixels;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> bytes(data, size);
  if (tessera::detect_image_format(bytes) != tessera::ImageFormat::png) return 0;
  const std::optional<tessera::ImageRGBA8> fast = tessera::detail::decode_png_fast(bytes);
  const tessera::Result<tessera::ImageRGBA8> ref = tessera::detail::decode_png_spng(bytes, "f");
  if (fast && (!ref || !same(*fast, *ref))) std::abort();
  const tessera::Result<tessera::ImageRGBA8> got = tessera::decode_image(bytes, "f");
  if (got.ok() != ref.ok()) std::abort();
  if (got.ok() ? !same(*got, *ref) : got.status().message != ref.status().message) std::abort();
  return 0;
}
