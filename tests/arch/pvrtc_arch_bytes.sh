#!/usr/bin/env bash
# The arm64 stage of scripts/test.sh: the PVRTC encoder gives the same bytes on every SIMD
# backend, and the NEON backend passes its own checks.
#
#   bash tests/arch/pvrtc_arch_bytes.sh [NATIVE_BUILD]     (default: build)
#
# 1. Cross-compiles the library for AArch64 (cmake/aarch64-linux-gnu.cmake: Debian's
#    g++-aarch64-linux-gnu and multiarch arm64 packages, which `scripts/setup.sh --arm64`
#    installs) into build-arm64/: the NEON backend. Only what runs below is built: the
#    library, pvrtc_arch_bytes and the unit tests of the SIMD wrapper and of the code that uses
#    it (PVRTC, texture sampling, rasteriser, core).
# 2. Builds pvrtc_arch_bytes natively with TESSERA_NO_SIMD (the portable scalar backend) into
#    build-nosimd/.
# 3. Runs those tests under qemu-aarch64: simd_test holds NEON to the SSE2 semantics lane by
#    lane; the others hold NEON's vector paths (TESSERA_SIMD_VECTOR) to their expected results.
#    Left out under qemu: PvrtcEncode.IdenticalForAnyThreadCount (half a minute of emulated
#    threads; thread-count independence is the same code on every target and runs natively).
# 4. Runs pvrtc_arch_bytes (pvrtc_arch_bytes.cpp beside this script: which images and sizes,
#    and why) four times: x86-64 with the AVX2 kernels dispatched (where the CPU has AVX2),
#    x86-64 with the baseline SSE2 kernels forced, the scalar build, and AArch64 NEON under
#    qemu-aarch64; then compares the SHA-256 of every file (encoded bytes, decoded texels,
#    inputs). Any differing byte fails, naming the case and its first differing byte.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
native="${1:-build}"
jobs="$(nproc)"
# What the stage needs, by the tests' skip-or-fail rule (tests/support/test_require.h): where it
# is missing, exit 77 (skipped) with a message, or fail where $TESSERA_TEST_REQUIRE names arm64
# or is "all" (scripts/test.sh).
missing() {
  case ",${TESSERA_TEST_REQUIRE:-}," in
    *,all,* | *,arm64,*) echo "FAIL: $1 (TESSERA_TEST_REQUIRE asks for arm64)" >&2; exit 1 ;;
  esac
  echo "SKIP: $1" >&2
  exit 77
}
images="$PWD/../shared/data/images"
[ -d "$images" ] || missing "no $images (shared/data beside the repository)"
[ -x "$native/bin/pvrtc_arch_bytes" ] || { echo "missing $native/bin/pvrtc_arch_bytes" >&2; exit 1; }
for tool in aarch64-linux-gnu-g++ qemu-aarch64; do
  command -v "$tool" >/dev/null || missing "no $tool: run bash scripts/setup.sh --arm64"
done
# The loader and libc of the multiarch libc6:arm64 (see cmake/aarch64-linux-gnu.cmake).
qemu=(qemu-aarch64 -L /)

# (Not pvrtc_modulation_test: all of it compares the AVX2 kernels with the baseline.)
arm64_tests=(simd_test simd_int_test simd_wide_test pvrtc_codec_test pvrtc_search_test pvrtc_search_kernel_test pvrtc_dilation_test
             texture_test texture_filtering_test raster_test core_test)

echo "-- cross-compiling for AArch64 (build-arm64/)"
cmake -S . -B build-arm64 -G Ninja --no-warn-unused-cli -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_TOOLCHAIN_FILE=cmake/aarch64-linux-gnu.cmake -DTESSERA_WERROR=ON \
  -DTESSERA_BUILD_PYTHON=OFF -DTESSERA_BUILD_BENCH=OFF >/dev/null
cmake --build build-arm64 -j "$jobs" --target pvrtc_arch_bytes "${arm64_tests[@]}"
echo "   (${SECONDS} s so far)"

echo "-- x86-64 with TESSERA_NO_SIMD (build-nosimd/)"
cmake -S . -B build-nosimd -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS=-DTESSERA_NO_SIMD \
  -DTESSERA_WERROR=ON -DTESSERA_BUILD_PYTHON=OFF -DTESSERA_BUILD_BENCH=OFF >/dev/null
cmake --build build-nosimd -j "$jobs" --target pvrtc_arch_bytes
echo "   (${SECONDS} s so far)"

status=0
echo "-- NEON unit tests under qemu-aarch64"
# Counts for scripts/test.sh's summary: build-arm64/test-counts.tsv (stage, label, run, skipped,
# failed), one line per test program; GoogleTest's own lines give them.
counts=build-arm64/test-counts.tsv
: >"$counts"
gtest_count() {  # PATTERN LOG: the number on GoogleTest's summary line PATTERN, else 0
  sed -n -E "s/^\[ *$1 *\] ([0-9]+) tests?.*/\1/p" "$2" | head -n 1 | grep . || echo 0
}
for t in "${arm64_tests[@]}"; do
  filter=()
  [ "$t" = pvrtc_codec_test ] && filter=(--gtest_filter=-PvrtcEncode.IdenticalForAnyThreadCount)
  log="build-arm64/$t.log"
  if "${qemu[@]}" "build-arm64/bin/$t" "${filter[@]}" >"$log" 2>&1; then
    echo "$t: $(grep -E '^\[  PASSED  \]' "$log")"
  else
    status=1
    grep -E -A4 'Failure$' "$log" | head -60 >&2 || true
    tail -n 15 "$log" >&2
    echo "FAILED: $t (AArch64, NEON); the whole log: $log" >&2
  fi
  ran="$(sed -n -E 's/^\[==========\] ([0-9]+) tests? from .* ran.*/\1/p' "$log" | head -n 1)"
  skipped="$(gtest_count SKIPPED "$log")"
  failed="$(gtest_count FAILED "$log")"
  # A program that stopped before its summary counts as one failed test.
  [ -n "$ran" ] || { ran=1; skipped=0; failed=1; }
  printf 'arm64 (qemu)\tunit\t%s\t%s\t%s\n' "$((ran - skipped))" "$skipped" "$failed" >>"$counts"
done
echo "   (${SECONDS} s so far)"

echo "-- PVRTC bytes on every backend"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
run() {  # NAME COMMAND...: writes $out/NAME/ and $out/NAME.sha256
  local name="$1"
  shift
  mkdir -p "$out/$name"
  "$@" "$images" "$out/$name"
  (cd "$out/$name" && sha256sum -- * >"../$name.sha256")
}
run x86-64-dispatch "$native/bin/pvrtc_arch_bytes" | tee "$out/x86-64-dispatch.log"
# Where the CPU has AVX2, the dispatched run must use the AVX2 kernels, or the comparison below
# holds SSE2 to itself (the program's last line says "AVX2 kernels on|off").
if grep -qw avx2 /proc/cpuinfo && ! grep -q "AVX2 kernels on" "$out/x86-64-dispatch.log"; then
  case ",${TESSERA_TEST_REQUIRE:-}," in
    *,all,* | *,avx2,*)
      status=1
      echo "FAILED: this CPU has AVX2 but $native/bin/pvrtc_arch_bytes did not dispatch the AVX2 kernels (TESSERA_TEST_REQUIRE asks for avx2)" >&2 ;;
    *) echo "note: this CPU has AVX2 but $native/bin/pvrtc_arch_bytes did not dispatch the AVX2 kernels" ;;
  esac
fi
run x86-64-sse2 "$native/bin/pvrtc_arch_bytes" --baseline
run x86-64-scalar build-nosimd/bin/pvrtc_arch_bytes
run arm64-neon "${qemu[@]}" build-arm64/bin/pvrtc_arch_bytes
for name in x86-64-sse2 x86-64-scalar arm64-neon; do
  if diff -q "$out/x86-64-dispatch.sha256" "$out/$name.sha256" >/dev/null; then
    echo "$name: $(wc -l <"$out/$name.sha256") files, the same bytes as x86-64-dispatch"
    continue
  fi
  status=1
  differ=()
  for f in "$out/x86-64-dispatch"/*; do
    g="$out/$name/$(basename "$f")"
    cmp -s "$f" "$g" || differ+=("$(basename "$f"): $(cmp "$f" "$g" 2>&1 | sed 's/.*differ: //')")
  done
  echo "FAILED: $name: ${#differ[@]} of $(wc -l <"$out/x86-64-dispatch.sha256") files differ from x86-64-dispatch:" >&2
  printf '  %s\n' "${differ[@]}" | head -n 40 >&2
done
echo "   (${SECONDS} s in all)"
exit "$status"
