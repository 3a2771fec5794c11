// The OpenGL backend of the adaptive-supersampling experiment: gl::DeferredRenderer
// (tessera/gl_deferred.h) on a headless context of its own behind the AaBackend interface of
// tessera/experiments/aa_backend.h, so that `experiments::run_aa` (in the GL-free main library)
// renders with OpenGL when a program linking tessera_gl hands it gl::experiment_backends()
// (`tessera aa --backend gl|both`). The CPU twin is src/experiments/aa_backend_cpu.cpp. Times:
// each pass's host wall time to the end of its closing glFinish (what llvmpipe's compute work
// costs) and its GL_TIME_ELAPSED beside it.
#include "experiments/gpu_shade.h"
#include "gl/experiment_backends_internal.h"
#include "tessera/gl.h"
#include "tessera/gl_deferred.h"

namespace tessera::gl {

using experiments::AaBackend;
using experiments::AaMethod;
using experiments::AaShadeOptions;
using experiments::AaShadeOutput;

namespace {

class GlAaBackend final : public GlBackend<AaBackend, DeferredRenderer> {
 public:
  using GlBackend::GlBackend;

  Status check_size(int width, int height, int m) const override {
    return r_->check_size(width, height, m);
  }

  Result<PassTime> render_gbuffer(const scene::Camera& camera, int width, int height,
                                  int m) override {
    if (Status s = r_->render_gbuffer(camera, width, height, m); !s.ok()) return s;
    return PassTime{"gbuffer", r_->last_gbuffer_wall_ms(), r_->last_gbuffer_ms()};
  }

  Result<AaShadeOutput> shade(AaMethod method, const deferred::ShadingOptions& so,
                              const AaShadeOptions& o) override {
    return experiments::shade_on_gpu(*r_, method, so, o);
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
