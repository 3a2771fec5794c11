// The experiment of Holländer, Boubekeur & Eisemann 2013 (Table 1, Figures 6a, 7 and 8):
// adaptive supersampling of an enlarged G-buffer against full supersampling, plain 1x deferred
// shading and FXAA 3.11, measured side by side in one run.
#include <chrono>
#include <cmath>
#include <cstdio>

#include "tessera/experiments.h"
#include "tessera/metrics.h"

namespace tessera::experiments {

namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

Result<AaQuality> quality(const ImageRGBA8& ref, const ImageRGBA8& img, int threads) {
  CompareOptions co;
  co.threads = threads;
  const Result<ImageComparison> c = compare_images(ref, img, co);
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
  if (c.backend != Backend::cpu) {
    return Status::error(ErrorCode::unsupported, std::string("aa: backend '") +
                                                     backend_name(c.backend) +
                                                     "' is not yet implemented for this "
                                                     "experiment (only 'cpu')");
  }
  const std::shared_ptr<const scene::Scene> sc =
      c.scene ? c.scene : std::make_shared<const scene::Scene>(scene::builtin_scene());
  const scene::Camera camera = c.camera ? *c.camera : scene::orbit_camera(*sc, 1, 8);
  if (c.on_ready) {
    if (Status s = c.on_ready(); !s.ok()) return s;
  }
  Result<std::unique_ptr<deferred::DeferredRenderer>> rr =
      deferred::DeferredRenderer::create(*sc, c.threads);
  if (!rr) return rr.status();
  deferred::DeferredRenderer& renderer = **rr;

  AaResult res;
  res.threads = c.threads > 0 ? c.threads : default_thread_count();
  deferred::ShadingOptions normal = deferred::scene_shading(*sc, c.lights, &camera);
  normal.threads = c.threads;
  deferred::ShadingOptions heavy = normal;
  heavy.heavy = true;
  if (c.heavy_terms >= 0) heavy.heavy_terms = c.heavy_terms;
  res.heavy_terms = heavy.heavy_terms;
  res.lights = normal.lights.size();
  deferred::FxaaOptions fxo;
  fxo.preset = c.fxaa_preset;
  fxo.threads = c.threads;
  const int modes = c.heavy ? 2 : 1;
  const std::uint64_t pixels = std::uint64_t(c.width) * std::uint64_t(c.height);

  // The paper's 1x1 rows: a w x h G-buffer, one sample per pixel, and FXAA on it.
  {
    deferred::GBuffer gb;
    for (int f = 0; f < c.frames; ++f) {
      auto t0 = std::chrono::steady_clock::now();
      if (Status s = renderer.render_gbuffer(camera, c.width, c.height, 1, gb); !s.ok()) return s;
      res.gbuffer_1x1.frame_ms.push_back(ms_since(t0));
      for (int mode = 0; mode < modes; ++mode) {
        const deferred::ShadingOptions& so = mode ? heavy : normal;
        for (int k = 0; k < 2; ++k) {
          const int method = (k + f) % 2;
          t0 = std::chrono::steady_clock::now();
          ImageRGBA8 img = to_srgb8(renderer.shade_default(gb, so), c.threads);
          if (method == 1) {
            Result<ImageRGBA8> fx = deferred::fxaa(img, fxo);
            if (!fx) return fx.status();
            img = std::move(*fx);
          }
          AaTiming& tt = method ? res.fxaa_1x1 : res.default_1x1;
          (mode ? tt.heavy : tt.normal).frame_ms.push_back(ms_since(t0));
        }
      }
    }
  }

  for (int m : c.ssaa) {
    AaRateResult rate;
    rate.m = m;
    for (AaMethod k : kAaMethods) rate.method(k).method = k;
    deferred::GBuffer gb;
    deferred::AdaptiveResult ad, ad_heavy;
    for (int f = 0; f < c.frames; ++f) {
      auto t0 = std::chrono::steady_clock::now();
      if (Status s = renderer.render_gbuffer(camera, c.width, c.height, m, gb); !s.ok()) return s;
      rate.gbuffer.frame_ms.push_back(ms_since(t0));
      for (int mode = 0; mode < modes; ++mode) {
        const deferred::ShadingOptions& so = mode ? heavy : normal;
        // Methods alternated per frame, in the order of `AaMethod` rotated by the frame.
        for (int k = 0; k < 4; ++k) {
          const AaMethod method = kAaMethods[std::size_t((k + f) % 4)];
          AaMethodResult& mr = rate.method(method);
          ImageRGBA8& out = mode ? mr.image_heavy : mr.image;
          t0 = std::chrono::steady_clock::now();
          if (method == AaMethod::default_1spp || method == AaMethod::fxaa) {
            out = to_srgb8(renderer.shade_default(gb, so), c.threads);
            if (method == AaMethod::fxaa) {
              Result<ImageRGBA8> fx = deferred::fxaa(out, fxo);
              if (!fx) return fx.status();
              out = std::move(*fx);
            }
          } else if (method == AaMethod::reference) {
            out = to_srgb8(renderer.shade_reference(gb, so), c.threads);
          } else {
            deferred::AdaptiveResult r = renderer.shade_adaptive(gb, so, c.adaptive);
            out = to_srgb8(r.image, c.threads);
            if (mode == 0) {
              rate.adaptive_first.frame_ms.push_back(r.ms_first);
              rate.adaptive_metric.frame_ms.push_back(r.ms_metric);
              rate.adaptive_rest.frame_ms.push_back(r.ms_rest);
            }
            (mode ? ad_heavy : ad) = std::move(r);
          }
          (mode ? mr.timing.heavy : mr.timing.normal).frame_ms.push_back(ms_since(t0));
        }
      }
    }
    const double total = double(pixels) * double(m * m);
    auto pct = [&](std::uint64_t s) { return 100.0 * double(s) / total; };
    const ImageRGBA8& ref = rate.method(AaMethod::reference).image;
    for (AaMethod k : kAaMethods) {
      AaMethodResult& mr = rate.method(k);
      Result<AaQuality> q = quality(ref, mr.image, res.threads);
      if (!q) return q.status();
      mr.quality = *q;
    }
    rate.method(AaMethod::default_1spp).samples_pct = 100.0 / (m * m);
    rate.method(AaMethod::fxaa).samples_pct = 100.0 / (m * m);
    rate.method(AaMethod::reference).samples_pct = 100.0;
    rate.method(AaMethod::adaptive).samples_pct = pct(ad.samples_shaded);
    rate.adaptive_samples = std::move(ad.samples);
    rate.adaptive_extra_albedo_lookups_pct = 100.0 * double(ad.extra_lookups) / double(pixels);
    if (c.heavy) {
      Result<AaQuality> q = quality(rate.method(AaMethod::reference).image_heavy,
                                    rate.method(AaMethod::adaptive).image_heavy, res.threads);
      if (!q) return q.status();
      rate.adaptive_heavy_quality = *q;
      rate.adaptive_heavy_samples_pct = pct(ad_heavy.samples_shaded);
    }

    // Ablations (Figure 8): one metric at a time, on the last frame's G-buffer.
    for (int which = 0; which < 2; ++which) {
      deferred::AdaptiveOptions ao = c.adaptive;
      (which == 0 ? ao.use_shading : ao.use_geometry) = false;
      deferred::AdaptiveResult r = renderer.shade_adaptive(gb, normal, ao);
      AaAblation& ab = which == 0 ? rate.ablation_geometry : rate.ablation_shading;
      ab.image = to_srgb8(r.image, c.threads);
      ab.samples = std::move(r.samples);
      ab.samples_pct = pct(r.samples_shaded);
      Result<AaQuality> q = quality(ref, ab.image, res.threads);
      if (!q) return q.status();
      ab.quality = *q;
    }
    if (c.progress) c.progress(rate_line(rate, rate.method(AaMethod::adaptive).samples_pct));
    res.rates.push_back(std::move(rate));
  }
  return res;
}

}  // namespace tessera::experiments
