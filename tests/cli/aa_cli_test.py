#!/usr/bin/env python3
"""CLI tests of `tessera aa` (adaptive supersampling experiment): outputs and error paths.

Usage: aa_cli_test.py PATH/TO/tessera
Exit codes: 0 ok, 1 bad input (missing scene, unwritable output), 2 bad usage (--ssaa list).
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, finish, run_command  # noqa: E402
from cli_harness import expect_error as harness_expect_error  # noqa: E402

TESSERA = sys.argv[1]


def run(*args):
    return run_command([TESSERA, *args], timeout=300)


def expect_error(name, args, code, must_name=None):
    return harness_expect_error(run, name, args, code, must_name)


tmp = tempfile.mkdtemp(prefix="tessera-aa-")
try:
    out = os.path.join(tmp, "aa")
    rc, so, se = run("-j", "2", "aa", "--width", "64", "--height", "48", "--ssaa", "2,3",
                     "--frames", "2", "--heavy", "--heavy-terms", "4", "-o", out)
    check("aa runs", rc == 0, se)
    j = json.load(open(os.path.join(out, "aa.json")))
    check("json rates", [r["m"] for r in j["rates"]] == [2, 3], j.get("rates"))
    for r in j["rates"]:
        m = r["m"]
        for key in ("default", "fxaa", "reference", "adaptive", "edge_per_sample"):
            check(f"{m}: {key} timed", r[key]["shade_ms"] > 0 and "shade_ms_heavy" in r[key], r[key])
        ad = r["adaptive"]
        check(f"{m}: samples pct", 100.0 / (m * m) <= ad["samples_pct"] <= 100.0, ad)
        check(f"{m}: adaptive beats 1x",
              ad["quality"]["mse_8bit"] < r["default"]["quality"]["mse_8bit"], r)
        check(f"{m}: reference 100%", r["reference"]["samples_pct"] == 100.0, r)
        # The engine baseline (Lauritzen 2010) on the CPU backend: adaptive's fields.
        eps = r["edge_per_sample"]
        for field in ("frame_ms", "shade_ms", "shade_ms_frames", "samples_pct", "quality"):
            check(f"{m}: edge_per_sample {field}", field in eps, eps)
        check(f"{m}: edge_per_sample samples", 100.0 / (m * m) < eps["samples_pct"] < 100.0, eps)
        check(f"{m}: edge_per_sample beats 1x",
              eps["quality"]["mse_8bit"] < r["default"]["quality"]["mse_8bit"], eps)
        for name in eps["images"].values():
            check(f"{m}: {name} written", os.path.isfile(os.path.join(out, name)), name)
        check(f"{m}: no GL keys on the CPU", "gl" not in r and "gl_vs_cpu" not in r
              and "passes" not in ad, sorted(r))
        for name in r["images"].values():
            check(f"{m}: {name} written", os.path.isfile(os.path.join(out, name)), name)
        for ab in ("ablation_geometry", "ablation_shading"):
            check(f"{m}: {ab}", ab in r and r[ab]["samples_pct"] <= ad["samples_pct"] + 1e-9, r.get(ab))
    md = open(os.path.join(out, "aa.md")).read()
    check("markdown table", "| 2×2 | Adaptive |" in md and "| 1×1 | FXAA |" in md, md[:400])
    check("markdown edge_per_sample row", "| 3×3 | Edge per sample (Lauritzen 2010) |" in md,
          md[:1600])
    check("no backend key on the CPU", "backend" not in j and "gpu_renderer" not in j, sorted(j))
    check("no probe left", not os.path.exists(os.path.join(out, ".tessera-aa-probe")))

    # Usage errors.
    for bad in ("2,x", "0", "9", "", "2,,3", "-1"):
        expect_error(f"--ssaa {bad!r}", ["aa", "--ssaa", bad, "--width", "8", "--height", "8",
                                         "-o", os.path.join(tmp, "bad")], 2, "--ssaa")
    expect_error("bad fxaa preset", ["aa", "--fxaa-preset", "30", "-o", os.path.join(tmp, "bad")], 2)
    expect_error("missing -o", ["aa"], 2)
    # Bad input.
    missing = os.path.join(tmp, "nope.gltf")
    expect_error("missing scene", ["aa", "--scene", missing, "--width", "8", "--height", "8",
                                   "-o", os.path.join(tmp, "m")], 1, missing)
    blocker = os.path.join(tmp, "file")
    open(blocker, "w").write("x")
    expect_error("unwritable -o", ["aa", "--width", "8", "--height", "8", "-o",
                                   os.path.join(blocker, "sub")], 1, blocker)
finally:
    shutil.rmtree(tmp, ignore_errors=True)

sys.exit(finish())
