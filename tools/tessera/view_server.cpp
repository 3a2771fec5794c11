// tessera view: the local server (cpp-httplib). Bound to 127.0.0.1 only, a random token that
// every request carries (?token=), Host and Origin checked against DNS rebinding, request
// bodies capped, only the opened inputs' results served (content-addressed blobs); encodes run
// one at a time on a worker thread and report their progress to the page's polling.
#include <fcntl.h>
#include <httplib.h>
#include <pthread.h>
#include <spawn.h>
#include <unistd.h>

#include <condition_variable>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <fstream>
#include <random>
#include <thread>

#include "view.h"

extern char** environ;

namespace tessera::cli {

namespace {

constexpr std::size_t kMaxBody = 64 * 1024;  ///< Largest request body (settings JSON): 413 above.
constexpr std::size_t kMaxQueued = 8;        ///< Encodes waiting at once: 503 above.

std::string random_token() {
  std::random_device rd;  // /dev/urandom on Linux
  std::string t;
  static constexpr char kHex[] = "0123456789abcdef";
  for (int i = 0; i < 48; ++i) t += kHex[rd() & 15];
  return t;
}

bool same_secret(const std::string& a, const std::string& b) {
  if (a.size() != b.size()) return false;
  unsigned char d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d |= static_cast<unsigned char>(a[i] ^ b[i]);
  return d == 0;
}

struct Job {
  int input = 0;
  ViewSettings settings;
  std::string key;
  std::atomic<double> fraction{0.0};
  std::string state = "queued";  ///< queued, running, done, error (under State::mutex)
  std::string result;            ///< Result id when done.
  std::string error;
};

class State {
 public:
  State(std::vector<ViewInput> inputs, int threads) : inputs_(std::move(inputs)), threads_(threads) {}

  const std::vector<ViewInput>& inputs() const { return inputs_; }
  BlobStore& blobs() { return blobs_; }

  std::string add_result(nlohmann::json result) {
    std::lock_guard<std::mutex> lock(mutex_);
    const std::string id = "r" + std::to_string(results_.size());
    result["id"] = id;
    results_[id] = std::move(result);
    return id;
  }

  /// The job of (input, settings): an existing one with the same key, or a new queued one;
  /// null when the queue is full.
  std::shared_ptr<Job> submit(int input, const ViewSettings& settings, std::string& id) {
    const std::string key = std::to_string(input) + settings_to_json(settings).dump();
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& [jid, job] : jobs_) {
      if (job->key == key && job->state != "error") {
        id = jid;
        return job;
      }
    }
    if (queue_.size() >= kMaxQueued) return nullptr;
    auto job = std::make_shared<Job>();
    job->input = input;
    job->settings = settings;
    job->key = key;
    id = "j" + std::to_string(jobs_.size());
    jobs_[id] = job;
    queue_.push_back(job);
    wake_.notify_one();
    return job;
  }

  nlohmann::json job_json(const std::string& id) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = jobs_.find(id);
    if (it == jobs_.end()) return nullptr;
    const Job& j = *it->second;
    nlohmann::json out = {{"id", id}, {"state", j.state}, {"fraction", j.fraction.load()}};
    if (j.state == "done") out["result"] = results_.at(j.result);
    if (j.state == "error") out["error"] = j.error;
    return out;
  }

  nlohmann::json results_json() {
    std::lock_guard<std::mutex> lock(mutex_);
    nlohmann::json a = nlohmann::json::array();
    for (const auto& [id, r] : results_) a.push_back(r);
    return a;
  }

  /// Runs queued encodes until `stop`.
  void work() {
    for (;;) {
      std::shared_ptr<Job> job;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
        if (stopping_) return;
        job = queue_.front();
        queue_.pop_front();
        job->state = "running";
      }
      const ViewInput& in = inputs_[std::size_t(job->input)];
      Result<nlohmann::json> r = encode_view_result(
          in, job->settings, threads_, blobs_, [&job](double f) { job->fraction.store(f); });
      std::string id;
      if (r) {
        nlohmann::json j = std::move(r).value();
        j["input_index"] = job->input;
        id = add_result(std::move(j));
      } else {
        std::fprintf(stderr, "tessera: %s\n", r.status().message.c_str());
      }
      std::lock_guard<std::mutex> lock(mutex_);
      job->state = r ? "done" : "error";
      job->result = id;
      if (!r) job->error = r.status().message;
    }
  }

  void stop() {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
    wake_.notify_all();
  }

 private:
  std::vector<ViewInput> inputs_;
  int threads_;
  BlobStore blobs_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  std::map<std::string, nlohmann::json> results_;
  std::map<std::string, std::shared_ptr<Job>> jobs_;
  std::deque<std::shared_ptr<Job>> queue_;
};

void reply_json(httplib::Response& res, const nlohmann::json& j, int status = 200) {
  res.status = status;
  res.set_content(j.dump(), "application/json");
}

void reply_error(httplib::Response& res, int status, const std::string& message) {
  reply_json(res, {{"error", message}}, status);
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
    reply_error(res, 403, "forbidden: Host '" + host + "' is not this server");
    return httplib::Server::HandlerResponse::Handled;
  }
  if (req.has_header("Origin")) {
    const std::string origin = req.get_header_value("Origin");
    if (origin != "http://127.0.0.1:" + p && origin != "http://localhost:" + p) {
      reply_error(res, 403, "forbidden: Origin '" + origin + "' is not this server");
      return httplib::Server::HandlerResponse::Handled;
    }
  }
  if (!same_secret(req.get_param_value("token"), token)) {
    reply_error(res, 403, "forbidden: a missing or wrong token (use the URL tessera view printed)");
    return httplib::Server::HandlerResponse::Handled;
  }
  return httplib::Server::HandlerResponse::Unhandled;
}

void add_routes(httplib::Server& svr, State& state, const nlohmann::json& page_data) {
  svr.Get("/", [&state, page_data](const httplib::Request&, httplib::Response& res) {
    nlohmann::json data = page_data;
    data["results"] = state.results_json();
    res.set_header("Content-Security-Policy",
                   "default-src 'none'; script-src 'unsafe-inline'; style-src 'unsafe-inline'; "
                   "img-src 'self' data: blob:; connect-src 'self' data:");
    res.set_content(view_page(data), "text/html; charset=utf-8");
  });
  svr.Get(R"(/blob/([0-9a-f]{16}))", [&state](const httplib::Request& req, httplib::Response& res) {
    std::shared_ptr<const BlobStore::Blob> b = state.blobs().get(req.matches[1]);
    if (!b) return reply_error(res, 404, "no such blob");
    res.set_content(reinterpret_cast<const char*>(b->bytes.data()), b->bytes.size(), b->mime.c_str());
  });
  svr.Get("/api/job", [&state](const httplib::Request& req, httplib::Response& res) {
    nlohmann::json j = state.job_json(req.get_param_value("id"));
    if (j.is_null()) return reply_error(res, 404, "no such job");
    reply_json(res, j);
  });
  svr.Post("/api/encode", [&state](const httplib::Request& req, httplib::Response& res) {
    nlohmann::json body = nlohmann::json::parse(req.body, nullptr, false);
    if (body.is_discarded() || !body.is_object() || !body.contains("input") ||
        !body["input"].is_number_integer() || !body.contains("settings")) {
      return reply_error(res, 400, "bad request: want {\"input\": N, \"settings\": {...}}");
    }
    const int input = body["input"].get<int>();
    if (input < 0 || input >= int(state.inputs().size()) ||
        state.inputs()[std::size_t(input)].is_texture ||
        !state.inputs()[std::size_t(input)].error.empty()) {
      return reply_error(res, 404, "no such image input");
    }
    Result<ViewSettings> s = settings_from_json(body["settings"]);
    if (!s) return reply_error(res, 400, s.status().message);
    std::string id;
    if (!state.submit(input, *s, id)) return reply_error(res, 503, "busy: too many encodes queued");
    reply_json(res, state.job_json(id));
  });
}

/// Opens `url` in the desktop's browser when there is a desktop (xdg-open), not waiting.
void open_browser(const std::string& url) {
  if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY")) return;
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
  std::string prog = "xdg-open";
  char* argv[] = {prog.data(), const_cast<char*>(url.c_str()), nullptr};
  pid_t pid = 0;
  posix_spawnp(&pid, "xdg-open", &fa, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&fa);
}

}  // namespace

int serve_view(std::vector<ViewInput> inputs, const ViewServeOptions& options) {
  // SIGINT and SIGTERM go to one waiting thread (blocked everywhere else, before any thread
  // starts), which stops the server; SIGPIPE (a closed browser tab) is ignored.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);
  std::signal(SIGPIPE, SIG_IGN);

  State state(std::move(inputs), options.threads);
  nlohmann::json page = {{"mode", "server"},
                         {"version", TESSERA_VERSION_STRING},
                         {"inputs", nlohmann::json::array()},
                         {"initial", nlohmann::json::array()}};
  for (std::size_t i = 0; i < state.inputs().size(); ++i) {
    const ViewInput& in = state.inputs()[i];
    page["inputs"].push_back(input_json(in, int(i)));
    if (in.is_texture && in.error.empty()) {
      Result<nlohmann::json> r = texture_view_result(in, options.threads, state.blobs());
      if (!r) {
        std::fprintf(stderr, "tessera: %s\n", r.status().message.c_str());
        page["inputs"].back()["error"] = r.status().message;
        continue;
      }
      nlohmann::json j = std::move(r).value();
      j["input_index"] = int(i);
      state.add_result(std::move(j));
    }
  }
  for (const ViewSettings& s : options.initial) page["initial"].push_back(settings_to_json(s));

  httplib::Server svr;
  svr.set_payload_max_length(kMaxBody);
  const int port = options.port ? (svr.bind_to_port("127.0.0.1", options.port) ? options.port : -1)
                                : svr.bind_to_any_port("127.0.0.1");
  if (port <= 0) {
    std::fprintf(stderr, "tessera: cannot listen on 127.0.0.1:%d (in use?)\n", options.port);
    return kExitBadInput;
  }
  const std::string token = random_token();
  page["token"] = token;
  svr.set_pre_routing_handler([port, token](const httplib::Request& req, httplib::Response& res) {
    return guard(req, res, port, token);
  });
  add_routes(svr, state, page);
  svr.set_error_handler([](const httplib::Request&, httplib::Response& res) {
    if (res.body.empty()) {
      res.set_content(nlohmann::json{{"error", res.status == 413 ? "request body too large"
                                                                 : "not found"}}.dump(),
                      "application/json");
    }
  });

  std::thread worker([&state] { state.work(); });
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
  if (!options.quiet) {
    std::fprintf(stderr, "tessera view: serving %zu input(s) on 127.0.0.1:%d; Ctrl-C stops\n",
                 state.inputs().size(), port);
  }
  if (options.open) open_browser(url);
  svr.listen_after_bind();
  if (!signalled) pthread_kill(waiter.native_handle(), SIGTERM);  // listen ended on its own
  waiter.join();
  state.stop();
  worker.join();
  if (!options.quiet) std::fprintf(stderr, "tessera view: stopped\n");
  return kExitOk;
}

}  // namespace tessera::cli
