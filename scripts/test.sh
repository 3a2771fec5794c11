#!/usr/bin/env bash
# Sets up everything and runs every test:
#   0. clang-format 14 (.clang-format): any unformatted C/C++ file fails (scripts/check_format.sh);
#   1. GCC Release build (warnings are errors): the whole CTest suite, PVRTexTool oracle included;
#   2. Clang build with AddressSanitizer + UndefinedBehaviorSanitizer (warnings are errors), with
#      the libFuzzer targets: the unit tests again, and each fuzzer over its seeds plus a bounded
#      number of generated inputs;
#   3. arm64: the library cross-compiled for AArch64 (NEON backend) and run under qemu-user: the
#      SIMD, PVRTC, texture and raster unit tests, and the PVRTC encoder's bytes on a fixed image
#      set compared with x86-64's (AVX2 dispatch, SSE2, scalar): any differing byte fails
#      (tests/arch/pvrtc_arch_bytes.sh).
# Stages 1 and 2 require the GL device, the oracles and ../shared/data (TESSERA_TEST_REQUIRE=all);
# every optional part must be built and every AVX2 test run (on an AVX2 CPU). At the end: the
# counts of tests run, skipped and failed per stage and label.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
# Each stage's wall time, printed at the end beside the counts (what grew, where).
stage_names=() stage_secs=() stage_start=$(date +%s) stage_name="setup and build"
stage() {
  local now
  now=$(date +%s)
  stage_names+=("$stage_name") stage_secs+=($((now - stage_start)))
  stage_name="$1" stage_start=$now
  echo "== $1"
}
bash scripts/setup.sh --arm64
jobs="$(nproc)"
# What CI has, the tests must find: without a GL device, the PVRTexTool or ktx-parse oracles or
# ../shared/data, the tests that need them fail here and say why (a plain `ctest` skips them).
export TESSERA_TEST_REQUIRE=all
# At the end, pass or fail: the tests run, skipped and failed per stage and label
# (scripts/test_summary.py, from each ctest run's JUnit file and the arm64 stage's counts).
mkdir -p build build-asan build-arm64
rm -f build/ctest-junit.xml build-asan/ctest-junit.xml build-arm64/test-counts.tsv
summary() {
  stage "(end)" >/dev/null
  echo "Wall time per stage (seconds):"
  for i in "${!stage_names[@]}"; do printf '  %-44s %6d\n' "${stage_names[$i]}" "${stage_secs[$i]}"; done
  python3 scripts/test_summary.py "GCC Release=build:build/ctest-junit.xml" \
    "Clang ASan+UBSan=build-asan:build-asan/ctest-junit.xml" \
    --counts build-arm64/test-counts.tsv || true
}
trap summary EXIT

stage "clang-format: every C/C++ file formatted"
bash scripts/check_format.sh

stage "GCC Release: all tests"
ctest --test-dir build --output-on-failure -j "$jobs" --output-junit ctest-junit.xml

stage "Clang ASan+UBSan: build, unit and fuzz tests"
cache="${TESSERA_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/tessera}"
CC=clang CXX=clang++ cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DTESSERA_SANITIZE=ON -DTESSERA_WERROR=ON -DTESSERA_BUILD_BENCH=OFF -DTESSERA_BUILD_FUZZ=ON \
  -DTESSERA_PVRTEXTOOL="$cache/peers/PVRTexToolCLI" >/dev/null
cmake --build build-asan
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir build-asan --output-on-failure -j "$jobs" -L 'unit|fuzz' --output-junit ctest-junit.xml

stage "arm64 (cross-compiled, qemu-user): NEON bytes equal x86-64"
bash tests/arch/pvrtc_arch_bytes.sh build
