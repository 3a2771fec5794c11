// Internal to src/vk (and tools/vk_passes, which builds the embedded passes with them): the
// bindings of vk::AdaptiveSupersampler's resources in its descriptor set (tessera/vk_adaptive.h,
// 2.).
#pragma once

#include <cstdint>

namespace tessera::vk {

inline constexpr std::uint32_t kBindParams = 0, kBindWork = 1, kBindList = 2, kBindColour = 3,
                               kBindCounts = 4, kBindGBuffer = 5;

}  // namespace tessera::vk
