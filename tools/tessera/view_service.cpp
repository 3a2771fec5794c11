// tessera view, serving: the inputs, results and encode jobs behind the HTTP module
// (view_http.h), which this file loads with dlopen. Encodes run one at a time on a worker
// thread; their progress (EncodeOptions::progress) is what the page polls. Results are kept
// under a memory budget: past it the least recently used results that are not pinned are
// evicted (their blobs freed, their jobs forgotten: asking again encodes again).
#include <dlfcn.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <pthread.h>

#include <algorithm>
#include <condition_variable>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <iterator>
#include <set>
#include <thread>

#include "view.h"
#include "view_http.h"
#include "view_originals.h"

namespace tessera::cli {

namespace {

constexpr std::size_t kMaxQueued = 8;  ///< Encodes waiting at once: 503 above.
/// Places in the queue the overview's background encodes leave to the page's own.
constexpr std::size_t kOverviewRoom = 2;
constexpr int kThumbnail = 96;  ///< The overview's thumbnails: texels on their longer side.

struct Job {
  std::string id;
  int input = 0;
  ViewSettings settings;
  std::string key;
  std::atomic<double> fraction{0.0};
  std::string state = "queued";  ///< queued, running, done, error (under Service::mutex_)
  std::string result;            ///< Result id when done.
  std::string error;
};

nlohmann::json error(const std::string& message) { return {{"error", message}}; }

/// Gives freed memory back to the system (glibc keeps it otherwise, and RSS would only grow).
void trim_heap() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

/// The blob keys in a result's JSON: every string that names a blob of `blobs`.
void collect_blob_keys(const nlohmann::json& j, const BlobStore& blobs,
                       std::set<std::string>& keys) {
  if (j.is_string()) {
    const std::string& s = j.get_ref<const std::string&>();
    if (s.size() == 16 && blobs.has(s)) keys.insert(s);
  } else if (j.is_structured()) {
    for (const auto& v : j) collect_blob_keys(v, blobs, keys);
  }
}

class Service final : public ViewBackend {
 public:
  Service(std::vector<ViewInput> inputs, int threads, std::size_t budget)
      : inputs_(std::move(inputs)), threads_(threads), budget_(budget) {}

  /// The page's start-up data (inputs, initial settings), set once before serving; the
  /// overview measures every image with `overview` (the first encode's settings).
  void set_page(nlohmann::json page, const ViewSettings& overview) {
    page_ = std::move(page);
    overview_settings_ = overview;
  }

  std::size_t input_count() const override { return inputs_.size(); }
  const std::vector<ViewInput>& inputs() const { return inputs_; }
  BlobStore& blobs() { return blobs_; }
  /// The blob key of image input `index`'s own texels (the page's first draw, before any
  /// result: view_originals.h).
  std::string original_key(int index) {
    return originals_.add(index, inputs_[std::size_t(index)].path);
  }

  std::string page(const std::string& token) override {
    std::lock_guard<std::mutex> lock(mutex_);
    nlohmann::json data = page_;
    data["token"] = token;
    data["results"] = nlohmann::json::array();
    for (const auto& [id, r] : results_) data["results"].push_back(r.json);
    return view_page(data);
  }

  bool blob(const std::string& key, std::string& mime, std::string& bytes) override {
    if (std::shared_ptr<const BlobStore::Blob> o = originals_.get(key, inputs_)) {
      mime = o->mime;
      bytes.assign(o->bytes.begin(), o->bytes.end());
      return true;
    }
    std::shared_ptr<const BlobStore::Blob> b = blobs_.get(key);
    if (!b) return false;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (auto it = users_.find(key); it != users_.end()) {
        for (const std::string& id : it->second) touch(id);
      }
    }
    mime = b->mime;
    bytes.assign(b->bytes.begin(), b->bytes.end());
    return true;
  }

  int encode(const std::string& body_text, std::string& out) override {
    nlohmann::json body = nlohmann::json::parse(body_text, nullptr, false);
    if (body.is_discarded() || !body.is_object() || !body.contains("input") ||
        !body["input"].is_number_integer() || !body.contains("settings")) {
      out = dump_json(error("bad request: want {\"input\": N, \"settings\": {...}}"));
      return 400;
    }
    const long long input = body["input"].get<long long>();
    const ViewInput* in = input_at(input);
    if (!in || in->is_texture || !in->error.empty()) {
      out = dump_json(error("no such image input"));
      return 404;
    }
    Result<ViewSettings> s = settings_from_json(body["settings"]);
    if (!s) {
      out = dump_json(error(s.status().message));
      return 400;
    }
    const std::string id = submit(int(input), *s);
    if (id.empty()) {
      out = dump_json(error("busy: too many encodes queued"));
      return 503;
    }
    return job(id, out);
  }

  int job(const std::string& id, std::string& out) override {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = jobs_.find(id);
    if (it == jobs_.end()) {
      out = dump_json(error("no such job"));
      return 404;
    }
    const Job& j = *it->second;
    nlohmann::json r = {{"id", id}, {"state", j.state}, {"fraction", j.fraction.load()}};
    if (j.state == "done") {
      r["result"] = results_.at(j.result).json;
      touch(j.result);
    }
    if (j.state == "error") r["error"] = j.error;
    out = dump_json(r);
    return 200;
  }

  int pin(const std::string& id, bool pinned, std::string& out) override {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = results_.find(id);
    if (it == results_.end()) {
      out = dump_json(error("no such result (evicted?)"));
      return 404;
    }
    it->second.pinned = pinned;
    touch(id);
    out = dump_json({{"id", id}, {"pinned", pinned}});
    return 200;
  }

  int overview(std::string& out) override;
  int open(const std::string& name, std::string bytes, std::string& out) override;
  int download(const std::string& id, const std::string& as, std::string& mime, std::string& bytes,
               std::string& out) override;

  /// Adds a result; `permanent` ones (a texture input's own) are never evicted.
  std::string add_result(nlohmann::json result, bool permanent = false) {
    std::set<std::string> keys;
    collect_blob_keys(result, blobs_, keys);
    std::lock_guard<std::mutex> lock(mutex_);
    const std::string id = "r" + std::to_string(next_result_++);
    result["id"] = id;
    Entry& e = results_[id];
    e.json = std::move(result);
    e.pinned = permanent;
    e.keys.assign(keys.begin(), keys.end());
    for (const std::string& k : e.keys) users_[k].insert(id);
    touch(id);
    evict(id);
    return id;
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
      Result<nlohmann::json> r =
          encode_view_result(*input_at(job->input), job->settings, threads_, blobs_,
                             [&job](double f) {  // never backwards
                               if (f > job->fraction.load()) job->fraction.store(f);
                             });
      std::string id;
      if (r) {
        nlohmann::json j = std::move(r).value();
        j["input_index"] = job->input;
        id = add_result(std::move(j));
      } else {
        std::fprintf(stderr, "tessera: %s\n", r.status().message.c_str());
      }
      {
        std::lock_guard<std::mutex> lock(mutex_);
        job->state = r ? "done" : "error";
        if (r) job->fraction.store(1.0);  // 1 only when done
        job->result = id;
        if (!r) job->error = r.status().message;
        if (r && job->key == key_of(job->input, overview_settings_)) {
          const nlohmann::json m =
              results_.count(id) ? results_.at(id).json["metrics"] : nlohmann::json::object();
          measured_[job->input] = {{"psnr", m.value("psnr_rgb", nlohmann::json())},
                                   {"max_abs", m.value("max_abs", nlohmann::json())}};
        }
        // An evicted result's job is forgotten too: the same settings encode again.
        if (r && !results_.count(id)) jobs_.erase(job->id);
      }
      trim_heap();
    }
  }

  void stop() {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
    wake_.notify_all();
  }

 private:
  struct Entry {
    nlohmann::json json;
    std::vector<std::string> keys;  ///< The blobs it shows.
    bool pinned = false;
    std::uint64_t used = 0;  ///< Its last use (a clock of uses).
  };

  void touch(const std::string& id) {
    if (auto it = results_.find(id); it != results_.end()) it->second.used = ++clock_;
  }

  /// Evicts the least recently used results that are neither pinned nor `keep` (the newest)
  /// while the blobs are over the budget; a blob goes with the last result that shows it.
  void evict(const std::string& keep) {
    bool freed = false;
    while (blobs_.bytes() > budget_) {
      auto victim = results_.end();
      for (auto it = results_.begin(); it != results_.end(); ++it) {
        if (it->second.pinned || it->first == keep) continue;
        if (victim == results_.end() || it->second.used < victim->second.used) victim = it;
      }
      if (victim == results_.end()) break;  // everything left is pinned
      for (const std::string& k : victim->second.keys) {
        auto u = users_.find(k);
        if (u == users_.end()) continue;
        u->second.erase(victim->first);
        if (u->second.empty()) {
          users_.erase(u);
          blobs_.erase(k);
        }
      }
      for (auto j = jobs_.begin(); j != jobs_.end();) {
        j = j->second->result == victim->first ? jobs_.erase(j) : std::next(j);
      }
      results_.erase(victim);
      freed = true;
    }
    if (freed) trim_heap();
  }

  /// The id of the job of (input, settings): an existing one with the same key (unless it
  /// failed), or a new queued one; "" when the queue is full.
  std::string submit(int input, const ViewSettings& settings) {
    std::lock_guard<std::mutex> lock(mutex_);
    return submit_locked(input, settings, kMaxQueued);
  }
  static std::string key_of(int input, const ViewSettings& settings) {
    return std::to_string(input) + dump_json(settings_to_json(settings));
  }
  /// submit() under mutex_, with room for `limit` queued encodes.
  std::string submit_locked(int input, const ViewSettings& settings, std::size_t limit) {
    const std::string key = key_of(input, settings);
    for (const auto& [jid, job] : jobs_) {
      if (job->key == key && job->state != "error") return jid;
    }
    if (queue_.size() >= limit) return "";
    auto job = std::make_shared<Job>();
    job->input = input;
    job->settings = settings;
    job->key = key;
    const std::string id = "j" + std::to_string(next_job_++);
    job->id = id;
    jobs_[id] = job;
    queue_.push_back(job);
    wake_.notify_one();
    return id;
  }

  /// Input `i`: one given on the command line, then those opened from the page (a deque:
  /// an opened input stays where it is while more are added).
  const ViewInput* input_at(long long i) {
    std::lock_guard<std::mutex> lock(mutex_);
    return input_at_locked(i);
  }
  const ViewInput* input_at_locked(long long i) const {
    if (i < 0) return nullptr;
    if (std::size_t(i) < inputs_.size()) return &inputs_[std::size_t(i)];
    i -= static_cast<long long>(inputs_.size());
    return std::size_t(i) < opened_.size() ? &opened_[std::size_t(i)] : nullptr;
  }

  std::vector<ViewInput> inputs_;
  std::deque<ViewInput> opened_;
  ViewSettings overview_settings_;
  std::map<int, nlohmann::json> measured_;  ///< The overview's metrics, kept past eviction.
  nlohmann::json page_;
  int threads_;
  std::size_t budget_;
  BlobStore blobs_;
  ViewOriginals originals_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  std::map<std::string, Entry> results_;
  std::map<std::string, std::set<std::string>> users_;  ///< Blob key -> results showing it.
  std::map<std::string, std::shared_ptr<Job>> jobs_;
  std::deque<std::shared_ptr<Job>> queue_;
  std::uint64_t clock_ = 0, next_result_ = 0, next_job_ = 0;
};

int Service::overview(std::string& out) {
  std::lock_guard<std::mutex> lock(mutex_);
  nlohmann::json items = nlohmann::json::array();
  const std::size_t limit = kMaxQueued - kOverviewRoom;
  for (const nlohmann::json& in : page_["inputs"]) {
    const int i = in["index"].get<int>();
    nlohmann::json e = {{"index", i},         {"name", in["name"]},
                        {"kind", in["kind"]}, {"thumbnail", in.value("thumbnail", "")},
                        {"psnr", nullptr},    {"max_abs", nullptr}};
    if (in.contains("error")) {
      e["state"] = "error";
      e["error"] = in["error"];
    } else if (in["kind"] == "texture") {
      e["state"] = "texture";  // shown as it is: nothing to measure it against
    } else if (auto m = measured_.find(i); m != measured_.end()) {
      e["state"] = "done";
      e["psnr"] = m->second["psnr"];
      e["max_abs"] = m->second["max_abs"];
    } else {
      // Not measured yet: its encode at the overview's settings, queued while there is room
      // (once: an encode that failed is reported, not tried again).
      const std::string key = key_of(i, overview_settings_);
      auto job = std::find_if(jobs_.begin(), jobs_.end(),
                              [&](const auto& j) { return j.second->key == key; });
      if (job == jobs_.end()) {
        const std::string id = submit_locked(i, overview_settings_, limit);
        job = id.empty() ? jobs_.end() : jobs_.find(id);
      }
      e["state"] = job == jobs_.end() ? "waiting" : job->second->state;
      if (job != jobs_.end() && job->second->state == "error") e["error"] = job->second->error;
    }
    items.push_back(std::move(e));
  }
  out = dump_json({{"settings", settings_to_json(overview_settings_)}, {"inputs", items}});
  return 200;
}

int Service::open(const std::string& name, std::string bytes, std::string& out) {
  const std::string file_name = opened_file_name(name);
  ViewInput in = view_input_from_bytes(file_name, file_name,
                                       std::vector<std::uint8_t>(bytes.begin(), bytes.end()));
  bytes.clear();
  bytes.shrink_to_fit();
  if (!in.error.empty()) std::fprintf(stderr, "tessera: view: %s\n", in.error.c_str());
  const std::string thumbnail = put_thumbnail(in, kThumbnail, threads_, blobs_);
  const ViewInput* added = nullptr;
  nlohmann::json j;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const int index = int(inputs_.size() + opened_.size());
    opened_.push_back(std::move(in));
    added = &opened_.back();
    j = input_json(*added, index);
    if (!thumbnail.empty()) j["thumbnail"] = thumbnail;
    page_["inputs"].push_back(j);  // in index order (a texture's error is added below)
  }
  nlohmann::json results = nlohmann::json::array();
  if (added->is_texture && added->error.empty()) {
    Result<nlohmann::json> r = texture_view_result(*added, threads_, blobs_);
    if (r) {
      nlohmann::json t = std::move(r).value();
      t["input_index"] = j["index"];
      const std::string id = add_result(t, true);
      t["id"] = id;
      results.push_back(std::move(t));
    } else {
      std::fprintf(stderr, "tessera: view: %s\n", r.status().message.c_str());
      j["error"] = r.status().message;
    }
  }
  if (j.contains("error")) {
    std::lock_guard<std::mutex> lock(mutex_);
    page_["inputs"][j["index"].get<std::size_t>()] = j;
  }
  out = dump_json({{"input", j}, {"results", results}});
  return 200;
}

int Service::download(const std::string& id, const std::string& as, std::string& mime,
                      std::string& bytes, std::string& out) {
  nlohmann::json r;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = results_.find(id);
    if (it == results_.end()) {
      out = dump_json(error("no such result (evicted?)"));
      return 404;
    }
    r = it->second.json;
    touch(id);
  }
  std::string key;
  if (as == "pvr" || as == "png" || as == "ktx" || as == "ktx2") {
    key = r.value("file", "");  // another container or the decoded image made on request
  } else if (as == "heatmap") {
    key = r["images"].empty() ? "" : r["images"][0].value("heatmap", "");
  } else {
    out = dump_json(error("as: want pvr, ktx, ktx2, png or heatmap"));
    return 400;
  }
  std::shared_ptr<const BlobStore::Blob> b = key.empty() ? nullptr : blobs_.get(key);
  if (!b) {
    out = dump_json(error("this result has no " + as + " download"));
    return 404;
  }
  if (as == "png") {
    Result<std::vector<std::uint8_t>> png = decoded_png(b->bytes, threads_);
    if (!png) {
      out = dump_json(error(png.status().message));
      return 500;
    }
    mime = "image/png";
    bytes.assign(png->begin(), png->end());
  } else if (as != "heatmap") {
    Result<std::vector<std::uint8_t>> file = convert_texture(b->bytes, as);
    if (!file) {
      out = dump_json(error(file.status().message));
      return 500;
    }
    mime = "application/octet-stream";
    bytes.assign(file->begin(), file->end());
  } else {
    mime = b->mime;
    bytes.assign(b->bytes.begin(), b->bytes.end());
  }
  return 200;
}

/// The HTTP module's entry point: $TESSERA_VIEW_HTTP, else beside the build tree's binary
/// (bin/../lib/), else where it is installed; null with `why` set when none loads.
ViewHttpServe load_http_module(std::string& why) {
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("TESSERA_VIEW_HTTP"); env && *env) candidates.push_back(env);
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const std::filesystem::path bin = exe.parent_path();
    candidates.push_back((bin / ".." / "lib" / "tessera-view-http.so").string());
    candidates.push_back((bin / TESSERA_VIEW_HTTP_INSTALLED).string());
  }
  for (const std::string& path : candidates) {
    if (!std::filesystem::exists(path, ec)) continue;
    void* module = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!module) {
      why = dlerror();
      return nullptr;
    }
    if (void* f = dlsym(module, kViewHttpServeSymbol)) return reinterpret_cast<ViewHttpServe>(f);
    why = path + ": no " + kViewHttpServeSymbol;
    return nullptr;
  }
#ifdef TESSERA_HAVE_VIEW_HTTP
  why = "tessera-view-http.so not found beside " + exe.string() + " (set TESSERA_VIEW_HTTP)";
#else
  why =
      "this tessera was built without libcpp-httplib-dev (install it and rebuild); "
      "`tessera view INPUT --html -o VIEW.html` works";
#endif
  return nullptr;
}

}  // namespace

int serve_view(std::vector<ViewInput> inputs, const ViewServeOptions& options) {
#if defined(__GLIBC__)
  // Image-sized buffers (decoded texels, PNGs) are made on several threads: mapped and unmapped
  // on their own, they go back to the system when freed instead of staying in a thread's heap
  // (glibc otherwise raises this threshold after the first such free).
  mallopt(M_MMAP_THRESHOLD, 1 << 20);
#endif
  std::string why;
  const ViewHttpServe serve = load_http_module(why);
  if (!serve) {
    std::fprintf(stderr, "tessera: view: cannot serve: %s\n", why.c_str());
    return kExitBadInput;
  }
  // SIGINT and SIGTERM are the server's to wait for: blocked before any thread starts.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);

  Service service(std::move(inputs), options.threads, options.memory_budget);
  nlohmann::json page = {{"mode", "server"},
                         {"version", TESSERA_VERSION_STRING},
                         {"inputs", nlohmann::json::array()},
                         {"initial", nlohmann::json::array()}};
  for (const ViewSettings& s : options.initial) page["initial"].push_back(settings_to_json(s));
  for (std::size_t i = 0; i < service.inputs().size(); ++i) {
    const ViewInput& in = service.inputs()[i];
    page["inputs"].push_back(input_json(in, int(i)));
    if (needs_resize_pot(in)) add_originals(page["inputs"][i], in, service.blobs());
    const std::string thumbnail = put_thumbnail(in, kThumbnail, options.threads, service.blobs());
    if (!thumbnail.empty()) page["inputs"][i]["thumbnail"] = thumbnail;
    if (!in.is_texture && in.error.empty() && in.images.empty() && !needs_resize_pot(in)) {
      page["inputs"][i]["original"] = service.original_key(int(i));  // drawn while encoding
    }
    if (!in.is_texture || !in.error.empty()) continue;
    Result<nlohmann::json> r = texture_view_result(in, options.threads, service.blobs());
    if (!r) {
      std::fprintf(stderr, "tessera: %s\n", r.status().message.c_str());
      page["inputs"][i]["error"] = r.status().message;
      continue;
    }
    nlohmann::json j = std::move(r).value();
    j["input_index"] = int(i);
    service.add_result(std::move(j), true);
  }
  for (const auto& [t, im] : texture_pairs(service.inputs())) {
    const ViewInput& image = service.inputs()[std::size_t(im)];
    Result<nlohmann::json> r = texture_view_result(
        service.inputs()[std::size_t(t)], options.threads, service.blobs(), pair_references(image));
    if (!r) continue;  // reported above, as the texture's own result
    nlohmann::json j = std::move(r).value();
    j["input_index"] = im;
    service.add_result(std::move(j), true);
  }
  service.set_page(std::move(page),
                   options.initial.empty() ? ViewSettings{} : options.initial.front());

  std::thread worker([&service] { service.work(); });
  ViewHttpOptions http;
  http.port = options.port;
  http.open = options.open;
  http.quiet = options.quiet;
  const int rc = serve(&service, &http);
  service.stop();
  worker.join();
  if (!options.quiet && rc == 0) std::fprintf(stderr, "tessera view: stopped\n");
  return rc;
}

}  // namespace tessera::cli
