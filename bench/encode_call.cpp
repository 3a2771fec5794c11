// The C++ side of bench/python_encode.py: times `compress_image`, the call that the Python
// module's `tessera.encode` wraps, on one image, in a warm process, so that the two are compared
// call against call (the CLI's `time_ms` would add a cold process: first touch of the thread
// pool, page faults of a fresh heap).
//
//   encode_call IMAGE --format pvrtc1-4|pvrtc1-2 --quality fast|normal|high --threads N
//               --repeats N
//
// Prints one JSON object: {"ms": [per-call milliseconds...], "bytes": level-0 size}. One
// untimed warm-up call comes first, as the Python side makes one.
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
  if (argc < 2) return fail("usage: encode_call IMAGE [--format F] [--quality Q] [--threads N] "
                            "[--repeats N]");
  const std::string path = argv[1];
  std::string format = "pvrtc1-4", quality = "normal";
  int threads = 0, repeats = 7;
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "--format") format = value;
    else if (key == "--quality") quality = value;
    else if (key == "--threads") threads = std::atoi(value.c_str());
    else if (key == "--repeats") repeats = std::atoi(value.c_str());
    else return fail("unknown option '" + key + "'");
  }
  if (format != "pvrtc1-4" && format != "pvrtc1-2") return fail("bad --format '" + format + "'");
  if (quality != "fast" && quality != "normal" && quality != "high") {
    return fail("bad --quality '" + quality + "'");
  }
  if (repeats < 1) return fail("--repeats must be positive");

  auto image = io::read_image(path);
  if (!image.ok()) return fail(image.status().message);
  texture_file::CompressOptions o;
  o.encode.format = format == "pvrtc1-2" ? pvrtc::Format::pvrtc1_2bpp : pvrtc::Format::pvrtc1_4bpp;
  o.encode.quality = quality == "fast"   ? pvrtc::Quality::fast
                     : quality == "high" ? pvrtc::Quality::high
                                         : pvrtc::Quality::normal;
  o.encode.threads = threads;

  std::size_t bytes = 0;
  std::vector<double> ms;
  for (int i = 0; i <= repeats; ++i) {
    ImageRGBA8 copy = *image;  // the binding copies the array into an ImageRGBA8 too
    const auto t0 = std::chrono::steady_clock::now();
    auto r = texture_file::compress_image(std::move(copy), o, path);
    const auto t1 = std::chrono::steady_clock::now();
    if (!r.ok()) return fail(r.status().message);
    bytes = r->texture.levels.at(0).size();
    if (i > 0) ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
  }
  std::printf("{\"bytes\": %zu, \"ms\": [", bytes);
  for (std::size_t i = 0; i < ms.size(); ++i) std::printf("%s%.4f", i ? ", " : "", ms[i]);
  std::printf("]}\n");
  return 0;
}
