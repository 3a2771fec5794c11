// Helpers shared by the experiments tests (experiments_test.cpp,
// experiments_seams_backend_test.cpp): the tiny seam experiment and its one cached result.
#pragma once

#include <gtest/gtest.h>

#include "tessera/experiments.h"

namespace tessera::experiments::test {

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

}  // namespace tessera::experiments::test
