// The experiments' own Vulkan device (src/vk/headless_device.h): made from libvulkan.so.1
// opened at run time (no loader linked by tessera_vk), under the validation layer, an empty
// submission through its command pool and fence, a device index past the usable ones as a
// one-line error, and a messenger that counts (a deliberate misuse must be counted: the
// negative control that the count is live).
#include <gtest/gtest.h>

#include <cstdlib>

#include "test_require.h"
#include "vk/headless_device.h"

namespace tessera::vk {
namespace {

std::unique_ptr<HeadlessDevice> make(HeadlessDeviceOptions o, std::shared_ptr<ValidationLog> log,
                                     Status* status) {
  Result<std::unique_ptr<HeadlessDevice>> d = HeadlessDevice::create(o, std::move(log));
  if (!d) {
    *status = d.status();
    return nullptr;
  }
  return std::move(*d);
}

TEST(VkHeadlessDevice, SubmitsUnderValidationWithoutMessages) {
  auto log = std::make_shared<ValidationLog>();
  Status s = Status::success();
  std::unique_ptr<HeadlessDevice> d = make({nullptr, true, -1}, log, &s);
  if (!d) {
    TESSERA_SKIP_OR_FAIL(
        s.message.find("validation") != std::string::npos ? "vulkan-validation" : "vulkan",
        s.message);
  }
  EXPECT_FALSE(d->device_name().empty());
  EXPECT_EQ(d->device_version().rfind("Vulkan 1.", 0), 0u) << d->device_version();
  EXPECT_GT(d->timestamp_ms_per_tick(), 0.0);
  for (int i = 0; i < 3; ++i) {
    Result<VkCommandBuffer> cmd = d->begin();
    ASSERT_TRUE(cmd.ok()) << cmd.status().message;
    ASSERT_TRUE(d->submit_and_wait(*cmd).ok());
  }
  EXPECT_EQ(d->validation_messages(), 0) << log->first;
  // Negative control: a zero-sized buffer is invalid usage the layer reports.
  VkBufferCreateInfo bi{};
  bi.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  bi.size = 0;  // invalid: size must be > 0
  bi.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  VkBuffer buffer = VK_NULL_HANDLE;
  if (d->api().CreateBuffer(d->api().device(), &bi, nullptr, &buffer) == VK_SUCCESS &&
      buffer != VK_NULL_HANDLE) {
    d->api().DestroyBuffer(d->api().device(), buffer, nullptr);
  }
  EXPECT_GT(d->validation_messages(), 0) << "the messenger counted no message";
}

TEST(VkHeadlessDevice, DeviceIndexPastTheUsableOnesIsOneLine) {
  Status s = Status::success();
  std::unique_ptr<HeadlessDevice> first = make({nullptr, false, 0}, nullptr, &s);
  if (!first) TESSERA_SKIP_OR_FAIL("vulkan", s.message);
  first.reset();
  std::unique_ptr<HeadlessDevice> d = make({nullptr, false, 99}, nullptr, &s);
  ASSERT_EQ(d, nullptr);
  EXPECT_EQ(s.code, ErrorCode::invalid_argument);
  EXPECT_NE(s.message.find("device 99"), std::string::npos) << s.message;
  EXPECT_EQ(s.message.find('\n'), std::string::npos) << s.message;
  // A $TESSERA_VK_DEVICE that is no index: named, not read as device 0.
  setenv("TESSERA_VK_DEVICE", "gpu0", 1);
  d = make({nullptr, false, -1}, nullptr, &s);
  unsetenv("TESSERA_VK_DEVICE");
  ASSERT_EQ(d, nullptr);
  EXPECT_EQ(s.code, ErrorCode::invalid_argument);
  EXPECT_NE(s.message.find("TESSERA_VK_DEVICE 'gpu0'"), std::string::npos) << s.message;
}

}  // namespace
}  // namespace tessera::vk
