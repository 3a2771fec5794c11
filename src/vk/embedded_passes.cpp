// The embedded passes' SPIR-V (generated/vk_passes_spirv.cpp) with the component's descriptor
// set and the specialized passes' sampler bindings patched in.
#include "vk/embedded_passes.h"

#include <cstring>
#include <map>

#include "core/embedded.h"

namespace tessera::vk {

namespace {

// SPIR-V: a 5-word header, then instructions whose first word is (word count << 16) | opcode.
constexpr std::uint32_t kOpName = 5, kOpDecorate = 71, kBinding = 33, kDescriptorSet = 34;

/// The literal string of OpName's words from `at` (nul-terminated, packed little-endian).
std::string literal(const std::vector<std::uint32_t>& words, std::size_t at, std::size_t end) {
  std::string s;
  for (; at < end; ++at) {
    for (int b = 0; b < 4; ++b) {
      const char c = char((words[at] >> (8 * b)) & 0xffu);
      if (c == '\0') return s;
      s += c;
    }
  }
  return s;
}

}  // namespace

std::vector<std::uint32_t> embedded_pass(
    const std::string& name, std::uint32_t set,
    const std::vector<std::pair<std::string, std::uint32_t>>& bindings) {
  const std::string file = name + ".spv";
  for (const EmbeddedFile& f : embedded::adaptive_pass_spirv()) {
    if (f.name != file) continue;
    std::vector<std::uint32_t> words(f.data.size() / 4);
    std::memcpy(words.data(), f.data.data(), words.size() * 4);
    // Names come before decorations (the module's logical layout): one pass finds both.
    std::map<std::uint32_t, std::uint32_t> binding_of;  // result id -> binding
    std::size_t patched = 0;
    for (std::size_t at = 5; at < words.size();) {
      const std::uint32_t count = words[at] >> 16, opcode = words[at] & 0xffffu;
      if (count == 0 || at + count > words.size()) return {};  // malformed: compile instead
      if (opcode == kOpName && count >= 3) {
        const std::string n = literal(words, at + 2, at + count);
        for (const auto& [variable, binding] : bindings) {
          if (n == variable) binding_of[words[at + 1]] = binding;
        }
      } else if (opcode == kOpDecorate && count == 4 && words[at + 2] == kDescriptorSet) {
        words[at + 3] = set;
      } else if (opcode == kOpDecorate && count == 4 && words[at + 2] == kBinding) {
        if (auto it = binding_of.find(words[at + 1]); it != binding_of.end()) {
          words[at + 3] = it->second;
          ++patched;
        }
      }
      at += count;
    }
    // A variable the compiler dropped (unused by the pass) has no binding to patch.
    if (patched != binding_of.size()) return {};
    return words;
  }
  return {};
}

}  // namespace tessera::vk
