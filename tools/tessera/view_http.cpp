// tessera view's HTTP server module (tessera-view-http.so, loaded by `tessera view`): cpp-httplib
// bound to 127.0.0.1 only, a random token that every request carries (?token=), Host and
// Origin checked against DNS rebinding, request bodies capped (413), nothing routed but the
// page, the blobs of the opened inputs' results and the encode/job API; clean shutdown on
// SIGINT and SIGTERM. See view_http.h for why it is a module.
#include "view_http.h"

#include <fcntl.h>
#include <httplib.h>
#include <pthread.h>
#include <spawn.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <thread>

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

/// The checks every request passes before routing: Host and Origin name this server (a page
/// of another site that rebinds its name to 127.0.0.1 sends its own), and the token.
httplib::Server::HandlerResponse guard(const httplib::Request& req, httplib::Response& res,
                                       int port, const std::string& token) {
  const std::string p = std::to_string(port);
  const std::string host = req.get_header_value("Host");
  res.set_header("Cache-Control", "no-store");
  res.set_header("X-Content-Type-Options", "nosniff");
  res.set_header("Referrer-Policy", "no-referrer");
  if (host != "127.0.0.1:" + p && host != "localhost:" + p) {
    reply(res, 403, error_json("forbidden: Host '" + host + "' is not this server"));
    return httplib::Server::HandlerResponse::Handled;
  }
  if (req.has_header("Origin")) {
    const std::string origin = req.get_header_value("Origin");
    if (origin != "http://127.0.0.1:" + p && origin != "http://localhost:" + p) {
      reply(res, 403, error_json("forbidden: Origin '" + origin + "' is not this server"));
      return httplib::Server::HandlerResponse::Handled;
    }
  }
  if (!same_secret(req.get_param_value("token"), token)) {
    reply(res, 403,
          error_json("forbidden: a missing or wrong token (use the URL tessera view "
                     "printed)"));
    return httplib::Server::HandlerResponse::Handled;
  }
  return httplib::Server::HandlerResponse::Unhandled;
}

void add_routes(httplib::Server& svr, ViewBackend& backend, const std::string& token) {
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
  svr.Post("/api/encode", [&backend](const httplib::Request& req, httplib::Response& res) {
    std::string json;
    const int status = backend.encode(req.body, json);
    reply(res, status, json);
  });
  svr.set_error_handler([](const httplib::Request&, httplib::Response& res) {
    if (res.body.empty()) {
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

/// Opens `url` in the desktop's browser when there is a desktop (xdg-open), not waiting.
void open_browser(const std::string& url) {
  if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY")) return;
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
  std::string prog = "xdg-open", arg = url;
  char* argv[] = {prog.data(), arg.data(), nullptr};
  pid_t pid = 0;
  posix_spawnp(&pid, "xdg-open", &fa, nullptr, argv, environ);
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
  svr.set_payload_max_length(options->max_body);
  // A browser holds idle keep-alive connections: short timeouts let Ctrl-C end the server at
  // once rather than after httplib's default 5 s.
  svr.set_keep_alive_timeout(1);
  svr.set_read_timeout(10, 0);
  const int port = options->port
                       ? (svr.bind_to_port("127.0.0.1", options->port) ? options->port : -1)
                       : svr.bind_to_any_port("127.0.0.1");
  if (port <= 0) {
    std::fprintf(stderr, "tessera: cannot listen on 127.0.0.1:%d (in use?)\n", options->port);
    return 1;
  }
  const std::string token = random_token();
  svr.set_pre_routing_handler([port, token](const httplib::Request& req, httplib::Response& res) {
    return guard(req, res, port, token);
  });
  add_routes(svr, *backend, token);

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
  if (options->open) open_browser(url);
  svr.listen_after_bind();
  if (!signalled) pthread_kill(waiter.native_handle(), SIGTERM);  // listen ended on its own
  waiter.join();
  return 0;
}
