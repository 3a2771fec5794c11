// KTX 2.0 container: not implemented yet (the reader and writer are being written); both
// entry points say so in one line.
#include "tessera/texture_file.h"

namespace tessera::texture_file {

Result<CompressedTexture> parse_ktx2(std::span<const std::uint8_t>, const std::string& name) {
  return Status::error(ErrorCode::unsupported, name + ": KTX 2.0 files are not supported yet");
}

Result<std::vector<std::uint8_t>> serialise_ktx2(const CompressedTexture&, const Ktx2Options&) {
  return Status::error(ErrorCode::unsupported, "KTX 2.0 output is not supported yet");
}

}  // namespace tessera::texture_file
