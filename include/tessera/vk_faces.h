// tessera/vk_faces.h — per-face (Ptex-style) textures on the engine's VkDevice: a
// faces::FaceTextureSet packed as tessera/faces_gpu.h says (the layout gl::FaceTextureSet uses,
// the same bytes) into one 2D-array image per face-resolution class, every mip level uploaded
// from the CPU chains, plus a storage buffer of faces::FaceRecord; a descriptor-set layout and
// one descriptor set the engine includes in its own pipeline layout at a set index it chooses,
// read by the shipped seams.glsl (tessera_seams_sample_discard, ...) in the engine's own shaders.
// Contract: the upload is either recorded into the engine's command buffer
// (FaceUpload::engine_command_buffer: `create` submits nothing; the engine calls `record_upload`
// once, before the first command that reads the set, in a command buffer for
// `DeviceContext::queue_family`, and `release_staging` once that command buffer completed — the
// frames-in-flight model of tessera/vk.h), or made by `create` through `DeviceContext::queue`
// (FaceUpload::queue_submit, the default: one staging buffer, one submit, one fence waited on
// before it returns; the queue must not be used by another thread during `create`). Afterwards
// the images are in SHADER_READ_ONLY_OPTIMAL and the uploads visible to every later command on
// that queue; the object records nothing and submits nothing more. Not thread-safe; destroy it
// after the GPU is done with every command buffer that bound its descriptor set. Recipe:
// docs/engine_integration.md
// ("vk::FaceTextureSet"); examples/engine_ptex_vk.
// Tests: tests/vk/vk_faces_test.cpp (against the CPU renderer; every texel format and the upload
// recorded in the engine's command buffer), tests/vk/engine_ptex_vk_test.py.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tessera/core.h"
#include "tessera/faces_gpu.h"
#include "tessera/vk.h"

namespace tessera::vk {

namespace detail {
struct FaceTextureSetState;
}

/// The binding numbers of the set, chosen by the engine (seams.glsl's macros of the same
/// meaning: TESSERA_SEAMS_FACES_BINDING, TESSERA_SEAMS_BORDER_BINDING,
/// TESSERA_SEAMS_CLAMP_BINDING; `FaceTextureSet::glsl_defines` writes them). Samplers and
/// buffers share a set's binding numbers: the three must differ.
struct FaceTextureSetBindings {
  std::uint32_t faces = 0;   ///< STORAGE_BUFFER: the face records.
  std::uint32_t border = 1;  ///< COMBINED_IMAGE_SAMPLER[classes]: clamp-to-border (0,0,0,0).
  std::uint32_t clamp = 2;   ///< COMBINED_IMAGE_SAMPLER[classes]: clamp-to-edge.
  /// The stages that read the set (VkDescriptorSetLayoutBinding::stageFlags).
  VkShaderStageFlags stages = VK_SHADER_STAGE_FRAGMENT_BIT;
};

/// Who submits the upload (see the file comment).
enum class FaceUpload {
  queue_submit,           ///< `create` submits on DeviceContext::queue and waits on a fence.
  engine_command_buffer,  ///< `record_upload(cmd)` into the engine's frame; nothing submitted.
};

struct FaceTextureSetOptions {
  FaceTextureSetBindings bindings;
  /// The arrays' texel format (tessera/faces_gpu.h: R32G32B32A32_SFLOAT = the CPU texels,
  /// R16G16B16A16_SFLOAT, R8G8B8A8_UNORM, R8G8B8A8_SRGB), converted on the CPU as GL's.
  faces::TexelFormat format = faces::TexelFormat::rgba32f;
  FaceUpload upload = FaceUpload::queue_submit;
  /// Upper bound of the samplers' maxAnisotropy (1..16, clamped to the device's
  /// maxSamplerAnisotropy); above 1 only where the engine enabled samplerAnisotropy
  /// (DeviceContext::enabled_features), else the samplers are trilinear, as GL's without the
  /// extension. 1 = trilinear, the filter of the CPU faces::FaceRenderer.
  float max_anisotropy = 16.0f;
};

/// The Vulkan objects of a packed face set. Images: of `options.format` (R32G32B32A32_SFLOAT,
/// the default, exactly the CPU texels), 2D arrays with the full mip chain, usage SAMPLED |
/// TRANSFER_DST, sharing EXCLUSIVE to `DeviceContext::queue_family` (another family needs the
/// engine's ownership transfer), left in SHADER_READ_ONLY_OPTIMAL. Samplers: LINEAR / LINEAR /
/// mipmap LINEAR, all levels, one with CLAMP_TO_BORDER and FLOAT_TRANSPARENT_BLACK (the zero taps
/// Discard needs, a standard border colour), one with CLAMP_TO_EDGE. The engine must not write,
/// transition or destroy these objects, nor update or free the descriptor set; it binds the set
/// with vkCmdBindDescriptorSets (or `bind`) at the set index its pipeline layout put `set_layout()`
/// at, the index it also gives `glsl_defines`.
class FaceTextureSet {
 public:
  /// Packs `set` against the device's limits (maxImageDimension2D, maxImageArrayLayers,
  /// maxStorageBufferRange, at most 16 classes and maxPerStageDescriptorSamplers / 2), checks
  /// the bindings and that `options.format` is sampled with linear filtering, then creates
  /// everything and uploads it (queue_submit) or fills the staging buffer (engine_command_buffer)
  /// (see the file comment). One-line errors before anything is created or submitted:
  /// invalid_argument (no faces, bindings that collide), too_large (a limit, by its Vulkan name),
  /// unsupported (the device, the format); a failed Vulkan call names itself.
  static Result<std::unique_ptr<FaceTextureSet>> create(const DeviceContext& device,
                                                        const faces::FaceTextureSet& set,
                                                        const FaceTextureSetOptions& options = {});
  ~FaceTextureSet();
  FaceTextureSet(const FaceTextureSet&) = delete;
  FaceTextureSet& operator=(const FaceTextureSet&) = delete;

  const faces::PackedFaces& layout() const;
  int class_count() const;
  const FaceTextureSetBindings& bindings() const;
  /// The layout to put in the engine's VkPipelineLayoutCreateInfo::pSetLayouts[set].
  VkDescriptorSetLayout set_layout() const;
  /// The one descriptor set, written at creation (records, border and clamp arrays).
  VkDescriptorSet descriptor_set() const;
  /// The class's image (2D array, layers = the class's faces) and its view.
  VkImage image(int cls) const;
  VkImageView image_view(int cls) const;
  VkBuffer record_buffer() const;
  VkSampler border_sampler() const;
  VkSampler clamp_sampler() const;
  /// The anisotropy the samplers got (1 = trilinear).
  float anisotropy() const;
  /// Bytes of image storage (all levels of all arrays, texel_bytes(format()) per texel).
  std::uint64_t texture_bytes() const;
  faces::TexelFormat format() const;

  /// FaceUpload::engine_command_buffer: records the upload (barriers, buffer-to-image copies of
  /// every level, the records' copy, barriers to every later shader read) into the engine's
  /// `cmd` (recording, outside a render pass), once. invalid_argument (nothing recorded) for a
  /// null command buffer, a second call, or the queue_submit mode.
  Status record_upload(VkCommandBuffer cmd);
  /// Frees the staging buffer once the command buffer holding `record_upload` completed (the
  /// engine's fence). invalid_argument before `record_upload`.
  Status release_staging();
  /// Whether the upload has been made (queue_submit) or recorded (engine_command_buffer).
  bool upload_recorded() const;

  /// Records vkCmdBindDescriptorSets(cmd, bind_point, pipeline_layout, set, 1, ...): the only
  /// command this object records. invalid_argument (nothing recorded) for a null command
  /// buffer or layout, or `set` >= maxBoundDescriptorSets.
  Status bind(VkCommandBuffer cmd, VkPipelineBindPoint bind_point, VkPipelineLayout pipeline_layout,
              std::uint32_t set) const;

  /// The lines a shader that includes seams.glsl needs before the include, for the set index
  /// `set`: "#define TESSERA_SEAMS_CLASSES N", "#define TESSERA_SEAMS_SET S",
  /// "#define TESSERA_SEAMS_FACES_BINDING B", "..._BORDER_BINDING", "..._CLAMP_BINDING" (for
  /// glsl::ExpandOptions::preamble; compile with VULKAN defined, as glslc -fshader-stage /
  /// shaderc's Vulkan target do).
  std::vector<std::string> glsl_defines(std::uint32_t set) const;

 private:
  explicit FaceTextureSet(std::unique_ptr<detail::FaceTextureSetState> s);
  std::unique_ptr<detail::FaceTextureSetState> s_;
};

}  // namespace tessera::vk
