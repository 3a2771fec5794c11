#!/usr/bin/env python3
"""CLI tests of `tessera seams`: a tiny run of the experiment and its error paths.

Usage: seams_cli_test.py PATH/TO/tessera [SHARED_DATA_DIR]
Checks the outputs (JSON, Markdown, CSV, SVG plots, images), that every method and rate was
timed and compared, exit codes (0 ok, 1 bad input, 2 bad usage), one-line errors naming the
file, and that failed runs leave no output folder behind. With the shared Ptex samples, also
runs the teapot with its own .ptx and checks that the triangle/non-quad meshes are refused.
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, finish, missing_part, run_command  # noqa: E402

TESSERA = sys.argv[1]
SHARED = sys.argv[2] if len(sys.argv) > 2 else ""


def run(*args):
    return run_command([TESSERA, "-j", "2", *args], timeout=300)


def expect_error(name, args, code, must_name=None, out_dir=None):
    rc, out, err = run(*args)
    lines = [l for l in err.splitlines() if l.strip()]
    check(name + " exit code", rc == code, f"rc={rc} stderr={err!r}")
    if code == 1:
        check(name + " one line", len(lines) == 1, f"stderr={err!r}")
        if must_name:
            check(name + " names file", must_name in err, f"stderr={err!r}")
    if out_dir:
        check(name + " leaves no output", not os.path.exists(out_dir), out_dir)


tmp = tempfile.mkdtemp(prefix="tessera-seams-")
try:
    out = os.path.join(tmp, "tiny")
    rc, so, se = run("seams", "--frames", "2", "--msaa", "1,4", "--width", "48", "--height", "40",
                     "--reference-factor", "4", "--quiet", "-o", out)
    check("tiny run rc", rc == 0, se)
    for f in ("seams.json", "seams.md", "cdf.csv", "fig5_left.svg", "fig5_right.svg",
              "fig5_left.png", "fig5_right.png",
              "images/reference.png", "images/discard_1x.png", "images/traverse_4x.png",
              "images/zoom_clamp_1x.png", "images/zoom_reference.png"):
        check("output " + f, os.path.isfile(os.path.join(out, f)))
    if os.path.isfile(os.path.join(out, "seams.json")):
        j = json.load(open(os.path.join(out, "seams.json")))
        for rate in ("1x", "4x"):
            for m in ("clamp", "discard", "traverse", "traverse_corners", "shading_only"):
                t = j["timing"][rate][m]
                check(f"timed {m} {rate}", len(t["frame_ms"]) == 2 and t["median_ms"] > 0)
            for m in ("clamp", "discard", "traverse", "traverse_corners"):
                cdf = j["quality"]["vs_reference"][m][rate]["cdf"]
                check(f"cdf {m} {rate}", abs(cdf[0] - 1.0) < 1e-12 and
                      all(a >= b for a, b in zip(cdf, cdf[1:])), str(cdf[:3]))
            check("counted " + rate, j["quality"]["counted_pixels"][rate] > 0)
        pairs = j["scene"]["edge_pairings"]
        check("all 16 pairings", len(pairs) == 16 and min(pairs) > 0, str(pairs))
    md = open(os.path.join(out, "seams.md")).read() if os.path.isfile(os.path.join(out, "seams.md")) else ""
    check("markdown says which pixels", "geometry only" in md)
    svg = open(os.path.join(out, "fig5_left.svg")).read() if os.path.isfile(os.path.join(out, "fig5_left.svg")) else ""
    check("svg plot", svg.startswith("<svg") and "polyline" in svg)
    png_path = os.path.join(out, "fig5_right.png")
    png = open(png_path, "rb").read() if os.path.isfile(png_path) else b""
    check("png plot", png.startswith(b"\x89PNG") and len(png) > 2000, f"{len(png)} bytes")

    # Error paths.
    expect_error("missing mesh", ["seams", "--scene", os.path.join(tmp, "nope.obj"), "--quiet",
                                  "-o", os.path.join(tmp, "e1")], 1, "nope.obj",
                 os.path.join(tmp, "e1"))
    tri = os.path.join(tmp, "tri.obj")
    with open(tri, "w") as f:
        f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    # A triangle mesh is split into quads (3 per triangle) and renders.
    rc, so, se = run("seams", "--scene", tri, "--frames", "1", "--msaa", "1", "--width", "32",
                     "--height", "24", "--reference-factor", "2", "--quiet", "-o",
                     os.path.join(tmp, "tri"))
    check("triangle obj split rc", rc == 0, se)
    if rc == 0:
        j = json.load(open(os.path.join(tmp, "tri", "seams.json")))
        check("triangle obj split faces", j["scene"]["faces"] == 3, str(j["scene"]["faces"]))
    quad = os.path.join(tmp, "quad.obj")
    with open(quad, "w") as f:
        f.write("v 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\nf 1 2 3 4\n")
    bad_ptx = os.path.join(tmp, "bad.ptx")
    with open(bad_ptx, "wb") as f:
        f.write(b"Ptex\x01\x00\x00\x00garbage")
    expect_error("corrupt ptx", ["seams", "--scene", quad, "--ptex", bad_ptx, "--quiet", "-o",
                                 os.path.join(tmp, "e3")], 1, "bad.ptx", os.path.join(tmp, "e3"))
    expect_error("ptex without mesh", ["seams", "--ptex", bad_ptx, "-o", os.path.join(tmp, "e4")],
                 2)
    expect_error("bad msaa", ["seams", "--msaa", "1,3", "-o", os.path.join(tmp, "e5")], 2)
    expect_error("no output", ["seams"], 2)

    # A procedural quad mesh renders too.
    rc, so, se = run("seams", "--scene", quad, "--frames", "1", "--msaa", "1", "--width", "32",
                     "--height", "24", "--reference-factor", "2", "--quiet", "-o",
                     os.path.join(tmp, "quad"))
    check("quad obj rc", rc == 0, se)

    if SHARED and os.path.isdir(os.path.join(SHARED, "ptex")):
        p = os.path.join(SHARED, "ptex")
        rc, so, se = run("seams", "--scene", os.path.join(p, "teapot", "teapot.obj"), "--ptex",
                         os.path.join(p, "teapot", "teapot.ptx"), "--frames", "1", "--msaa", "1",
                         "--width", "48", "--height", "40", "--reference-factor", "2", "--quiet",
                         "-o", os.path.join(tmp, "teapot"))
        check("teapot with ptx rc", rc == 0, se)
        # Non-quad faces split into Ptex subfaces match the file's faces.
        for name in ("nonquad", "pentagon"):
            rc, so, se = run("seams", "--scene", os.path.join(p, name, name + ".obj"), "--ptex",
                             os.path.join(p, name, name + ".ptx"), "--frames", "1", "--msaa", "1",
                             "--width", "32", "--height", "24", "--reference-factor", "2",
                             "--quiet", "-o", os.path.join(tmp, name))
            check(name + " with subfaces rc", rc == 0, se)
        # A triangle-mesh Ptex file is refused with a clear message.
        expect_error("triangle ptex", ["seams", "--scene", os.path.join(p, "triangle", "triangle.obj"),
                                       "--ptex", os.path.join(p, "triangle", "triangle.ptx"),
                                       "--quiet", "-o", os.path.join(tmp, "e6")], 1, "triangle-mesh",
                     os.path.join(tmp, "e6"))
        expect_error("face count mismatch", ["seams", "--scene", quad, "--ptex",
                                             os.path.join(p, "teapot", "teapot.ptx"), "--quiet",
                                             "-o", os.path.join(tmp, "e7")], 1, "teapot.ptx",
                     os.path.join(tmp, "e7"))
    else:
        missing_part("shared", "shared Ptex samples absent: no teapot checks")
finally:
    shutil.rmtree(tmp, ignore_errors=True)

sys.exit(finish())
