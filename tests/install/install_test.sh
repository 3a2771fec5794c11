#!/usr/bin/env bash
# Installs the build tree into a scratch prefix and builds examples/consumer against it with
# find_package(tessera), then runs it; where tessera::gl was installed, also examples/engine_aa
# and examples/engine_ptex with find_package(tessera COMPONENTS gl), run at a small size (no GL
# device is not an error here: the build is what is checked, the CTests engine_aa and
# engine_ptex check the images); where tessera::vk was installed, examples/engine_aa_vk with
# find_package(tessera COMPONENTS vk) the same way (its CTest engine_aa_vk checks the image).
# Usage: install_test.sh SOURCE_DIR BINARY_DIR
set -euo pipefail
src="$1"
bin="$2"
work="$bin/test-tmp/install"
rm -rf "$work"
cmake --install "$bin" --prefix "$work/prefix" >/dev/null
cmake -S "$src/examples/consumer" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/build" >/dev/null
"$work/build/consumer"
if [ -f "$work/prefix/lib/cmake/tessera/tesseraGlTargets.cmake" ] ||
   ls "$work"/prefix/lib*/cmake/tessera/tesseraGlTargets.cmake >/dev/null 2>&1; then
  cmake -S "$src/examples/engine_aa" -B "$work/build_engine_aa" -G Ninja \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
  cmake --build "$work/build_engine_aa" >/dev/null
  set +e
  out=$("$work/build_engine_aa/engine_aa" --size 64x48 --m 2 2>&1)
  rc=$?
  set -e
  echo "$out"
  if [ $rc -ne 0 ] && ! grep -q "no OpenGL 4.5 device" <<<"$out"; then exit 1; fi
  # examples/engine_ptex the same way (its CTest engine_ptex checks the image), run on the
  # teapot where the shared Ptex samples are.
  cmake -S "$src/examples/engine_ptex" -B "$work/build_engine_ptex" -G Ninja \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
  cmake --build "$work/build_engine_ptex" >/dev/null
  teapot="$src/../shared/data/ptex/teapot"
  if [ -f "$teapot/teapot.ptx" ]; then
    set +e
    out=$("$work/build_engine_ptex/engine_ptex" "$teapot/teapot.obj" "$teapot/teapot.ptx" \
      --size 64x48 --check 2>&1)
    rc=$?
    set -e
    echo "$out"
    if [ $rc -ne 0 ] && ! grep -q "no OpenGL 4.5 device" <<<"$out"; then exit 1; fi
  fi
fi
if ls "$work"/prefix/lib*/cmake/tessera/tesseraVkTargets.cmake >/dev/null 2>&1; then
  cmake -S "$src/examples/engine_aa_vk" -B "$work/build_engine_aa_vk" -G Ninja \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
  cmake --build "$work/build_engine_aa_vk" >/dev/null
  set +e
  out=$("$work/build_engine_aa_vk/engine_aa_vk" --size 64x48 --m 2 2>&1)
  rc=$?
  set -e
  echo "$out"
  if [ $rc -ne 0 ] && ! grep -q "no Vulkan device" <<<"$out"; then exit 1; fi
fi
