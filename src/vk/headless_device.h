// Internal to src/vk: a Vulkan device of tessera's own, for the experiments' Vulkan backends
// (vk::experiment_backends, tessera/vk_experiments.h), the way gl::Context is a headless GL
// context of tessera's own. Engines never see it: their components take the engine's device.
//
// The loader comes from `HeadlessDeviceOptions::get_instance_proc_addr`, or, when that is null,
// from libvulkan.so.1 opened at run time (tessera_vk links no loader). The instance is Vulkan 1.3
// (lower where the loader is older); with `validation` it enables VK_LAYER_KHRONOS_validation with
// synchronization validation and a debug-utils messenger counting every warning and error. The
// device: the first physical device (or the `device_index`-th, $TESSERA_VK_DEVICE) with a
// graphics + compute queue family, every supported core feature except robustBufferAccess, and
// synchronization2 where the device has Vulkan 1.3, VK_EXT_depth_clip_control where it has it.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "vk/vk_api.h"

namespace tessera::vk {

struct HeadlessDeviceOptions {
  /// The loader's entry point; null = dlopen("libvulkan.so.1").
  PFN_vkGetInstanceProcAddr get_instance_proc_addr = nullptr;
  /// VK_LAYER_KHRONOS_validation with synchronization validation (unsupported when the layer
  /// is not installed).
  bool validation = false;
  /// Which physical device with a graphics + compute queue (-1: $TESSERA_VK_DEVICE, else 0).
  int device_index = -1;
};

/// What the validation messenger counted (shared by every device of a factory).
struct ValidationLog {
  std::atomic<int> messages{0};
  std::mutex mutex;
  std::string first;  ///< The first message's text.
};

class HeadlessDevice {
 public:
  /// Instance, (messenger,) device, queue, command pool. One-line errors: no loader, no
  /// layer, no device with a graphics + compute queue.
  static Result<std::unique_ptr<HeadlessDevice>> create(const HeadlessDeviceOptions& options,
                                                        std::shared_ptr<ValidationLog> log = {});
  ~HeadlessDevice();
  HeadlessDevice(const HeadlessDevice&) = delete;
  HeadlessDevice& operator=(const HeadlessDevice&) = delete;

  /// The device as an engine would hand it to a component.
  const DeviceContext& context() const { return api_.ctx; }
  /// The loaded entry points (components' and TESSERA_VK_GRAPHICS_FUNCTIONS), properties.
  const Api& api() const { return api_; }
  const VkPhysicalDeviceFeatures& features() const { return api_.ctx.enabled_features; }

  /// VkPhysicalDeviceProperties::deviceName, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  std::string device_name() const;
  /// "Vulkan 1.3.238, driver 0.0.1" (API version, driver version as the vendor encodes it).
  std::string device_version() const;
  /// Milliseconds per timestamp tick; 0 when the queue family has no timestamps.
  double timestamp_ms_per_tick() const;

  /// A fresh primary command buffer of the queue family, begun (one-time submit).
  Result<VkCommandBuffer> begin();
  /// Ends, submits and waits for `cmd` (a fence), then frees it; also on failure.
  Status submit_and_wait(VkCommandBuffer cmd);

  /// Whether VK_EXT_depth_clip_control is enabled (where the device has it): pipelines may
  /// keep OpenGL's [-w, w] clip depth (negativeOneToOne).
  bool depth_clip_control() const { return depth_clip_control_; }

  /// Validation warnings and errors so far (0 without validation).
  int validation_messages() const { return log_ ? log_->messages.load() : 0; }

 private:
  HeadlessDevice() = default;
  Status create_instance(const HeadlessDeviceOptions& options, std::shared_ptr<ValidationLog> log);
  Status create_device(const HeadlessDeviceOptions& options);
  void destroy();

  void* loader_ = nullptr;  ///< dlopen handle, or null.
  Api api_;
  std::shared_ptr<ValidationLog> log_;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  bool depth_clip_control_ = false;
};

}  // namespace tessera::vk
