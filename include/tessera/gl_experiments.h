// tessera/gl_experiments.h — the OpenGL backends of the two paper experiments: the one
// implementation of `experiments::GpuBackendFactory` (tessera/experiments/common.h). Part of the
// optional `tessera_gl` library (src/gl/experiment_backends.cpp, seams_backend.cpp,
// aa_backend.cpp), which defines what this header declares; the main `tessera` library, where
// `run_seams` and `run_aa` live, never links OpenGL and reaches GL only through the factory a
// caller puts in the config (`SeamsConfig::gl_factory`, `AaConfig::gl_factory`).
//
// The seam backend is gl::FaceRenderer (tessera/gl_face_renderer.h), the AA backend
// gl::DeferredRenderer (tessera/gl_deferred.h), each on a headless context of its own created
// on the calling thread with the device TESSERA_EGL_DEVICE names (gl.h).
// Tests: tests/gl/gl_face_renderer_test.cpp, tests/gl/gl_deferred_renderer_test.cpp,
// tests/gl/aa_gl_cli_test.py, seams_gl_cli_test.py.
#pragma once

#include <filesystem>
#include <memory>

#include "tessera/experiments/common.h"
#include "tessera/gl_deferred.h"

namespace tessera::gl {

struct ExperimentBackendOptions {
  /// Development override of the embedded GLSL (see tessera/glsl.h); empty: embedded.
  std::filesystem::path glsl_dir;
  /// The AA backend's extra-sample schedule (DeferredRendererOptions::schedule).
  ExtraSchedule schedule = ExtraSchedule::frame_list;
};

/// The GL backends of both experiments. Creating a backend fails with one line when there is no
/// usable OpenGL 4.5 device or the shaders are missing.
std::shared_ptr<const experiments::GpuBackendFactory> experiment_backends(
    const ExperimentBackendOptions& options);
/// The same with the default options and `glsl_dir`.
std::shared_ptr<const experiments::GpuBackendFactory> experiment_backends(
    const std::filesystem::path& glsl_dir = {});

}  // namespace tessera::gl
