// Shared pieces of the experiments: medians, names, error statistics.
#include <algorithm>
#include <cmath>

#include "tessera/experiments.h"

namespace tessera::experiments {

const char* backend_name(Backend backend) {
  switch (backend) {
    case Backend::cpu:
      return "cpu";
    case Backend::gl:
      return "gl";
    case Backend::vk:
      return "vk";
    case Backend::both:
      return "both";
  }
  return "?";
}

Result<Backend> parse_backend(std::string_view text) {
  for (Backend b : {Backend::cpu, Backend::gl, Backend::vk, Backend::both}) {
    if (text == backend_name(b)) return b;
  }
  return Status::error(ErrorCode::invalid_argument,
                       "backend '" + std::string(text) + "': expected cpu, gl, vk or both");
}

double FrameTimes::median_ms() const { return tessera::median(frame_ms); }

double ErrorStats::at(double x) const {
  if (cdf.empty()) return 0.0;
  const long i = std::lround(x / kSeamsCdfStep);
  return cdf[std::size_t(std::clamp<long>(i, 0, long(cdf.size()) - 1))];
}

const char* aa_method_name(AaMethod method) {
  switch (method) {
    case AaMethod::default_1spp:
      return "default";
    case AaMethod::fxaa:
      return "fxaa";
    case AaMethod::reference:
      return "reference";
    case AaMethod::adaptive:
      return "adaptive";
    case AaMethod::edge_per_sample:
      return "edge_per_sample";
  }
  return "?";
}

bool AaQuality::identical() const { return !std::isfinite(psnr_db); }

}  // namespace tessera::experiments
