// The experiment of Holländer, Boubekeur & Eisemann 2013 (Table 1, Figures 6a, 7 and 8):
// adaptive supersampling of an enlarged G-buffer against full supersampling, plain 1x deferred
// shading, FXAA 3.11 and the engine baseline (per-sample shading of edge pixels, Lauritzen
// 2010), measured side by side in one run on an `AaBackend` (the CPU, OpenGL through
// `AaConfig::gl_factory`, or both).
#include "tessera/experiments/aa.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>

#include "gpu_factory.h"
#include "tessera/metrics.h"

namespace tessera::experiments {

namespace {

Result<AaQuality> quality(const ImageRGBA8& ref, const ImageRGBA8& img, int threads) {
  metrics::CompareOptions co;
  co.threads = threads;
  const Result<metrics::ImageComparison> c = metrics::compare_images(ref, img, co);
  if (!c) return c.status();
  return AaQuality{c->mse_rgb, c->psnr_rgb, c->ssim_gray};
}

std::string num(const char* format, double v) {
  char b[64];
  std::snprintf(b, sizeof b, format, v);
  return b;
}

/// The progress line of one rate.
std::string rate_line(const AaRateResult& r, double pct_adaptive) {
  const AaQuality& q = r.method(AaMethod::adaptive).quality;
  const std::string name = std::to_string(r.m) + "x" + std::to_string(r.m);
  char b[512];
  std::snprintf(b, sizeof b,
                "%s: gbuffer %.0f ms; shading default %.0f, fxaa %.0f, reference %.0f, "
                "adaptive %.0f ms; adaptive %.1f%% samples, PSNR %s dB",
                name.c_str(), r.gbuffer.median_ms(),
                r.method(AaMethod::default_1spp).timing.normal.median_ms(),
                r.method(AaMethod::fxaa).timing.normal.median_ms(),
                r.method(AaMethod::reference).timing.normal.median_ms(),
                r.method(AaMethod::adaptive).timing.normal.median_ms(), pct_adaptive,
                q.identical() ? "∞" : num("%.2f", q.psnr_db).c_str());
  return b;
}

/// Everything one backend renders, shared by its calls.
struct Run {
  const AaConfig& c;
  AaBackend& be;
  const scene::Camera& camera;
  const deferred::ShadingOptions& normal;
  const deferred::ShadingOptions& heavy;
  const AaShadeOptions& options;
  bool gpu() const { return be.backend() != Backend::cpu; }
};

/// Appends one call's times: wall (and, on GL, GPU) to `t`'s normal or heavy frames.
void record(const Run& run, AaTiming& t, int mode, const AaShadeOutput& o) {
  (mode ? t.heavy : t.normal).frame_ms.push_back(o.wall_ms);
  if (run.gpu()) (mode ? t.gpu_heavy : t.gpu).frame_ms.push_back(o.gpu_ms);
}

void record_passes(const Run& run, std::vector<AaPassFrames>& passes, const AaShadeOutput& o) {
  for (const PassTime& p : o.passes) {
    auto it = std::find_if(passes.begin(), passes.end(),
                           [&](const AaPassFrames& f) { return f.pass == p.pass; });
    if (it == passes.end()) it = passes.insert(passes.end(), AaPassFrames{p.pass, {}, {}});
    it->wall.frame_ms.push_back(p.wall_ms);
    if (run.gpu()) it->gpu.frame_ms.push_back(p.gpu_ms);
  }
}

Status record_gbuffer(const Run& run, const Result<PassTime>& t, FrameTimes& wall,
                      FrameTimes& gpu) {
  if (!t) return t.status();
  wall.frame_ms.push_back(t->wall_ms);
  if (run.gpu()) gpu.frame_ms.push_back(t->gpu_ms);
  return Status::success();
}

/// GL: one untimed call of each method (both shading modes) on a G-buffer of window m, so
/// that compiling the pass variants of m is not timed. Nothing on the CPU.
Status warm_up(const Run& run, int m, std::initializer_list<AaMethod> methods) {
  if (!run.gpu()) return Status::success();
  if (Result<PassTime> t = run.be.render_gbuffer(run.camera, run.c.width, run.c.height, m); !t) {
    return t.status();
  }
  for (int mode = 0; mode < (run.c.heavy ? 2 : 1); ++mode) {
    for (AaMethod k : methods) {
      if (Result<AaShadeOutput> o = run.be.shade(k, mode ? run.heavy : run.normal, run.options);
          !o) {
        return o.status();
      }
    }
  }
  return Status::success();
}

/// The paper's 1x1 rows: a w x h G-buffer, one sample per pixel, and FXAA on it.
Status run_1x1(const Run& run, AaResult& res) {
  const AaConfig& c = run.c;
  if (Status s = warm_up(run, 1, {AaMethod::default_1spp, AaMethod::fxaa}); !s.ok()) return s;
  for (int f = 0; f < c.frames; ++f) {
    if (Status s = record_gbuffer(run, run.be.render_gbuffer(run.camera, c.width, c.height, 1),
                                  res.gbuffer_1x1, res.gbuffer_1x1_gpu);
        !s.ok()) {
      return s;
    }
    for (int mode = 0; mode < (c.heavy ? 2 : 1); ++mode) {
      for (int k = 0; k < 2; ++k) {
        const int method = (k + f) % 2;
        Result<AaShadeOutput> o = run.be.shade(method ? AaMethod::fxaa : AaMethod::default_1spp,
                                               mode ? run.heavy : run.normal, run.options);
        if (!o) return o.status();
        record(run, method ? res.fxaa_1x1 : res.default_1x1, mode, *o);
      }
    }
  }
  return Status::success();
}

/// One rate: every method per frame (rotated), qualities, ablations.
Result<AaRateResult> run_rate(const Run& run, int m, int threads) {
  const AaConfig& c = run.c;
  AaRateResult rate;
  rate.m = m;
  for (AaMethod k : kAaMethods) rate.method(k).method = k;
  AaShadeOutput ad, ad_heavy, edge;
  constexpr int kCount = int(kAaMethods.size());
  if (Status s = warm_up(run, m,
                         {AaMethod::default_1spp, AaMethod::fxaa, AaMethod::reference,
                          AaMethod::adaptive, AaMethod::edge_per_sample});
      !s.ok()) {
    return s;
  }
  for (int f = 0; f < c.frames; ++f) {
    if (Status s = record_gbuffer(run, run.be.render_gbuffer(run.camera, c.width, c.height, m),
                                  rate.gbuffer, rate.gbuffer_gpu);
        !s.ok()) {
      return s;
    }
    for (int mode = 0; mode < (c.heavy ? 2 : 1); ++mode) {
      // Methods alternated per frame, in the order of `AaMethod` rotated by the frame.
      for (int k = 0; k < kCount; ++k) {
        const AaMethod method = kAaMethods[std::size_t((k + f) % kCount)];
        AaMethodResult& mr = rate.method(method);
        Result<AaShadeOutput> o = run.be.shade(method, mode ? run.heavy : run.normal, run.options);
        if (!o) return o.status();
        record(run, mr.timing, mode, *o);
        if (mode == 0) record_passes(run, mr.passes, *o);
        if (method == AaMethod::adaptive && mode == 0 && o->passes.size() == 3) {
          rate.adaptive_first.frame_ms.push_back(o->passes[0].wall_ms);
          rate.adaptive_metric.frame_ms.push_back(o->passes[1].wall_ms);
          rate.adaptive_rest.frame_ms.push_back(o->passes[2].wall_ms);
        }
        (mode ? mr.image_heavy : mr.image) = std::move(o->image);
        if (method == AaMethod::adaptive) (mode ? ad_heavy : ad) = std::move(*o);
        if (method == AaMethod::edge_per_sample && mode == 0) edge = std::move(*o);
      }
    }
  }
  const std::uint64_t pixels = std::uint64_t(c.width) * std::uint64_t(c.height);
  const double total = double(pixels) * double(m * m);
  auto pct = [&](std::uint64_t s) { return 100.0 * double(s) / total; };
  const ImageRGBA8& ref = rate.method(AaMethod::reference).image;
  for (AaMethod k : kAaMethods) {
    AaMethodResult& mr = rate.method(k);
    Result<AaQuality> q = quality(ref, mr.image, threads);
    if (!q) return q.status();
    mr.quality = *q;
  }
  rate.method(AaMethod::default_1spp).samples_pct = 100.0 / (m * m);
  rate.method(AaMethod::fxaa).samples_pct = 100.0 / (m * m);
  rate.method(AaMethod::reference).samples_pct = 100.0;
  rate.method(AaMethod::adaptive).samples_pct = pct(ad.samples_shaded);
  rate.method(AaMethod::edge_per_sample).samples_pct = pct(edge.samples_shaded);
  rate.adaptive_samples = std::move(ad.samples);
  rate.edge_samples = std::move(edge.samples);
  rate.adaptive_extra_albedo_lookups_pct = 100.0 * double(ad.extra_lookups) / double(pixels);
  if (c.heavy) {
    Result<AaQuality> q = quality(rate.method(AaMethod::reference).image_heavy,
                                  rate.method(AaMethod::adaptive).image_heavy, threads);
    if (!q) return q.status();
    rate.adaptive_heavy_quality = *q;
    rate.adaptive_heavy_samples_pct = pct(ad_heavy.samples_shaded);
  }

  // Ablations (Figure 8): one metric at a time, on the last frame's G-buffer.
  for (int which = 0; which < 2; ++which) {
    AaShadeOptions ao = run.options;
    (which == 0 ? ao.adaptive.use_shading : ao.adaptive.use_geometry) = false;
    Result<AaShadeOutput> r = run.be.shade(AaMethod::adaptive, run.normal, ao);
    if (!r) return r.status();
    AaAblation& ab = which == 0 ? rate.ablation_geometry : rate.ablation_shading;
    ab.image = std::move(r->image);
    ab.samples = std::move(r->samples);
    ab.samples_pct = pct(r->samples_shaded);
    Result<AaQuality> q = quality(ref, ab.image, threads);
    if (!q) return q.status();
    ab.quality = *q;
  }
  return rate;
}

/// The whole experiment on one backend into `res`.
Status run_backend(const Run& run, AaResult& res) {
  res.backend = run.be.backend();
  res.gpu_renderer = run.be.device_name();
  res.gpu_version = run.be.device_version();
  if (Status s = run_1x1(run, res); !s.ok()) return s;
  for (int m : run.c.ssaa) {
    Result<AaRateResult> rate = run_rate(run, m, res.threads);
    if (!rate) return rate.status();
    if (run.c.progress) {
      const Backend b = run.be.backend();
      run.c.progress((b == Backend::gl   ? "GL "
                      : b == Backend::vk ? "Vulkan "
                                         : "") +
                     rate_line(*rate, rate->method(AaMethod::adaptive).samples_pct));
    }
    res.rates.push_back(std::move(*rate));
  }
  return Status::success();
}

/// Backend::both: GL's adaptive image and k map against the CPU's, per rate.
Status compare_backends(AaResult& cpu, const AaResult& gl) {
  for (std::size_t i = 0; i < cpu.rates.size() && i < gl.rates.size(); ++i) {
    AaRateResult& a = cpu.rates[i];
    const AaRateResult& b = gl.rates[i];
    metrics::CompareOptions co;
    co.threads = cpu.threads;
    co.compute_ssim = false;
    Result<metrics::ImageComparison> q = metrics::compare_images(
        a.method(AaMethod::adaptive).image, b.method(AaMethod::adaptive).image, co);
    if (!q) return q.status();
    if (a.adaptive_samples.size() != b.adaptive_samples.size()) {
      return Status::error(ErrorCode::size_mismatch, "aa: GL and CPU k maps differ in size");
    }
    std::size_t differ = 0;
    for (std::size_t p = 0; p < a.adaptive_samples.size(); ++p) {
      differ += a.adaptive_samples[p] != b.adaptive_samples[p];
    }
    a.gl_vs_cpu = AaGlVsCpu{q->psnr_rgb, a.adaptive_samples.empty()
                                             ? 0.0
                                             : double(differ) / double(a.adaptive_samples.size())};
  }
  return Status::success();
}

/// run_aa once the configuration is checked: the backends (`factory`: the GPU one, or null),
/// every G-buffer size, `on_ready`, then the experiment on each.
Result<AaResult> run_backends(const AaConfig& c, const GpuBackendFactory* factory) {
  const std::shared_ptr<const scene::Scene> sc =
      c.scene ? c.scene : std::make_shared<const scene::Scene>(scene::builtin_scene());
  const scene::Camera camera = c.camera ? *c.camera : scene::orbit_camera(*sc, 1, 8);

  // Backends and every G-buffer size before `on_ready` (no output folder when they fail).
  std::unique_ptr<AaBackend> cpu, gpu;
  if (uses_cpu(c.backend)) {
    Result<std::unique_ptr<AaBackend>> r = create_cpu_aa_backend(*sc, {c.threads});
    if (!r) return r.status();
    cpu = std::move(*r);
  }
  if (factory != nullptr) {
    Result<std::unique_ptr<AaBackend>> r = factory->create_aa(*sc);
    if (!r) return r.status();
    if (!*r) return Status::error(ErrorCode::unsupported, "aa: the GPU factory returned nothing");
    gpu = std::move(*r);
  }
  for (AaBackend* be : {cpu.get(), gpu.get()}) {
    if (!be) continue;
    if (Status s = be->check_size(c.width, c.height, 1); !s.ok()) return s;
    for (int m : c.ssaa) {
      if (Status s = be->check_size(c.width, c.height, m); !s.ok()) return s;
    }
  }
  if (c.on_ready) {
    if (Status s = c.on_ready(); !s.ok()) return s;
  }

  AaResult res;
  res.threads = c.threads > 0 ? c.threads : default_thread_count();
  deferred::ShadingOptions normal = deferred::scene_shading(*sc, c.lights, &camera);
  normal.threads = c.threads;
  deferred::ShadingOptions heavy = normal;
  heavy.heavy = true;
  if (c.heavy_terms >= 0) heavy.heavy_terms = c.heavy_terms;
  res.heavy_terms = heavy.heavy_terms;
  res.lights = normal.lights.size();
  AaShadeOptions options;
  options.adaptive = c.adaptive;
  options.fxaa.preset = c.fxaa_preset;
  options.fxaa.threads = c.threads;
  options.edge = c.edge;
  options.edge.threads = c.threads;

  AaBackend& primary = cpu ? *cpu : *gpu;
  if (Status s = run_backend(Run{c, primary, camera, normal, heavy, options}, res); !s.ok()) {
    return s;
  }
  if (c.backend == Backend::both) {
    AaResult g;
    g.threads = res.threads;
    g.heavy_terms = res.heavy_terms;
    g.lights = res.lights;
    if (Status s = run_backend(Run{c, *gpu, camera, normal, heavy, options}, g); !s.ok()) return s;
    if (Status s = compare_backends(res, g); !s.ok()) return s;
    res.gpu_renderer = g.gpu_renderer;
    res.gpu_version = g.gpu_version;
    res.gl = std::make_shared<const AaResult>(std::move(g));
    res.backend = Backend::both;
  }
  return res;
}

}  // namespace

Result<AaResult> run_aa(const AaConfig& c) {
  if (c.ssaa.empty() || c.width < 1 || c.height < 1 || c.frames < 1 || c.lights < 0 ||
      !deferred::valid_fxaa_preset(c.fxaa_preset)) {
    return Status::error(ErrorCode::invalid_argument, "aa: bad configuration");
  }
  for (int m : c.ssaa) {
    if (m < 1 || m > 8) {
      return Status::error(ErrorCode::invalid_argument,
                           "aa: window size " + std::to_string(m) + " not in [1, 8]");
    }
  }
  Result<const GpuBackendFactory*> factory =
      detail::gpu_factory("aa", c.backend, c.gl_factory, c.vk_factory);
  if (!factory) return factory.status();
  Result<AaResult> res = run_backends(c, *factory);  // the backends are gone when it returns
  if (*factory != nullptr) {
    if (Status s = (*factory)->device_status(); !s.ok()) return s;
  }
  return res;
}

}  // namespace tessera::experiments
