#!/usr/bin/env python3
"""CLI tests of the foundation commands: `tessera compare` output and every error path.

Usage: cli_test.py PATH/TO/tessera
Checks exit codes (0 ok, 1 bad input, 2 bad usage), that errors are one line naming the file,
and that failed commands leave no output behind.
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
    return run_command([TESSERA, *args], timeout=120)


def expect_error(name, args, code, must_name=None):
    return harness_expect_error(run, name, args, code, must_name)


tmp = tempfile.mkdtemp(prefix="tessera-cli-")
try:
    # Make inputs with the demo (procedural PNGs).
    rc, out, err = run("demo", "-o", os.path.join(tmp, "demo"), "--size", "64")
    check("demo runs", rc == 0, err)
    img = os.path.join(tmp, "demo", "img")
    a = os.path.join(img, "images-noise.png")
    b = os.path.join(img, "images-noise-half.png")
    rgba = os.path.join(img, "images-foliage.png")
    check("demo report", os.path.isfile(os.path.join(tmp, "demo", "report.html")))

    # Happy paths.
    rc, out, err = run("compare", a, b, "--json")
    check("compare --json rc", rc == 0, err)
    j = json.loads(out)
    for key in ("psnr_rgb", "ssim_gray", "mse", "max_abs"):
        check("json key " + key, key in j, out)
    check("psnr plausible", 20 < j["psnr_rgb"] < 80, out)
    check("ssim plausible", 0.5 < j["ssim_gray"] < 1.0, out)
    rc, out, err = run("compare", a, a, "--json")
    j = json.loads(out)
    check("identical: psnr null", j["psnr_rgb"] is None and j["identical_rgb"], out)
    check("identical: ssim 1", j["ssim_gray"] == 1.0 and j["mse"] == 0 and j["max_abs"] == 0, out)
    rc, out, err = run("compare", rgba, rgba)
    check("text output has alpha line", rc == 0 and "PSNR alpha" in out, out)
    heat = os.path.join(tmp, "heat.png")
    rc, out, err = run("compare", a, b, "--heatmap", heat)
    check("heatmap written", rc == 0 and os.path.isfile(heat), err)

    # Help and usage.
    rc, out, err = run("--help")
    check("--help", rc == 0 and "compare" in out and "demo" in out, out)
    rc, out, err = run("compare", "--help")
    check("compare --help", rc == 0 and "--json" in out, out)
    expect_error("no subcommand", [], 2)
    expect_error("missing operand", ["compare", a], 2)
    expect_error("unknown flag", ["compare", a, b, "--bogus"], 2)
    expect_error("bad -j", ["-j", "-3", "compare", a, b], 2)

    # Bad input.
    missing = os.path.join(tmp, "nope.png")
    expect_error("missing file", ["compare", missing, b], 1, missing)
    with open(a, "rb") as f:
        data = f.read()
    for cut in (0, 8, 30, len(data) // 2, len(data) - 1):
        t = os.path.join(tmp, f"trunc{cut}.png")
        with open(t, "wb") as f:
            f.write(data[:cut])
        expect_error(f"truncated at {cut}", ["compare", a, t], 1, t)
    corrupt = os.path.join(tmp, "corrupt.png")
    with open(corrupt, "wb") as f:
        f.write(data[:60] + bytes(b ^ 0xFF for b in data[60:90]) + data[90:])
    expect_error("corrupt", ["compare", corrupt, a], 1, corrupt)
    wrong = os.path.join(tmp, "wrong.png")
    with open(wrong, "wb") as f:
        f.write(b"GIF89a" + data[6:])
    expect_error("wrong magic", ["compare", wrong, a], 1, wrong)
    small = os.path.join(tmp, "demo32", "img", "images-noise.png")
    run("demo", "-o", os.path.join(tmp, "demo32"), "--size", "32")
    expect_error("size mismatch", ["compare", a, small], 1, small)
    expect_error("directory as input", ["compare", tmp, a], 1, tmp)

    # Unwritable outputs leave nothing behind.
    heat2 = os.path.join(tmp, "no", "such", "dir", "heat.png")
    expect_error("unwritable heatmap", ["compare", a, b, "--heatmap", heat2], 1, heat2)
    blocker = os.path.join(tmp, "blocker")
    open(blocker, "w").close()
    expect_error("demo into a file", ["demo", "-o", os.path.join(blocker, "sub")], 1, "blocker")
    leftovers = [n for n in os.listdir(tmp) if ".tmp" in n]
    check("no temp files left", not leftovers, str(leftovers))
finally:
    shutil.rmtree(tmp, ignore_errors=True)

sys.exit(finish())
