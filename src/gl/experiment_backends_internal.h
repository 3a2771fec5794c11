// Internal to tessera_gl: the GL backends of the two experiments, made by
// gl::experiment_backends (experiment_backends.cpp; tessera/gl_experiments.h).
#pragma once

#include <filesystem>
#include <memory>

#include "tessera/experiments/aa_backend.h"
#include "tessera/experiments/seams_backend.h"
#include "tessera/gl.h"
#include "tessera/gl_deferred.h"

namespace tessera::gl {

/// What both GL backends share: a headless context of their own and the renderer on it
/// (`Renderer`), which goes first, with the context current.
template <typename Interface, typename Renderer>
class GlBackend : public Interface {
 public:
  GlBackend(std::unique_ptr<Context> ctx, std::unique_ptr<Renderer> r)
      : ctx_(std::move(ctx)), r_(std::move(r)) {}
  ~GlBackend() override {
    if (ctx_ && ctx_->make_current().ok()) r_.reset();
  }
  GlBackend(const GlBackend&) = delete;
  GlBackend& operator=(const GlBackend&) = delete;

  experiments::Backend backend() const override { return experiments::Backend::gl; }
  std::string device_name() const override { return ctx_->renderer(); }
  std::string device_version() const override { return ctx_->version(); }

 protected:
  std::unique_ptr<Context> ctx_;
  std::unique_ptr<Renderer> r_;
};

/// gl::FaceRenderer on a headless context of its own (seams_backend.cpp).
Result<std::unique_ptr<experiments::SeamsBackend>> create_seams_backend(
    const faces::FaceScene& scene, const faces::FaceTextureSet& textures,
    const std::filesystem::path& glsl_dir);

/// gl::DeferredRenderer on a headless context of its own (aa_backend.cpp).
Result<std::unique_ptr<experiments::AaBackend>> create_aa_backend(
    const scene::Scene& scene, const std::filesystem::path& glsl_dir, ExtraSchedule schedule);

}  // namespace tessera::gl
