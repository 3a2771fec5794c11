// The skip-or-fail rule of the C++ tests, header-only so that the standalone SIMD tests
// (simd_*_test, which link neither the library nor test_support.cpp) use it too: a test that
// needs something the run lacks skips with a message, or fails where $TESSERA_TEST_REQUIRE asks
// for that thing (scripts/test.sh sets "all"). The Python side is cli_harness.py
// (`skip_or_fail`), the CMake side cmake/require_or_skip.cmake.
#pragma once

#include <cstdlib>
#include <string>

namespace tessera::test {

/// Whether the run must have `what` ("gl", "pvrtextool", "shared", "ktx-parse", "avx2"): named
/// in the comma-separated $TESSERA_TEST_REQUIRE, or that variable is "all". The README's test
/// command (scripts/test.sh) sets "all", so that a missing GL device, oracle or data set fails
/// the run there; a plain `ctest` without it skips those tests with a message.
inline bool required(const std::string& what) {
  const char* env = std::getenv("TESSERA_TEST_REQUIRE");
  if (!env) return false;
  const std::string list = std::string(",") + env + ",";
  return list == ",all," || list.find("," + what + ",") != std::string::npos;
}

/// Whether this CPU runs AVX2 code (x86-64 with AVX2; false on every other architecture).
inline bool cpu_has_avx2() {
#if defined(__x86_64__) || defined(__i386__)
  return __builtin_cpu_supports("avx2") != 0;
#else
  return false;
#endif
}

}  // namespace tessera::test

/// Skips the current test with `message` when `what` is missing, or fails it when the run
/// requires `what` (see `tessera::test::required`).
#define TESSERA_SKIP_OR_FAIL(what, message)                                     \
  do {                                                                          \
    if (::tessera::test::required(what)) {                                      \
      FAIL() << message << " (TESSERA_TEST_REQUIRE asks for " << (what) << ")"; \
    }                                                                           \
    GTEST_SKIP() << message;                                                    \
  } while (0)

/// Lets the test run where `available` (the AVX2 code under test is built and runs); else skips
/// with `message` where the CPU has no AVX2, and where it has (the build lacks the AVX2 code) skips
/// or fails by the rule above for "avx2": a run that requires it cannot pass with these tests
/// skipped on a CPU that could run them.
#define TESSERA_SKIP_WITHOUT_AVX2(available, message)                    \
  do {                                                                   \
    if (!(available)) {                                                  \
      if (::tessera::test::cpu_has_avx2()) {                             \
        TESSERA_SKIP_OR_FAIL("avx2", message << " (this CPU has AVX2)"); \
      }                                                                  \
      GTEST_SKIP() << message;                                           \
    }                                                                    \
  } while (0)
