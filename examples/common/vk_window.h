// vk_window.h — the Vulkan example engines' own GLFW window and swapchain (nothing here is
// tessera's), for their --frame-loop --window: each frame blits the engine's view 0 image, its
// render size, to the window's size (the upscale a dynamic-resolution engine does) and presents
// it: FIFO, an acquire semaphore per frame slot, a render-done semaphore per swapchain image.
// Under Xvfb lavapipe presents through X11. The swapchain image's barriers are Vulkan 1.0's
// (vkCmdPipelineBarrier), so that a device without synchronization2 presents too; the engine
// puts its source image in TRANSFER_SRC_OPTIMAL, visible to transfer reads, itself.
//
// Header-only, beside vk_engine.h (the device it builds on), shared by examples/engine_aa_vk
// and examples/engine_ptex_vk (both link GLFW: Debian libglfw3-dev).
#pragma once

#include <vulkan/vulkan.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "vk_engine.h"

namespace engine {

class Window {
 public:
  /// The window `title` (no GL context) of w x h; "" or the reason (no display, no GLFW).
  std::string open(int w, int h, const char* title) {
    if (glfwInit() != GLFW_TRUE) return "no window system (GLFW: no X display; run under xvfb-run)";
    if (glfwVulkanSupported() != GLFW_TRUE) return "GLFW finds no Vulkan loader";
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
    window_ = glfwCreateWindow(w, h, title, nullptr, nullptr);
    return window_ != nullptr ? "" : "glfwCreateWindow failed";
  }

  /// The instance extensions the window system needs (after open).
  std::vector<const char*> instance_extensions() const {
    std::uint32_t n = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&n);
    return std::vector<const char*>(names, names + n);
  }

  /// The surface and the swapchain on `d` (created with instance_extensions() and
  /// VK_KHR_swapchain); "" or the reason.
  std::string create_swapchain(DeviceBase& d, std::uint32_t frames_in_flight) {
    if (glfwCreateWindowSurface(d.instance, window_, nullptr, &surface_) != VK_SUCCESS) {
      return "glfwCreateWindowSurface failed";
    }
    VkBool32 supported = VK_FALSE;
    vkGetPhysicalDeviceSurfaceSupportKHR(d.physical, d.family, surface_, &supported);
    if (!supported) return "the queue family cannot present to the window";
    VkSurfaceCapabilitiesKHR caps{};
    vkGetPhysicalDeviceSurfaceCapabilitiesKHR(d.physical, surface_, &caps);
    if ((caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT) == 0) {
      return "the swapchain images cannot be blit destinations";
    }
    std::uint32_t n = 0;
    vkGetPhysicalDeviceSurfaceFormatsKHR(d.physical, surface_, &n, nullptr);
    std::vector<VkSurfaceFormatKHR> formats(n);
    vkGetPhysicalDeviceSurfaceFormatsKHR(d.physical, surface_, &n, formats.data());
    if (formats.empty()) return "the surface has no format";
    VkSurfaceFormatKHR format = formats[0];
    for (const VkSurfaceFormatKHR& f : formats) {
      // Linear HDR in, sRGB encoded by the blit.
      if (f.format == VK_FORMAT_B8G8R8A8_SRGB) format = f;
    }
    extent_ = caps.currentExtent;
    VkSwapchainCreateInfoKHR si{};
    si.sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR;
    si.surface = surface_;
    si.minImageCount =
        std::max(caps.minImageCount,
                 std::min(frames_in_flight + 1, caps.maxImageCount ? caps.maxImageCount : 16u));
    si.imageFormat = format.format;
    si.imageColorSpace = format.colorSpace;
    si.imageExtent = extent_;
    si.imageArrayLayers = 1;
    si.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    si.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    si.preTransform = caps.currentTransform;
    si.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    si.presentMode = VK_PRESENT_MODE_FIFO_KHR;
    si.clipped = VK_TRUE;
    if (vkCreateSwapchainKHR(d.device, &si, nullptr, &swapchain_) != VK_SUCCESS) {
      return "vkCreateSwapchainKHR failed";
    }
    vkGetSwapchainImagesKHR(d.device, swapchain_, &n, nullptr);
    images_.resize(n);
    vkGetSwapchainImagesKHR(d.device, swapchain_, &n, images_.data());
    for (std::uint32_t i = 0; i < frames_in_flight; ++i) {
      acquired_.push_back(make_semaphore(d.device));
    }
    for (std::uint32_t i = 0; i < n; ++i) rendered_.push_back(make_semaphore(d.device));
    return "";
  }

  /// Acquires the next image for frame slot `slot`; "" or the reason.
  std::string acquire(DeviceBase& d, std::uint32_t slot) {
    const VkResult r = vkAcquireNextImageKHR(d.device, swapchain_, UINT64_MAX, acquired_[slot],
                                             VK_NULL_HANDLE, &image_);
    if (r != VK_SUCCESS && r != VK_SUBOPTIMAL_KHR) {
      return "vkAcquireNextImageKHR: VkResult " + std::to_string(int(r));
    }
    return "";
  }

  /// Records the blit of `src`'s top-left `size` texels (in TRANSFER_SRC_OPTIMAL, its last
  /// write made visible to transfer reads by the engine) to the acquired image, from UNDEFINED
  /// after the acquire semaphore's wait (at the transfer stage: Window::kWaitStage), then the
  /// transition to PRESENT_SRC_KHR.
  void record_blit(VkCommandBuffer cmd, VkImage src, VkExtent2D size,
                   VkFilter filter = VK_FILTER_LINEAR) {
    const VkImage dst = images_[image_];
    swapchain_barrier(cmd, dst, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                      kWaitStage, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
    VkImageBlit region{};
    region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.srcOffsets[1] = {std::int32_t(size.width), std::int32_t(size.height), 1};
    region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.dstOffsets[1] = {std::int32_t(extent_.width), std::int32_t(extent_.height), 1};
    vkCmdBlitImage(cmd, src, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region, filter);
    swapchain_barrier(cmd, dst, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                      VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_TRANSFER_BIT,
                      VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0);
  }

  /// The stage at which the frame's submission waits for acquired(slot).
  static constexpr VkPipelineStageFlags kWaitStage = VK_PIPELINE_STAGE_TRANSFER_BIT;
  /// What the frame's submission waits for (at kWaitStage) and signals.
  VkSemaphore acquired(std::uint32_t slot) const { return acquired_[slot]; }
  VkSemaphore rendered() const { return rendered_[image_]; }

  /// Presents the acquired image after `rendered()`; "" or the reason.
  std::string present(DeviceBase& d) {
    VkPresentInfoKHR pi{};
    pi.sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR;
    pi.waitSemaphoreCount = 1;
    pi.pWaitSemaphores = &rendered_[image_];
    pi.swapchainCount = 1;
    pi.pSwapchains = &swapchain_;
    pi.pImageIndices = &image_;
    const VkResult r = vkQueuePresentKHR(d.queue, &pi);
    if (r != VK_SUCCESS && r != VK_SUBOPTIMAL_KHR) {
      return "vkQueuePresentKHR: VkResult " + std::to_string(int(r));
    }
    ++presented;
    glfwPollEvents();
    return "";
  }

  /// The swapchain, semaphores and surface (the device idle first), then the window.
  void destroy(DeviceBase& d) {
    if (d.device) {
      vkDeviceWaitIdle(d.device);
      for (VkSemaphore s : acquired_) vkDestroySemaphore(d.device, s, nullptr);
      for (VkSemaphore s : rendered_) vkDestroySemaphore(d.device, s, nullptr);
      if (swapchain_) vkDestroySwapchainKHR(d.device, swapchain_, nullptr);
    }
    acquired_.clear();
    rendered_.clear();
    if (surface_ && d.instance) vkDestroySurfaceKHR(d.instance, surface_, nullptr);
    surface_ = VK_NULL_HANDLE;
    swapchain_ = VK_NULL_HANDLE;
    close();
  }

  /// The window alone (no Vulkan object made yet).
  void close() {
    if (window_) glfwDestroyWindow(window_);
    window_ = nullptr;
    glfwTerminate();
  }

  int presented = 0;

 private:
  static VkSemaphore make_semaphore(VkDevice dev) {
    VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO, nullptr, 0};
    VkSemaphore s = VK_NULL_HANDLE;
    vkCreateSemaphore(dev, &si, nullptr, &s);
    return s;
  }

  static void swapchain_barrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from,
                                VkImageLayout to, VkPipelineStageFlags src_stage,
                                VkAccessFlags src_access, VkPipelineStageFlags dst_stage,
                                VkAccessFlags dst_access) {
    VkImageMemoryBarrier b{};
    b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
    b.srcAccessMask = src_access;
    b.dstAccessMask = dst_access;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 0, nullptr, 0, nullptr, 1, &b);
  }

  GLFWwindow* window_ = nullptr;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkExtent2D extent_{0, 0};
  std::vector<VkImage> images_;
  std::vector<VkSemaphore> acquired_, rendered_;
  std::uint32_t image_ = 0;
};

}  // namespace engine
