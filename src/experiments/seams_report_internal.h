// Internal to src/experiments: what seams_report.cpp (seams.json) and
// seams_report_markdown.cpp (seams.md) share: the rate keys, number formatting and the
// summary facts both reports state.
#pragma once

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "tessera/experiments/seams.h"

namespace tessera::experiments::seams_report {

using faces::SeamMethod;

inline constexpr double kStep = kSeamsCdfStep;
inline constexpr int kBins = kSeamsCdfBins;

inline std::string rate_key(int r) { return std::to_string(r) + "x"; }

inline std::string fmt(const char* format, double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, value);
  return buf;
}

inline float norm_rgb(const float* a, const float* b) {
  const float d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
  return std::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
}

/// The first MSAA rate at which Discard's mean near-seam error is no larger than Traverse's at
/// the same rate, or null when it never is.
inline nlohmann::json discard_catches_traverse(const SeamsResult& res) {
  for (const SeamsRateResult& rate : res.rates) {
    if (rate.method(SeamMethod::discard).vs_reference_near_seams.mean <=
        rate.method(SeamMethod::traverse).vs_reference_near_seams.mean) {
      return rate.msaa;
    }
  }
  return nullptr;
}

/// Whether GL ran on a software rasteriser (llvmpipe, softpipe): its GPU timer is partial.
/// (Vulkan's timestamps on lavapipe, also "llvmpipe", are written in command order: whole.)
inline bool software_gl(const SeamsResult& res) {
  return res.backend != Backend::vk && (res.gpu_renderer.find("llvmpipe") != std::string::npos ||
                                        res.gpu_renderer.find("softpipe") != std::string::npos);
}

/// "OpenGL" or "Vulkan": the API of a GPU result (gl, vk, both's GL side).
inline const char* gpu_api_name(const SeamsResult& res) {
  return res.backend == Backend::vk ? "Vulkan" : "OpenGL";
}

/// The GL-vs-CPU result of a GL rate (`--backend both`), or null.
inline const SeamsGlRateResult* gl_rate_result(const SeamsResult& res, int msaa) {
  if (res.backend != Backend::both) return nullptr;
  for (const SeamsGlRateResult& g : res.gl_rates) {
    if (g.msaa == msaa) return &g;
  }
  return nullptr;
}

}  // namespace tessera::experiments::seams_report
