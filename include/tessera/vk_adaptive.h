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
//    libshaderc-dev, in the optional module tessera-vk-glsl.so), one compute pipeline per pass:
//    the hook is often generated from the engine's material system at run time and its G-buffer
//    accessors from the layout. The passes that do not shade (the metrics, the budget's
//    histogram, select and apply, the frame list and its dispatch arguments) are SPIR-V compiled
//    when tessera is built and embedded, the metrics and the frame list reading m and the
//    layout as specialization constants; `create` compiles only the passes with the hook (the
//    first sample, the extra samples or the frame list's shade and resolve, the reference). Ahead
//    of time: `shader_binary()` returns every pass's SPIR-V, keyed by the options and the device's
//    limits, and `compile_shader_binary` makes the same without a device (a build step, for
//    every device kind the engine ships on: `shader_target`); given back as
//    `options.shader_binary`, `create` compiles no GLSL and needs no compiler module (and
//    `options.pipeline_cache`, the engine's VkPipelineCache, skips the driver's work). Errors
//    name the hook's own lines: "HOOK_NAME:LINE: message". The hook's `#include "x.glsl"` resolve
//    to `AdaptiveShadingHook::include_paths`, then to tessera's shipped files (compiled into the
//    library: nothing is read from share/ at run time). VULKAN is defined.
// 2. Descriptor sets. The hook may read the engine's own resources through the engine's
//    descriptor-set layouts (`AdaptiveSupersamplerOptions::hook_set_layouts`, sets 0 .. E-1,
//    declared in the hook with `layout(set = s, binding = b)`); the component's own resources
//    are in set E = hook_set_layouts.size() (TESSERA_ADAPTIVE_SET), bindings 0 uniform block,
//    1 work buffer, 2 frame list, 3 output image, 4 sample-count image, 5 + s G-buffer slot s
//    (combined image sampler, an immutable nearest/clamp sampler; read with texelFetch).
//    `AdaptiveFrame::hook_sets` binds the engine's sets. The component's own set is one per
//    (frame slot, view), written by the record that uses it (tessera/vk.h, frames in flight).
// 2b. Frames, views, sizes. `begin_frame(i)` opens frame slot i (< `frames_in_flight`) once
//    the engine's fence says the slot's last submission completed; the frame's records are its
//    views 0, 1, 2, ... in recording order, each with its own descriptor set, output images and
//    profile queries. `options.width` x `options.height` is the largest output; each record
//    names its `render_size` (dynamic resolution: any size up to the largest, no re-create, no
//    wait, the same bytes as a component created for that size) and reads the G-buffer's
//    top-left (m*w) x (m*h) texels (images may be larger: an engine's max-size G-buffer). The
//    output is the component's own image for that (slot, view), valid until `begin_frame` opens
//    the slot again, or the engine's own image (`AdaptiveFrame::output`), written in its
//    top-left w x h texels.
// 2c. Devices. Without shaderFloat64 the depth metric accumulates in float (compensated sums;
//    k maps agree with the double path on >= 99.9 % of pixels, tests/vk/vk_frames_test.cpp);
//    `tile_list` needs 64*m*m*24 + 4 bytes of workgroup memory (24,580 at m = 4, above the
//    16 KiB every device has): beyond maxComputeSharedMemorySize it runs `loop` (the same image;
//    `schedule()` says which runs).
// 3. Recording. `record(cmd, frame)` records into the engine's VkCommandBuffer (primary or
//    secondary, recording, outside a render pass, of `DeviceContext::queue_family`):
//      * one barrier first: each G-buffer image from (its `layout`, `stage`, `access`) to
//        SHADER_READ_ONLY_OPTIMAL (GENERAL stays GENERAL) for COMPUTE_SHADER /
//        SHADER_SAMPLED_READ; the output images from UNDEFINED (their contents are rewritten;
//        an engine-owned output from its `stage`/`access`) after ALL_COMMANDS / MEMORY_WRITE to
//        GENERAL for COMPUTE_SHADER / SHADER_STORAGE_WRITE; the
//        component's buffers from its previous record (COMPUTE_SHADER, DRAW_INDIRECT, TRANSFER)
//        to TRANSFER writes;
//      * vkCmdUpdateBuffer / vkCmdFillBuffer of the parameter block and the work header, a
//        TRANSFER -> COMPUTE_SHADER barrier, then the passes (vkCmdDispatch, one
//        vkCmdDispatchIndirect for the frame list), each followed by a global memory barrier
//        COMPUTE_SHADER (storage write) -> COMPUTE_SHADER | DRAW_INDIRECT (uniform, storage,
//        indirect-command reads and writes);
//      * with `profile`, timestamps around the passes, then copies of them
//        (vkCmdCopyQueryPoolResults), of the sample counter and of the frame number to the
//        (slot, view)'s host-visible buffer (TRANSFER -> HOST barrier): read_profile answers
//        once that frame number is there, and never calls vkGetQueryPoolResults.
//    Barriers are vkCmdPipelineBarrier2 when `DeviceContext::synchronization2`, else
//    vkCmdPipelineBarrier with the same scopes. The compute pipeline and compute descriptor
//    bindings of `cmd` are left changed (rebind yours after), nothing else: no graphics state,
//    no push constants. It never submits, waits or reads anything back.
//    After the commands: the G-buffer images are in the layout `AdaptiveOutput::gbuffer_layout`
//    says, last read at COMPUTE_SHADER / SHADER_SAMPLED_READ; the output (`AdaptiveOutput::
//    colour`, and `sample_counts`) is in GENERAL, last written at COMPUTE_SHADER /
//    SHADER_STORAGE_WRITE: the engine's next use records its own barrier from that scope. It
//    may leave the output in any layout: the next record starts from UNDEFINED.
// 4. Creation checks the device (the queue family's compute support; the features, named when
//    missing from DeviceContext::enabled_features: shaderStorageImageExtendedFormats for the
//    r8ui sample counts; the storage formats of the outputs; shaderFloat64 picks the depth
//    metric's precision, 2c) and the options, then compiles; `record` checks the frame (no
//    begin_frame, null handles, a render size above the largest or a G-buffer smaller than
//    m x it, format, usage without VK_IMAGE_USAGE_SAMPLED_BIT, a layout that cannot be sampled,
//    an output image of the wrong format, usage or size, a negative budget, the hook's set
//    count) before recording anything: one-line errors, nothing recorded on failure. Vulkan
//    failures keep their meaning (vk::result_code: out_of_memory, device_lost, unsupported).
// Resources: device-local buffers shared by every record (parameter block, work buffer of 16
// bytes per output pixel + 8 KiB, the frame list of 24 bytes per item, all at the largest
// size); per (frame slot, view): a descriptor set, the output image(s) unless the engine gives
// its own, and with `profile` a timestamp query pool and a 16-byte host-visible buffer.
// Destroy the component before the device, after every command buffer that recorded it has
// completed.
// Tests: tests/vk/vk_adaptive_test.cpp (budget, barriers, hook sets, bad input),
// vk_frames_test.cpp (frames in flight, views, render sizes, output, no fp64, shader binary),
// vk_adaptive_gl_test.cpp (the GL twin's image).
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
  /// The engine's frames in flight F (1..16): `begin_frame` takes a slot index below it.
  std::uint32_t frames_in_flight = 2;
  /// The engine's VkPipelineCache for the component's compute pipelines (optional, owned by
  /// the engine and externally synchronised as Vulkan requires): a warm cache skips the
  /// driver's compilation at `create`.
  VkPipelineCache pipeline_cache = VK_NULL_HANDLE;
  /// A shader binary from `shader_binary()` of a component created with the same options on a
  /// device of the same limits and features, or from `compile_shader_binary` for a list of
  /// targets including this device's: `create` then compiles no GLSL (an engine ships it and
  /// needs no GLSL compiler at run time). A binary made for other options, another
  /// device's limits (maxStorageBufferRange, maxComputeSharedMemorySize, shaderFloat64) or
  /// another tessera is refused (invalid_argument), a malformed one is corrupt_data.
  std::vector<std::uint8_t> shader_binary;
};

/// What of a device decides the component's shaders (its GLSL defines), for compiling them
/// without the device: `AdaptiveSupersampler::shader_target(device)` reads it from one.
struct AdaptiveShaderTarget {
  bool float64 = true;  ///< shaderFloat64 enabled (else the float depth metric).
  /// maxComputeSharedMemorySize (tile_list runs `loop` where its tile does not fit).
  std::uint32_t max_compute_shared_memory_size = 32768;
  /// maxStorageBufferRange (the frame list's capacity is bounded by it).
  std::uint32_t max_storage_buffer_range = 1u << 27;
};

/// One record's inputs (one view of the current frame).
struct AdaptiveFrame {
  /// The G-buffer images by slot (at least (m*w) x (m*h) for the render size w x h, sampled
  /// usage; the top-left m*w x m*h texels are read); empty slots are ignored.
  std::array<ImageResource, 4> gbuffer{};
  /// This record's output size w x h, at most options.width x options.height; {0, 0} = that
  /// largest size.
  VkExtent2D render_size{0, 0};
  /// The engine's own colour output (FSR2's `output`): the image, its view, extent at least the
  /// render size, format R16G16B16A16_SFLOAT / R32G32B32A32_SFLOAT as `options.output`, usage
  /// with VK_IMAGE_USAGE_STORAGE_BIT, and the layout/stage/access of its last use (its
  /// contents are replaced in the top-left render-size texels, the rest may be undefined).
  /// VK_NULL_HANDLE image = the component's own image for this (frame slot, view).
  ImageResource output{};
  /// The engine's descriptor sets for `hook_set_layouts` (same count and order).
  std::vector<VkDescriptorSet> hook_sets;
  /// As gl::AdaptiveFrame::budget: at most this many extra samples; negative = an error.
  std::optional<std::int64_t> budget;
};

/// What `record` leaves (see the header comment, 3.; gl::AdaptiveOutput's twin, whose profile
/// figures come with it: here they come from read_profile once the frame completed).
struct AdaptiveOutput {
  /// The output image: `AdaptiveFrame::output` when given, else the component's own for this
  /// (frame slot, view), valid until begin_frame opens the slot again. Its top-left
  /// `render_size` texels hold the image (the own image's extent is the largest size).
  ImageResource colour;
  ImageResource sample_counts;  ///< R8_UINT k + 1 per pixel (null unless requested).
  std::array<VkImageLayout, 4> gbuffer_layout{};  ///< Each slot's layout after the commands.
  VkExtent2D render_size{0, 0};                   ///< The texels written, from (0, 0).
  std::uint32_t frame_slot = 0;                   ///< begin_frame's index.
  std::uint32_t view = 0;                         ///< This record's place in its frame (0, 1, ...).
};

/// With `profile`: what one completed record measured.
struct AdaptiveProfile {
  std::uint64_t frame = 0;  ///< The frame that recorded it: the count of begin_frame calls.
  std::uint32_t frame_slot = 0, view = 0;
  VkExtent2D render_size{0, 0};
  std::uint64_t extra_samples = 0;  ///< Sum of k (all m*m-1 per pixel for the reference).
  /// Per pass, in order: gpu_ms from GPU timestamps (NaN where the queue family has none);
  /// wall_ms NaN (the commands run after `record` returns).
  std::vector<PassTime> passes;
  double total_gpu_ms() const;
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

  /// Opens frame slot `frame_slot` (< frames_in_flight) for the following records, after the
  /// engine waited for the fence of the slot's last submission (tessera/vk.h). The slot's
  /// previous outputs and profiles are then reused. invalid_argument when out of range.
  Status begin_frame(std::uint32_t frame_slot);

  /// Records the adaptive image into `cmd` as the next view of the current frame. Fails
  /// (invalid_argument / size_mismatch / too_large naming the slot or the size;
  /// out_of_memory when a new view's resources cannot be made; nothing recorded) on a bad
  /// frame (see the header comment, 4.).
  Result<AdaptiveOutput> record(VkCommandBuffer cmd, const AdaptiveFrame& frame);
  /// Full supersampling: all m*m samples, footprint 1 (same checks).
  Result<AdaptiveOutput> record_reference(VkCommandBuffer cmd, const AdaptiveFrame& frame);
  /// S alone: one sample per pixel (sample 0 of the order), footprint m.
  Result<AdaptiveOutput> record_first_sample(VkCommandBuffer cmd, const AdaptiveFrame& frame);

  /// Replaces the thresholds for the following records (recorded with each; no recompilation).
  void set_thresholds(const AdaptiveThresholds& thresholds);
  /// With `profile`: what the record of (frame slot, view) measured, once the command buffer
  /// that holds it has completed (unsupported without `profile`; invalid_argument for a
  /// (slot, view) never recorded, or whose record has not completed: its queries are not all
  /// available). The profile names the frame that recorded it.
  Result<AdaptiveProfile> read_profile(std::uint32_t frame_slot, std::uint32_t view = 0) const;

  const AdaptiveSupersamplerOptions& options() const;
  /// The schedule that runs (tile_list falls back to loop beyond the device's shared memory).
  AdaptiveSchedule schedule() const;
  /// True when the depth metric accumulates in double (the device's shaderFloat64 enabled).
  bool float64() const;
  /// Every pass's SPIR-V with the key of these options and device: store it (a file, the
  /// engine's asset cache) and give it back as `options.shader_binary` to skip compilation.
  const std::vector<std::uint8_t>& shader_binary() const;

  /// The shader binary `create` with `options` loads on a device of any of `targets`, made
  /// without a device (the GLSL compiler module is needed here, not where it is loaded): one
  /// entry per distinct target, each every pass's SPIR-V. Of the options only what the shaders
  /// depend on is read (the Vulkan handles are not: `hook_set_layouts` gives the set index by
  /// its size); the option checks and errors are `create`'s, compile errors name the hook's
  /// lines; invalid_argument for no target.
  static Result<std::vector<std::uint8_t>> compile_shader_binary(
      const AdaptiveSupersamplerOptions& options, const std::vector<AdaptiveShaderTarget>& targets);
  /// The target of `device` (its enabled shaderFloat64 and its limits): what an engine lists
  /// for each device kind it ships on.
  static Result<AdaptiveShaderTarget> shader_target(const DeviceContext& device);
  /// The component's descriptor-set index (= hook_set_layouts.size()).
  std::uint32_t descriptor_set_index() const;

  struct State;

 private:
  AdaptiveSupersampler() = default;
  std::unique_ptr<State> state_;
};

}  // namespace tessera::vk
