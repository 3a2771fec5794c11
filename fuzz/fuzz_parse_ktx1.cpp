// libFuzzer target: KTX 1.1 parsing on arbitrary bytes. A file that parses must decode every
// image (level, layer, face), re-serialise and parse back to the same texture
// (container_round_trip.h).
#include <cstddef>
#include <cstdint>

#include "container_round_trip.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return tessera::fuzz::container_round_trip(
      {data, size}, tessera::texture_file::parse_ktx1,
      [](const tessera::texture_file::CompressedTexture& t) {
        return tessera::texture_file::serialise_ktx1(t);
      },
      "fuzz.ktx", "again.ktx");
}
