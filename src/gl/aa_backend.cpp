// The OpenGL backend of the adaptive-supersampling experiment: gl::DeferredGlRenderer
// (tessera/gl_deferred.h) on a headless context of its own behind the AaBackend interface of
// tessera/experiments.h, so that `experiments::run_aa` (in the GL-free main library) renders with
// OpenGL when a program linking tessera_gl hands it this factory (`tessera aa --backend
// gl|both`). Times: each pass's host wall time to the end of its closing glFinish (what
// llvmpipe's compute work costs) and its GL_TIME_ELAPSED beside it.
#include "tessera/experiments.h"
#include "tessera/gl.h"
#include "tessera/gl_deferred.h"

namespace tessera::experiments {

namespace {

/// The passes of a GL result: wall and GPU times paired by position (same passes, same order).
std::vector<AaPassTime> pair_passes(const std::vector<gl::PassTime>& gpu,
                                    const std::vector<gl::PassTime>& wall) {
  std::vector<AaPassTime> out;
  for (std::size_t i = 0; i < wall.size(); ++i) {
    out.push_back({wall[i].pass, wall[i].ms, i < gpu.size() ? gpu[i].ms : 0.0});
  }
  return out;
}

class GlAaBackend final : public AaBackend {
 public:
  GlAaBackend(std::unique_ptr<gl::Context> ctx, std::unique_ptr<gl::DeferredGlRenderer> r)
      : ctx_(std::move(ctx)), r_(std::move(r)) {}
  ~GlAaBackend() override {
    // GL objects go before their context, with the context current.
    if (ctx_ && ctx_->make_current().ok()) r_.reset();
  }
  GlAaBackend(const GlAaBackend&) = delete;
  GlAaBackend& operator=(const GlAaBackend&) = delete;

  Backend backend() const override { return Backend::gl; }
  std::string device_name() const override { return ctx_->renderer(); }
  std::string device_version() const override { return ctx_->version(); }
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
      Result<gl::GlFxaaResult> x = r_->shade_default_fxaa(so, o.fxaa);
      if (!x) return x.status();
      out.image = std::move(x->image);
      out.wall_ms = x->total_wall_ms();
      out.gpu_ms = x->total_ms();
      out.passes = pair_passes(x->passes, x->wall_passes);
      return out;
    }
    Result<gl::GlShadeResult> x = method == AaMethod::default_1spp ? r_->shade_default(so)
                                  : method == AaMethod::reference  ? r_->shade_reference(so)
                                  : method == AaMethod::adaptive
                                      ? r_->shade_adaptive(so, o.adaptive)
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

 private:
  std::unique_ptr<gl::Context> ctx_;
  std::unique_ptr<gl::DeferredGlRenderer> r_;
};

}  // namespace

Result<std::unique_ptr<AaBackend>> create_gl_aa_backend(const scene::Scene& scene,
                                                        const std::string& glsl_dir) {
  Result<std::unique_ptr<gl::Context>> ctx = gl::Context::create();
  if (!ctx) {
    return Status::error(ctx.status().code,
                         "aa: no OpenGL backend: " + ctx.status().message);
  }
  gl::DeferredGlOptions go;
  go.glsl_dir = glsl_dir;
  Result<std::unique_ptr<gl::DeferredGlRenderer>> r = gl::DeferredGlRenderer::create(scene, go);
  if (!r) return r.status();
  return std::unique_ptr<AaBackend>(
      std::make_unique<GlAaBackend>(std::move(*ctx), std::move(*r)));
}

}  // namespace tessera::experiments
