// Internal to src/vk: GLSL compute (or vertex / fragment) source (already include-expanded, with
// #line bookkeeping) to SPIR-V with shaderc inside the compiler module tessera-vk-glsl.so
// (loaded at the first compile; an `unsupported` error naming where it looked when it is not
// there), and a compute pipeline from it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tessera/glsl.h"
#include "vk/vk_api.h"

namespace tessera::vk {

/// Compiles `text` as a Vulkan 1.0 compute shader (VULKAN defined). On failure the status
/// message is shaderc's log, unformatted (lines "FILE_INDEX:LINE: error: ...").
Result<std::vector<std::uint32_t>> compile_compute_spirv(const std::string& text);
/// The same for a vertex or fragment stage (invalid_argument for any other).
Result<std::vector<std::uint32_t>> compile_graphics_spirv(const std::string& text,
                                                          glsl::Stage stage);

/// A compute pipeline of `spirv` in `layout` (through the engine's `cache` when not null, with
/// `specialization` when not null); the shader module is destroyed before returning.
Result<Pipeline> create_compute_pipeline(const Api& api, const std::vector<std::uint32_t>& spirv,
                                         VkPipelineLayout layout, const std::string& what,
                                         VkPipelineCache cache = VK_NULL_HANDLE,
                                         const VkSpecializationInfo* specialization = nullptr);

}  // namespace tessera::vk
