// Internal to src/gl: the state of tessera::gl::AdaptiveSupersampler, shared by
// adaptive_supersampler.cpp (GL limits, programs, objects) and adaptive_dispatch.cpp (the frame
// checks, the passes, the GL state guard); the backend-neutral part is src/adaptive/.
#pragma once

#include <GL/glcorearb.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "adaptive/adaptive_host.h"
#include "tessera/gl.h"
#include "tessera/gl_adaptive.h"

namespace tessera::gl {

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
  adaptive::Derived derived;  // n, sample order, slots, list capacity
  int texture_unit = 0, uniform_binding = 0, storage_binding = 0, image_unit = 0;
  Object params_ubo, work_buf, list_buf, colour_tex, counts_tex, sampler;
  std::map<std::string, Program> programs;  // by pass name
};

}  // namespace tessera::gl
