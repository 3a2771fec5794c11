// Internal to src/vk: vk::AdaptiveSupersampler's passes that do not shade, compiled to SPIR-V at
// build time and embedded (tools/vk_passes, src/CMakeLists.txt): those that read neither the
// hook nor the G-buffer layout, and METRICS and LIST, which read the layout through
// specialization constants (src/adaptive/adaptive_specialized.cpp), so one module serves every
// option set; `create` compiles only the passes with the hook.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace tessera::vk {

/// The hook-free, layout-free passes the build embeds (their names in adaptive::pass_programs);
/// METRICS and LIST are embedded too, as the variants of adaptive::specialized_variants().
inline constexpr const char* kEmbeddedPasses[] = {"HISTOGRAM", "SELECT", "APPLY", "ARGS"};

/// The embedded SPIR-V of `name` (a pass or a specialized variant) with every DescriptorSet
/// decoration set to `set` (the component's set index) and the Binding decoration of each named
/// variable in `bindings` set to its value; empty when `name` is not embedded (or the build
/// had no glslangValidator: every pass is then compiled at create).
std::vector<std::uint32_t> embedded_pass(
    const std::string& name, std::uint32_t set,
    const std::vector<std::pair<std::string, std::uint32_t>>& bindings = {});

}  // namespace tessera::vk
