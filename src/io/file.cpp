// Whole-file reads and atomic writes.
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "tessera/io.h"

namespace tessera {

namespace {
struct FileCloser {
  void operator()(std::FILE* f) const {
    if (f) std::fclose(f);
  }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

std::string errno_text() { return std::strerror(errno); }
}  // namespace

Result<std::vector<std::uint8_t>> read_file(const std::string& path, std::uint64_t max_bytes) {
  FilePtr f(std::fopen(path.c_str(), "rb"));
  if (!f) return Status::error(ErrorCode::io_error, path + ": cannot open: " + errno_text());
  if (std::fseek(f.get(), 0, SEEK_END) != 0) {
    return Status::error(ErrorCode::io_error, path + ": cannot seek: " + errno_text());
  }
  const long size = std::ftell(f.get());
  if (size < 0) {
    return Status::error(ErrorCode::io_error, path + ": not a regular file or unreadable");
  }
  if (std::uint64_t(size) > max_bytes) {
    return Status::error(ErrorCode::too_large, path + ": file of " + std::to_string(size) +
                                                   " bytes exceeds the limit of " +
                                                   std::to_string(max_bytes) + " bytes");
  }
  std::rewind(f.get());
  std::vector<std::uint8_t> data(static_cast<std::size_t>(size));
  if (size > 0 && std::fread(data.data(), 1, data.size(), f.get()) != data.size()) {
    return Status::error(ErrorCode::io_error, path + ": read error: " + errno_text());
  }
  return data;
}

Status write_file_atomic(const std::string& path, std::span<const std::uint8_t> data) {
  static std::atomic<unsigned> counter{0};
  const std::string tmp = path + ".tmp." + std::to_string(::getpid()) + "." +
                          std::to_string(counter.fetch_add(1));
  FilePtr f(std::fopen(tmp.c_str(), "wb"));
  if (!f) return Status::error(ErrorCode::io_error, path + ": cannot write: " + errno_text());
  bool good = data.empty() || std::fwrite(data.data(), 1, data.size(), f.get()) == data.size();
  good = (std::fflush(f.get()) == 0) && good;
  const int saved_errno = errno;
  good = (std::fclose(f.release()) == 0) && good;
  if (!good) {
    std::remove(tmp.c_str());
    return Status::error(ErrorCode::io_error,
                         path + ": write failed: " + std::strerror(saved_errno ? saved_errno : EIO));
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string why = errno_text();
    std::remove(tmp.c_str());
    return Status::error(ErrorCode::io_error, path + ": cannot replace: " + why);
  }
  return Status::success();
}

}  // namespace tessera
