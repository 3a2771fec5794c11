#!/usr/bin/env python3
"""The bad-command-line table: each wrong command line gives one line on stderr that says what is
wrong (the words below), and exit code 2 for bad usage or 1 for bad input. README's
"Command-line errors" section shows the same table.

Usage: cli_usage_test.py PATH/TO/tessera
"""
import os
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
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
     "not a PVR v3 or KTX 1.1 texture"),
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
    rc, _, err = run_command([TESSERA, "demo", "-o", os.path.join(tmp, "d"), "--size", "32"])
    check("demo for inputs", rc == 0, err)
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
    rc, out, err = run_command([TESSERA, "--version"])
    check("--version", rc == 0 and out.startswith("tessera "), out + err)
finally:
    shutil.rmtree(tmp, ignore_errors=True)

sys.exit(finish())
