// The Vulkan backend of the adaptive-supersampling experiment: vk::DeferredRenderer
// (deferred_renderer.h) on a HeadlessDevice of its own behind the AaBackend interface of
// tessera/experiments/aa_backend.h, so that `experiments::run_aa` renders with Vulkan when a
// program linking tessera_vk hands it vk::experiment_backends(). The twin of
// src/gl/aa_backend.cpp: the same passes and pass names, the same AaShadeOutput. Times: each
// pass's GPU timestamps; the wall time from submit to fence (deferred_passes.comp passes are
// one submission each; the component's passes share one, whose wall time is the method's and
// is split between its passes by their GPU times).
#include "experiments/gpu_shade.h"
#include "tessera/core.h"
#include "vk/deferred_renderer.h"
#include "vk/experiment_backends_internal.h"

namespace tessera::vk {

namespace {

using experiments::AaMethod;

class VkAaBackend final : public experiments::AaBackend {
 public:
  VkAaBackend(std::unique_ptr<HeadlessDevice> device, std::unique_ptr<DeferredRenderer> r)
      : device_(std::move(device)), r_(std::move(r)) {}

  experiments::Backend backend() const override { return experiments::Backend::vk; }
  std::string device_name() const override { return device_->device_name(); }
  std::string device_version() const override { return device_->device_version(); }

  Status check_size(int width, int height, int m) const override {
    return r_->check_size(width, height, m);
  }

  Result<PassTime> render_gbuffer(const scene::Camera& camera, int width, int height,
                                  int m) override {
    return r_->render_gbuffer(camera, width, height, m);
  }

  Result<experiments::AaShadeOutput> shade(AaMethod method, const deferred::ShadingOptions& so,
                                           const experiments::AaShadeOptions& o) override {
    return experiments::shade_on_gpu(*r_, method, so, o);
  }

 private:
  std::unique_ptr<HeadlessDevice> device_;  // outlives the renderer (declared first)
  std::unique_ptr<DeferredRenderer> r_;
};

}  // namespace

Result<std::unique_ptr<experiments::AaBackend>> create_aa_backend(
    const scene::Scene& scene, const HeadlessDeviceOptions& options,
    std::shared_ptr<ValidationLog> log) {
  Result<std::unique_ptr<HeadlessDevice>> device = HeadlessDevice::create(options, std::move(log));
  if (!device) {
    return Status::error(device.status().code, "aa: no Vulkan backend: " + device.status().message);
  }
  Result<std::unique_ptr<DeferredRenderer>> r = DeferredRenderer::create(**device, scene);
  if (!r) return r.status();
  return std::unique_ptr<experiments::AaBackend>(
      std::make_unique<VkAaBackend>(std::move(*device), std::move(*r)));
}

}  // namespace tessera::vk
