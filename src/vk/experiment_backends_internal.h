// Internal to tessera_vk: the Vulkan backends of the two experiments, made by
// vk::experiment_backends (experiment_backends.cpp; tessera/vk_experiments.h). Each makes its own
// HeadlessDevice from `device` and reports validation messages into `log` (shared by the
// factory, which turns them into its device_status()).
#pragma once

#include <memory>

#include "tessera/experiments/aa_backend.h"
#include "tessera/experiments/seams_backend.h"
#include "vk/headless_device.h"

namespace tessera::vk {

/// The seam experiment on Vulkan: seams_render.vert/.frag with vk::FaceTextureSet
/// (seams_backend.cpp).
Result<std::unique_ptr<experiments::SeamsBackend>> create_seams_backend(
    const faces::FaceScene& scene, const faces::FaceTextureSet& textures,
    const HeadlessDeviceOptions& device, std::shared_ptr<ValidationLog> log);

/// The AA experiment on Vulkan: the G-buffer pass, vk::AdaptiveSupersampler and
/// deferred_passes.comp (aa_backend.cpp).
Result<std::unique_ptr<experiments::AaBackend>> create_aa_backend(
    const scene::Scene& scene, const HeadlessDeviceOptions& device,
    std::shared_ptr<ValidationLog> log);

}  // namespace tessera::vk
