// Google Benchmark of the texture sampler: single-thread lookups per second on a 1024x1024
// mipmapped texture (linear float RGBA, 16 MiB at level 0).
//
// Coherent runs (the headline numbers) walk a 64x64-pixel screen tile row by row, as a
// rasteriser's fragment shader does: uv = origin + x * ddx + y * ddy, with the same explicit
// gradients for every pixel. The minor axis of the footprint is 3 texels (LOD ~1.58, so
// trilinear reads two levels); anisotropic runs stretch the major axis N times, so 16x aniso
// takes 16 trilinear probes = 128 taps per lookup. The scattered run draws positions from a
// fixed pseudo-random table and mostly measures cache misses. BM_Sample4Trilinear makes the
// coherent trilinear lookups four at a time through `Texture::sample4`.
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "tessera/procedural.h"
#include "tessera/texture.h"

namespace {

using tessera::texture::SamplerState;
using tessera::texture::TapList;
using tessera::texture::Texture;
using tessera::texture::TextureFilter;
using tessera::texture::Uv;
using tessera::texture::UvGradients;

struct Lookup {
  Uv uv;
  UvGradients grad;
};

const Texture& bench_texture() {
  static const Texture tex = [] {
    const auto img = tessera::make_procedural(tessera::Procedural::noise, 1024, 1024, 7);
    return std::move(Texture::from_rgba8(img)).value();
  }();
  return tex;
}

/// One 64x64 tile of a coherent walk: pixel (x, y) looks up origin + x * d/dx + y * d/dy.
/// `ratio` is the major/minor footprint ratio; the major axis is d/dx, rotated by 30 degrees.
std::vector<Lookup> coherent_lookups(float ratio) {
  std::vector<Lookup> out;
  out.reserve(64 * 64);
  const float minor = 3.0f / 1024.0f;
  const float c = std::cos(0.5235988f);
  const float s = std::sin(0.5235988f);
  const UvGradients g{c * minor * ratio, s * minor * ratio, -s * minor, c * minor};
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      out.push_back({{0.3f + float(x) * g.dudx + float(y) * g.dudy,
                      0.2f + float(x) * g.dvdx + float(y) * g.dvdy},
                     g});
  return out;
}

/// 4096 scattered lookups with a 2-6 texel footprint of random orientation.
std::vector<Lookup> scattered_lookups(float ratio) {
  std::vector<Lookup> out(4096);
  std::uint32_t state = 12345u;
  auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / float(1u << 24);
  };
  for (Lookup& l : out) {
    l.uv = {next() * 1.2f - 0.1f, next() * 1.2f - 0.1f};
    const float minor = (2.0f + 4.0f * next()) / 1024.0f;
    const float angle = next() * 6.2831853f;
    const float c = std::cos(angle);
    const float s = std::sin(angle);
    l.grad = {c * minor * ratio, s * minor * ratio, -s * minor, c * minor};
  }
  return out;
}

void run_sample(benchmark::State& state, TextureFilter filter, int max_aniso, float ratio,
                bool scattered = false) {
  const Texture& tex = bench_texture();
  const std::vector<Lookup> lookups =
      scattered ? scattered_lookups(ratio) : coherent_lookups(ratio);
  SamplerState sampler;
  sampler.filter = filter;
  sampler.max_aniso = max_aniso;
  std::size_t i = 0;
  for (auto _ : state) {
    const Lookup& l = lookups[i];
    i = (i + 1) & (lookups.size() - 1);
    benchmark::DoNotOptimize(tex.sample(sampler, l.uv, l.grad));
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_SampleNearest(benchmark::State& state) {
  run_sample(state, TextureFilter::nearest, 1, 1.0f);
}
void BM_SampleBilinear(benchmark::State& state) {
  run_sample(state, TextureFilter::bilinear, 1, 1.0f);
}
void BM_SampleTrilinear(benchmark::State& state) {
  run_sample(state, TextureFilter::trilinear, 1, 1.0f);
}
void BM_SampleTrilinearScattered(benchmark::State& state) {
  run_sample(state, TextureFilter::trilinear, 1, 1.0f, true);
}
void BM_SampleAniso(benchmark::State& state) {
  const int n = int(state.range(0));
  run_sample(state, TextureFilter::anisotropic, n, float(n));
}

/// `Texture::sample4`: four consecutive coherent lookups per call (items count lookups).
void BM_Sample4Trilinear(benchmark::State& state) {
  const Texture& tex = bench_texture();
  const std::vector<Lookup> lookups = coherent_lookups(1.0f);
  SamplerState sampler;
  sampler.filter = TextureFilter::trilinear;
  std::array<Uv, 4> uv;
  std::array<UvGradients, 4> grad;
  std::array<std::array<float, 4>, 4> out;
  std::size_t i = 0;
  for (auto _ : state) {
    for (std::size_t lane = 0; lane < 4; ++lane) {
      uv[lane] = lookups[i + lane].uv;
      grad[lane] = lookups[i + lane].grad;
    }
    i = (i + 4) & (lookups.size() - 1);
    tex.sample4(sampler, uv, grad, 15u, out);
    benchmark::DoNotOptimize(out);
  }
  state.SetItemsProcessed(state.iterations() * 4);
}

void BM_TapsAniso16(benchmark::State& state) {
  const Texture& tex = bench_texture();
  const std::vector<Lookup> lookups = coherent_lookups(16.0f);
  SamplerState sampler;
  sampler.filter = TextureFilter::anisotropic;
  TapList taps;
  std::size_t i = 0;
  for (auto _ : state) {
    const Lookup& l = lookups[i];
    i = (i + 1) & (lookups.size() - 1);
    tex.taps(sampler, l.uv, l.grad, 0, taps);
    benchmark::DoNotOptimize(tex.resolve(sampler, taps));
  }
  state.SetItemsProcessed(state.iterations());
}

}  // namespace

BENCHMARK(BM_SampleNearest);
BENCHMARK(BM_SampleBilinear);
BENCHMARK(BM_SampleTrilinear);
BENCHMARK(BM_SampleTrilinearScattered);
BENCHMARK(BM_Sample4Trilinear);
BENCHMARK(BM_SampleAniso)->Arg(2)->Arg(4)->Arg(8)->Arg(16);
BENCHMARK(BM_TapsAniso16);
BENCHMARK_MAIN();
