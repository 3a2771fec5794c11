// The OpenGL backend of the adaptive-supersampling experiment: gl::DeferredRenderer
// (tessera/gl_deferred.h) on a headless context of its own behind the AaBackend interface of
// tessera/experiments/aa_backend.h, so that `experiments::run_aa` (in the GL-free main library)
// renders with OpenGL when a program linking tessera_gl hands it gl::experiment_backends()
// (`tessera aa --backend gl|both`). The CPU twin is src/experiments/aa_backend_cpu.cpp. Times:
// each pass's host wall time to the end of its closing glFinish (what llvmpipe's compute work
// costs) and its GL_TIME_ELAPSED beside it.
#include "gl/experiment_backends_internal.h"
#include "tessera/gl.h"
#include "tessera/gl_deferred.h"

namespace tessera::gl {

using experiments::AaBackend;
using experiments::AaMethod;
using experiments::AaPassTime;
using experiments::AaShadeOptions;
using experiments::AaShadeOutput;

namespace {

/// The passes of a GL result: wall and GPU times paired by position (same passes, same order).
std::vector<AaPassTime> pair_passes(const std::vector<PassTime>& gpu,
                                    const std::vector<PassTime>& wall) {
  std::vector<AaPassTime> out;
  for (std::size_t i = 0; i < wall.size(); ++i) {
    out.push_back({wall[i].pass, wall[i].ms, i < gpu.size() ? gpu[i].ms : 0.0});
  }
  return out;
}

class GlAaBackend final : public GlBackend<AaBackend, DeferredRenderer> {
 public:
  using GlBackend::GlBackend;

  Status check_size(int width, int height, int m) const override {
    return r_->check_size(width, height, m);
  }

  Result<AaPassTime> render_gbuffer(const scene::Camera& camera, int width, int height,
                                    int m) override {
    if (Status s = r_->render_gbuffer(camera, width, height, m); !s.ok()) return s;
    return AaPassTime{"gbuffer", r_->last_gbuffer_wall_ms(), r_->last_gbuffer_ms()};
  }

  Result<AaShadeOutput> shade(AaMethod method, const deferred::ShadingOptions& so,
                              const AaShadeOptions& o) override {
    AaShadeOutput out;
    if (method == AaMethod::fxaa) {
      Result<FxaaResult> x = r_->shade_default_fxaa(so, o.fxaa);
      if (!x) return x.status();
      out.image = std::move(x->image);
      out.wall_ms = x->total_wall_ms();
      out.gpu_ms = x->total_ms();
      out.passes = pair_passes(x->passes, x->wall_passes);
      return out;
    }
    Result<ShadeResult> x = method == AaMethod::default_1spp ? r_->shade_default(so)
                            : method == AaMethod::reference  ? r_->shade_reference(so)
                            : method == AaMethod::adaptive   ? r_->shade_adaptive(so, o.adaptive)
                                                           : r_->shade_edge_per_sample(so, o.edge);
    if (!x) return x.status();
    out.image = to_srgb8(x->image, {so.threads});
    if (method == AaMethod::adaptive || method == AaMethod::edge_per_sample) {
      out.samples = std::move(x->samples);
      out.samples_shaded = x->samples_shaded;
    }
    out.wall_ms = x->total_wall_ms();
    out.gpu_ms = x->total_ms();
    out.passes = pair_passes(x->passes, x->wall_passes);
    return out;
  }
};

}  // namespace

Result<std::unique_ptr<AaBackend>> create_aa_backend(const scene::Scene& scene,
                                                     const std::filesystem::path& glsl_dir,
                                                     ExtraSchedule schedule) {
  Result<std::unique_ptr<Context>> ctx = Context::create();
  if (!ctx) {
    return Status::error(ctx.status().code, "aa: no OpenGL backend: " + ctx.status().message);
  }
  DeferredRendererOptions go;
  go.glsl_dir = glsl_dir;
  go.schedule = schedule;
  Result<std::unique_ptr<DeferredRenderer>> r = DeferredRenderer::create(scene, go);
  if (!r) return r.status();
  return std::unique_ptr<AaBackend>(std::make_unique<GlAaBackend>(std::move(*ctx), std::move(*r)));
}

}  // namespace tessera::gl
