// The embedded passes' SPIR-V (generated/vk_passes_spirv.cpp) with the component's descriptor
// set patched in.
#include "vk/embedded_passes.h"

#include <cstring>

#include "core/embedded.h"

namespace tessera::vk {

std::vector<std::uint32_t> embedded_pass(const std::string& pass, std::uint32_t set) {
  const std::string name = pass + ".spv";
  for (const EmbeddedFile& f : embedded::adaptive_pass_spirv()) {
    if (f.name != name) continue;
    std::vector<std::uint32_t> words(f.data.size() / 4);
    std::memcpy(words.data(), f.data.data(), words.size() * 4);
    // SPIR-V: a 5-word header, then instructions whose first word is (word count << 16) |
    // opcode. OpDecorate (71) TARGET DescriptorSet (34) VALUE: VALUE becomes `set`.
    constexpr std::uint32_t kOpDecorate = 71, kDescriptorSet = 34;
    for (std::size_t at = 5; at < words.size();) {
      const std::uint32_t count = words[at] >> 16, opcode = words[at] & 0xffffu;
      if (count == 0 || at + count > words.size()) return {};  // malformed: compile instead
      if (opcode == kOpDecorate && count == 4 && words[at + 2] == kDescriptorSet) {
        words[at + 3] = set;
      }
      at += count;
    }
    return words;
  }
  return {};
}

}  // namespace tessera::vk
