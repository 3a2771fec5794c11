// tessera view: the interface between the CLI and its HTTP server module. The server (cpp-httplib,
// which pulls in OpenSSL and Brotli) lives in a separate shared module, tessera-view-http.so,
// that `tessera view` loads with dlopen when it serves: linked into the CLI, those libraries
// would double the start-up time of every other command. The CLI implements ViewBackend (the
// inputs, the encodes, the blobs); the module does HTTP, the guards and the signals.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace tessera::cli {

/// What the server asks of the view; called from the server's threads (thread-safe).
class ViewBackend {
 public:
  virtual ~ViewBackend() = default;
  /// The page (HTML) for a browser holding `token`.
  virtual std::string page(const std::string& token) = 0;
  /// The blob `key` (its MIME type and bytes); false when there is none.
  virtual bool blob(const std::string& key, std::string& mime, std::string& bytes) = 0;
  /// Starts (or finds) the encode a request body asks for; returns the HTTP status, `json` the
  /// reply (the job, or {"error": ...}).
  virtual int encode(const std::string& body, std::string& json) = 0;
  /// The state of job `id`; returns the HTTP status, `json` the reply.
  virtual int job(const std::string& id, std::string& json) = 0;
  /// Pins (or unpins) result `id`: a pinned result is never evicted under the memory budget.
  virtual int pin(const std::string& id, bool pinned, std::string& json) = 0;
  /// Every input with its thumbnail and, at the default settings, its PSNR and max error, and
  /// the encodes of those not measured yet queued (as room allows); `json` the reply.
  virtual int overview(std::string& json) = 0;
  /// Adds a file's `bytes` (an image or texture named `name`) as a new input; `json` the reply
  /// ({"input": ..., "results": [...]}, an input with "error" when the bytes are not readable).
  virtual int open(const std::string& name, std::string bytes, std::string& json) = 0;
  /// Result `id` as `as` ("pvr", "ktx", "ktx2", "png": decoded level 0, "heatmap": its PNG).
  virtual int download(const std::string& id, const std::string& as, std::string& mime,
                       std::string& bytes, std::string& json) = 0;
  /// Opened inputs (for the start-up line).
  virtual std::size_t input_count() const = 0;
};

/// How the module serves.
struct ViewHttpOptions {
  int port = 0;        ///< 0 = a random free port.
  bool open = true;    ///< Start the desktop's browser (xdg-open) when there is a display.
  bool quiet = false;  ///< Print only the URL.
  std::size_t max_body = 64 * 1024;  ///< Larger request bodies get 413 (chunked ones too).
  std::size_t max_open_body = std::size_t{256} << 20;  ///< The same for POST /api/open.
  int header_deadline_s = 10;         ///< A request line and headers that take longer: reset.
  int read_timeout_s = 3;             ///< A read that waits longer ends its connection.
  std::size_t max_connections = 128;  ///< Connections served at once (a thread each).
  /// A connection that receives more is shut down (an endless request line).
  std::uint64_t max_connection_bytes = std::uint64_t{4} << 20;
};

/// The module's entry point (C linkage, found with dlsym): serves on 127.0.0.1 until SIGINT or
/// SIGTERM, printing the URL with its token on stdout; returns the exit code.
using ViewHttpServe = int (*)(ViewBackend* backend, const ViewHttpOptions* options);
inline constexpr const char* kViewHttpServeSymbol = "tessera_view_http_serve";

}  // namespace tessera::cli
