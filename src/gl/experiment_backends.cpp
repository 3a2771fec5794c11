// gl::experiment_backends (tessera/gl_experiments.h): the one implementation of
// experiments::GpuBackendFactory, handing out the GL backends of seams_backend.cpp and
// aa_backend.cpp.
#include "gl/experiment_backends_internal.h"
#include "tessera/gl_experiments.h"

namespace tessera::gl {

namespace {

class GlBackends final : public experiments::GpuBackendFactory {
 public:
  explicit GlBackends(ExperimentBackendOptions options) : options_(std::move(options)) {}

  experiments::Backend backend() const override { return experiments::Backend::gl; }

  Result<std::unique_ptr<experiments::SeamsBackend>> create_seams(
      const faces::FaceScene& scene, const faces::FaceTextureSet& textures) const override {
    return create_seams_backend(scene, textures, options_.glsl_dir);
  }
  Result<std::unique_ptr<experiments::AaBackend>> create_aa(
      const scene::Scene& scene) const override {
    return create_aa_backend(scene, options_.glsl_dir, options_.schedule);
  }

 private:
  ExperimentBackendOptions options_;
};

}  // namespace

std::shared_ptr<const experiments::GpuBackendFactory> experiment_backends(
    const ExperimentBackendOptions& options) {
  return std::make_shared<const GlBackends>(options);
}

std::shared_ptr<const experiments::GpuBackendFactory> experiment_backends(
    const std::filesystem::path& glsl_dir) {
  ExperimentBackendOptions options;
  options.glsl_dir = glsl_dir;
  return experiment_backends(options);
}

}  // namespace tessera::gl
