// engine_aa_vk's scene targets (nothing here is tessera's): one view's G-buffer images at
// the largest size, the scene's vertices, the hook's descriptor set 0 (the frame block and RT1),
// the geometry pass into the top-left render area (dynamic resolution), and the description of
// an image just rendered that tessera's record takes.
#pragma once

#include <vulkan/vulkan.h>

#include "aa_scene.h"
#include "engine.h"
#include "tessera/vk.h"

namespace engine {

/// The engine's G-buffer and its frame data (one per view, and per frame in flight in the
/// frame loop).
struct Frame {
  engine::Image rt0, rt1, depth;
  engine::Buffer vertices, ubo;
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VkDescriptorSet set = VK_NULL_HANDLE;
  VkSampler sampler = VK_NULL_HANDLE;
  std::size_t vertex_count = 0;
  engine::Camera cam;  // aa_scene.h's, with Vulkan's projection
};

/// The view's targets at w x h (G-buffer m times it), the scene, its set 0; `view` > 0 turns
/// the camera (another viewport).
void setup(Device& d, int w, int h, int m, int view, Frame& f);
/// The frame block for a G-buffer grid of gw x gh texels (the render size times m).
void set_grid(Frame& f, std::uint32_t gw, std::uint32_t gh);
void destroy(Device& d, Frame& f);
/// The geometry pass into the top-left `area` ({0, 0} = the whole images).
void record_gbuffer(VkCommandBuffer cmd, const GeometryPipeline& gp, const Frame& f,
                    VkExtent2D area = {0, 0});
/// tessera's view of an engine image just rendered (COLOR_ATTACHMENT_OPTIMAL, written by the
/// colour-attachment output stage).
tessera::vk::ImageResource rendered(const Image& img);

}  // namespace engine
