// vk::experiment_backends (tessera/vk_experiments.h): the Vulkan implementation of
// experiments::GpuBackendFactory, handing out the backends of seams_backend.cpp and
// aa_backend.cpp, with one validation log for all of them.
#include "tessera/vk_experiments.h"
#include "vk/experiment_backends_internal.h"

namespace tessera::vk {

namespace {

class VkBackends final : public experiments::GpuBackendFactory {
 public:
  explicit VkBackends(const ExperimentBackendOptions& options)
      : log_(std::make_shared<ValidationLog>()) {
    device_.get_instance_proc_addr = options.get_instance_proc_addr;
    device_.validation = options.validation;
    device_.device_index = options.device_index;
  }

  experiments::Backend backend() const override { return experiments::Backend::vk; }
  Result<std::unique_ptr<experiments::SeamsBackend>> create_seams(
      const faces::FaceScene& scene, const faces::FaceTextureSet& textures) const override {
    return create_seams_backend(scene, textures, device_, log_);
  }
  Result<std::unique_ptr<experiments::AaBackend>> create_aa(
      const scene::Scene& scene) const override {
    return create_aa_backend(scene, device_, log_);
  }
  Status device_status() const override {
    const int n = log_->messages.load();
    if (n == 0) return Status::success();
    std::lock_guard<std::mutex> lock(log_->mutex);
    return Status::error(ErrorCode::unsupported, "vulkan validation: " + std::to_string(n) +
                                                     " message(s), the first: " + log_->first);
  }

 private:
  HeadlessDeviceOptions device_;
  std::shared_ptr<ValidationLog> log_;
};

}  // namespace

std::shared_ptr<const experiments::GpuBackendFactory> experiment_backends(
    const ExperimentBackendOptions& options) {
  return std::make_shared<const VkBackends>(options);
}

}  // namespace tessera::vk
