// tessera view's HTTP server module (tessera-view-http.so, loaded by `tessera view`): cpp-httplib
// bound to 127.0.0.1 only, a random token that every request carries (?token=), Host and
// Origin checked exactly against DNS rebinding, nothing routed but the page, the blobs of the
// opened inputs' results, the encode/job/pin API and the workflow's overview/open/download
// (view_http_flow.cpp); clean shutdown on SIGINT and SIGTERM.
//
// What it holds against (the README, `tessera view`): the port is never shared (no SO_REUSEPORT);
// every request body is refused before it is read unless it is an encode or open request, whose
// body is read through its route's cap that stops it as it streams (chunked or not: 413,
// connection closed); reads time out (ViewHttpOptions::read_timeout_s) and each connection has
// its own thread from a pool that grows to max_connections, so clients that send half a request
// cannot hold up the others; one Host header; a connection that receives more request line and
// headers than any page sends (an endless line), or takes longer than header_deadline_s to send
// them (a byte at a time), is reset (view_http_watch.cpp). See view_http.h for why this is a
// module.
#include "view_http.h"

#include <arpa/inet.h>
#include <dirent.h>
#include <fcntl.h>
#include <httplib.h>
#include <netinet/in.h>
#include <pthread.h>
#include <spawn.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <mutex>
#include <random>
#include <thread>
#include <vector>

#include "view_http_flow.h"
#include "view_http_watch.h"

extern char** environ;

namespace tessera::cli {

namespace {

std::string random_token() {
  std::random_device rd;  // /dev/urandom on Linux
  static constexpr char kHex[] = "0123456789abcdef";
  std::string t;
  for (int i = 0; i < 48; ++i) t += kHex[rd() & 15];
  return t;
}

bool same_secret(const std::string& a, const std::string& b) {
  if (a.size() != b.size()) return false;
  unsigned char d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d |= static_cast<unsigned char>(a[i] ^ b[i]);
  return d == 0;
}

}  // namespace

/// {"error": message} with quotes and backslashes escaped and anything outside printable ASCII
/// replaced (messages are this file's own words plus a header value, which may hold anything,
/// not UTF-8 included).
std::string error_json(const std::string& message) {
  std::string out = "{\"error\":\"";
  for (char c : message) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (u < 0x20 || u >= 0x7f) {
      out += '?';
    } else {
      out += c;
    }
  }
  return out + "\"}";
}

void reply(httplib::Response& res, int status, const std::string& json) {
  res.status = status;
  res.set_content(json, "application/json");
}

/// Replies and then closes the connection: for a request whose body is not read (or not read
/// to its end), which would otherwise be parsed as the next request. cpp-httplib closes a
/// keep-alive connection when writing a response fails; a content provider that writes the
/// whole reply and then reports failure makes it do so after the reply is sent.
void reply_and_close(httplib::Response& res, int status, const std::string& json) {
  res.status = status;
  res.set_header("Connection", "close");
  auto body = std::make_shared<const std::string>(json);
  res.set_content_provider(body->size(), "application/json",
                           [body](std::size_t offset, std::size_t, httplib::DataSink& sink) {
                             if (offset < body->size()) {
                               sink.write(body->data() + offset, body->size() - offset);
                             }
                             return false;
                           });
}

namespace {

/// True when `req` may carry a body: a method cpp-httplib reads one for, or a length or a
/// transfer coding.
bool may_have_body(const httplib::Request& req) {
  return req.method == "POST" || req.method == "PUT" || req.method == "PATCH" ||
         req.method == "DELETE" || req.method == "PRI" || req.has_header("Transfer-Encoding") ||
         (req.has_header("Content-Length") && req.get_header_value("Content-Length") != "0");
}

/// The checks every request passes before routing (and before its body is read): one Host,
/// naming this server exactly, and any Origin too (a page of another site that rebinds its
/// name to 127.0.0.1 sends its own); the token; then a body only where one is read (POST
/// /api/encode, /api/open), its declared length within the route's cap. Every refusal closes the
/// connection.
httplib::Server::HandlerResponse guard(const httplib::Request& req, httplib::Response& res,
                                       int port, const std::string& token, std::size_t max_body) {
  const std::string p = std::to_string(port);
  res.set_header("Cache-Control", "no-store");
  res.set_header("X-Content-Type-Options", "nosniff");
  res.set_header("Referrer-Policy", "no-referrer");
  using HR = httplib::Server::HandlerResponse;
  for (const char* once : {"Host", "Origin", "Content-Length", "Transfer-Encoding"}) {
    if (req.get_header_value_count(once) > 1) {
      reply_and_close(res, 400, error_json(std::string("bad request: more than one ") + once));
      return HR::Handled;
    }
  }
  const std::string host = req.get_header_value("Host");
  if (host != "127.0.0.1:" + p && host != "localhost:" + p) {
    reply_and_close(res, 403, error_json("forbidden: Host '" + host + "' is not this server"));
    return HR::Handled;
  }
  if (req.has_header("Origin")) {
    const std::string origin = req.get_header_value("Origin");
    if (origin != "http://127.0.0.1:" + p && origin != "http://localhost:" + p) {
      reply_and_close(res, 403,
                      error_json("forbidden: Origin '" + origin + "' is not this server"));
      return HR::Handled;
    }
  }
  if (!same_secret(req.get_param_value("token"), token)) {
    reply_and_close(res, 403,
                    error_json("forbidden: a missing or wrong token (use the URL tessera view "
                               "printed)"));
    return HR::Handled;
  }
  if (!may_have_body(req)) return HR::Unhandled;
  if (req.method != "POST" || (req.path != "/api/encode" && req.path != "/api/open")) {
    reply_and_close(res, 404, error_json("not found"));
    return HR::Handled;
  }
  if (req.has_header("Transfer-Encoding")) {
    if (req.has_header("Content-Length") ||
        req.get_header_value("Transfer-Encoding") != "chunked") {
      reply_and_close(res, 400, error_json("bad request: a transfer coding other than chunked"));
      return HR::Handled;
    }
    return HR::Unhandled;  // read through the cap (add_routes)
  }
  const std::string length = req.get_header_value("Content-Length");
  if (!length.empty()) {
    if (length.find_first_not_of("0123456789") != std::string::npos || length.size() > 18) {
      reply_and_close(res, length.size() > 18 ? 413 : 400, error_json("bad Content-Length"));
      return HR::Handled;
    }
    if (std::stoull(length) > max_body) {
      reply_and_close(res, 413, error_json("request body too large"));
      return HR::Handled;
    }
  }
  return HR::Unhandled;
}

void add_routes(httplib::Server& svr, ViewBackend& backend, const std::string& token,
                std::size_t max_body) {
  svr.Get("/", [&backend, token](const httplib::Request&, httplib::Response& res) {
    res.set_header("Content-Security-Policy",
                   "default-src 'none'; script-src 'unsafe-inline'; style-src 'unsafe-inline'; "
                   "img-src 'self' data: blob:; connect-src 'self' data:");
    res.set_content(backend.page(token), "text/html; charset=utf-8");
  });
  svr.Get(R"(/blob/([0-9a-f]{16}))",
          [&backend](const httplib::Request& req, httplib::Response& res) {
            std::string mime, bytes;
            if (!backend.blob(req.matches[1], mime, bytes))
              return reply(res, 404, error_json("no such blob"));
            res.set_content(bytes, mime.c_str());
          });
  svr.Get("/api/job", [&backend](const httplib::Request& req, httplib::Response& res) {
    std::string json;
    const int status = backend.job(req.get_param_value("id"), json);
    reply(res, status, json);
  });
  svr.Get("/api/pin", [&backend](const httplib::Request& req, httplib::Response& res) {
    std::string json;
    const int status =
        backend.pin(req.get_param_value("id"), req.get_param_value("pinned") != "0", json);
    reply(res, status, json);
  });
  // The body is read through a cap as it streams (a chunked body has no length to check
  // first): past `max_body` the reading stops, 413, and the connection closes.
  svr.Post("/api/encode", [&backend, max_body](const httplib::Request&, httplib::Response& res,
                                               const httplib::ContentReader& read) {
    std::string body;
    bool over = false;
    const bool ok = read([&](const char* data, std::size_t n) {
      if (body.size() + n > max_body) {
        over = true;
        return false;
      }
      body.append(data, n);
      return true;
    });
    if (over) return reply_and_close(res, 413, error_json("request body too large"));
    if (!ok) return reply_and_close(res, 400, error_json("bad request: the body did not arrive"));
    std::string json;
    const int status = backend.encode(body, json);
    reply(res, status, json);
  });
  svr.set_error_handler([](const httplib::Request&, httplib::Response& res) {
    if (res.body.empty() && !res.content_provider_) {
      res.set_content(error_json(res.status == 413 ? "request body too large" : "not found"),
                      "application/json");
    }
  });
  svr.set_exception_handler(
      [](const httplib::Request& req, httplib::Response& res, std::exception_ptr ep) {
        std::string what = "unknown";
        try {
          if (ep) std::rethrow_exception(ep);
        } catch (const std::exception& e) {
          what = e.what();
        } catch (...) {
        }
        std::fprintf(stderr, "tessera view: %s %s: internal error: %s\n", req.method.c_str(),
                     req.path.c_str(), what.c_str());
        reply(res, 500, error_json("internal error: " + what));
      });
}

/// The connection threads: one per connection, the pool growing on demand to `max_threads`
/// (an idle keep-alive connection or one that sends half a request holds only its own thread,
/// until its read times out). With every thread busy, up to `max_waiting` connections wait
/// for one; beyond that the accept loop waits here and new connections stay in the kernel's
/// backlog.
class ConnectionPool final : public httplib::TaskQueue {
 public:
  ConnectionPool(std::size_t max_threads, std::size_t max_waiting)
      : max_threads_(max_threads), max_waiting_(max_waiting) {}
  ConnectionPool(const ConnectionPool&) = delete;
  ConnectionPool& operator=(const ConnectionPool&) = delete;
  ~ConnectionPool() override = default;

  void enqueue(std::function<void()> fn) override {
    std::unique_lock<std::mutex> lock(mutex_);
    room_.wait(lock, [&] { return jobs_.size() < max_waiting_; });
    jobs_.push_back(std::move(fn));
    if (jobs_.size() > idle_ && threads_.size() < max_threads_) {
      threads_.emplace_back([this] { work(); });
    } else {
      ready_.notify_one();
    }
  }

  void shutdown() override {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    ready_.notify_all();
    for (std::thread& t : threads_) t.join();
  }

 private:
  void work() {
    for (;;) {
      std::function<void()> fn;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        ++idle_;
        ready_.wait(lock, [&] { return stopping_ || !jobs_.empty(); });
        --idle_;
        if (jobs_.empty()) return;  // stopping, nothing left
        fn = std::move(jobs_.front());
        jobs_.pop_front();
      }
      room_.notify_one();
      fn();
    }
  }

  const std::size_t max_threads_, max_waiting_;
  std::mutex mutex_;
  std::condition_variable ready_, room_;
  std::deque<std::function<void()>> jobs_;
  std::vector<std::thread> threads_;
  std::size_t idle_ = 0;
  bool stopping_ = false;
};

/// The listening socket's options: SO_REUSEADDR only (a restart need not wait out TIME_WAIT).
/// cpp-httplib's default sets SO_REUSEPORT, which lets a second process listen on the same
/// port and take a share of the connections: the token's requests among them.
void exclusive_socket_options(socket_t sock) {
  int yes = 1;
  setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
}

/// A private directory (0700) with a page (0600) that sends the browser on to `url`, so that
/// the browser is started with the page's path, not the token (a process's arguments are
/// visible to every user in `ps`). "" when it cannot be made.
std::string write_redirect_page(const std::string& url, std::string& dir) {
  const char* tmp = std::getenv("TMPDIR");
  std::string templ = std::string(tmp && *tmp ? tmp : "/tmp") + "/tessera-view-XXXXXX";
  if (!mkdtemp(templ.data())) return "";
  dir = templ;
  const std::string path = dir + "/open.html";
  const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) return "";
  const std::string page =
      "<!doctype html><meta charset=\"utf-8\"><meta name=\"referrer\" content=\"no-referrer\">"
      "<meta http-equiv=\"refresh\" content=\"0;url=" +
      url + "\"><title>tessera view</title><a href=\"" + url + "\">tessera view</a>\n";
  const bool ok = write(fd, page.data(), page.size()) == static_cast<ssize_t>(page.size());
  close(fd);
  return ok ? path : "";
}

/// Opens `url` in the desktop's browser when there is a desktop, not waiting: the opener
/// ($TESSERA_VIEW_OPENER, else xdg-open) gets the path of a private page that redirects to the
/// URL, never the URL itself. `dir` gets the page's directory (removed when serving ends).
void open_browser(const std::string& url, std::string& dir) {
  if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY")) return;
  std::string page = write_redirect_page(url, dir);
  if (page.empty()) {
    std::fprintf(stderr,
                 "tessera view: cannot write the page that opens the browser; open the "
                 "URL above\n");
    return;
  }
  const char* env = std::getenv("TESSERA_VIEW_OPENER");
  std::string prog = env && *env ? env : "xdg-open";
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
  char* argv[] = {prog.data(), page.data(), nullptr};
  pid_t pid = 0;
  posix_spawnp(&pid, prog.c_str(), &fa, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&fa);
}

}  // namespace

}  // namespace tessera::cli

extern "C" __attribute__((visibility("default"))) int tessera_view_http_serve(
    tessera::cli::ViewBackend* backend, const tessera::cli::ViewHttpOptions* options) {
  using namespace tessera::cli;
  // SIGINT and SIGTERM go to one waiting thread (blocked everywhere else, before any thread
  // starts), which stops the server; SIGPIPE (a closed browser tab) is ignored.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);
  std::signal(SIGPIPE, SIG_IGN);

  httplib::Server svr;
  svr.set_socket_options(exclusive_socket_options);
  // Declared lengths are checked in the guard before reading, each route's bodies capped as
  // they stream; this is cpp-httplib's own cap, the largest of them.
  svr.set_payload_max_length(std::max(options->max_body, options->max_open_body));
  // A browser holds idle keep-alive connections: short timeouts let Ctrl-C end the server at
  // once rather than after httplib's default 5 s. A read that waits longer than
  // read_timeout_s ends its connection (a client sending half a request).
  svr.set_keep_alive_timeout(1);
  svr.set_keep_alive_max_count(100);
  svr.set_read_timeout(options->read_timeout_s, 0);
  svr.set_write_timeout(10, 0);  // a browser reads what it asked for at once
  const std::size_t max_connections = options->max_connections;
  svr.new_task_queue = [max_connections] {
    return new ConnectionPool(max_connections, max_connections);
  };
  const int port = options->port
                       ? (svr.bind_to_port("127.0.0.1", options->port) ? options->port : -1)
                       : svr.bind_to_any_port("127.0.0.1");
  if (port <= 0) {
    std::fprintf(stderr,
                 "tessera: view: cannot listen on 127.0.0.1:%d: in use (choose another "
                 "--port, or leave it out for a free one)\n",
                 options->port);
    return 1;
  }
  const std::string token = random_token();
  const std::size_t max_body = options->max_body, max_open = options->max_open_body;
  ConnectionWatch watch(port, options->max_connection_bytes,
                        std::chrono::seconds(options->header_deadline_s));
  svr.set_pre_routing_handler([port, token, max_body, max_open, &watch](const httplib::Request& req,
                                                                        httplib::Response& res) {
    watch.headers_read(req.remote_addr, req.remote_port);
    return guard(req, res, port, token, req.path == "/api/open" ? max_open : max_body);
  });
  svr.set_post_routing_handler([&watch](const httplib::Request& req, httplib::Response&) {
    watch.request_done(req.remote_addr, req.remote_port);
  });
  add_routes(svr, *backend, token, max_body);
  add_flow_routes(svr, *backend, max_open);

  std::atomic<bool> signalled{false};
  std::thread waiter([&svr, &stop_signals, &signalled] {
    int sig = 0;
    sigwait(&stop_signals, &sig);
    signalled = true;
    svr.stop();
  });
  const std::string url = "http://127.0.0.1:" + std::to_string(port) + "/?token=" + token;
  std::printf("%s\n", url.c_str());
  std::fflush(stdout);
  if (!options->quiet) {
    std::fprintf(stderr, "tessera view: serving %zu input(s) on 127.0.0.1:%d; Ctrl-C stops\n",
                 backend->input_count(), port);
  }
  std::string open_dir;
  if (options->open) open_browser(url, open_dir);
  svr.listen_after_bind();
  if (!signalled) pthread_kill(waiter.native_handle(), SIGTERM);  // listen ended on its own
  waiter.join();
  if (!open_dir.empty()) {
    unlink((open_dir + "/open.html").c_str());
    rmdir(open_dir.c_str());
  }
  return 0;
}
