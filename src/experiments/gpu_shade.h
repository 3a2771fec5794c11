// Internal: one AA backend's `shade` over either GPU renderer (gl::DeferredRenderer, the Vulkan
// twin in src/vk/): the same methods under the same names, the same result types, one dispatch.
#pragma once

#include <utility>

#include "tessera/experiments/aa_backend.h"

namespace tessera::experiments {

/// `method` on `r` (a GPU deferred renderer's shade_* functions) as an AA backend's output.
template <class Renderer>
Result<AaShadeOutput> shade_on_gpu(Renderer& r, AaMethod method, const deferred::ShadingOptions& so,
                                   const AaShadeOptions& o) {
  if (method == AaMethod::fxaa) {
    Result<deferred::FxaaResult> x = r.shade_default_fxaa(so, o.fxaa);
    if (!x) return x.status();
    return aa_shade_output(std::move(*x));
  }
  Result<deferred::ShadeResult> x = method == AaMethod::default_1spp ? r.shade_default(so)
                                    : method == AaMethod::reference  ? r.shade_reference(so)
                                    : method == AaMethod::adaptive
                                        ? r.shade_adaptive(so, o.adaptive)
                                        : r.shade_edge_per_sample(so, o.edge);
  if (!x) return x.status();
  return aa_shade_output(method, std::move(*x), so.threads);
}

}  // namespace tessera::experiments
