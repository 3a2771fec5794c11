#!/usr/bin/env bash
# Installs the build tree into a scratch prefix and builds examples/consumer against it with
# find_package(tessera), then runs it. Where tessera::gl was installed, also builds, with
# find_package(tessera COMPONENTS gl) and outside the repository's build:
#  * tests/install/engine_context (engine_context_check): AdaptiveSupersampler (create, dispatch,
#    dispatch_reference) and FaceTextureSet (upload, bind, the program's own draw with
#    tessera_seams_sample_discard) on its own EGL context (with eglGetProcAddress and with no
#    loader), beside a live gl::Context, and on a GLFW window context under Xvfb; every image
#    hash must equal the gl::Context run's (bit for bit on llvmpipe), the engine's debug
#    callback and GL state must survive, calls without a context must fail with one line;
#  * examples/engine_aa and examples/engine_ptex, run headless (and in a window under Xvfb).
# The installed share/tessera/glsl is moved away first: nothing may read it (the GLSL is
# embedded in the library). No GL device (or no Xvfb / GLFW) skips those runs with a note, or
# fails when TESSERA_TEST_REQUIRE asks for gl (or all).
# The exported targets carry no build-only target (tessera_warnings, tessera_sanitizers); the Vulkan
# ones no GLSL compiler (shaderc, glslang, SPIRV-Tools live in the module tessera-vk-glsl.so, which
# exports two C functions), and engine_aa_vk's compile and link lines name none.
# Where tessera::vk was installed, first examples/engine_aa_vk and examples/engine_ptex_vk with
# find_package(tessera COMPONENTS vk), run at a small size with the installed GLSL folder moved away (no Vulkan device
# is not an error here: the build is what is checked, the CTest engine_aa_vk checks the image).
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
# The package exports no build-only target (warnings, sanitizers) to its consumers.
if grep -l "tessera_warnings\|tessera_sanitizers" "$work"/prefix/lib*/cmake/tessera/*.cmake; then
  echo "install test: the package exports tessera_warnings / tessera_sanitizers" >&2
  exit 1
fi
if ls "$work"/prefix/lib*/cmake/tessera/tesseraVkTargets.cmake >/dev/null 2>&1; then
  # tessera::vk brings no GLSL compiler onto an engine's link line (its own glslang of any
  # version links beside it): shaderc is inside the module tessera-vk-glsl.so, all local.
  if grep -il "shaderc\|glslang\|SPIRV" "$work"/prefix/lib*/cmake/tessera/tesseraVk*.cmake; then
    echo "install test: tesseraVkTargets names shaderc / glslang / SPIRV-Tools" >&2
    exit 1
  fi
  vk_module=$(ls "$work"/prefix/lib*/tessera/tessera-vk-glsl.so)
  if nm -D --defined-only "$vk_module" | grep -v " tessera_vk_glsl_\(compile\|free\)$" |
    grep " [TDBW] "; then
    echo "install test: $vk_module exports more than its two C functions" >&2
    exit 1
  fi
  cmake -S "$src/examples/engine_aa_vk" -B "$work/build_engine_aa_vk" -G Ninja \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
  cmake --build "$work/build_engine_aa_vk" >/dev/null
  if ninja -C "$work/build_engine_aa_vk" -t commands engine_aa_vk |
    grep -i "shaderc\|glslang\|SPIRV-Tools"; then
    echo "install test: engine_aa_vk's compile or link line names a GLSL compiler" >&2
    exit 1
  fi
  vk_glsl=$(ls -d "$work"/prefix/share/tessera/glsl)
  mv "$vk_glsl" "$work/glsl.vk.moved"  # engine_aa_vk must not need it
  set +e
  # The installed compiler module, named as an engine that ships it elsewhere would.
  out=$(env -u TESSERA_GLSL_DIR TESSERA_VK_GLSL="$vk_module" \
    "$work/build_engine_aa_vk/engine_aa_vk" --size 64x48 --m 2 2>&1)
  rc=$?
  set -e
  mv "$work/glsl.vk.moved" "$vk_glsl"
  echo "$out"
  if [ $rc -ne 0 ] && ! grep -q "no Vulkan device" <<<"$out"; then exit 1; fi
  # examples/engine_ptex_vk the same way, on the teapot when ../shared/data is there.
  cmake -S "$src/examples/engine_ptex_vk" -B "$work/build_engine_ptex_vk" -G Ninja \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
  cmake --build "$work/build_engine_ptex_vk" >/dev/null
  vk_teapot="$src/../shared/data/ptex/teapot"
  if [ -f "$vk_teapot/teapot.ptx" ]; then
    mv "$vk_glsl" "$work/glsl.vk.moved"  # engine_ptex_vk must not need it either
    set +e
    out=$(env -u TESSERA_GLSL_DIR "$work/build_engine_ptex_vk/engine_ptex_vk" \
      "$vk_teapot/teapot.obj" "$vk_teapot/teapot.ptx" --size 64x48 2>&1)
    rc=$?
    set -e
    mv "$work/glsl.vk.moved" "$vk_glsl"
    echo "$out"
    if [ $rc -ne 0 ] && ! grep -q "no Vulkan device" <<<"$out"; then exit 1; fi
  fi
fi
if ! ls "$work"/prefix/lib*/cmake/tessera/tesseraGlTargets.cmake >/dev/null 2>&1; then
  echo "install test: tessera::gl not installed (no EGL/GL development files): consumer only"
  exit 0
fi

required() {  # TESSERA_TEST_REQUIRE names $1, or is "all"
  [[ ",${TESSERA_TEST_REQUIRE:-}," == *",all,"* || ",${TESSERA_TEST_REQUIRE:-}," == *",$1,"* ]]
}
missing() {  # $1 what, $2 message: fail when required, else a note
  if required "$1"; then
    echo "FAIL: $2 (TESSERA_TEST_REQUIRE asks for $1)"
    exit 1
  fi
  echo "note: $2"
}
build() {  # $1 source folder, $2 build folder
  cmake -S "$1" -B "$2" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$work/prefix" \
    >/dev/null
  cmake --build "$2" >/dev/null
}
build "$src/tests/install/engine_context" "$work/build_engine_context"
build "$src/examples/engine_aa" "$work/build_engine_aa"
build "$src/examples/engine_ptex" "$work/build_engine_ptex"
glsl=$(ls -d "$work"/prefix/share/tessera/glsl)
mv "$glsl" "$work/glsl.moved"  # the programs below must not need it
unset TESSERA_GLSL_DIR

check="$work/build_engine_context/engine_context_check"
xvfb=()
if command -v xvfb-run >/dev/null; then xvfb=(xvfb-run -a -s "-screen 0 1280x1024x24"); fi
set +e
ref=$("$check" --context tessera 2>&1)
rc=$?
set -e
if [ $rc -eq 3 ]; then
  missing gl "no OpenGL 4.5 context here: $ref"
  exit 0
fi
[ $rc -eq 0 ] || { echo "FAIL: engine_context_check --context tessera: $ref"; exit 1; }
runs=("$ref")
for args in "--context egl" "--context egl --loader none" "--context both"; do
  # shellcheck disable=SC2086
  runs+=("$("$check" $args)")
done
if [ ${#xvfb[@]} -eq 0 ]; then
  missing xvfb "no xvfb-run: the GLFW window context is not tried"
else
  set +e
  out=$("${xvfb[@]}" "$check" --context glfw 2>&1)
  rc=$?
  set -e
  if [ $rc -eq 3 ]; then
    missing glfw "no GLFW window context: $out"
  elif [ $rc -ne 0 ]; then
    echo "FAIL: engine_context_check --context glfw: $out"
    exit 1
  else
    runs+=("$out")
  fi
fi
control=$("$check" --context egl --shift)
/usr/bin/env python3 - "$control" "${runs[@]}" <<'PY'
import json
import sys

control, ref, *others = (json.loads(a) for a in sys.argv[1:])
keys = ("adaptive", "reference", "faces")
want = ref["images"]
failures = []
if any("-flat" in want[k] for k in keys):
    failures.append(f"gl::Context images are one colour: {want}")
for r in others:
    images = r["images"] if isinstance(r["images"], list) else [r["images"]]
    for i in images:
        if any(i[k] != want[k] for k in keys):
            failures.append(f"{r['context']}/{r['loader']}: {i} != gl::Context {want}")
        if i["state_error"]:
            failures.append(f"{r['context']}/{r['loader']}: {i['state_error']}")
    if r["context"] in ("egl", "glfw"):
        for p in r["no_context"].split("|"):
            if "no OpenGL context is current on this thread" not in p:
                failures.append(f"{r['context']}: without a context: {p!r}")
if any(control["images"][k] == want[k] for k in keys):
    failures.append(f"the --shift control gives the same hash: {control['images']}")
for f in failures:
    print("FAIL:", f)
print(f"install test: {len(others)} engine-context runs against gl::Context {want}:",
      "same images" if not failures else f"{len(failures)} failures")
sys.exit(1 if failures else 0)
PY

# The example engines, headless and in their windows (their CTests check the images).
engine_run() {  # runs "$@", fails unless exit 0
  set +e
  out=$("$@" 2>&1)
  rc=$?
  set -e
  echo "$out"
  [ $rc -eq 0 ] || { echo "FAIL: $*"; exit 1; }
}
engine_run "$work/build_engine_aa/engine_aa" --headless --size 64x48 --m 2
[ ${#xvfb[@]} -eq 0 ] || engine_run "${xvfb[@]}" "$work/build_engine_aa/engine_aa" --size 64x48 --m 2
teapot="$src/../shared/data/ptex/teapot"
if [ -f "$teapot/teapot.ptx" ]; then
  engine_run "$work/build_engine_ptex/engine_ptex" "$teapot/teapot.obj" "$teapot/teapot.ptx" \
    --size 64x48 --check --headless
  [ ${#xvfb[@]} -eq 0 ] || engine_run "${xvfb[@]}" "$work/build_engine_ptex/engine_ptex" \
    "$teapot/teapot.obj" "$teapot/teapot.ptx" --size 64x48 --check
else
  missing shared "no Ptex teapot at $teapot: engine_ptex is built, not run"
fi
