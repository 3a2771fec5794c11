#!/usr/bin/env python3
"""Compares tessera's software rasteriser with Mesa llvmpipe (a real OpenGL driver on the CPU).

Usage: raster_vs_llvmpipe.py PATH/TO/tessera PATH/TO/tessera-glpeer
Same scene, camera, sample count and unlit trilinear shading on both sides:
  * built-in scene, flat white shading (coverage only): at 1x and 4x MSAA, at most 0.5 % of
    the pixels may differ (4x: OpenGL's sample pattern is the D3D one mirrored vertically,
    because GL rows go up), and PSNR >= 40 dB;
  * the glTF dungeon (../shared/data, skipped when absent), textured: PSNR >= 35 dB at 1x and
    4x MSAA, from two orbit positions.
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check as harness_check, finish, required  # noqa: E402

TESSERA, GLPEER = sys.argv[1], sys.argv[2]
HERE = os.path.dirname(os.path.abspath(__file__))
shared = os.environ.get("TESSERA_SHARED", os.path.join(HERE, "..", "..", "..", "shared"))
dungeon = os.path.join(shared, "data", "scenes", "dungeon", "level-dungeon.gltf")


def check(name, cond, detail):
    """cli_harness.check, printing the passed checks too (their detail is the measurement)."""
    harness_check(name, cond, detail, show_passed=True)


def render_both(tmp, scene, extra, tag):
    a = os.path.join(tmp, tag + "-tessera.png")
    b = os.path.join(tmp, tag + "-llvmpipe.png")
    subprocess.run([TESSERA, "render", scene, "-o", a, *extra], check=True, capture_output=True)
    subprocess.run([GLPEER, scene, "-o", b, *extra], check=True, capture_output=True)
    p = subprocess.run([TESSERA, "compare", a, b, "--json"], check=True, capture_output=True,
                       text=True)
    j = json.loads(p.stdout)
    ia = np.asarray(Image.open(a).convert("RGB"), dtype=np.int32)
    ib = np.asarray(Image.open(b).convert("RGB"), dtype=np.int32)
    differing = float((np.abs(ia - ib).max(axis=2) > 0).mean())
    psnr = j["psnr_rgb"] if j["psnr_rgb"] is not None else float("inf")
    return psnr, differing


tmp = tempfile.mkdtemp(prefix="tessera-peer-")
try:
    for msaa in (1, 4):
        psnr, diff = render_both(tmp, "builtin",
                                 ["--shading", "flat", "--msaa", str(msaa), "--orbit", "1/8"],
                                 f"flat{msaa}")
        check(f"builtin flat {msaa}x coverage", diff <= 0.005 and psnr >= 40,
              f"{diff * 100:.3f} % pixels differ, PSNR {psnr:.2f} dB")
    if os.path.isfile(dungeon):
        for msaa in (1, 4):
            for orbit in ("1/8", "5/8"):
                psnr, diff = render_both(tmp, dungeon, ["--msaa", str(msaa), "--orbit", orbit],
                                         f"dungeon{msaa}-{orbit.replace('/', '_')}")
                check(f"dungeon {msaa}x orbit {orbit}", psnr >= 35,
                      f"PSNR {psnr:.2f} dB ({diff * 100:.2f} % pixels differ)")
    else:
        if required("shared"):
            check("dungeon present", False, f"{dungeon} absent (TESSERA_TEST_REQUIRE asks for shared)")
        else:
            print(f"note: {dungeon} absent; dungeon comparison skipped")
finally:
    shutil.rmtree(tmp, ignore_errors=True)

sys.exit(finish())
