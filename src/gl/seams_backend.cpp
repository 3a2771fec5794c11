// The OpenGL backend of the seam experiment: gl::SeamsRenderer (tessera/gl_seams.h) on a headless
// context of its own behind the SeamsFrameRenderer interface of tessera/experiments.h, so that
// `experiments::run_seams` (in the GL-free main library) renders with OpenGL when a program
// linking tessera_gl hands it this factory (`tessera seams --backend gl|both`).
#include "tessera/experiments.h"
#include "tessera/gl.h"
#include "tessera/gl_seams.h"

namespace tessera::experiments {

namespace {

class GlSeamsRenderer final : public SeamsFrameRenderer {
 public:
  GlSeamsRenderer(std::unique_ptr<gl::Context> ctx, std::unique_ptr<gl::SeamsRenderer> r)
      : ctx_(std::move(ctx)), r_(std::move(r)) {}
  ~GlSeamsRenderer() override {
    // GL objects go before their context, with the context current.
    if (ctx_ && ctx_->make_current().ok()) r_.reset();
  }
  GlSeamsRenderer(const GlSeamsRenderer&) = delete;
  GlSeamsRenderer& operator=(const GlSeamsRenderer&) = delete;

  Backend backend() const override { return Backend::gl; }
  std::string device_name() const override { return ctx_->renderer(); }
  std::string device_version() const override { return ctx_->version(); }
  bool msaa_supported(int samples) override { return r_->msaa_supported(samples); }
  bool has_shading_only() const override { return false; }
  SeamsSamplePattern sample_pattern(int msaa) override {
    Result<gl::SamplePattern> p = r_->sample_pattern(msaa);
    if (!p) return {msaa, msaa, 0, {}};  // a refused rate: nothing to compare with
    // The positions on the CPU's 1/16-pixel grid (empty where they are off it), so that a
    // driver pattern that is no standard one can still be drawn by the CPU like for like.
    return {msaa, p->samples, p->cpu_msaa, gl::cpu_sample_offsets(p->positions)};
  }

  Result<SeamsBackendFrame> render(const scene::Camera& camera,
                                   const SeamsFrameOptions& options) override {
    if (options.shading_only) {
      return Status::error(ErrorCode::unsupported,
                           "seams: the GL backend has no shading-only pass");
    }
    if (!options.sample_pattern.empty()) {
      return Status::error(ErrorCode::unsupported,
                           "seams: the GL backend draws at the driver's sample positions, not "
                           "at an explicit pattern");
    }
    gl::SeamsRenderOptions o;
    o.width = options.width;
    o.height = options.height;
    o.msaa = options.msaa;
    o.method = options.method;
    o.filter = options.filter;
    o.max_aniso = options.max_aniso;
    o.clamp_fallback = options.clamp_fallback;
    o.read_back = options.keep_image;
    Result<gl::SeamsFrame> f = r_->render(camera, o);
    if (!f) return f.status();
    SeamsBackendFrame out;
    out.ms = f->gpu_ms();
    out.wall_ms = f->wall_ms;
    out.image = std::move(f->image);
    return out;
  }

  Result<ImageRGBAF> render_reference(const scene::Camera& camera, int width, int height,
                                      const faces::ReferenceOptions& options) override {
    return r_->render_reference(camera, width, height, options);
  }

 private:
  std::unique_ptr<gl::Context> ctx_;
  std::unique_ptr<gl::SeamsRenderer> r_;
};

}  // namespace

Result<std::unique_ptr<SeamsFrameRenderer>> create_gl_seams_renderer(
    const faces::FaceScene& scene, const faces::FaceTextureSet& textures,
    const std::string& glsl_dir) {
  Result<std::unique_ptr<gl::Context>> ctx = gl::Context::create();
  if (!ctx) return ctx.status();
  gl::SeamsRendererOptions ro;
  ro.glsl_dir = glsl_dir;
  Result<std::unique_ptr<gl::SeamsRenderer>> r = gl::SeamsRenderer::create(scene, textures, ro);
  if (!r) return r.status();
  return std::unique_ptr<SeamsFrameRenderer>(
      std::make_unique<GlSeamsRenderer>(std::move(*ctx), std::move(*r)));
}

}  // namespace tessera::experiments
