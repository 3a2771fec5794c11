// tessera compress IN... -o OUTDIR/: many images into a folder. Files are spread over the -j
// workers (each file encoded on one thread, so its bytes equal a single-file run's); results are
// printed in input order; a failing file fails alone.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>

#include "compress.h"
#include "progress.h"
#include "tessera/io.h"
#include "tessera/metrics.h"

namespace tessera::cli {

namespace {

namespace fs = std::filesystem;

/// The inputs of one output (one image, or with --cube / --array a folder's images) and the
/// output; `error` set when it fails before any work.
struct Job {
  std::vector<std::string> inputs;
  std::string output;
  std::string error;
  const std::string& input() const { return inputs.front(); }
};

/// What happened to one job.
struct Outcome {
  enum class Kind { done, skipped, failed } kind = Kind::failed;
  std::string error;
  int width = 0, height = 0, levels = 0, images = 1;
  std::size_t bytes = 0;
  double encode_ms = 0;
  double psnr_rgb = 0, ssim_gray = 0, psnr_alpha = 0;
  bool has_alpha = false, resized = false;
};

bool is_image_name(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".tga" || ext == ".bmp";
}

/// The cube face (0..5 = +X, -X, +Y, -Y, +Z, -Z) a file name's stem ends with ("sky_px",
/// "posx", "+X", "right", ...), and the stem without it; -1 when none.
std::pair<int, std::string> face_of(const fs::path& p) {
  static const std::vector<std::string> kTokens[6] = {
      {"px", "posx", "+x", "right"},     {"nx", "negx", "-x", "left"},
      {"py", "posy", "+y", "top", "up"}, {"ny", "negy", "-y", "bottom", "down"},
      {"pz", "posz", "+z", "front"},     {"nz", "negz", "-z", "back"}};
  std::string stem = p.stem().string();
  std::transform(stem.begin(), stem.end(), stem.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  for (int f = 0; f < 6; ++f) {
    for (const std::string& t : kTokens[f]) {
      if (!stem.ends_with(t)) continue;
      const std::size_t at = stem.size() - t.size();
      const bool signed_token = t[0] == '+' || t[0] == '-';
      if (at == 0 || signed_token || std::string("_.- ").find(stem[at - 1]) != std::string::npos) {
        return {f, stem.substr(0, at)};
      }
    }
  }
  return {-1, stem};
}

/// A folder's images as the faces/layers of one texture: name order, or for a cube map whose
/// every image names its face, by layer (the name without the face) then face.
std::vector<fs::path> texture_order(std::vector<fs::path> files, bool cube) {
  std::sort(files.begin(), files.end());
  if (!cube) return files;
  for (const fs::path& f : files) {
    if (face_of(f).first < 0) return files;
  }
  std::stable_sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    const auto fa = face_of(a), fb = face_of(b);
    return std::tie(fa.second, fa.first) < std::tie(fb.second, fb.first);
  });
  return files;
}

/// The images directly inside `dir`, sorted.
std::vector<fs::path> images_in(const fs::path& dir, std::error_code& ec) {
  std::vector<fs::path> found;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    std::error_code fec;
    if (e.is_regular_file(fec) && is_image_name(e.path())) found.push_back(e.path());
  }
  std::sort(found.begin(), found.end());
  return found;
}

/// --cube / --array in a batch: every folder (with -r, every folder below it that holds
/// images) is one texture, named after the folder.
void plan_texture_jobs(const CompressArgs& args, const std::string& ext,
                       const std::vector<std::string>& words, std::vector<Job>& jobs,
                       std::vector<std::string>& usage_problems) {
  const fs::path out_dir = args.output;
  for (const std::string& w : words) {
    std::error_code ec;
    if (!fs::is_directory(w, ec)) {
      usage_problems.push_back(w +
                               ": with --cube or --array, a batch takes folders (each one "
                               "texture); for one texture from files, give -o FILE");
      continue;
    }
    std::vector<fs::path> dirs = {fs::path(w)};
    if (args.recursive) {
      for (const auto& e :
           fs::recursive_directory_iterator(w, fs::directory_options::skip_permission_denied, ec)) {
        std::error_code dec;
        if (e.is_directory(dec)) dirs.push_back(e.path());
      }
      std::sort(dirs.begin() + 1, dirs.end());
    }
    const fs::path base = fs::path(w).lexically_normal();
    for (const fs::path& d : dirs) {
      std::error_code lec;
      std::vector<fs::path> files = images_in(d, lec);
      if (lec) {
        jobs.push_back({{d.string()}, "", d.string() + ": cannot list: " + lec.message()});
        continue;
      }
      if (files.empty() && (d != dirs.front() || args.recursive)) continue;
      fs::path name = base.filename().empty() ? base.parent_path().filename() : base.filename();
      const fs::path rel = d.lexically_normal().lexically_relative(base);
      if (!rel.empty() && rel != ".") name /= rel;
      Job job;
      for (const fs::path& f : texture_order(files, args.words.cube))
        job.inputs.push_back(f.string());
      job.output = (out_dir / name).string() + ext;
      if (job.inputs.empty()) {
        job.inputs.push_back(d.string());
        job.error = d.string() + ": no images in the folder";
      }
      jobs.push_back(std::move(job));
    }
  }
}

/// Expands the command line's inputs (files, folders, @lists) into jobs, in order: a folder's
/// images sorted by path; an output another input already makes is an error of the later one.
std::vector<Job> plan_jobs(const CompressArgs& args, const std::string& ext,
                           std::vector<std::string>& usage_problems) {
  std::vector<Job> jobs;
  std::vector<std::string> words;
  for (const std::string& in : args.inputs) {
    if (!in.starts_with('@')) {
      words.push_back(in);
      continue;
    }
    const std::string list = in.substr(1);
    Result<std::vector<std::uint8_t>> text = io::read_file(list, 64u << 20);
    if (!text) {
      usage_problems.push_back(text.status().message);
      continue;
    }
    std::string line;
    for (std::size_t i = 0; i <= text->size(); ++i) {
      const char c = i < text->size() ? char((*text)[i]) : '\n';
      if (c != '\n') {
        line += c;
        continue;
      }
      while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
      if (!line.empty() && line[0] != '#') words.push_back(line);
      line.clear();
    }
  }
  const fs::path out_dir = args.output;
  if (args.words.cube || args.words.array) {
    plan_texture_jobs(args, ext, words, jobs, usage_problems);
    words.clear();
  }
  for (const std::string& w : words) {
    if (w == "-") {
      usage_problems.push_back("'-' (stdin) takes one input, not a batch");
      continue;
    }
    std::error_code ec;
    if (fs::is_directory(w, ec)) {
      std::vector<fs::path> found;
      auto add = [&](const fs::directory_entry& e) {
        std::error_code fec;
        if (e.is_regular_file(fec) && is_image_name(e.path())) found.push_back(e.path());
      };
      if (args.recursive) {
        for (const auto& e : fs::recursive_directory_iterator(
                 w, fs::directory_options::skip_permission_denied, ec)) {
          add(e);
        }
      } else {
        for (const auto& e : fs::directory_iterator(w, ec)) add(e);
      }
      if (ec) {
        jobs.push_back({{w}, "", w + ": cannot list: " + ec.message()});
        continue;
      }
      std::sort(found.begin(), found.end());
      for (const fs::path& p : found) {
        fs::path rel = p.lexically_relative(w);
        jobs.push_back({{p.string()}, (out_dir / rel.replace_extension(ext)).string(), ""});
      }
    } else {
      jobs.push_back({{w}, (out_dir / fs::path(w).filename().replace_extension(ext)).string(), ""});
    }
  }
  // Two inputs naming one output: the first keeps it.
  std::vector<std::pair<std::string, std::size_t>> by_output;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    if (jobs[i].error.empty()) by_output.emplace_back(jobs[i].output, i);
  }
  std::stable_sort(by_output.begin(), by_output.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t k = 1; k < by_output.size(); ++k) {
    if (by_output[k].first == by_output[k - 1].first) {
      Job& later = jobs[std::max(by_output[k].second, by_output[k - 1].second)];
      const Job& first = jobs[std::min(by_output[k].second, by_output[k - 1].second)];
      later.error =
          later.input() + ": output " + later.output + " is also made from " + first.input();
    }
  }
  return jobs;
}

Outcome run_job(const Job& job, const CompressArgs& args, const std::string& container, int threads,
                bool measure) {
  Outcome o;
  if (!job.error.empty()) {
    o.error = job.error;
    return o;
  }
  if (args.skip_up_to_date && up_to_date(args, container, job.inputs, job.output)) {
    o.kind = Outcome::Kind::skipped;
    return o;
  }
  std::vector<ImageRGBA8> images;
  for (const std::string& input : job.inputs) {
    Result<ImageRGBA8> loaded = io::read_image(input);
    if (!loaded) {
      o.error = loaded.status().message;
      return o;
    }
    images.push_back(std::move(loaded).value());
  }
  Result<texture_file::CompressOptions> options = compress_options(args, threads);
  if (!options) {
    o.error = options.status().message;
    return o;
  }
  Result<texture_file::CompressedImage> made =
      texture_file::compress_images(std::move(images), texture_shape(args), *options, job.inputs);
  if (!made) {
    o.error = cli_option_names(made.status().message);
    return o;
  }
  const texture_file::CompressedTexture& tex = made->texture;
  texture_file::Ktx2Options ktx2;
  ktx2.zstd_level = args.words.zstd;
  Result<std::vector<std::uint8_t>> file =
      texture_file::serialise_texture(tex, container_of(container), ktx2);
  if (!file) {
    o.error = file.status().message;
    return o;
  }
  std::error_code ec;
  fs::create_directories(fs::path(job.output).parent_path(), ec);
  if (ec) {
    o.error = job.output + ": cannot create its folder: " + ec.message();
    return o;
  }
  if (Status s = io::write_file_atomic(job.output, *file); !s.ok()) {
    o.error = s.message;
    return o;
  }
  if (args.skip_up_to_date) {
    if (Status s = write_sidecar(args, container, job.inputs, job.output); !s.ok()) {
      o.error = s.message;
      return o;
    }
  }
  o.kind = Outcome::Kind::done;
  o.width = tex.width;
  o.height = tex.height;
  o.images = tex.image_count();
  o.levels = tex.level_count();
  o.bytes = file->size();
  o.encode_ms = made->encode_ms;
  o.has_alpha = tex.has_alpha;
  o.resized = made->resized;
  if (measure) {
    if (Result<metrics::ImageComparison> cmp =
            texture_file::measure_level0(made->texture, made->sources, threads)) {
      o.psnr_rgb = cmp->psnr_rgb;
      o.ssim_gray = cmp->ssim_gray;
      o.psnr_alpha = cmp->psnr_alpha;
    }
  }
  return o;
}

const char* kind_name(Outcome::Kind k) {
  return k == Outcome::Kind::done ? "done" : k == Outcome::Kind::skipped ? "skipped" : "failed";
}

/// The --json line of one file.
nlohmann::json outcome_json(const Job& job, const Outcome& o) {
  nlohmann::json j = {
      {"input", job.inputs.size() == 1 ? nlohmann::json(job.input()) : nlohmann::json(job.inputs)},
      {"output", job.output},
      {"status", kind_name(o.kind)}};
  if (o.kind == Outcome::Kind::failed) j["error"] = o.error;
  if (o.kind == Outcome::Kind::done) {
    j["width"] = o.width;
    j["height"] = o.height;
    j["resized"] = o.resized;
    j["has_alpha"] = o.has_alpha;
    j["levels"] = o.levels;
    j["bytes"] = o.bytes;
    j["time_ms"] = o.encode_ms;
    j["psnr_rgb"] = db_or_null(o.psnr_rgb);
    j["ssim_gray"] = o.ssim_gray;
    if (o.has_alpha) j["psnr_alpha"] = db_or_null(o.psnr_alpha);
  }
  return j;
}

/// The usage checks of a batch, its jobs and the output folder; returns -1 to go on, else the
/// exit code.
int plan_batch(const CompressArgs& args, const std::string& container, std::vector<Job>& jobs) {
  if (args.output == "-") return usage_error("several inputs need a folder for -o, not '-'");
  std::error_code dir_ec;
  if (!fs::is_directory(args.output, dir_ec) &&
      texture_file::container_from_extension(args.output) !=
          texture_file::ContainerFormat::unknown) {
    return usage_error("-o " + args.output +
                       ": several inputs (or a folder) need an output folder, not a file name");
  }
  if (std::string problem = compress_usage_problem(args, container); !problem.empty()) {
    return usage_error(problem);
  }
  std::vector<std::string> problems;
  jobs = plan_jobs(args, "." + container, problems);
  if (!problems.empty()) return usage_error(problems.front());
  std::error_code ec;
  fs::create_directories(args.output, ec);
  if (ec || !fs::is_directory(args.output)) {
    return fail(Status::error(ErrorCode::io_error, args.output +
                                                       ": cannot create the output folder: " +
                                                       (ec ? ec.message() : "not a directory")));
  }
  return -1;
}

}  // namespace

int run_compress_batch(const CompressArgs& args, const GlobalOptions& global) {
  const std::string container = args.container.empty() ? "pvr" : args.container;
  std::vector<Job> jobs;
  if (int rc = plan_batch(args, container, jobs); rc >= 0) return rc;

  const int workers =
      std::max(1, std::min<int>(global.threads > 0 ? global.threads : default_thread_count(),
                                int(std::max<std::size_t>(jobs.size(), 1))));
  // Fewer files than workers: the spare threads go into each file's encode (same bytes).
  const int per_file = std::max(1, (global.threads > 0 ? global.threads : default_thread_count()) /
                                       int(std::max<std::size_t>(jobs.size(), 1)));
  // The TTY progress line (progress.h): files done/total, MPixel/s, ETA.
  ProgressBar bar(!args.quiet && ::isatty(STDERR_FILENO));

  std::vector<std::optional<Outcome>> outcomes(jobs.size());
  std::mutex mutex;
  std::condition_variable changed;
  std::atomic<std::size_t> next{0};
  std::vector<std::thread> pool;
  for (int w = 0; w < workers; ++w) {
    pool.emplace_back([&] {
      for (std::size_t i; (i = next.fetch_add(1)) < jobs.size();) {
        Outcome o = run_job(jobs[i], args, container, per_file, args.json);
        std::lock_guard<std::mutex> lock(mutex);
        outcomes[i] = std::move(o);
        changed.notify_one();
      }
    });
  }

  // Report in input order as results arrive; redraw the progress line at most 10 times a second.
  const auto t0 = std::chrono::steady_clock::now();
  std::size_t reported = 0, finished = 0, done = 0, skipped = 0, failed = 0;
  double mpixels = 0;
  auto seconds = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  while (reported < jobs.size()) {
    std::vector<std::pair<std::size_t, Outcome>> ready;
    {
      std::unique_lock<std::mutex> lock(mutex);
      changed.wait_for(lock, std::chrono::milliseconds(100));
      finished = std::size_t(std::count_if(outcomes.begin(), outcomes.end(),
                                           [](const auto& o) { return o.has_value(); }));
      while (reported < jobs.size() && outcomes[reported]) {
        ready.emplace_back(reported, *outcomes[reported]);
        ++reported;
      }
    }
    for (const auto& [i, o] : ready) {
      bar.clear();
      switch (o.kind) {
        case Outcome::Kind::done:
          ++done;
          mpixels += double(o.width) * o.height * o.images / 1e6;
          break;
        case Outcome::Kind::skipped:
          ++skipped;
          break;
        case Outcome::Kind::failed:
          ++failed;
          std::fprintf(stderr, "tessera: %s\n", o.error.c_str());
          break;
      }
      if (args.json) {
        std::printf("%s\n", outcome_json(jobs[i], o).dump().c_str());
        std::fflush(stdout);
      }
    }
    bar.update(jobs.empty() ? 1.0 : double(finished) / double(jobs.size()),
               std::to_string(finished) + "/" + std::to_string(jobs.size()) + " files", mpixels);
  }
  for (std::thread& t : pool) t.join();
  const double total_s = seconds();
  bar.clear();
  if (args.json) {
    const nlohmann::json j = {{"summary", true},
                              {"files", jobs.size()},
                              {"done", done},
                              {"skipped", skipped},
                              {"failed", failed},
                              {"mpixels", mpixels},
                              {"seconds", total_s},
                              {"mpixel_per_s", total_s > 0 ? mpixels / total_s : 0.0},
                              {"threads", workers * per_file}};
    std::printf("%s\n", j.dump().c_str());
  } else if (!args.quiet) {
    std::printf(
        "compressed %zu of %zu file(s) into %s (%zu skipped, %zu failed): %.2f MPixel in "
        "%.2f s, %.1f MPixel/s\n",
        done, jobs.size(), args.output.c_str(), skipped, failed, mpixels, total_s,
        total_s > 0 ? mpixels / total_s : 0.0);
  }
  return failed ? kExitBadInput : kExitOk;
}

}  // namespace tessera::cli
