// The Vulkan backend of the seam experiment: the face renderer (face_renderer.h) on a
// HeadlessDevice of its own behind experiments::SeamsBackend (tessera/experiments/
// seams_backend.h), made by vk::experiment_backends (`tessera seams --backend vk`). The twin of
// gl::create_seams_backend (src/gl/seams_backend.cpp): the same options, refusals and frames.
#include <span>

#include "vk/experiment_backends_internal.h"
#include "vk/face_renderer.h"

namespace tessera::vk {

namespace {

using experiments::SeamsBackendFrame;
using experiments::SeamsSamplePattern;

class VkSeamsBackend final : public experiments::SeamsBackend {
 public:
  VkSeamsBackend(std::unique_ptr<HeadlessDevice> device, std::unique_ptr<FaceRenderer> renderer)
      : device_(std::move(device)), r_(std::move(renderer)) {}
  ~VkSeamsBackend() override { r_.reset(); }  // the renderer's objects go before the device

  experiments::Backend backend() const override { return experiments::Backend::vk; }
  std::string device_name() const override { return device_->device_name(); }
  std::string device_version() const override { return device_->device_version(); }

  bool msaa_supported(int samples) override { return r_->msaa_supported(samples); }
  bool has_shading_only() const override { return false; }
  // Vulkan allocates exactly the samples asked for; where the device has the standard sample
  // locations they are raster::sample_positions (both are Direct3D's tables, y down, and the
  // vertex shader's y flip makes framebuffer rows the image's).
  SeamsSamplePattern sample_pattern(int msaa) override {
    if (!r_->msaa_supported(msaa) || !r_->standard_sample_locations()) {
      return {msaa, msaa, 0, {}};
    }
    const std::span<const raster::SampleOffset> standard = raster::sample_positions(msaa);
    return {msaa, msaa, msaa, {standard.begin(), standard.end()}};
  }

  Result<SeamsBackendFrame> render(const scene::Camera& camera,
                                   const experiments::FaceFrameOptions& options) override {
    FaceFrameOptions o;
    static_cast<experiments::FaceFrameOptions&>(o) = options;
    Result<FaceFrame> frame = r_->render(camera, o);
    if (!frame) return frame.status();
    return SeamsBackendFrame(std::move(*frame));
  }

  Result<ImageRGBAF> render_reference(const scene::Camera& camera, int width, int height,
                                      const faces::ReferenceOptions& options) override {
    return r_->render_reference(camera, width, height, options);
  }

 private:
  std::unique_ptr<HeadlessDevice> device_;
  std::unique_ptr<FaceRenderer> r_;
};

}  // namespace

Result<std::unique_ptr<experiments::SeamsBackend>> create_seams_backend(
    const faces::FaceScene& scene, const faces::FaceTextureSet& textures,
    const HeadlessDeviceOptions& device, std::shared_ptr<ValidationLog> log) {
  Result<std::unique_ptr<HeadlessDevice>> d = HeadlessDevice::create(device, std::move(log));
  if (!d) return d.status();
  Result<std::unique_ptr<FaceRenderer>> r = FaceRenderer::create(**d, scene, textures);
  if (!r) return r.status();
  return std::unique_ptr<experiments::SeamsBackend>(
      std::make_unique<VkSeamsBackend>(std::move(*d), std::move(*r)));
}

}  // namespace tessera::vk
