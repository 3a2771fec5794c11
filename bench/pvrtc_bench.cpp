// Google Benchmark of the PVRTC codec: encode throughput per quality / format / thread count
// and decode throughput, in pixels per second (items). Each encode benchmark also reports the
// RGB PSNR of its result as a counter (computed once, outside the timed loop).
//
// Input: $TESSERA_BENCH_IMAGE (a power-of-two PNG) when set, else a 512x512 procedural `noise`.
#include <benchmark/benchmark.h>

#include <cstdlib>

#include "tessera/io.h"
#include "tessera/metrics.h"
#include "tessera/procedural.h"
#include "tessera/pvrtc.h"

namespace {

using namespace tessera;

const ImageRGBA8& bench_image() {
  static const ImageRGBA8 img = [] {
    if (const char* p = std::getenv("TESSERA_BENCH_IMAGE")) {
      auto r = io::read_image(p);
      if (r.ok()) return std::move(r).value();
    }
    return make_procedural(Procedural::noise, 512, 512);
  }();
  return img;
}

void BM_Encode(benchmark::State& state) {
  const ImageRGBA8& img = bench_image();
  pvrtc::EncodeOptions opt;
  opt.quality = pvrtc::Quality(state.range(0));
  opt.format = state.range(1) == 2 ? pvrtc::Format::pvrtc1_2bpp : pvrtc::Format::pvrtc1_4bpp;
  opt.threads = int(state.range(2));
  for (auto _ : state) benchmark::DoNotOptimize(pvrtc::encode(img, opt));
  state.SetItemsProcessed(state.iterations() * std::int64_t(img.pixel_count()));
  auto enc = pvrtc::encode(img, opt);
  if (!enc.ok()) {
    state.SkipWithError(enc.status().message.c_str());
    return;
  }
  auto dec = pvrtc::decode(*enc, opt.format, img.width, img.height);
  metrics::CompareOptions co;
  co.compute_ssim = false;
  auto cmp = metrics::compare_images(img, *dec, co);
  state.counters["psnr_rgb"] = cmp->psnr_rgb;
}

void BM_Decode(benchmark::State& state) {
  const ImageRGBA8& img = bench_image();
  pvrtc::EncodeOptions opt;
  opt.quality = pvrtc::Quality::fast;
  opt.format = state.range(0) == 2 ? pvrtc::Format::pvrtc1_2bpp : pvrtc::Format::pvrtc1_4bpp;
  auto enc = pvrtc::encode(img, opt);
  if (!enc.ok()) {
    state.SkipWithError(enc.status().message.c_str());
    return;
  }
  const int threads = int(state.range(1));
  for (auto _ : state) {
    benchmark::DoNotOptimize(pvrtc::decode(*enc, opt.format, img.width, img.height, {threads}));
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(img.pixel_count()));
}

}  // namespace

// Args: quality (0 fast, 1 normal, 2 high), bpp (4 or 2), threads (0 = all).
BENCHMARK(BM_Encode)
    ->ArgNames({"quality", "bpp", "threads"})
    ->Args({0, 4, 1})
    ->Args({0, 4, 0})
    ->Args({1, 4, 0})
    ->Args({2, 4, 0})
    ->Args({0, 2, 0})
    ->Args({2, 2, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();  // wall time: the encoder is multi-threaded
BENCHMARK(BM_Decode)
    ->ArgNames({"bpp", "threads"})
    ->Args({4, 1})
    ->Args({4, 0})
    ->Args({2, 0})
    ->UseRealTime();
BENCHMARK_MAIN();
