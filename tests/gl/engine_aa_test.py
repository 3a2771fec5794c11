#!/usr/bin/env python3
"""The example engine examples/engine_aa (a deferred renderer of its own anti-aliased with
tessera::gl::AdaptiveSupersampler) on this machine's OpenGL (Mesa llvmpipe without a GPU).

Usage: engine_aa_test.py PATH/TO/engine_aa headless|window
  headless: engine_aa --headless (its own surfaceless EGL context)
  window:   its GLFW window (GLX), run under xvfb-run: the frame in the window's back buffer must
            be adaptive.png (window_max_diff <= 1)
Exits 77 (CTest: skipped) when no OpenGL 4.5 context can be made (or, for window, no Xvfb
display or no GLFW in the build), or fails when TESSERA_TEST_REQUIRE asks for gl / xvfb / glfw.

The checks and bounds it shares with tests/vk/engine_aa_vk_test.py are in
tests/support/engine_aa_checks.py (the frame against the component's own full supersampling,
budget 0 as the negative control, the schedules, -o, the usage errors); here: the engine's own
context, the window's back buffer, no GL device.
"""
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, expect_error, finish, run_command, skip_or_fail  # noqa: E402
from engine_aa_checks import SIZE as AA_SIZE, check_engine  # noqa: E402

ENGINE = sys.argv[1]
MODE = sys.argv[2] if len(sys.argv) > 2 else "headless"
if MODE == "window" and not os.environ.get("DISPLAY"):
    skip_or_fail("xvfb", "no X display for the window (run under xvfb-run, Debian xvfb)")
SIZE = AA_SIZE + (["--headless"] if MODE == "headless" else [])


def run(*args, env=None):
    p = subprocess.run([ENGINE, *args], capture_output=True, text=True, timeout=600, env=env)
    return p.returncode, p.stdout, p.stderr


def report(*args):
    rc, out, err = run_command([ENGINE, *SIZE, "--json", *args], timeout=600)
    if rc != 0 and "built without GLFW" in err:
        skip_or_fail("glfw", f"engine_aa has no window: {err.strip()}")
    if rc != 0 and "no OpenGL 4.5 device" in err:
        skip_or_fail("gl", f"no OpenGL 4.5 context here: {err.strip()}")
    check(f"{args} exit 0", rc == 0, err)
    try:
        return json.loads(out)
    except json.JSONDecodeError:
        check(f"{args} JSON", False, out)
        return {}


r = check_engine(report, run, SIZE)
check(f"{MODE}: the engine's own context", r.get("context") == ("egl" if MODE == "headless"
                                                                else "glfw"), r)
if MODE == "window":
    check("window: the back buffer shows adaptive.png", 0 <= r.get("window_max_diff", -1) <= 1, r)

# Without a GL device: no EGL vendor library (headless), no X display (window): one line, exit 1.
# Dynamic resolution: 100 -> 70 -> 85 % on one component; the same size gives the same samples.
loop = report("--frame-loop", "4")
frames = loop.get("frames", [])
w, h = (int(v) for v in AA_SIZE[1].split("x"))
check("frame loop: 4 frames", len(frames) == 4, loop)
for i, f in enumerate(frames):
    scale = (100, 70, 85)[i % 3]
    size = [(w * scale + 50) // 100, (h * scale + 50) // 100]
    check(f"frame {i + 1}: {scale} % = {size}",
          f.get("scale_percent") == scale and f.get("render_size") == size, f)
if len(frames) == 4:
    check("frames 1 and 4 (100 %): the same samples",
          frames[0]["extra_samples"] == frames[3]["extra_samples"] > 0, frames)
    check("70 % shades fewer samples", frames[1]["extra_samples"] < frames[0]["extra_samples"],
          frames)

env = dict(os.environ, __EGL_VENDOR_LIBRARY_FILENAMES="/nonexistent.json", DISPLAY=":4097")
expect_error(lambda *a: run(*a, env=env), "no GL device", SIZE, 1, "no OpenGL 4.5 device")
sys.exit(finish())
