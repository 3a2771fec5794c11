# Optional parts of the build (tessera::gl, the Python module, the GLSL compilers, later Vulkan)
# and the tests that need them: where a part is not built, its tests are not registered, so a
# run could pass without testing it. tessera_require_or_skip(PART REASON) registers in their
# place one CTest test, `require_PART` (label PART), that fails when $TESSERA_TEST_REQUIRE names
# PART or is "all" (scripts/test.sh), and is reported skipped with REASON otherwise. The same
# rule as tests/support (test_support.h `required`, cli_harness.py `skip_or_fail`).
#
# Included by the top-level CMakeLists.txt; run by CTest as a script:
#   cmake -DPART=gl "-DREASON=..." -P cmake/require_or_skip.cmake
if(CMAKE_SCRIPT_MODE_FILE)
  cmake_minimum_required(VERSION 3.20)  # policies for IN_LIST in script mode
  string(REPLACE "," ";" _required "$ENV{TESSERA_TEST_REQUIRE}")
  if("all" IN_LIST _required OR PART IN_LIST _required)
    message(FATAL_ERROR "FAIL: ${REASON} (TESSERA_TEST_REQUIRE asks for ${PART})")
  endif()
  message(STATUS "SKIP: ${REASON}")
  return()
endif()

function(tessera_require_or_skip part reason)
  if(NOT TESSERA_BUILD_TESTS OR TEST require_${part})
    return()
  endif()
  add_test(NAME require_${part}
           COMMAND ${CMAKE_COMMAND} -DPART=${part} "-DREASON=${reason}"
                   -P ${PROJECT_SOURCE_DIR}/cmake/require_or_skip.cmake)
  set_tests_properties(require_${part} PROPERTIES LABELS ${part}
                       SKIP_REGULAR_EXPRESSION "-- SKIP: ")
  message(STATUS "${reason}: test require_${part} registered (fails under TESSERA_TEST_REQUIRE)")
endfunction()
