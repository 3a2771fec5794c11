// Byte-level helpers and error statuses shared by the PVR v3, KTX 1.1 and KTX 2.0 readers and
// writers (internal).
#pragma once

#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include "tessera/core.h"

namespace tessera::texture_file::container {

inline std::uint32_t load_u32(std::span<const std::uint8_t> b, std::size_t at, bool swap = false) {
  std::uint32_t v = std::uint32_t(b[at]) | std::uint32_t(b[at + 1]) << 8 |
                    std::uint32_t(b[at + 2]) << 16 | std::uint32_t(b[at + 3]) << 24;
  if (swap) {
    v = (v >> 24) | ((v >> 8) & 0xFF00u) | ((v << 8) & 0xFF0000u) | (v << 24);
  }
  return v;
}

inline std::uint64_t load_u64(std::span<const std::uint8_t> b, std::size_t at) {
  return std::uint64_t(load_u32(b, at)) | std::uint64_t(load_u32(b, at + 4)) << 32;
}

inline void store_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(std::uint8_t(v >> (8 * i)));
}

inline void store_u64(std::vector<std::uint8_t>& out, std::uint64_t v) {
  store_u32(out, std::uint32_t(v));
  store_u32(out, std::uint32_t(v >> 32));
}

inline std::string hex32(std::uint32_t v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%08X", v);
  return buf;
}

inline std::string plural_bytes(std::uint64_t n) {
  return std::to_string(n) + (n == 1 ? " byte" : " bytes");
}

/// A corrupt_data status "NAME: WHAT" (NAME: the file or stream being read).
inline Status corrupt(const std::string& name, const std::string& what) {
  return Status::error(ErrorCode::corrupt_data, name + ": " + what);
}

/// An unsupported status "NAME: WHAT".
inline Status unsupported(const std::string& name, const std::string& what) {
  return Status::error(ErrorCode::unsupported, name + ": " + what);
}

}  // namespace tessera::texture_file::container
