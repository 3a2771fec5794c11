// Google Benchmark of the metrics every experiment runs: PSNR and SSIM throughput.
#include <benchmark/benchmark.h>

#include "tessera/metrics.h"
#include "tessera/procedural.h"

namespace {

void BM_CompareNoSsim(benchmark::State& state) {
  const int size = int(state.range(0));
  const auto a = tessera::make_procedural(tessera::Procedural::noise, size, size, 1);
  const auto b = tessera::make_procedural(tessera::Procedural::noise, size, size, 2);
  tessera::metrics::CompareOptions options;
  options.compute_ssim = false;
  options.threads = 1;
  for (auto _ : state) benchmark::DoNotOptimize(tessera::metrics::compare_images(a, b, options));
  state.SetItemsProcessed(state.iterations() * std::int64_t(size) * size);
}

void BM_SsimGray(benchmark::State& state) {
  const int size = int(state.range(0));
  const int threads = int(state.range(1));
  const auto a = tessera::make_procedural(tessera::Procedural::noise, size, size, 1);
  const auto b = tessera::make_procedural(tessera::Procedural::noise, size, size, 2);
  for (auto _ : state) benchmark::DoNotOptimize(tessera::metrics::ssim_gray(a, b, {threads}));
  state.SetItemsProcessed(state.iterations() * std::int64_t(size) * size);
}

}  // namespace

BENCHMARK(BM_CompareNoSsim)->Arg(512)->Arg(2048);
BENCHMARK(BM_SsimGray)->Args({512, 1})->Args({512, 0})->Args({2048, 0});
BENCHMARK_MAIN();
