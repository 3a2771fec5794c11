// Google Benchmark of PNG decoding (tessera::io::decode_image: the fast path, libspng as fallback),
// in memory: generated images, plus the shared test images when ../shared/data is present.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "tessera/io.h"
#include "tessera/procedural.h"

namespace {

/// Decodes `png` once per iteration; bytes processed = the decoded RGBA8 pixels.
void decode_loop(benchmark::State& state, const std::vector<std::uint8_t>& png) {
  std::int64_t pixels = 0;
  for (auto _ : state) {
    tessera::Result<tessera::ImageRGBA8> img = tessera::io::decode_image(png, "bench.png");
    if (!img.ok()) {
      state.SkipWithError(img.status().message.c_str());
      return;
    }
    pixels = std::int64_t(img->pixel_count());
    benchmark::DoNotOptimize(img->pixels.data());
  }
  state.SetItemsProcessed(state.iterations() * pixels);
  state.SetBytesProcessed(state.iterations() * pixels * 4);
}

/// A generated size x size image (opaque noise: RGB; foliage: RGBA) encoded by encode_png.
void BM_DecodePngGenerated(benchmark::State& state) {
  const int size = int(state.range(0));
  const bool alpha = state.range(1) != 0;
  const tessera::ImageRGBA8 img = tessera::make_procedural(
      alpha ? tessera::Procedural::foliage : tessera::Procedural::noise, size, size, 1);
  const std::vector<std::uint8_t> png = *tessera::io::encode_png(img);
  decode_loop(state, png);
}

/// ../shared/data/images next to the source tree, or $TESSERA_SHARED/data/images.
std::filesystem::path shared_images() {
  if (const char* env = std::getenv("TESSERA_SHARED")) {
    return std::filesystem::path(env) / "data" / "images";
  }
  return std::filesystem::path(TESSERA_BENCH_SOURCE_DIR) / ".." / "shared" / "data" / "images";
}

/// Registers one benchmark per shared image that exists (none when the folder is absent).
void register_shared_images() {
  for (const char* name : {"ldr-rgb-metalrough.png", "ldr-rgb-diffuse.png", "ldr-rgba-diffuse.png",
                           "ldr-l-occlusion.png"}) {
    const std::filesystem::path path = shared_images() / name;
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) continue;
    tessera::Result<std::vector<std::uint8_t>> bytes = tessera::io::read_file(path.string());
    if (!bytes.ok()) continue;
    benchmark::RegisterBenchmark(
        (std::string("BM_DecodePngShared/") + name).c_str(),
        [png = std::move(*bytes)](benchmark::State& state) { decode_loop(state, png); })
        ->Unit(benchmark::kMillisecond);
  }
}

}  // namespace

BENCHMARK(BM_DecodePngGenerated)->Args({1024, 0})->Args({1024, 1})->Unit(benchmark::kMillisecond);

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  register_shared_images();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
