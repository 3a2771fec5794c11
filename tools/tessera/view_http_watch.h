// tessera view's HTTP module: a watch over the server's connections (a thread, every 20 ms)
// that resets a connection that has received more than any page sends (an endless request
// line) or that takes longer than a deadline to send a request line and its headers (a client
// that sends one byte every 2 s, under the per-read timeout, would hold its thread forever).
// cpp-httplib 0.11 has no deadline per request; the watch reads each connection's bytes received
// from the kernel (TCP_INFO) and learns from the server's routing hooks where requests end.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <thread>

namespace tessera::cli {

class ConnectionWatch {
 public:
  /// Watches connections to 127.0.0.1:`port` until destroyed.
  ConnectionWatch(int port, std::uint64_t flood_cap, std::chrono::milliseconds header_deadline);
  ConnectionWatch(const ConnectionWatch&) = delete;
  ConnectionWatch& operator=(const ConnectionWatch&) = delete;
  ~ConnectionWatch();

  /// The request of the connection from `addr`:`port` has its headers (the pre-routing hook):
  /// its body and reply are not timed here (a body has its own cap and read timeout).
  void headers_read(const std::string& addr, int port);
  /// Its reply is being written (the post-routing hook): what it receives next is a new request.
  void request_done(const std::string& addr, int port);

 private:
  struct Connection {
    std::uint64_t mark = 0;  ///< Bytes received when its last request ended.
    bool routed = false;     ///< Between headers_read and request_done.
    bool remark = false;     ///< request_done: take the mark on the next scan.
    bool seen = false;       ///< Found by the current scan.
    std::chrono::steady_clock::time_point start{};  ///< First byte of a pending request.
    bool started = false;
  };
  void scan();

  const int port_;
  const std::uint64_t flood_cap_;
  const std::chrono::milliseconds deadline_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::map<std::string, Connection> connections_;  ///< By "addr:port" of the peer.
  std::thread thread_;
};

}  // namespace tessera::cli
