// The fixture the GL test suites derive from: a tessera-owned OpenGL 4.5 context (gl::Context)
// made for each test. Without one the test skips with the reason, or fails where
// TESSERA_TEST_REQUIRE asks for gl (test_require.h).
#pragma once

#include <gtest/gtest.h>

#include <memory>

#include "tessera/gl.h"
#include "test_support.h"

namespace tessera::test {

class GlTest : public ::testing::Test {
 protected:
  /// A derived SetUp calls this first and returns when `ctx_` is null (skipped or failed).
  void SetUp() override { create_context({}); }
  /// A derived TearDown releases its GL objects first, then calls this.
  void TearDown() override { ctx_.reset(); }

  /// Makes `ctx_` with `options`, or skips / fails the test.
  void create_context(const gl::ContextOptions& options) {
    Result<std::unique_ptr<gl::Context>> c = gl::Context::create(options);
    if (!c) TESSERA_SKIP_OR_FAIL("gl", "no OpenGL 4.5 context: " << c.status().message);
    ctx_ = std::move(*c);
  }

  std::unique_ptr<gl::Context> ctx_;
};

}  // namespace tessera::test
