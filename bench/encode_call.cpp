// The C++ side of bench/python_encode.py: times `compress_image`, the call that the Python
// module's `tessera.encode` wraps, on one image, in a warm process, so that the two are compared
// call against call (the CLI's `time_ms` would add a cold process: first touch of the thread
// pool, page faults of a fresh heap).
//
//   encode_call IMAGE --format pvrtc1-4|pvrtc1-2 --quality fast|normal|high --threads N
//               [--repeats N | --serve]
//
// Prints one JSON object: {"ms": [per-call milliseconds...], "bytes": level-0 size}. One
// untimed warm-up call comes first, as the Python side makes one. With --serve it stays up
// after the warm-up (whose line it prints) and answers each line "N" on stdin with the JSON of
// N more timed calls, so that a benchmark can alternate single calls with another process's
// (the machine's load then hits both alike).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "tessera/io.h"
#include "tessera/texture_file.h"

namespace {

using namespace tessera;

int fail(const std::string& message) {
  std::fprintf(stderr, "encode_call: %s\n", message.c_str());
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2)
    return fail(
        "usage: encode_call IMAGE [--format F] [--quality Q] [--threads N] "
        "[--repeats N | --serve]");
  const std::string path = argv[1];
  texture_file::RecordedOptions words;  // the CLI's words and defaults
  int threads = 0, repeats = 7;
  bool serve = false;
  for (int i = 2; i < argc; i += 2) {
    const std::string key = argv[i];
    if (key == "--serve") {
      serve = true;
      --i;
      continue;
    }
    if (i + 1 >= argc) return fail("option '" + key + "' needs a value");
    const std::string value = argv[i + 1];
    if (key == "--format")
      words.format = value;
    else if (key == "--quality")
      words.quality = value;
    else if (key == "--threads")
      threads = std::atoi(value.c_str());
    else if (key == "--repeats")
      repeats = std::atoi(value.c_str());
    else
      return fail("unknown option '" + key + "'");
  }
  Result<texture_file::CompressOptions> options = texture_file::compress_options(words, threads);
  if (!options) return fail(options.status().message);
  const texture_file::CompressOptions& o = *options;
  if (repeats < 1) return fail("--repeats must be positive");

  auto image = io::read_image(path);
  if (!image.ok()) return fail(image.status().message);

  std::size_t bytes = 0;
  // `count` timed calls (after `warm_up` untimed ones), each on a fresh copy of the image made
  // just before its timer; prints their times as one JSON line.
  auto run = [&](int warm_up, int count) -> bool {
    std::vector<double> ms;
    for (int i = 0; i < warm_up + count; ++i) {
      ImageRGBA8 copy = *image;
      const auto t0 = std::chrono::steady_clock::now();
      auto r = texture_file::compress_image(std::move(copy), o, path);
      const auto t1 = std::chrono::steady_clock::now();
      if (!r.ok()) {
        fail(r.status().message);
        return false;
      }
      bytes = r->texture.levels.at(0).size();
      if (i >= warm_up) ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    }
    std::printf("{\"bytes\": %zu, \"ms\": [", bytes);
    for (std::size_t i = 0; i < ms.size(); ++i) std::printf("%s%.4f", i ? ", " : "", ms[i]);
    std::printf("]}\n");
    std::fflush(stdout);
    return true;
  };
  if (!serve) return run(1, repeats) ? 0 : 1;
  // Served: one untimed warm-up, then a line "N" on stdin asks for N timed calls, until EOF.
  if (!run(1, 0)) return 1;
  char line[64];
  while (std::fgets(line, sizeof line, stdin)) {
    const int n = std::atoi(line);
    if (n < 1)
      return fail("serve: expected a positive call count, got '" + std::string(line) + "'");
    if (!run(0, n)) return 1;
  }
  return 0;
}
