// Internal to src/gl: the state of tessera::gl::AdaptiveSupersampler, shared by
// adaptive_supersampler.cpp (options, GLSL generation, programs) and adaptive_dispatch.cpp
// (the passes, the budget, the GL state guard).
#pragma once

#include <GL/glcorearb.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "tessera/gl.h"
#include "tessera/gl_adaptive.h"

namespace tessera::gl {

/// std140 layout of TesseraAaParams (adaptive_component.glsl).
struct AdaptiveParams {
  std::int32_t size[4];
  std::int32_t flags[4];
  float metric[4];
  float metric2[4];
  std::uint32_t budget[4];
  std::int32_t order[64];
};
static_assert(sizeof(AdaptiveParams) == 5 * 16 + 256, "std140 layout");

/// Work-buffer layout (uints; adaptive_component.glsl's header comment).
inline constexpr std::size_t kAdaptiveHeaderUints = 16;
inline constexpr std::size_t kAdaptiveHistogramUints = 8 * 256;
inline constexpr std::size_t kAdaptiveListItemBytes = 24;
inline constexpr std::size_t kAdaptiveMaxPixels = std::size_t(1) << 26;  // item packing

/// The GL 4.5 entry points the dispatch code calls through its state (copies of tessera's table,
/// src/gl/gl_api.h).
struct AdaptiveGlExtra {
  PFNGLGETINTEGERI_VPROC GetIntegeri_v = nullptr;
  PFNGLGETINTEGER64I_VPROC GetInteger64i_v = nullptr;
  PFNGLBINDIMAGETEXTUREPROC BindImageTexture = nullptr;
  PFNGLBINDBUFFERRANGEPROC BindBufferRange = nullptr;
  PFNGLDISPATCHCOMPUTEINDIRECTPROC DispatchComputeIndirect = nullptr;
  PFNGLISTEXTUREPROC IsTexture = nullptr;
};
/// Copies them from the loaded table.
AdaptiveGlExtra adaptive_gl_extra();

struct AdaptiveSupersampler::State {
  AdaptiveSupersamplerOptions options;
  AdaptiveGlExtra gl;
  int n = 0;
  std::vector<std::uint8_t> order;
  int texture_unit = 0, uniform_binding = 0, storage_binding = 0, image_unit = 0;
  std::size_t list_capacity = 0;
  bool slot_used[4] = {false, false, false, false};
  /// Channels read from each slot: the highest component index + 1 (for the format check).
  int slot_channels[4] = {0, 0, 0, 0};
  Object params_ubo, work_buf, list_buf, colour_tex, counts_tex, sampler;
  std::map<std::string, Program> programs;  // by pass name
};

}  // namespace tessera::gl
