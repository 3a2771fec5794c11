// Internal to src/experiments: which GPU factory of a config a backend uses (gl_factory for gl
// and both, vk_factory for vk), and the one-line error when the program was built without it.
#pragma once

#include <memory>
#include <string>

#include "tessera/experiments/common.h"

namespace tessera::experiments::detail {

/// The factory `backend` renders with: null for the CPU; unsupported naming the runtime ("aa:
/// backend 'vk': not built with the Vulkan runtime") when it is needed and unset.
inline Result<const GpuBackendFactory*> gpu_factory(
    const char* experiment, Backend backend, const std::shared_ptr<const GpuBackendFactory>& gl,
    const std::shared_ptr<const GpuBackendFactory>& vk) {
  if (!uses_gpu(backend)) return static_cast<const GpuBackendFactory*>(nullptr);
  const bool vulkan = backend == Backend::vk;
  const GpuBackendFactory* f = vulkan ? vk.get() : gl.get();
  if (f == nullptr) {
    return Status::error(ErrorCode::unsupported, std::string(experiment) + ": backend '" +
                                                     backend_name(backend) +
                                                     "': not built with the " +
                                                     (vulkan ? "Vulkan" : "OpenGL") + " runtime");
  }
  return f;
}

}  // namespace tessera::experiments::detail
