// Internal to src/io: the two PNG decoders behind tessera::io::decode_image (8-bit output).
//
// decode_image tries `decode_png_fast` first and falls back to `decode_png_spng` whenever the
// fast path declines, so the result (pixels, has_alpha, or the error message) is always the
// one libspng would give. Exposed here only for tests/unit/io_test.cpp,
// tests/unit/io_png_fast_test.cpp and fuzz/fuzz_png_diff.cpp.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "tessera/core.h"

namespace tessera::io::detail {

/// DEFLATE cannot expand data by more than 1032:1 (258 bytes from a 2-bit length/distance
/// pair): both PNG decoders refuse a header whose image the compressed bytes cannot fill.
inline constexpr std::uint64_t kMaxDeflateRatio = 1032;

/// The common case only, with libdeflate instead of zlib: 8-bit, non-interlaced grey (0),
/// RGB (2), grey+alpha (4) or RGBA (6) without tRNS or PLTE, whose chunks are all
/// well-formed (every CRC checked, IHDR first, consecutive IDATs, IEND last) and whose
/// ancillary chunks cannot change the pixels or make libspng fail (a bounded amount of
/// iCCP/text; no tRNS, eXIf, sPLT). The zlib stream must fill exactly height * (1 + row bytes)
/// bytes, use all the IDAT bytes and pass its Adler-32 check; every filter byte must be 0-4.
/// Returns std::nullopt for anything else, corrupt files included: the caller then decodes
/// with libspng, which also writes the error message. Nothing is allocated from the header's
/// size before the compressed data is known to be large enough to fill it.
///
/// Known difference, on corrupt data only: libdeflate accepts a few Huffman code sets that
/// zlib rejects (an incomplete code with a single length-1 codeword in the code-length code,
/// an empty code); such a stream still has to pass the Adler-32 check over its output.
std::optional<ImageRGBA8> decode_png_fast(std::span<const std::uint8_t> bytes);

/// libspng alone (the reference the fast path must match): any PNG, 8-bit RGBA output.
/// `name` prefixes every error message.
Result<ImageRGBA8> decode_png_spng(std::span<const std::uint8_t> bytes, const std::string& name);

}  // namespace tessera::io::detail
