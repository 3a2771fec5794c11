// Helpers shared by the experiments tests (experiments_test.cpp, experiments_aa_test.cpp,
// experiments_seams_backend_test.cpp): the tiny seam experiment and its one cached result, and
// a GPU backend factory made of functions (fake GL / Vulkan backends).
#pragma once

#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tessera/experiments.h"

namespace tessera::experiments::test {

/// The JSON reports of one experiment run on Vulkan (`jv`) and on GL (`jg`) are twins: each
/// names its backend, and they have the same top-level keys.
inline void expect_twin_reports(const nlohmann::json& jv, const nlohmann::json& jg) {
  EXPECT_EQ(jv["backend"], "vk");
  EXPECT_EQ(jg["backend"], "gl");
  std::vector<std::string> kv, kg;
  for (const auto& [k, v] : jv.items()) kv.push_back(k);
  for (const auto& [k, v] : jg.items()) kg.push_back(k);
  EXPECT_EQ(kv, kg);
}

inline SeamsConfig tiny_seams() {
  SeamsConfig c;
  c.figure1.ground = 6;
  c.figure1.character = 4;
  c.figure1.texels_per_unit = 24.0f;
  c.width = 64;
  c.height = 56;
  c.frames = 2;
  c.msaa = {1, 4};
  c.reference_factor = 3;
  c.threads = 2;
  return c;
}

/// Runs the tiny seam experiment once for the whole suite (each run renders ~20 frames).
inline const SeamsResult& seams_result() {
  static const SeamsResult r = [] {
    Result<SeamsResult> res = run_seams(tiny_seams());
    EXPECT_TRUE(res.ok()) << res.status().message;
    return res.ok() ? *res : SeamsResult{};
  }();
  return r;
}

using SeamsFactoryFn = std::function<Result<std::unique_ptr<SeamsBackend>>(
    const faces::FaceScene&, const faces::FaceTextureSet&)>;
using AaFactoryFn = std::function<Result<std::unique_ptr<AaBackend>>(const scene::Scene&)>;

/// A GpuBackendFactory of `kind` (gl or vk) whose backends come from two functions; an unset
/// one fails (unsupported). `status` is its device_status().
class FunctionGpuFactory final : public GpuBackendFactory {
 public:
  FunctionGpuFactory(SeamsFactoryFn seams, AaFactoryFn aa, Backend kind = Backend::gl,
                     Status status = Status::success())
      : seams_(std::move(seams)), aa_(std::move(aa)), kind_(kind), status_(std::move(status)) {}
  Backend backend() const override { return kind_; }
  Status device_status() const override { return status_; }
  Result<std::unique_ptr<SeamsBackend>> create_seams(
      const faces::FaceScene& scene, const faces::FaceTextureSet& textures) const override {
    if (!seams_) return Status::error(ErrorCode::unsupported, "no fake seams backend");
    return seams_(scene, textures);
  }
  Result<std::unique_ptr<AaBackend>> create_aa(const scene::Scene& scene) const override {
    if (!aa_) return Status::error(ErrorCode::unsupported, "no fake aa backend");
    return aa_(scene);
  }

 private:
  SeamsFactoryFn seams_;
  AaFactoryFn aa_;
  Backend kind_;
  Status status_;
};

inline std::shared_ptr<const GpuBackendFactory> seams_factory(SeamsFactoryFn fn,
                                                              Backend kind = Backend::gl,
                                                              Status status = Status::success()) {
  return std::make_shared<const FunctionGpuFactory>(std::move(fn), nullptr, kind,
                                                    std::move(status));
}
inline std::shared_ptr<const GpuBackendFactory> aa_factory(AaFactoryFn fn,
                                                           Backend kind = Backend::gl,
                                                           Status status = Status::success()) {
  return std::make_shared<const FunctionGpuFactory>(nullptr, std::move(fn), kind,
                                                    std::move(status));
}

}  // namespace tessera::experiments::test
