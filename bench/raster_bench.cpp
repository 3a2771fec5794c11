// Rasteriser throughput on a procedural scene: a 128 x 128-cell wavy terrain (32,768 small
// triangles) seen in perspective at 1024 x 768 and filling the screen, with 5 varyings (uv,
// normal), a bilinear, wrapping 256 x 256 texture fetch and a Lambert term.
// Frame = per-tile clear + geometry + raster + shading; MSAA 1x and 4x, 1 and 2 threads.
// Items = triangles submitted. Run: build/bin/raster_bench --benchmark_filter=Frame
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "tessera/raster.h"

namespace {

using namespace tessera::raster;

constexpr int kWidth = 1024, kHeight = 768, kCells = 128;

struct Scene {
  std::vector<float> pos, var;
  std::vector<std::uint32_t> idx;
};

const Scene& scene() {
  static const Scene s = [] {
    Scene sc;
    // Camera at (0, 3, 4) looking at the origin: view = rotate about x, then GL perspective
    // with a 60 degree vertical field of view.
    const double pitch = std::atan2(3.0, 4.0);
    const double cp = std::cos(pitch), sp = std::sin(pitch);
    const double fy = 1.0 / std::tan(30.0 * 3.14159265358979 / 180.0);
    const double fx = fy * kHeight / kWidth;
    const double n = 0.1, f = 100.0;
    for (int j = 0; j <= kCells; ++j) {
      for (int i = 0; i <= kCells; ++i) {
        const double u = double(i) / kCells, v = double(j) / kCells;
        const double x = (u - 0.5) * 9.0, z = (v - 0.5) * 9.0;
        const double h = 0.15 * std::sin(x * 3.1) * std::cos(z * 2.3);
        const double dhdx = 0.15 * 3.1 * std::cos(x * 3.1) * std::cos(z * 2.3);
        const double dhdz = -0.15 * 2.3 * std::sin(x * 3.1) * std::sin(z * 2.3);
        double nx = -dhdx, ny = 1.0, nz = -dhdz;
        const double nl = std::sqrt(nx * nx + ny * ny + nz * nz);
        nx /= nl, ny /= nl, nz /= nl;
        // World -> view: translate by -(0, 3, 4), rotate by pitch about x.
        const double wx = x, wy = h - 3.0, wz = z - 4.0;
        const double vx = wx;
        const double vy = cp * wy - sp * wz;
        const double vz = sp * wy + cp * wz;
        sc.pos.insert(sc.pos.end(),
                      {float(fx * vx), float(fy * vy),
                       float((f + n) / (n - f) * vz + 2.0 * f * n / (n - f)), float(-vz)});
        sc.var.insert(sc.var.end(),
                      {float(u * 8.0), float(v * 8.0), float(nx), float(ny), float(nz)});
      }
    }
    for (int j = 0; j < kCells; ++j) {
      for (int i = 0; i < kCells; ++i) {
        const std::uint32_t a = std::uint32_t(j * (kCells + 1) + i), b = a + 1;
        const std::uint32_t c = a + kCells + 1, d = c + 1;
        sc.idx.insert(sc.idx.end(), {a, c, b, b, c, d});
      }
    }
    return sc;
  }();
  return s;
}

/// A 256 x 256 linear RGBA texture (procedural bricks), sampled bilinearly with wrapping.
constexpr int kTex = 256;
const std::vector<float>& texture() {
  static const std::vector<float> t = [] {
    std::vector<float> tex(std::size_t(kTex) * kTex * 4);
    for (int y = 0; y < kTex; ++y) {
      for (int x = 0; x < kTex; ++x) {
        const bool mortar = (y % 32) < 3 || ((x + (y / 32 % 2) * 32) % 64) < 3;
        const float n = float((x * 7 + y * 13) % 17) / 17.0f;
        float* p = &tex[(std::size_t(y) * kTex + std::size_t(x)) * 4];
        p[0] = mortar ? 0.8f : 0.5f + 0.2f * n;
        p[1] = mortar ? 0.8f : 0.2f + 0.1f * n;
        p[2] = mortar ? 0.75f : 0.15f;
        p[3] = 1.0f;
      }
    }
    return tex;
  }();
  return t;
}

void shade(const ShadeInput& in, float* out) {
  const float* tex = texture().data();
  const float u = in.varyings[0] * kTex - 0.5f, v = in.varyings[1] * kTex - 0.5f;
  const float fu = std::floor(u), fv = std::floor(v);
  const float au = u - fu, av = v - fv;
  const int x0 = int(fu) & (kTex - 1), y0 = int(fv) & (kTex - 1);
  const int x1 = (x0 + 1) & (kTex - 1), y1 = (y0 + 1) & (kTex - 1);
  const float* t00 = &tex[(std::size_t(y0) * kTex + std::size_t(x0)) * 4];
  const float* t10 = &tex[(std::size_t(y0) * kTex + std::size_t(x1)) * 4];
  const float* t01 = &tex[(std::size_t(y1) * kTex + std::size_t(x0)) * 4];
  const float* t11 = &tex[(std::size_t(y1) * kTex + std::size_t(x1)) * 4];
  const float lambert =
      std::max(0.0f, 0.3f * in.varyings[2] + 0.9f * in.varyings[3] + 0.3f * in.varyings[4]);
  for (int c = 0; c < 3; ++c) {
    const float top = t00[c] + au * (t10[c] - t00[c]);
    const float bottom = t01[c] + au * (t11[c] - t01[c]);
    out[c] = (top + av * (bottom - top)) * lambert;
  }
  out[3] = 1.0f;
}

DrawCall make_draw() {
  const Scene& s = scene();
  DrawCall d;
  d.positions = s.pos.data();
  d.varyings = s.var.data();
  d.varying_count = 5;
  d.vertex_count = s.pos.size() / 4;
  d.indices = s.idx.data();
  d.index_count = s.idx.size();
  d.shader = shade;
  d.cull = CullMode::none;
  return d;
}

/// The benchmarks' kWidth x kHeight frame buffer at `msaa` samples per pixel.
FrameBuffer frame_buffer(int msaa) {
  FrameBufferDesc desc;
  desc.width = kWidth;
  desc.height = kHeight;
  desc.msaa = msaa;
  return std::move(FrameBuffer::create(desc)).value();
}

void BM_RasterFrame(benchmark::State& state) {
  const int threads = int(state.range(1));
  FrameBuffer fb = frame_buffer(int(state.range(0)));
  Rasteriser r({.threads = threads});
  const DrawCall d = make_draw();
  ClearValues clear;
  RasterStats st;
  for (auto _ : state) {
    st = *r.render(fb, d, &clear);
    benchmark::DoNotOptimize(fb.data().data());
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(st.triangles_in));
  state.counters["quads"] = double(st.quads);
  state.counters["samples"] = double(st.samples_written);
  state.counters["tris_setup"] = double(st.triangles_setup);
}
BENCHMARK(BM_RasterFrame)
    ->ArgNames({"msaa", "threads"})
    ->Args({1, 1})
    ->Args({1, 2})
    ->Args({4, 1})
    ->Args({4, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_Resolve(benchmark::State& state) {
  const int threads = int(state.range(1));
  FrameBuffer fb = frame_buffer(int(state.range(0)));
  Rasteriser r({.threads = threads});
  ClearValues clear;
  if (tessera::Result<RasterStats> st = r.render(fb, make_draw(), &clear); !st) {
    state.SkipWithError(st.status().message.c_str());
    return;
  }
  for (auto _ : state) {
    tessera::ImageRGBA8 img = resolve_srgb8(fb, {threads});
    benchmark::DoNotOptimize(img.pixels.data());
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * kWidth * kHeight);
}
BENCHMARK(BM_Resolve)
    ->ArgNames({"msaa", "threads"})
    ->Args({1, 2})
    ->Args({4, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
