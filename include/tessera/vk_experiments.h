// tessera/vk_experiments.h — the Vulkan backends of the two paper experiments: the Vulkan
// implementation of `experiments::GpuBackendFactory` (tessera/experiments/common.h), beside
// OpenGL's (tessera/gl_experiments.h). Part of the optional `tessera_vk` library
// (src/vk/experiment_backends.cpp, seams_backend.cpp, aa_backend.cpp); `run_seams` and `run_aa`
// reach Vulkan only through the factory a caller puts in the config (`SeamsConfig::vk_factory`,
// `AaConfig::vk_factory`).
//
// Each backend makes a Vulkan device of its own (src/vk/headless_device.h: the first physical
// device with a graphics + compute queue, or the one $TESSERA_VK_DEVICE numbers) from the
// loader the options name or libvulkan.so.1; the seam backend draws with seams_render.vert/.frag
// and vk::FaceTextureSet (tessera/vk_faces.h), the AA backend rasterises the G-buffer with
// deferred_gbuffer.vert/.frag and shades it with vk::AdaptiveSupersampler (tessera/vk_adaptive.h)
// and deferred_passes.comp: the same shipped GLSL as OpenGL's backends. Times are GPU timestamps.
// Tests: tests/vk/vk_aa_backend_test.cpp, vk_seams_backend_test.cpp, vk_cli_test.py.
#pragma once

#include <vulkan/vulkan.h>

#include <memory>

#include "tessera/experiments/common.h"

namespace tessera::vk {

struct ExperimentBackendOptions {
  /// The loader's vkGetInstanceProcAddr; null: libvulkan.so.1, opened when a backend is made.
  PFN_vkGetInstanceProcAddr get_instance_proc_addr = nullptr;
  /// Run every device under VK_LAYER_KHRONOS_validation with synchronization validation; any
  /// warning or error makes `device_status()` (and so `run_seams` / `run_aa`) fail. Creating a
  /// backend fails (unsupported) when the layer is not installed.
  bool validation = false;
  /// The physical device (among those with a graphics + compute queue); -1: $TESSERA_VK_DEVICE,
  /// else the first.
  int device_index = -1;
};

/// The Vulkan backends of both experiments. Creating a backend fails with one line when there is
/// no Vulkan loader or device, the device lacks a feature (named), or validation is asked for
/// and the layer is missing.
std::shared_ptr<const experiments::GpuBackendFactory> experiment_backends(
    const ExperimentBackendOptions& options = {});

}  // namespace tessera::vk
