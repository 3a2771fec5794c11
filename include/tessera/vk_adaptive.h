// tessera/vk_adaptive.h — adaptive supersampling for deferred shading (Hollander, Boubekeur &
// Eisemann 2013) as a Vulkan engine component: the engine's own enlarged G-buffer and its own
// GLSL shading in, the anti-aliased image out, recorded into the engine's command buffer
// (tessera::vk; the device hand-off is tessera/vk.h).
//
// The twin of gl::AdaptiveSupersampler (tessera/gl_adaptive.h): the same options
// (tessera/adaptive_supersampler.h: G-buffer layout descriptor, shading hook
// `vec4 tessera_shade_sample(ivec2 grid_texel, float footprint)` with its optional
// TESSERA_ADAPTIVE_SAMPLE0_AGAIN / TESSERA_ADAPTIVE_CUSTOM_LUMA, thresholds, sample order,
// schedules, HDR resolve, outputs), budget, compiled from the same shipped GLSL
// (adaptive_component.glsl) by the same host code, giving the same image. What differs is
// Vulkan's:
//
// 1. The hook becomes SPIR-V at `create`, with shaderc (Google's glslang front end, Debian
//    libshaderc-dev, linked statically), one compute pipeline per pass: the hook is often
//    generated from the engine's material system at run time and its G-buffer accessors from the
//    layout, so an offline step would have to know both. Errors name the hook's own lines:
//    "HOOK_NAME:LINE: message". The hook's `#include "x.glsl"` resolve to
//    `AdaptiveShadingHook::include_paths`, then to tessera's shipped files (compiled into the
//    library: nothing is read from share/ at run time). VULKAN is defined.
// 2. Descriptor sets. The hook may read the engine's own resources through the engine's
//    descriptor-set layouts (`AdaptiveSupersamplerOptions::hook_set_layouts`, sets 0 .. E-1,
//    declared in the hook with `layout(set = s, binding = b)`); the component's own resources
//    are in set E = hook_set_layouts.size() (TESSERA_ADAPTIVE_SET), bindings 0 uniform block,
//    1 work buffer, 2 frame list, 3 output image, 4 sample-count image, 5 + s G-buffer slot s
//    (combined image sampler, an immutable nearest/clamp sampler; read with texelFetch).
//    `AdaptiveFrame::hook_sets` binds the engine's sets. The component keeps `descriptor_sets`
//    sets of its own, one per combination of G-buffer views (the views of up to that many
//    frames may be in flight).
// 3. Recording. `record(cmd, frame)` records into the engine's VkCommandBuffer (primary or
//    secondary, recording, outside a render pass, of `DeviceContext::queue_family`):
//      * one barrier first: each G-buffer image from (its `layout`, `stage`, `access`) to
//        SHADER_READ_ONLY_OPTIMAL (GENERAL stays GENERAL) for COMPUTE_SHADER /
//        SHADER_SAMPLED_READ; the output images from UNDEFINED (their contents are rewritten)
//        after ALL_COMMANDS / MEMORY_WRITE to GENERAL for COMPUTE_SHADER /
//        SHADER_STORAGE_WRITE; the
//        component's buffers from its previous record (COMPUTE_SHADER, DRAW_INDIRECT, TRANSFER)
//        to TRANSFER writes;
//      * vkCmdUpdateBuffer / vkCmdFillBuffer of the parameter block and the work header, a
//        TRANSFER -> COMPUTE_SHADER barrier, then the passes (vkCmdDispatch, one
//        vkCmdDispatchIndirect for the frame list), each followed by a global memory barrier
//        COMPUTE_SHADER (storage write) -> COMPUTE_SHADER | DRAW_INDIRECT (uniform, storage,
//        indirect-command reads and writes);
//      * with `profile`, timestamps around the passes and a copy of the sample counter to a
//        host-visible buffer (TRANSFER -> HOST barrier).
//    Barriers are vkCmdPipelineBarrier2 when `DeviceContext::synchronization2`, else
//    vkCmdPipelineBarrier with the same scopes. The compute pipeline and compute descriptor
//    bindings of `cmd` are left changed (rebind yours after), nothing else: no graphics state,
//    no push constants. It never submits, waits or reads anything back.
//    After the commands: the G-buffer images are in the layout `AdaptiveRecord::gbuffer_layout`
//    says, last read at COMPUTE_SHADER / SHADER_SAMPLED_READ; the output (`AdaptiveRecord::
//    colour`, and `sample_counts`) is in GENERAL, last written at COMPUTE_SHADER /
//    SHADER_STORAGE_WRITE: the engine's next use records its own barrier from that scope. It
//    may leave the output in any layout: the next record starts from UNDEFINED.
// 4. Creation checks the device (the queue family's compute support; the features, named when
//    missing from DeviceContext::enabled_features: shaderFloat64 always (the depth metric's
//    variance is accumulated in double, as on the CPU), shaderStorageImageExtendedFormats for
//    the r8ui sample counts; the storage formats of the outputs) and the options,
//    then compiles; `record` checks the frame (null handles, extent, format, usage without
//    VK_IMAGE_USAGE_SAMPLED_BIT, a layout that cannot be sampled, a negative budget, the hook's
//    set count) before recording anything: one-line errors, nothing recorded on failure.
// Resources: device-local buffers (parameter block, work buffer of 16 bytes per output pixel
// + 8 KiB, the frame list of 24 bytes per item), the output image(s), one host-visible buffer
// and one timestamp query pool with `profile`. Destroy the component before the device, after
// the engine's last command buffer that recorded it has completed.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tessera/adaptive_supersampler.h"
#include "tessera/core.h"
#include "tessera/vk.h"

namespace tessera::vk {

/// The Vulkan component's options: the shared ones (tessera/adaptive_supersampler.h; the
/// largest list is clamped to maxStorageBufferRange, the outputs are R16G16B16A16_SFLOAT /
/// R32G32B32A32_SFLOAT and R8_UINT) and Vulkan's. `profile` on Vulkan: timestamps per pass
/// and the extra-sample count, read by `read_profile` once the command buffer has completed.
struct AdaptiveSupersamplerOptions : AdaptiveCommonOptions {
  /// The engine's descriptor-set layouts the hook reads (sets 0 .. size-1); owned by the
  /// engine, alive while the component is.
  std::vector<VkDescriptorSetLayout> hook_set_layouts;
  /// Component descriptor sets (one per G-buffer view combination in flight), >= 1.
  int descriptor_sets = 8;
};

/// One frame's inputs.
struct AdaptiveFrame {
  /// The G-buffer images by slot ((m*w) x (m*h), sampled usage); empty slots are ignored.
  std::array<ImageResource, 4> gbuffer{};
  /// The engine's descriptor sets for `hook_set_layouts` (same count and order).
  std::vector<VkDescriptorSet> hook_sets;
  /// As gl::AdaptiveFrame::budget: at most this many extra samples; negative = an error.
  std::optional<std::int64_t> budget;
};

/// What `record` leaves (see the header comment, 3.).
struct AdaptiveRecord {
  ImageResource colour;         ///< The output image (owned by the component).
  ImageResource sample_counts;  ///< R8_UINT k + 1 per pixel (null unless requested).
  std::array<VkImageLayout, 4> gbuffer_layout{};  ///< Each slot's layout after the commands.
};

/// With `profile`: what the last completed record measured.
struct AdaptiveProfile {
  std::uint64_t extra_samples = 0;  ///< Sum of k (all m*m-1 per pixel for the reference).
  std::vector<PassTime> passes;     ///< GPU timestamps per pass, in order.
  double total_ms() const;
};

class AdaptiveSupersampler {
 public:
  /// Checks the device and the options (invalid_argument / unsupported / too_large naming the
  /// field or the feature), compiles every pass with the hook (a compile error names the hook's
  /// file and line), then creates the Vulkan objects (a failure destroys what was made).
  static Result<std::unique_ptr<AdaptiveSupersampler>> create(
      const DeviceContext& device, const AdaptiveSupersamplerOptions& options);
  ~AdaptiveSupersampler();
  AdaptiveSupersampler(const AdaptiveSupersampler&) = delete;
  AdaptiveSupersampler& operator=(const AdaptiveSupersampler&) = delete;

  /// Records the adaptive image into `cmd`. Fails (invalid_argument / size_mismatch naming the
  /// slot; nothing recorded) on a bad frame (see the header comment, 4.).
  Result<AdaptiveRecord> record(VkCommandBuffer cmd, const AdaptiveFrame& frame);
  /// Full supersampling: all m*m samples, footprint 1 (same checks).
  Result<AdaptiveRecord> record_reference(VkCommandBuffer cmd, const AdaptiveFrame& frame);
  /// S alone: one sample per pixel (sample 0 of the order), footprint m.
  Result<AdaptiveRecord> record_first_sample(VkCommandBuffer cmd, const AdaptiveFrame& frame);

  /// Replaces the thresholds for the following records (recorded with each; no recompilation).
  void set_thresholds(const AdaptiveThresholds& thresholds);
  /// With `profile`, after the command buffer of the last record completed: its counts and
  /// pass times (unsupported without `profile`; invalid_argument before any record).
  Result<AdaptiveProfile> read_profile() const;

  const AdaptiveSupersamplerOptions& options() const;
  /// The component's descriptor-set index (= hook_set_layouts.size()).
  std::uint32_t descriptor_set_index() const;

  struct State;

 private:
  AdaptiveSupersampler() = default;
  std::unique_ptr<State> state_;
};

}  // namespace tessera::vk
