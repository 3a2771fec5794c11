// The CPU backend of the adaptive-supersampling experiment: deferred::DeferredRenderer behind
// the AaBackend interface of tessera/experiments/aa_backend.h (the GL and Vulkan twins are
// src/gl/aa_backend.cpp and src/vk/aa_backend.cpp), and aa_shade_output, which both GPU
// backends' results go through.
#include <chrono>
#include <cmath>
#include <limits>

#include "tessera/experiments/aa_backend.h"

namespace tessera::experiments {

namespace {

double elapsed_ms(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

constexpr double kNoGpu = std::numeric_limits<double>::quiet_NaN();

class CpuAaBackend final : public AaBackend {
 public:
  CpuAaBackend(std::unique_ptr<deferred::DeferredRenderer> r, const Parallel& parallel)
      : r_(std::move(r)), parallel_(parallel) {}

  Backend backend() const override { return Backend::cpu; }
  std::string device_name() const override { return {}; }
  std::string device_version() const override { return {}; }
  Status check_size(int width, int height, int m) const override {
    if (width < 1 || height < 1 || m < 1 || m > 8) {
      return Status::error(ErrorCode::invalid_argument, "aa: bad G-buffer size");
    }
    return Status::success();
  }

  Result<PassTime> render_gbuffer(const scene::Camera& camera, int width, int height,
                                  int m) override {
    const auto t0 = std::chrono::steady_clock::now();
    if (Status s = r_->render_gbuffer(camera, width, height, m, gb_); !s.ok()) return s;
    return PassTime{"gbuffer", elapsed_ms(t0), kNoGpu};
  }

  Result<AaShadeOutput> shade(AaMethod method, const deferred::ShadingOptions& so,
                              const AaShadeOptions& o) override {
    AaShadeOutput out;
    out.gpu_ms = kNoGpu;
    const auto t0 = std::chrono::steady_clock::now();
    switch (method) {
      case AaMethod::default_1spp:
      case AaMethod::fxaa: {
        out.image = to_srgb8(r_->shade_default(gb_, so), parallel_);
        if (method == AaMethod::fxaa) {
          Result<ImageRGBA8> fx = deferred::fxaa(out.image, o.fxaa);
          if (!fx) return fx.status();
          out.image = std::move(*fx);
        }
        break;
      }
      case AaMethod::reference:
        out.image = to_srgb8(r_->shade_reference(gb_, so), parallel_);
        break;
      case AaMethod::adaptive:
      case AaMethod::edge_per_sample: {
        deferred::AdaptiveResult r = method == AaMethod::adaptive
                                         ? r_->shade_adaptive(gb_, so, o.adaptive)
                                         : deferred::shade_edge_per_sample(*r_, gb_, so, o.edge);
        out.image = to_srgb8(r.image, parallel_);
        out.samples = std::move(r.samples);
        out.samples_shaded = r.samples_shaded;
        out.extra_lookups = r.extra_lookups;
        if (method == AaMethod::adaptive) {
          out.passes = {{"first", r.ms_first, kNoGpu},
                        {"metrics", r.ms_metric, kNoGpu},
                        {"extra", r.ms_rest, kNoGpu}};
        } else {
          out.passes = {{"classify", r.ms_metric, kNoGpu}, {"shade", r.ms_rest, kNoGpu}};
        }
        break;
      }
    }
    out.wall_ms = elapsed_ms(t0);
    return out;
  }

 private:
  std::unique_ptr<deferred::DeferredRenderer> r_;
  Parallel parallel_;
  deferred::GBuffer gb_;
};

}  // namespace

Result<std::unique_ptr<AaBackend>> create_cpu_aa_backend(const scene::Scene& scene,
                                                         const Parallel& parallel) {
  Result<std::unique_ptr<deferred::DeferredRenderer>> r =
      deferred::DeferredRenderer::create(scene, parallel);
  if (!r) return r.status();
  return std::unique_ptr<AaBackend>(std::make_unique<CpuAaBackend>(std::move(*r), parallel));
}

AaShadeOutput aa_shade_output(AaMethod method, deferred::ShadeResult result, int threads) {
  AaShadeOutput out;
  out.image = to_srgb8(result.image, {threads});
  if (method == AaMethod::adaptive || method == AaMethod::edge_per_sample) {
    out.samples = std::move(result.samples);
    out.samples_shaded = result.samples_shaded;
  }
  out.wall_ms = result.total_wall_ms();
  out.gpu_ms = result.total_gpu_ms();
  out.passes = std::move(result.passes);
  return out;
}

AaShadeOutput aa_shade_output(deferred::FxaaResult result) {
  AaShadeOutput out;
  out.image = std::move(result.image);
  out.wall_ms = result.total_wall_ms();
  out.gpu_ms = result.total_gpu_ms();
  out.passes = std::move(result.passes);
  return out;
}

}  // namespace tessera::experiments
