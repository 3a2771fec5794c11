#!/usr/bin/env python3
"""The example engine examples/engine_aa_vk (a Vulkan deferred renderer of its own,
anti-aliased with tessera::vk::AdaptiveSupersampler) on this machine's Vulkan (lavapipe
without a GPU), under the validation layer with synchronization validation.

Usage: engine_aa_vk_test.py PATH/TO/engine_aa_vk [headless|window]
  window: the frame loop presenting in its GLFW window, under xvfb-run
Exits 77 (CTest: skipped) when there is no Vulkan 1.3 device or no validation layer, or fails
when TESSERA_TEST_REQUIRE asks for vulkan / vulkan-validation (or is "all").

The checks and bounds it shares with tests/gl/engine_aa_test.py are in
tests/support/engine_aa_checks.py (the frame against the component's own full supersampling,
budget 0 as the negative control, the schedules, -o, the usage errors); here: the backend, no
Vulkan driver. Every run must report zero validation messages (the engine exits 1 on any, and
the message is named).
"""
import os
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, expect_error, finish, skip_or_fail  # noqa: E402
from engine_aa_checks import SIZE, check_engine  # noqa: E402
from engine_vk_harness import reporter, runner  # noqa: E402

ENGINE = sys.argv[1]
MODE = sys.argv[2] if len(sys.argv) > 2 else "headless"


run = runner(ENGINE)
report = reporter([ENGINE, *SIZE], "no Vulkan 1.3 device here")

if MODE == "window":
    # The frame loop presenting view 0 in a GLFW window every frame (lavapipe presents to X11):
    # 3 frames in flight, 2 views, 100 -> 70 -> 85 %, validation-clean, every frame presented.
    if not os.environ.get("DISPLAY"):
        skip_or_fail("xvfb", "no X display for the window (run under xvfb-run, Debian xvfb)")
    win = report("--frame-loop", "6", "--frames-in-flight", "3", "--window")
    check("window: 6 frames presented", win.get("presented") == 6, win)
    check("window: the render scales", [f.get("scale_percent") for f in win.get("frames", [])] ==
          [100, 70, 85, 100, 70, 85], win)
    expect_error(run, "--window without --frame-loop", [*SIZE, "--window"], 1, "--frame-loop")
    sys.exit(finish())


r = check_engine(report, run, SIZE)
check("backend vk", r.get("backend") == "vk", r)

# The frame loop: 3 frames in flight, 2 views, the render scale 100 -> 70 -> 85 % (frame_loop.h),
# every record of a frame before the GPU finished the frames before it.
loop = report(*SIZE, "--frame-loop", "6", "--frames-in-flight", "3", "--views", "2")
frames = loop.get("frames", [])
check("frame loop: 6 frames", len(frames) == 6, loop)
w, h = (int(v) for v in SIZE[1].split("x"))
for i, f in enumerate(frames):
    scale = (100, 70, 85)[i % 3]
    size = [(w * scale + 50) // 100, (h * scale + 50) // 100]
    check(f"frame {i + 1}: numbered, slot {i % 3}, {scale} %",
          (f.get("frame"), f.get("slot"), f.get("scale_percent")) == (i + 1, i % 3, scale), f)
    views = f.get("views", [])
    check(f"frame {i + 1}: 2 views at {size}",
          len(views) == 2 and all(v.get("render_size") == size for v in views), f)
    check(f"frame {i + 1}: extra samples in every view",
          all(v.get("extra_samples", 0) > 0 for v in views), f)
if len(frames) == 6:
    # The same view at the same size gives the same samples, frames in flight or not.
    for i in range(3):
        a, b = frames[i]["views"], frames[i + 3]["views"]
        check(f"frames {i + 1} and {i + 4}: the same samples",
              [v["extra_samples"] for v in a] == [v["extra_samples"] for v in b], (a, b))
    smaller = frames[1]["views"][0]["extra_samples"] < frames[0]["views"][0]["extra_samples"]
    check("70 % shades fewer samples than 100 %", smaller, frames[:2])
expect_error(run, "--frames-in-flight 0", [*SIZE, "--frame-loop", "2", "--frames-in-flight", "0"],
             1, "--frames-in-flight 0")

# Shaders ahead of time: the first run saves tessera's SPIR-V, the second loads it (no GLSL
# compiled): the same frame; a file that is not a shader binary is refused, naming the file.
with tempfile.TemporaryDirectory() as tmp:
    binary = os.path.join(tmp, "tessera_aa.spv")
    saved = report(*SIZE, "--shader-binary", binary)
    check("shader binary written", os.path.getsize(binary) > 1000 if os.path.exists(binary)
          else False)
    loaded = report(*SIZE, "--shader-binary", binary)
    check("shader binary loaded: the same frame",
          (saved.get("extra_samples"), saved.get("psnr_db")) ==
          (loaded.get("extra_samples"), loaded.get("psnr_db")), (saved, loaded))
    check("create_ms reported", loaded.get("create_ms", -1) >= 0, loaded)
    bogus = os.path.join(tmp, "bogus.spv")
    with open(bogus, "wb") as f:
        f.write(b"\x89PNG not tessera")
    expect_error(run, "--shader-binary of another file", [*SIZE, "--shader-binary", bogus], 1,
                 bogus)

env = dict(os.environ, VK_ICD_FILENAMES="/nonexistent/icd.json")
expect_error(lambda *a: run(*a, env=env), "no Vulkan driver", SIZE, 1, "no Vulkan device")
sys.exit(finish())
