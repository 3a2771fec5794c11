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
images="$PWD/../shared/data/images"
[ -d "$images" ] || { echo "missing $images (shared/data beside the repository)" >&2; exit 1; }
[ -x "$native/bin/pvrtc_arch_bytes" ] || { echo "missing $native/bin/pvrtc_arch_bytes" >&2; exit 1; }
for tool in aarch64-linux-gnu-g++ qemu-aarch64; do
  command -v "$tool" >/dev/null || { echo "missing $tool: run bash scripts/setup.sh --arm64" >&2; exit 1; }
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
for t in "${arm64_tests[@]}"; do
  filter=()
  [ "$t" = pvrtc_codec_test ] && filter=(--gtest_filter=-PvrtcEncode.IdenticalForAnyThreadCount)
  if "${qemu[@]}" "build-arm64/bin/$t" "${filter[@]}" >"build-arm64/$t.log" 2>&1; then
    echo "$t: $(grep -E '^\[  PASSED  \]' "build-arm64/$t.log")"
  else
    status=1
    grep -E -A4 'Failure$' "build-arm64/$t.log" | head -60 >&2 || true
    tail -n 15 "build-arm64/$t.log" >&2
    echo "FAILED: $t (AArch64, NEON); the whole log: build-arm64/$t.log" >&2
  fi
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
run x86-64-dispatch "$native/bin/pvrtc_arch_bytes"
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
