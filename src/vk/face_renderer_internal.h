// Internal to the Vulkan face renderer (face_renderer.h): its state, shared by
// face_renderer.cpp (creation, pipelines, the frame) and face_renderer_targets.cpp (render
// passes, attachments, texture sets per anisotropy, read-back).
#pragma once

#include <map>
#include <memory>
#include <tuple>
#include <vector>

#include "tessera/faces_gpu.h"
#include "vk/face_renderer.h"
#include "vk/vk_api.h"

namespace tessera::vk {

inline constexpr VkFormat kColourFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
inline constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

/// An image with its memory and a view (members destroyed view first, memory last).
struct Attachment {
  Memory memory;
  RawImage image;
  ImageView view;
};

/// The frame's targets for one size and sample count.
struct FaceTargets {
  int width = 0, height = 0, samples = 0;
  Attachment colour, depth;  ///< `samples` samples each.
  Attachment resolved;       ///< One sample; only where samples > 1.
  Framebuffer framebuffer;
  Buffer read_back;  ///< Host-visible, width x height RGBA floats.
};

/// Which shader variant and pipeline a draw needs.
struct FaceVariant {
  int method = 1, fallback = 1, output = 0, samples = 1;
  /// The face class as specialization constant 0 (devices without
  /// shaderSampledImageArrayDynamicIndexing); -1: the class is a push constant.
  int cls = -1;
  auto key() const { return std::tuple(method, fallback, output, samples, cls); }
};

struct FaceRenderer::State {
  HeadlessDevice* device = nullptr;
  const Api* api = nullptr;
  const faces::FaceScene* scene = nullptr;
  const faces::FaceTextureSet* set = nullptr;
  std::unique_ptr<FaceTextureSet> textures;  ///< maxAnisotropy 16 (the paper's filter)
  VkSampleCountFlags sample_counts = 0;      ///< What msaa_supported allows.
  double ms_per_tick = 0;
  std::uint64_t timestamp_mask = ~std::uint64_t(0);

  PipelineLayout layout;  ///< Set 0: the textures; push constant: the class (fragment, int).
  std::vector<std::uint32_t> vertex_spirv;
  std::map<std::tuple<int, int, int>, std::vector<std::uint32_t>> fragment_spirv;
  std::map<std::tuple<int, int, int, int, int>, Pipeline> pipelines;
  /// The device lacks shaderSampledImageArrayDynamicIndexing: one pipeline per class, the
  /// class a specialization constant (seams_render.frag's TESSERA_RENDER_CLASS_CONSTANT).
  bool class_constant = false;
  std::map<int, RenderPass> passes;  ///< By sample count.

  /// The textures with samplers of other anisotropies (by anisotropy; `textures` is 16x).
  std::map<float, std::unique_ptr<FaceTextureSet>> other_textures;

  Buffer clip, normals, indices;
  std::vector<float> clip_host;  ///< 16 floats per face.
  std::vector<faces::FaceClassDraw> draws;
  QueryPool timestamps;  ///< 3: before the pass, after it, after the resolve.
  FaceTargets targets;

  // face_renderer_targets.cpp
  Result<VkRenderPass> render_pass(int samples);
  Status ensure_targets(int width, int height, int samples);
  /// The descriptor set of the textures whose samplers have `anisotropy` (1 = trilinear).
  Result<VkDescriptorSet> descriptor_set(float anisotropy);
  /// The resolved (or single-sampled) colour of the last frame, through a second submission.
  Result<ImageRGBAF> read_back();
  /// The resolve of a multisampled frame and its timestamp (after `record_pass`).
  void record_resolve(VkCommandBuffer cmd);
  // face_renderer.cpp
  Result<VkPipeline> pipeline(const FaceVariant& v);
  /// The timestamps' reset and first two, the render pass and the class-grouped draws (the
  /// class's pipeline per draw, or one pipeline and the class in the push constant); returns
  /// the draw calls.
  int record_pass(VkCommandBuffer cmd, VkRenderPass pass, const FaceFrameOptions& o,
                  const std::vector<VkPipeline>& class_pipelines, VkDescriptorSet textures_set);
};

}  // namespace tessera::vk
