// Internal to src/vk: vk::AdaptiveSupersampler's passes compiled to SPIR-V at build time and
// embedded (tools/vk_passes, src/CMakeLists.txt): those that read neither the hook nor the
// G-buffer layout, so one module serves every option set; `create` compiles only the others.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace tessera::vk {

/// The passes the build embeds (their names in adaptive::pass_programs).
inline constexpr const char* kEmbeddedPasses[] = {"HISTOGRAM", "SELECT", "APPLY", "ARGS"};

/// The embedded SPIR-V of `pass` with every DescriptorSet decoration set to `set` (the
/// component's set index), or empty when `pass` is not embedded (or the build had no
/// glslangValidator: every pass is then compiled at create).
std::vector<std::uint32_t> embedded_pass(const std::string& pass, std::uint32_t set);

}  // namespace tessera::vk
