// The CPU backend of the seam experiment: faces::FaceRenderer behind the SeamsBackend interface
// (tessera/experiments/seams_backend.h; the GL twin is src/gl/seams_backend.cpp).
#include "tessera/experiments/seams_backend.h"

namespace tessera::experiments {

namespace {

class CpuSeamsBackend final : public SeamsBackend {
 public:
  explicit CpuSeamsBackend(std::unique_ptr<faces::FaceRenderer> r) : r_(std::move(r)) {}

  Backend backend() const override { return Backend::cpu; }
  std::string device_name() const override { return {}; }
  std::string device_version() const override { return {}; }
  bool msaa_supported(int samples) override { return raster::valid_msaa(samples); }
  bool has_shading_only() const override { return true; }

  Result<SeamsBackendFrame> render(const scene::Camera& camera,
                                   const FaceFrameOptions& options) override {
    faces::FaceRenderOptions o;
    o.width = options.width;
    o.height = options.height;
    o.threads = options.threads;
    o.msaa = options.msaa;
    o.sample_pattern = options.sample_pattern;
    o.sampling.filter = options.filter;
    o.sampling.max_aniso = options.max_aniso;
    o.shading_only = options.shading_only;
    o.sampling.method = options.shading_only ? faces::SeamMethod::clamp : options.method;
    o.sampling.clamp_fallback = options.clamp_fallback;
    Result<faces::FaceFrame> f = r_->render(camera, o);
    if (!f) return f.status();
    return SeamsBackendFrame{std::move(f->image), f->ms(), f->ms()};
  }

  Result<ImageRGBAF> render_reference(const scene::Camera& camera, int width, int height,
                                      const faces::ReferenceOptions& options) override {
    return r_->render_reference(camera, width, height, options);
  }

 private:
  std::unique_ptr<faces::FaceRenderer> r_;
};

}  // namespace

Result<std::unique_ptr<SeamsBackend>> create_cpu_seams_backend(
    const faces::FaceScene& scene, const faces::FaceTextureSet& textures) {
  Result<std::unique_ptr<faces::FaceRenderer>> r = faces::FaceRenderer::create(scene, textures);
  if (!r) return r.status();
  return std::unique_ptr<SeamsBackend>(std::make_unique<CpuSeamsBackend>(std::move(*r)));
}

}  // namespace tessera::experiments
