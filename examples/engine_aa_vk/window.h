// engine_aa_vk --window: the engine's own GLFW window and swapchain (nothing here is tessera's).
// Each frame of the frame loop (frame_loop.h) blits view 0's anti-aliased image, its render size,
// to the window's size (the upscale a dynamic-resolution engine does) and presents it: FIFO,
// an acquire semaphore per frame slot, a render-done semaphore per swapchain image. Under Xvfb
// lavapipe presents through X11.
#pragma once

#include <vulkan/vulkan.h>

#include <string>
#include <vector>

#include "engine.h"
#include "tessera/vk.h"

struct GLFWwindow;

namespace engine {

class Window {
 public:
  /// The window (no GL context) of w x h; "" or the reason (no display, no GLFW).
  std::string open(int w, int h);
  /// The instance extensions the window system needs (after open).
  std::vector<const char*> instance_extensions() const;
  /// The surface and the swapchain on `d` (created with instance_extensions() and
  /// VK_KHR_swapchain); "" or the reason.
  std::string create_swapchain(Device& d, std::uint32_t frames_in_flight);
  /// Acquires the next image for frame slot `slot`; "" or the reason.
  std::string acquire(Device& d, std::uint32_t slot);
  /// Records the blit of `image`'s top-left `size` texels (last written at its stage/access, in
  /// its layout) to the acquired image, then the transition to PRESENT_SRC_KHR.
  void record_blit(VkCommandBuffer cmd, const tessera::vk::ImageResource& image, VkExtent2D size);
  /// What the frame's submission waits for and signals.
  VkSemaphore acquired(std::uint32_t slot) const { return acquired_[slot]; }
  VkSemaphore rendered() const { return rendered_[image_]; }
  /// Presents the acquired image after `rendered()`; "" or the reason.
  std::string present(Device& d);
  /// The swapchain, semaphores and surface (the device idle first), then the window.
  void destroy(Device& d);
  /// The window alone (no Vulkan object made yet).
  void close();
  int presented = 0;

 private:
  GLFWwindow* window_ = nullptr;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkExtent2D extent_{0, 0};
  std::vector<VkImage> images_;
  std::vector<VkSemaphore> acquired_, rendered_;
  std::uint32_t image_ = 0;
};

}  // namespace engine
