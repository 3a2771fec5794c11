#!/usr/bin/env python3
"""The bad-command-line table: each wrong command line gives one line on stderr that says what is
wrong (the words below), and exit code 2 for bad usage or 1 for bad input. README's
"Command-line errors" section shows the same table. Then -q and --json where commands print
results: `demo --json` (one object on stdout, human text on stderr), `compare -q` (silence, exit
status only, --heatmap still written) and `info -q` (validation only).

Usage: cli_usage_test.py PATH/TO/tessera
"""
import json
import os
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, finish, run_command  # noqa: E402

TESSERA = sys.argv[1]
tmp = tempfile.mkdtemp(prefix="tessera-usage-")
png = os.path.join(tmp, "in.png")
pvr = os.path.join(tmp, "in.pvr")
missing = os.path.join(tmp, "nonexist.png")

# (command line, exit code, the one line on stderr must contain this)
TABLE = [
    ([], 2, "tessera: no command given"),
    (["bogus"], 2, "tessera: unknown command 'bogus'"),
    (["-V"], 2, "tessera: unknown option '-V'"),
    (["--bogus"], 2, "tessera: unknown option '--bogus'"),
    (["-j"], 2, "tessera: -j: needs a value"),
    (["-j", "abc", "info", pvr], 2, "--threads: 'abc' is not an integer"),
    (["-j", "-3", "info", pvr], 2, "--threads: -3 is out of range"),
    (["render", "--bogus"], 2, "tessera render: unknown option '--bogus'"),
    (["render", "builtin"], 2, "tessera render: --output is required"),
    (["render", "builtin", "-o", "x.png", "--width", "abc"], 2,
     "tessera render: --width: 'abc' is not an integer"),
    (["render", "builtin", "-o", "x.png", "--width", "0"], 2,
     "tessera render: --width: 0 is out of range"),
    (["render", "builtin", "-o", "x.png", "--msaa", "3"], 2,
     "tessera render: --msaa: '3' is not one of 1, 2, 4, 8, 16"),
    (["render", "builtin", "-o", "x.png", "--orbit", "9/4"], 2,
     "tessera render: --orbit: expected FRAME/N with 0 <= FRAME < N, got '9/4'"),
    (["render", "builtin", "-o", "x.png", "--camera", "1,2"], 2,
     "tessera render: --camera: expected 10 numbers"),
    (["render", "builtin", "-o", "x.png", "--camera", "0,0,1,0,0,0,0,1,0,45", "--orbit", "1/2"],
     2, "tessera render: --camera and --orbit cannot be used together"),
    (["render", "builtin", "-o", "x.gif"], 2, "x.gif: cannot write '.gif' images"),
    (["render", "builtin", "--width"], 2, "tessera render: --width: needs a value"),
    (["render", "nonexist.obj", "-o", os.path.join(tmp, "r.png")], 1,
     "nonexist.obj: cannot open: No such file or directory"),
    (["compress"], 2, "tessera compress: missing INPUT"),
    (["compress", png], 2, "tessera compress: --output is required"),
    (["compress", png, "-o", "x.pvr", "--quality", "best"], 2,
     "--quality: 'best' is not one of fast, normal, high"),
    (["compress", png, "-o", "x.pvr", "--format", "pvrtc2"], 2,
     "--format: 'pvrtc2' is not one of pvrtc1-4, pvrtc1-2"),
    (["compress", png, "-o", "x.pvr", "--iterations", "many"], 2,
     "--iterations: 'many' is not an integer"),
    (["compress", png, "-o", "x.dds"], 2, "x.dds: unknown output extension"),
    (["compress", png, "-o", "x.pvr", "--container", "dds"], 2,
     "--container: 'dds' is not one of pvr, ktx"),
    (["compress", png, "png2", "-o", "x.pvr"], 2,
     "-o x.pvr: several inputs (or a folder) need an output folder, not a file name"),
    (["compress", missing, "-o", os.path.join(tmp, "x.pvr")], 1,
     "nonexist.png: cannot open: No such file or directory"),
    (["compress", tmp, "-o", os.path.join(tmp, "x.pvr")], 2, "need an output folder"),
    (["compress", png, "png2", "-o", "-"], 2, "several inputs need a folder for -o, not '-'"),
    (["decompress", pvr, "-o", "x.webp"], 2, "x.webp: cannot write '.webp' images"),
    (["decompress", pvr, "-o", os.path.join(tmp, "d.png"), "--level", "7"], 1,
     "--level 7 is out of range"),
    (["decompress", pvr, "-o", os.path.join(tmp, "d.png"), "--level", "x"], 2,
     "--level: 'x' is not an integer"),
    (["decompress", png, "-o", os.path.join(tmp, "d.png")], 1,
     "not a PVR v3, KTX 1.1 or KTX 2.0 texture"),
    (["info"], 2, "tessera info: missing FILE"),
    (["info", missing], 1, "nonexist.png: cannot open: No such file or directory"),
    (["compare", png], 2, "tessera compare: missing B"),
    (["compare", png, "-"], 2, "only the first image can be '-'"),
    (["compare", png, png, "--heatmap", "h.gif"], 2, "h.gif: cannot write '.gif' images"),
    (["aa"], 2, "tessera aa: --output is required"),
    (["aa", "-o", tmp, "--ssaa", "x"], 2, "tessera aa: --ssaa"),
    (["seams", "-o", tmp, "--bogus"], 2, "tessera seams: unknown option '--bogus'"),
    (["demo", "--size", "abc"], 2, "tessera demo: --size: 'abc' is not an integer"),
]

try:
    # The inputs come from the demo, run with --json: one object on stdout (the report's path and
    # the numbers of its tables), the human line on stderr.
    rc, out, err = run_command([TESSERA, "demo", "-o", os.path.join(tmp, "d"), "--size", "32",
                                "--json"])
    check("demo for inputs", rc == 0, err)
    try:
        summary = json.loads(out)
    except ValueError:
        summary = {}
    check("demo --json: one JSON object on stdout", isinstance(summary, dict) and summary, out)
    check("demo --json: the report's path",
          summary.get("report") == os.path.join(tmp, "d", "report.html"), str(summary)[:300])
    check("demo --json: every section",
          all(k in summary for k in ("images", "pvrtc", "render", "seams", "aa")),
          str(list(summary)))
    images = summary.get("images", [])
    check("demo --json: the images table, one row per image", len(images) == 5 and all(
        0 < r["ssim_gray"] <= 1 and r["psnr_rgb"] > 5 for r in images), str(images)[:300])
    variants = summary.get("pvrtc", {}).get("variants", [])
    check("demo --json: PVRTC variants with PSNR, SSIM and time", len(variants) == 20 and all(
        r["psnr_rgb"] > 15 and r["encode_ms"] >= 0 for r in variants), str(variants)[:300])
    check("demo --json: the human line goes to stderr",
          "wrote " in err and "wrote " not in out, err)
    shutil.copy(os.path.join(tmp, "d", "img", "images-noise.png"), png)
    rc, _, err = run_command([TESSERA, "compress", png, "-o", pvr, "-q"])
    check("compress for inputs", rc == 0, err)
    check("at least 30 bad command lines", len(TABLE) >= 30, str(len(TABLE)))
    for args, code, words in TABLE:
        rc, out, err = run_command([TESSERA, *args], timeout=120)
        lines = [line for line in err.splitlines() if line.strip()]
        name = "tessera " + " ".join(a.replace(tmp, "TMP") for a in args)
        check(name + ": exit code", rc == code, f"rc={rc} (want {code}) stderr={err!r}")
        check(name + ": one line", len(lines) == 1, f"stderr={err!r}")
        check(name + ": says", words in err, f"want {words!r} in {err!r}")
        check(name + ": prefix", err.startswith("tessera"), f"stderr={err!r}")

    # -q and --json on the commands that print results.
    half = os.path.join(tmp, "d", "img", "images-noise-half.png")
    other = os.path.join(tmp, "d", "img", "render-1x.png")  # 512x384: another size
    heat = os.path.join(tmp, "heat.png")
    rc, out, err = run_command([TESSERA, "compare", png, half, "-q", "--heatmap", heat])
    check("compare -q: exit 0, prints nothing", rc == 0 and out == "" and err == "",
          f"rc={rc} out={out!r} err={err!r}")
    check("compare -q: still writes --heatmap", os.path.getsize(heat) > 0)
    rc, out, err = run_command([TESSERA, "compare", png, other, "-q"])
    check("compare -q: a size mismatch is exit 1 with one line",
          rc == 1 and out == "" and len(err.splitlines()) == 1 and "differs" in err, err)
    rc, out, err = run_command([TESSERA, "compare", png, half, "--json"])
    check("compare --json: one object", rc == 0 and "ssim_gray" in json.loads(out) and err == "",
          out + err)
    rc, out, err = run_command([TESSERA, "info", pvr, "-q"])
    check("info -q: a valid texture is exit 0 and silence", rc == 0 and out == "" and err == "",
          f"rc={rc} out={out!r} err={err!r}")
    bad = os.path.join(tmp, "bad.pvr")
    with open(pvr, "rb") as f, open(bad, "wb") as g:
        g.write(f.read()[:60])
    rc, out, err = run_command([TESSERA, "info", bad, "-q"])
    check("info -q: a truncated texture is exit 1 with one line",
          rc == 1 and out == "" and len(err.splitlines()) == 1 and "truncated" in err, err)
    rc, out, err = run_command([TESSERA, "info", png, "-q"])
    check("info -q: an image is not a texture (exit 1)", rc == 1 and out == "", err)
    rc, out, err = run_command([TESSERA, "info", pvr, "--json"])
    check("info --json: one object", rc == 0 and json.loads(out)["width"] == 32, out + err)

    rc, out, err = run_command([TESSERA, "--version"])
    check("--version", rc == 0 and out.startswith("tessera "), out + err)
finally:
    shutil.rmtree(tmp, ignore_errors=True)

sys.exit(finish())
