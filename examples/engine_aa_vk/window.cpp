// engine_aa_vk --window (window.h).
#include "window.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>

namespace engine {

namespace {

VkSemaphore make_semaphore(VkDevice dev) {
  VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO, nullptr, 0};
  VkSemaphore s = VK_NULL_HANDLE;
  vkCreateSemaphore(dev, &si, nullptr, &s);
  return s;
}

}  // namespace

std::string Window::open(int w, int h) {
  if (glfwInit() != GLFW_TRUE) return "no window system (GLFW: no X display; run under xvfb-run)";
  if (glfwVulkanSupported() != GLFW_TRUE) return "GLFW finds no Vulkan loader";
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
  window_ = glfwCreateWindow(w, h, "engine_aa_vk", nullptr, nullptr);
  return window_ != nullptr ? "" : "glfwCreateWindow failed";
}

std::vector<const char*> Window::instance_extensions() const {
  std::uint32_t n = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&n);
  return std::vector<const char*>(names, names + n);
}

std::string Window::create_swapchain(Device& d, std::uint32_t frames_in_flight) {
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
    if (f.format == VK_FORMAT_B8G8R8A8_SRGB) format = f;  // linear HDR in, sRGB encoded by the blit
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
  for (std::uint32_t i = 0; i < frames_in_flight; ++i)
    acquired_.push_back(make_semaphore(d.device));
  for (std::uint32_t i = 0; i < n; ++i) rendered_.push_back(make_semaphore(d.device));
  return "";
}

std::string Window::acquire(Device& d, std::uint32_t slot) {
  const VkResult r = vkAcquireNextImageKHR(d.device, swapchain_, UINT64_MAX, acquired_[slot],
                                           VK_NULL_HANDLE, &image_);
  if (r != VK_SUCCESS && r != VK_SUBOPTIMAL_KHR) {
    return "vkAcquireNextImageKHR: VkResult " + std::to_string(int(r));
  }
  return "";
}

void Window::record_blit(VkCommandBuffer cmd, const tessera::vk::ImageResource& image,
                         VkExtent2D size) {
  const VkImage dst = images_[image_];
  // The source: from its last write to TRANSFER_SRC_OPTIMAL (tessera's next record of it starts
  // from UNDEFINED); the swapchain image from UNDEFINED after the acquire semaphore's wait (at
  // the transfer stage).
  barrier(cmd, image.image, image.layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image.stage,
          image.access, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  barrier(cmd, dst, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
          VK_PIPELINE_STAGE_2_BLIT_BIT, 0, VK_PIPELINE_STAGE_2_BLIT_BIT,
          VK_ACCESS_2_TRANSFER_WRITE_BIT);
  VkImageBlit region{};
  region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.srcOffsets[1] = {std::int32_t(size.width), std::int32_t(size.height), 1};
  region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.dstOffsets[1] = {std::int32_t(extent_.width), std::int32_t(extent_.height), 1};
  vkCmdBlitImage(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region, VK_FILTER_LINEAR);
  barrier(cmd, dst, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
          VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_NONE,
          0);
}

std::string Window::present(Device& d) {
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

void Window::destroy(Device& d) {
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

void Window::close() {
  if (window_) glfwDestroyWindow(window_);
  window_ = nullptr;
  glfwTerminate();
}

}  // namespace engine
