// The Vulkan tests' engine: its own instance with VK_LAYER_KHRONOS_validation (synchronization
// validation on through VkValidationFeaturesEXT), a debug-utils messenger that counts every
// warning and error (any one fails the test), a device (lavapipe in CI) with a compute +
// graphics queue, command buffers, and image upload / read-back. It links the Vulkan loader
// and calls it directly, as an engine would; tessera::vk gets only the function pointers.
#pragma once

#include <gtest/gtest.h>
#include <vulkan/vulkan.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tessera/core.h"
#include "tessera/vk.h"
#include "test_require.h"

namespace tessera::vk_test {

struct EngineOptions {
  bool validation = true;
  bool synchronization2 = true;  ///< Enable the feature (and tell tessera).
  bool extended_formats = true;  ///< Enable shaderStorageImageExtendedFormats.
  bool float64 = true;           ///< Enable shaderFloat64.
};

/// A device-local image the engine owns, with its memory and view.
struct EngineImage {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  vk::ImageResource resource;
};

/// A host-visible, coherent, mapped buffer the engine owns.
struct EngineBuffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* data = nullptr;
};

/// A copy of an image into a host buffer, recorded; its floats once the commands completed.
struct PendingRead {
  EngineBuffer buffer;
  std::size_t texels = 0, texel_bytes = 0;
};

class Engine {
 public:
  /// Instance, messenger, device; an error (with the reason) when there is no Vulkan device or
  /// no validation layer. `missing` says which: "vulkan" or "vulkan-validation".
  static Result<std::unique_ptr<Engine>> create(const EngineOptions& options, std::string* missing);
  ~Engine();
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  const vk::DeviceContext& context() const { return ctx_; }
  std::string device_name() const;

  /// A fresh primary command buffer, begun (one-time submit).
  VkCommandBuffer begin();
  /// A primary command buffer allocated but not begun (recording into it is a validation error).
  VkCommandBuffer idle_command_buffer();
  /// Ends, submits and waits for `cmd`, then frees it.
  void submit_and_wait(VkCommandBuffer cmd);

  /// An image of `format` (w x h) holding `texels` (RGBA floats per texel, converted to the
  /// format: R32G32B32A32_SFLOAT or R16G16B16A16_SFLOAT), uploaded and left in
  /// TRANSFER_DST_OPTIMAL after a copy (the resource's stage/access say so).
  EngineImage upload_rgba(VkFormat format, int w, int h, const std::vector<float>& texels,
                          VkImageUsageFlags extra_usage = 0);
  void destroy(EngineImage& img);
  EngineBuffer host_buffer(VkDeviceSize bytes, VkBufferUsageFlags usage);
  void destroy(EngineBuffer& buf);
  /// Reads back an image the component left in `from` (RGBA32F/RGBA16F as floats, R8_UINT as
  /// one float per texel), recording the barrier from its stage/access; `region` = its
  /// top-left texels (0 = the whole image). Leaves it in TRANSFER_SRC_OPTIMAL.
  std::vector<float> read_back(const vk::ImageResource& from, VkExtent2D region = {0, 0});
  /// The same, recorded into `cmd` (the engine's frame); finish_read once it completed.
  PendingRead record_read(VkCommandBuffer cmd, const vk::ImageResource& from,
                          VkExtent2D region = {0, 0});
  std::vector<float> finish_read(PendingRead& read);

  /// Frames in flight: a timeline semaphore the host signals, a fence, a submission of `cmd`
  /// (ended here) that waits for `timeline` >= `wait_value` and signals `fence`, the wait for
  /// a fence (then reset), freeing a command buffer.
  VkSemaphore timeline_semaphore();
  void signal(VkSemaphore timeline, std::uint64_t value);
  VkFence fence();
  void submit(VkCommandBuffer cmd, VkSemaphore timeline, std::uint64_t wait_value, VkFence fence);
  void wait_and_reset(VkFence fence);
  void free(VkCommandBuffer cmd);

  /// Validation messages (warnings and errors) so far, and the first few texts.
  int messages() const { return messages_.load(); }
  std::string first_messages() const;
  /// Destroys the device and the instance (leak reports arrive here); idempotent.
  void shutdown();

 private:
  Engine() = default;
  static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                   VkDebugUtilsMessageTypeFlagsEXT types,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                   void* self);
  std::uint32_t memory_type(std::uint32_t bits, VkMemoryPropertyFlags want) const;

  vk::DeviceContext ctx_;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  std::atomic<int> messages_{0};
  std::vector<std::string> texts_;
};

/// A test with an engine of its own (`make_engine`, by default in SetUp with the default
/// options): it skips, or fails under TESSERA_TEST_REQUIRE, without a Vulkan device or the
/// validation layer, and TearDown fails it on any validation message (leaks included: they are
/// reported when the engine shuts down).
class EngineTest : public ::testing::Test {
 protected:
  void SetUp() override { make_engine({}); }
  void make_engine(const EngineOptions& eo) {
    std::string missing;
    auto e = Engine::create(eo, &missing);
    if (!e) TESSERA_SKIP_OR_FAIL(missing, e.status().message);
    engine_ = std::move(*e);
  }
  void TearDown() override {
    if (!engine_) return;
    engine_->shutdown();
    EXPECT_EQ(engine_->messages(), 0) << "validation messages:" << engine_->first_messages();
  }
  std::unique_ptr<Engine> engine_;
};

}  // namespace tessera::vk_test
