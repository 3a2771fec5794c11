// The OpenGL backend of the seam experiment: gl::FaceRenderer (tessera/gl_face_renderer.h) on a
// headless context of its own behind the SeamsBackend interface of
// tessera/experiments/seams_backend.h, so that `experiments::run_seams` (in the GL-free main
// library) renders with OpenGL when a program linking tessera_gl hands it gl::experiment_backends()
// (`tessera seams --backend gl|both`). The CPU twin is src/experiments/seams_backend_cpu.cpp.
#include "gl/experiment_backends_internal.h"
#include "tessera/gl.h"
#include "tessera/gl_face_renderer.h"

namespace tessera::gl {

using experiments::SeamsBackendFrame;
using experiments::SeamsSamplePattern;

namespace {

class GlSeamsBackend final : public GlBackend<experiments::SeamsBackend, FaceRenderer> {
 public:
  using GlBackend::GlBackend;

  bool msaa_supported(int samples) override { return r_->msaa_supported(samples); }
  bool has_shading_only() const override { return false; }
  SeamsSamplePattern sample_pattern(int msaa) override {
    Result<SamplePattern> p = r_->sample_pattern(msaa);
    if (!p) return {msaa, msaa, 0, {}};  // a refused rate: nothing to compare with
    // The positions on the CPU's 1/16-pixel grid (empty where they are off it), so that a
    // driver pattern that is no standard one can still be drawn by the CPU like for like.
    return {msaa, p->samples, p->cpu_msaa, cpu_sample_offsets(p->positions)};
  }

  Result<SeamsBackendFrame> render(const scene::Camera& camera,
                                   const experiments::FaceFrameOptions& options) override {
    if (options.shading_only) {
      return Status::error(ErrorCode::unsupported,
                           "seams: the GL backend has no shading-only pass");
    }
    if (!options.sample_pattern.empty()) {
      return Status::error(ErrorCode::unsupported,
                           "seams: the GL backend draws at the driver's sample positions, not "
                           "at an explicit pattern");
    }
    FaceFrameOptions o;
    o.width = options.width;
    o.height = options.height;
    o.msaa = options.msaa;
    o.method = options.method;
    o.filter = options.filter;
    o.max_aniso = options.max_aniso;
    o.clamp_fallback = options.clamp_fallback;
    o.read_back = options.keep_image;
    Result<FaceFrame> f = r_->render(camera, o);
    if (!f) return f.status();
    return SeamsBackendFrame{std::move(f->image), f->gpu_ms(), f->wall_ms};
  }

  Result<ImageRGBAF> render_reference(const scene::Camera& camera, int width, int height,
                                      const faces::ReferenceOptions& options) override {
    return r_->render_reference(camera, width, height, options);
  }
};

}  // namespace

Result<std::unique_ptr<experiments::SeamsBackend>> create_seams_backend(
    const faces::FaceScene& scene, const faces::FaceTextureSet& textures,
    const std::filesystem::path& glsl_dir) {
  Result<std::unique_ptr<Context>> ctx = Context::create();
  if (!ctx) return ctx.status();
  FaceRendererOptions ro;
  ro.glsl_dir = glsl_dir;
  Result<std::unique_ptr<FaceRenderer>> r = FaceRenderer::create(scene, textures, ro);
  if (!r) return r.status();
  return std::unique_ptr<experiments::SeamsBackend>(
      std::make_unique<GlSeamsBackend>(std::move(*ctx), std::move(*r)));
}

}  // namespace tessera::gl
