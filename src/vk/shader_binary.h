// Internal to src/vk: the shader binary of vk::AdaptiveSupersampler (tessera/vk_adaptive.h,
// AdaptiveSupersamplerOptions::shader_binary): every pass's SPIR-V, keyed by a hash of the
// expanded GLSL each pass would compile (the options, the hook, the device-derived defines and
// tessera's own GLSL), so that a binary made for other options, another device's limits or
// another tessera is refused. One binary may hold several keys (one per device target:
// AdaptiveSupersampler::compile_shader_binary). Little-endian layout:
//   "TSAS", u32 format (2), u32 entry count, then per entry: u64 key, u32 pass count, then per
//   pass: u32 name bytes, the name (zero-padded to 4 bytes), u32 SPIR-V words, the words.
// Format 1 (one entry, no entry count) is read too.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "tessera/core.h"

namespace tessera::vk {

/// FNV-1a 64 of each (pass name, expanded source) in order, and of tessera's version.
std::uint64_t shader_key(const std::map<std::string, std::string>& expanded);

/// Every pass's SPIR-V by pass name.
using ShaderPasses = std::map<std::string, std::vector<std::uint32_t>>;
struct ShaderBinaryEntry {
  std::uint64_t key = 0;
  ShaderPasses spirv;
};

std::vector<std::uint8_t> write_shader_binary(const std::vector<ShaderBinaryEntry>& entries);

/// The passes' SPIR-V of the entry of `bytes` whose key is `key`: corrupt_data for a truncated
/// or malformed binary, invalid_argument when no entry has the key or a pass is missing
/// (messages start "shader_binary: ").
Result<std::map<std::string, std::vector<std::uint32_t>>> read_shader_binary(
    const std::vector<std::uint8_t>& bytes, std::uint64_t key,
    const std::vector<std::string>& passes);

}  // namespace tessera::vk
