// tessera view's HTTP module: the connection watch (view_http_watch.h).
#include "view_http_watch.h"

#include <arpa/inet.h>
#include <dirent.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace tessera::cli {

namespace {

/// The bytes connection `fd` has received, from TCP_INFO's tcpi_bytes_received (Linux 4.1 and
/// later, at byte 128 of the kernel's struct tcp_info, a fixed ABI; glibc's <netinet/tcp.h>
/// declares the struct only to byte 104); -1 when unknown or no longer established.
long long bytes_received(int fd) {
  alignas(8) unsigned char info[256] = {};
  socklen_t length = sizeof info;
  if (getsockopt(fd, IPPROTO_TCP, TCP_INFO, info, &length) != 0 || length < 136) return -1;
  if (info[0] != 1) return -1;  // tcpi_state: not TCP_ESTABLISHED (already shut down, say)
  std::uint64_t bytes = 0;
  std::memcpy(&bytes, info + 128, sizeof bytes);
  return static_cast<long long>(bytes);
}

/// Resets connection `fd` rather than closing it in order: its reads end at once (SHUT_RD)
/// and, lingering 0 s, cpp-httplib's close answers the sender with RST, so it stops sending.
void reset(int fd) {
  const linger now{1, 0};
  setsockopt(fd, SOL_SOCKET, SO_LINGER, &now, sizeof now);
  shutdown(fd, SHUT_RD);
}

std::string peer_key(const std::string& addr, int port) {
  return addr + ":" + std::to_string(port);
}

}  // namespace

ConnectionWatch::ConnectionWatch(int port, std::uint64_t flood_cap,
                                 std::chrono::milliseconds header_deadline)
    : port_(port), flood_cap_(flood_cap), deadline_(header_deadline), thread_([this] {
        std::unique_lock<std::mutex> lock(mutex_);
        while (!stop_) {
          scan();
          wake_.wait_for(lock, std::chrono::milliseconds(20), [this] { return stop_; });
        }
      }) {}

ConnectionWatch::~ConnectionWatch() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void ConnectionWatch::headers_read(const std::string& addr, int port) {
  std::lock_guard<std::mutex> lock(mutex_);
  Connection& c = connections_[peer_key(addr, port)];
  c.routed = true;
  c.started = false;
}

void ConnectionWatch::request_done(const std::string& addr, int port) {
  std::lock_guard<std::mutex> lock(mutex_);
  Connection& c = connections_[peer_key(addr, port)];
  c.routed = false;
  c.remark = true;
  c.started = false;
}

/// One pass over this process's sockets (under mutex_, so the hooks never race a pass): the
/// connections to this server, each checked against the flood cap and the header deadline;
/// entries of connections that are gone are dropped.
void ConnectionWatch::scan() {
  DIR* dir = opendir("/proc/self/fd");
  if (!dir) return;
  const auto now = std::chrono::steady_clock::now();
  for (auto& [key, c] : connections_) c.seen = false;
  while (const dirent* e = readdir(dir)) {
    char* end = nullptr;
    const long fd = std::strtol(e->d_name, &end, 10);
    if (end == e->d_name || *end != '\0' || fd == dirfd(dir)) continue;
    sockaddr_in local{}, peer{};
    socklen_t n = sizeof local, m = sizeof peer;
    if (getsockname(int(fd), reinterpret_cast<sockaddr*>(&local), &n) != 0 ||
        local.sin_family != AF_INET || ntohs(local.sin_port) != port_ ||
        getpeername(int(fd), reinterpret_cast<sockaddr*>(&peer), &m) != 0) {
      continue;  // not a connection to this server (the listener has no peer)
    }
    const long long got = bytes_received(int(fd));
    if (got < 0) continue;
    const std::uint64_t bytes = std::uint64_t(got);
    char addr[INET_ADDRSTRLEN] = {};
    inet_ntop(AF_INET, &peer.sin_addr, addr, sizeof addr);
    Connection& c = connections_[peer_key(addr, ntohs(peer.sin_port))];
    c.seen = true;
    if (c.remark) {
      c.mark = bytes;
      c.remark = false;
    }
    if (c.routed || bytes <= c.mark) continue;  // a body is capped by its route
    if (bytes - c.mark > flood_cap_) {
      reset(int(fd));
      c.mark = bytes;
      std::fprintf(stderr, "tessera view: a connection sent over %llu MiB: closed\n",
                   static_cast<unsigned long long>(flood_cap_ >> 20));
      continue;
    }
    if (!c.started) {
      c.started = true;
      c.start = now;
    } else if (now - c.start > deadline_) {
      reset(int(fd));
      c.started = false;
      c.mark = bytes;
      std::fprintf(stderr,
                   "tessera view: a connection took over %lld s to send a request's headers: "
                   "closed\n",
                   static_cast<long long>(deadline_.count() / 1000));
    }
  }
  closedir(dir);
  for (auto it = connections_.begin(); it != connections_.end();) {
    it = it->second.seen ? std::next(it) : connections_.erase(it);
  }
}

}  // namespace tessera::cli
