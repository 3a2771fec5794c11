// Whole-file reads (regular files, pipes, devices, stdin) and writes that never replace what is
// not the user's file.
//
// A write goes one of three ways:
//   * "-": straight to standard output;
//   * an existing character or block device, FIFO or socket, or a path that reaches its object
//     through /proc (/dev/stdout, /dev/fd/N, /proc/self/fd/N): opened and written in place, no
//     temporary, no rename, since replacing it would destroy what the user pointed at;
//   * anything else: the symbolic-link chain is followed to the final target, the data goes to
//     a temporary file beside that target (created with the target's permission bits when it
//     exists), and the temporary is renamed over the target only when every byte was written.
//     A link stays a link; a dangling link gets its target created; a failure leaves the old
//     file untouched and removes the temporary.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <string_view>

#include "tessera/io.h"

namespace tessera::io {

namespace {

std::string errno_text(int e) { return std::strerror(e); }

/// Closes a file descriptor when it goes out of scope.
class Fd {
 public:
  explicit Fd(int fd) : fd_(fd) {}
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  ~Fd() {
    if (fd_ >= 0) ::close(fd_);
  }
  int get() const { return fd_; }
  /// Closes now and returns 0 or the errno of a failed close.
  int close() {
    const int r = fd_ >= 0 ? ::close(fd_) : 0;
    fd_ = -1;
    return r == 0 ? 0 : errno;
  }

 private:
  int fd_;
};

/// Writes all of `data` to `fd`; returns 0 or the errno of the failing write.
int write_all(int fd, std::span<const std::uint8_t> data) {
  std::size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    if (n == 0) return EIO;
    done += std::size_t(n);
  }
  return 0;
}

/// Reads `fd` to its end in chunks (pipes, devices, stdin: no size known in advance).
Result<std::vector<std::uint8_t>> read_stream(int fd, const std::string& name,
                                              std::uint64_t max_bytes) {
  std::vector<std::uint8_t> data;
  std::size_t used = 0;
  for (;;) {
    if (data.size() - used < 65536) data.resize(std::max<std::size_t>(data.size() * 2, 65536));
    const ssize_t n = ::read(fd, data.data() + used, data.size() - used);
    if (n < 0) {
      if (errno == EINTR) continue;
      return Status::error(ErrorCode::io_error, name + ": read error: " + errno_text(errno));
    }
    if (n == 0) break;
    used += std::size_t(n);
    if (used > max_bytes) {
      return Status::error(ErrorCode::too_large, name + ": input exceeds the limit of " +
                                                     std::to_string(max_bytes) + " bytes");
    }
  }
  data.resize(used);
  data.shrink_to_fit();
  return data;
}

std::string parent_of(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

std::string base_of(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

bool under_proc(std::string_view p) {
  return p.starts_with("/proc/") || p.starts_with("/dev/fd/") || p == "/dev/stdout" ||
         p == "/dev/stderr";
}

/// Where a write to `path` must go.
struct WriteTarget {
  std::string path;     ///< The final object: `path` itself or the end of its link chain.
  bool direct = false;  ///< Write in place (device, FIFO, socket, /proc magic link).
  bool exists = false;  ///< An existing regular file (its mode is kept).
  struct stat st {};
};

Result<WriteTarget> resolve_write_target(const std::string& path) {
  WriteTarget t;
  t.path = path;
  // Follow the chain of links by hand, so the rename replaces the final target, never a link.
  for (int hop = 0;; ++hop) {
    if (hop == 40) {
      return Status::error(ErrorCode::io_error, path + ": cannot write: " + errno_text(ELOOP));
    }
    if (under_proc(t.path)) {
      // /dev/stdout -> /proc/self/fd/1 -> "pipe:[…]" or a terminal: only the kernel can
      // follow these "magic" links, so the object is opened through the path as given.
      t.path = path;
      t.direct = true;
      break;
    }
    struct stat lst {};
    if (::lstat(t.path.c_str(), &lst) != 0) {
      if (errno == ENOENT) return t;  // a new file (or a dangling link's target)
      return Status::error(ErrorCode::io_error, path + ": cannot write: " + errno_text(errno));
    }
    if (!S_ISLNK(lst.st_mode)) break;
    std::string link(std::size_t(lst.st_size > 0 ? lst.st_size : 255) + 1, '\0');
    const ssize_t n = ::readlink(t.path.c_str(), link.data(), link.size());
    if (n < 0) {
      return Status::error(ErrorCode::io_error, path + ": cannot write: " + errno_text(errno));
    }
    link.resize(std::size_t(n));
    t.path = link.starts_with('/') ? link : parent_of(t.path) + "/" + link;
  }
  if (::stat(t.path.c_str(), &t.st) != 0) {
    if (errno == ENOENT && !t.direct) return t;
    return Status::error(ErrorCode::io_error, path + ": cannot write: " + errno_text(errno));
  }
  if (S_ISDIR(t.st.st_mode)) {
    return Status::error(ErrorCode::invalid_argument, path + ": is a directory");
  }
  if (!S_ISREG(t.st.st_mode)) t.direct = true;
  t.exists = !t.direct;
  return t;
}

Status write_direct(const std::string& path, std::span<const std::uint8_t> data) {
  Fd fd(::open(path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC));
  if (fd.get() < 0) {
    return Status::error(ErrorCode::io_error, path + ": cannot write: " + errno_text(errno));
  }
  // A regular file reached through /proc (stdout redirected to a file) is rewritten whole.
  struct stat st {};
  if (::fstat(fd.get(), &st) == 0 && S_ISREG(st.st_mode) && ::ftruncate(fd.get(), 0) != 0) {
    return Status::error(ErrorCode::io_error, path + ": cannot write: " + errno_text(errno));
  }
  int e = write_all(fd.get(), data);
  const int ce = fd.close();
  if (!e) e = ce;
  if (e) return Status::error(ErrorCode::io_error, path + ": write failed: " + errno_text(e));
  return Status::success();
}

}  // namespace

std::string io_name(const std::string& path, bool output) {
  if (path == "-") return output ? "<stdout>" : "<stdin>";
  return path;
}

Result<std::vector<std::uint8_t>> read_file(const std::string& path, std::uint64_t max_bytes) {
  if (path == "-") return read_stream(STDIN_FILENO, io_name(path, false), max_bytes);
  if (path.empty()) return Status::error(ErrorCode::io_error, "empty input file name");
  Fd fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY));
  if (fd.get() < 0) {
    return Status::error(ErrorCode::io_error, path + ": cannot open: " + errno_text(errno));
  }
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0) {
    return Status::error(ErrorCode::io_error, path + ": cannot open: " + errno_text(errno));
  }
  if (S_ISDIR(st.st_mode)) {
    return Status::error(ErrorCode::io_error, path + ": is a directory");
  }
  // Pipes, FIFOs, character devices, /dev/stdin, process substitution: read to the end.
  if (!S_ISREG(st.st_mode)) return read_stream(fd.get(), path, max_bytes);
  if (std::uint64_t(st.st_size) > max_bytes) {
    return Status::error(ErrorCode::too_large, path + ": file of " + std::to_string(st.st_size) +
                                                   " bytes exceeds the limit of " +
                                                   std::to_string(max_bytes) + " bytes");
  }
  std::vector<std::uint8_t> data(static_cast<std::size_t>(st.st_size));
  std::size_t used = 0;
  while (used < data.size()) {
    const ssize_t n = ::read(fd.get(), data.data() + used, data.size() - used);
    if (n < 0) {
      if (errno == EINTR) continue;
      return Status::error(ErrorCode::io_error, path + ": read error: " + errno_text(errno));
    }
    if (n == 0) break;  // the file shrank while it was read
    used += std::size_t(n);
  }
  data.resize(used);
  return data;
}

Status write_file_atomic(const std::string& path, std::span<const std::uint8_t> data) {
  if (path == "-") {
    if (int e = write_all(STDOUT_FILENO, data)) {
      return Status::error(ErrorCode::io_error, "<stdout>: write failed: " + errno_text(e));
    }
    return Status::success();
  }
  if (path.empty()) return Status::error(ErrorCode::invalid_argument, "empty output file name");
  Result<WriteTarget> target = resolve_write_target(path);
  if (!target) return target.status();
  if (target->direct) return write_direct(target->path, data);

  static std::atomic<unsigned> counter{0};
  // ".NAME.tmpPID-N" beside the target: hidden, same file system, short enough for NAME_MAX.
  const std::string dir = parent_of(target->path);
  const std::string tmp = dir + "/." + base_of(target->path).substr(0, 200) + ".tmp" +
                          std::to_string(::getpid()) + "-" + std::to_string(counter.fetch_add(1));
  // A new file gets 0666 less the umask, like any tool's output; an existing one keeps its mode.
  Fd fd(::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOCTTY,
               target->exists ? 0600 : 0666));
  if (fd.get() < 0) {
    return Status::error(ErrorCode::io_error, path + ": cannot write: " + errno_text(errno));
  }
  int e = 0;
  if (target->exists) {
    if (target->st.st_uid != ::geteuid() || target->st.st_gid != ::getegid()) {
      // Keep the owner where allowed (root); otherwise the file becomes the writer's, as with
      // any editor that saves through a rename.
      [[maybe_unused]] const int ignored = ::fchown(fd.get(), target->st.st_uid, target->st.st_gid);
    }
    if (::fchmod(fd.get(), target->st.st_mode & 07777) != 0) e = errno;
  }
  if (!e) e = write_all(fd.get(), data);
  const int ce = fd.close();
  if (!e) e = ce;
  if (e) {
    ::unlink(tmp.c_str());
    return Status::error(ErrorCode::io_error, path + ": write failed: " + errno_text(e));
  }
  if (::rename(tmp.c_str(), target->path.c_str()) != 0) {
    e = errno;
    ::unlink(tmp.c_str());
    return Status::error(ErrorCode::io_error, path + ": cannot replace: " + errno_text(e));
  }
  return Status::success();
}

}  // namespace tessera::io
