#!/usr/bin/env python3
"""CLI tests of `tessera compress`, `decompress` and `info` (PVRTC1 in PVR v3 / KTX 1.1).

Usage: pvrtc_cli_test.py PATH/TO/tessera [PATH/TO/PVRTexToolCLI]
Happy paths (round trips, --json fields and PSNR thresholds, mip chains, --resize-pot) and every
error path: missing, truncated, corrupt and lying files, non-power-of-two input, out-of-range
--level, unwritable outputs (exit 1, one stderr line naming the file, no output left behind)
and bad flags (exit 2). Input images are generated here (stdlib PNG writer), so the test needs
nothing but the binary; with PVRTexToolCLI it also checks that the oracle decodes our files.
"""
import json
import math
import os
import shutil
import struct
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, finish, missing_part, run_command, write_png  # noqa: E402

TESSERA = sys.argv[1]
PVRTEXTOOL = sys.argv[2] if len(sys.argv) > 2 and os.path.isfile(sys.argv[2]) else None


def run(*args, tool=None):
    return run_command([tool or TESSERA, *args], timeout=300)


def smooth(x, y):
    return (int(128 + 100 * math.sin(x / 9.0)), int(128 + 100 * math.cos(y / 11.0)),
            (x * 2 + y) % 256, 255)


def leafy(x, y):
    r, g, b, _ = smooth(x, y)
    a = 0 if (x // 8 + y // 8) % 3 == 0 else min(255, 64 + 3 * x)
    return (r, g, b, a)


def leftovers(folder, keep):
    """Files in `folder` other than those in `keep` (temporary files of failed writes)."""
    return sorted(set(os.listdir(folder)) - set(keep))


def expect_error(name, args, code, must_name=None, no_output=None, contains=None):
    rc, out, err = run(*args)
    lines = [l for l in err.splitlines() if l.strip()]
    check(name + " exit code", rc == code, f"rc={rc} stderr={err!r}")
    if code == 1:
        check(name + " one line", len(lines) == 1 and lines[0].startswith("tessera: "),
              f"stderr={err!r}")
        if must_name:
            check(name + " names file", must_name in err, f"stderr={err!r}")
    if contains:
        check(name + " says why", contains in err, f"stderr={err!r}")
    if no_output:
        check(name + " leaves no output", not os.path.exists(no_output), no_output)
    return err


tmp = tempfile.mkdtemp(prefix="tessera-pvrtc-cli-")
try:
    rgb = os.path.join(tmp, "rgb.png")
    rgba = os.path.join(tmp, "rgba.png")
    wide = os.path.join(tmp, "wide.png")
    npot = os.path.join(tmp, "npot.png")
    write_png(rgb, 64, 64, smooth, False)
    write_png(rgba, 32, 32, leafy, True)
    write_png(wide, 64, 16, smooth, False)
    write_png(npot, 127, 128, smooth, False)
    inputs = {"rgb.png", "rgba.png", "wide.png", "npot.png"}

    # --- Happy paths -------------------------------------------------------------------------
    psnr = {}
    for q in ("fast", "normal", "high"):
        out_pvr = os.path.join(tmp, f"rgb-{q}.pvr")
        rc, out, err = run("compress", rgb, "-o", out_pvr, "--quality", q, "--json")
        check(f"compress {q} rc", rc == 0, err)
        j = json.loads(out) if rc == 0 else {}
        for key in ("time_ms", "width", "height", "format", "quality", "levels", "bytes",
                    "psnr_rgb", "ssim_gray"):
            check(f"compress {q} json has {key}", key in j, out)
        check(f"compress {q} size", j.get("width") == 64 and j.get("height") == 64, out)
        check(f"compress {q} no alpha key for RGB", "psnr_alpha" not in j, out)
        check(f"compress {q} bytes", j.get("bytes") == os.path.getsize(out_pvr), out)
        check(f"compress {q} 4bpp size", j.get("bytes") == 52 + 15 + 64 * 64 // 2, out)
        psnr[q] = j.get("psnr_rgb") or 0.0
        check(f"compress {q} psnr", psnr[q] > 30.0, f"psnr={psnr[q]}")
        check(f"compress {q} ssim", (j.get("ssim_gray") or 0) > 0.9, out)
    check("normal not worse than fast", psnr["normal"] >= psnr["fast"] - 0.05, str(psnr))
    check("high not worse than normal", psnr["high"] >= psnr["normal"] - 0.05, str(psnr))

    # -j works after the subcommand too (`compress IN -o OUT -j N`, where scripts append it after
    # the other options), with the same bytes as before it and as one thread.
    j_after = os.path.join(tmp, "rgb-j-after.pvr")
    rc, out, err = run("compress", rgb, "-o", j_after, "--quality", "normal", "-j", "2")
    check("compress ... -j 2 rc", rc == 0, err)
    check("compress ... -j 2 same bytes as -j 1 before the subcommand",
          rc == 0 and open(j_after, "rb").read() ==
          open(os.path.join(tmp, "rgb-normal.pvr"), "rb").read())
    expect_error("compress ... -j -1", ["compress", rgb, "-o", j_after + "x", "-j", "-1"], 2)

    # --iterations / --exact-search-rounds replace the preset's schedule: fast plus least-squares
    # sweeps refines the dilation result (not worse than fast alone, since a sweep is kept only
    # when the exact error drops); both are echoed in --json.
    sched_pvr = os.path.join(tmp, "rgb-sched.pvr")
    rc, out, err = run("compress", rgb, "-o", sched_pvr, "--quality", "fast", "--iterations", "2",
                       "--json")
    check("compress fast --iterations 2 rc", rc == 0, err)
    j = json.loads(out) if rc == 0 else {}
    check("--iterations echoed", j.get("iterations") == 2 and j.get("exact_search_rounds") == 0,
          out)
    check("fast + 2 sweeps not worse than fast", (j.get("psnr_rgb") or 0) >= psnr["fast"], out)
    rc, out, err = run("compress", rgb, "-o", sched_pvr, "--quality", "normal",
                       "--exact-search-rounds", "2", "--json")
    check("compress normal --exact-search-rounds 2 rc", rc == 0, err)
    j = json.loads(out) if rc == 0 else {}
    check("--exact-search-rounds echoed", j.get("exact_search_rounds") == 2, out)
    check("normal + 2 search rounds psnr", (j.get("psnr_rgb") or 0) > 30.0, out)

    # decompress agrees with compress --json.
    dec = os.path.join(tmp, "rgb-normal.png")
    rc, out, err = run("decompress", os.path.join(tmp, "rgb-normal.pvr"), "-o", dec)
    check("decompress rc", rc == 0, err)
    rc, out, err = run("compare", rgb, dec, "--json")
    check("compare decoded rc", rc == 0, err)
    if rc == 0:
        check("decompress psnr matches compress --json",
              abs(json.loads(out)["psnr_rgb"] - psnr["normal"]) < 1e-6, out)

    # 2bpp, RGBA, sRGB, mipmaps, KTX; info on both containers.
    ktx = os.path.join(tmp, "rgba.ktx")
    rc, out, err = run("compress", rgba, "-o", ktx, "--format", "pvrtc1-2", "--mipmaps", "--srgb",
                       "--json")
    check("compress rgba ktx rc", rc == 0, err)
    j = json.loads(out) if rc == 0 else {}
    check("compress rgba levels", j.get("levels") == 6, out)
    check("compress rgba alpha psnr", (j.get("psnr_alpha") or 0) > 15.0, out)
    rc, out, err = run("info", ktx, "--json")
    check("info ktx rc", rc == 0, err)
    j = json.loads(out) if rc == 0 else {}
    check("info ktx container", j.get("container") == "KTX 1.1", out)
    check("info ktx format", j.get("format") == "PVRTC1 2bpp RGBA", out)
    check("info ktx srgb", j.get("colour_space") == "sRGB", out)
    check("info ktx levels", [l["width"] for l in j.get("levels", [])] == [32, 16, 8, 4, 2, 1], out)
    check("info ktx level bytes", [l["bytes"] for l in j.get("levels", [])] ==
          [256, 64, 32, 32, 32, 32], out)
    rc, out, err = run("info", os.path.join(tmp, "rgb-fast.pvr"))
    check("info pvr text", rc == 0 and "PVR v3" in out and "PVRTC1 4bpp RGB" in out, out + err)
    last = os.path.join(tmp, "level5.png")
    rc, out, err = run("decompress", ktx, "-o", last, "--level", "5")
    check("decompress last level", rc == 0 and os.path.isfile(last), err)
    rc, out, err = run("-j", "1", "compress", wide, "-o", os.path.join(tmp, "wide.pvr"), "--mipmaps")
    check("compress non-square with mipmaps", rc == 0, err)
    rc, out, err = run("info", os.path.join(tmp, "wide.pvr"), "--json")
    check("non-square levels", rc == 0 and len(json.loads(out)["levels"]) == 7, out + err)

    # --resize-pot.
    rc, out, err = run("compress", npot, "-o", os.path.join(tmp, "npot.pvr"), "--resize-pot",
                       "--json")
    check("resize-pot rc", rc == 0, err)
    j = json.loads(out) if rc == 0 else {}
    check("resize-pot size", j.get("width") == 128 and j.get("height") == 128, out)

    # Identical output for any thread count.
    for n in ("1", "2"):
        run("-j", n, "compress", rgba, "-o", os.path.join(tmp, f"j{n}.pvr"), "--mipmaps")
    with open(os.path.join(tmp, "j1.pvr"), "rb") as f1, open(os.path.join(tmp, "j2.pvr"), "rb") as f2:
        check("thread count does not change output", f1.read() == f2.read())

    # The oracle decodes what we write.
    if PVRTEXTOOL:
        for name in ("rgb-normal.pvr", "wide.pvr"):
            odec = os.path.join(tmp, name + ".oracle.png")
            rc, out, err = run("-i", os.path.join(tmp, name), "-o", os.path.join(tmp, "scratch.pvr"),
                               "-f", "r8g8b8a8", "-d", odec, "-shh", tool=PVRTEXTOOL)
            check(f"PVRTexTool reads {name}", rc == 0, err)
            ours = os.path.join(tmp, name + ".ours.png")
            run("decompress", os.path.join(tmp, name), "-o", ours)
            rc, out, err = run("compare", ours, odec, "--json")
            check(f"PVRTexTool decodes {name} identically",
                  rc == 0 and json.loads(out)["identical_rgb"], out + err)
    else:
        missing_part("pvrtextool", "PVRTexToolCLI not given: no oracle checks")

    # --- Errors: bad input (exit 1), nothing left behind -------------------------------------
    err_dir = os.path.join(tmp, "errors")
    os.makedirs(err_dir)
    out_png = os.path.join(err_dir, "out.png")
    out_pvr = os.path.join(err_dir, "out.pvr")
    missing = os.path.join(tmp, "missing.png")
    expect_error("compress missing input", ["compress", missing, "-o", out_pvr], 1, missing, out_pvr)
    expect_error("decompress missing input", ["decompress", os.path.join(tmp, "none.pvr"), "-o",
                                              out_png], 1, "none.pvr", out_png)
    expect_error("info missing input", ["info", os.path.join(tmp, "none.ktx")], 1, "none.ktx")
    expect_error("compress NPOT", ["compress", npot, "-o", out_pvr], 1, npot, out_pvr,
                 contains="--resize-pot")
    shared_npot = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..",
                               "shared", "data", "images", "ldr-rgb-10.png")
    if os.path.isfile(shared_npot):
        expect_error("compress ldr-rgb-10 (127x128)", ["compress", shared_npot, "-o", out_pvr], 1,
                     "ldr-rgb-10.png", out_pvr, contains="127x128")
    not_image = os.path.join(tmp, "text.png")
    with open(not_image, "w") as f:
        f.write("hello")
    expect_error("compress non-image", ["compress", not_image, "-o", out_pvr], 1, not_image, out_pvr)

    with open(os.path.join(tmp, "rgb-fast.pvr"), "rb") as f:
        good = f.read()
    for cut in (0, 3, 20, 51, 52, 60, 67, 68, 100, len(good) - 1):
        bad = os.path.join(tmp, f"cut{cut}.pvr")
        with open(bad, "wb") as f:
            f.write(good[:cut])
        expect_error(f"decompress truncated at {cut}", ["decompress", bad, "-o", out_png], 1, bad,
                     out_png)
        expect_error(f"info truncated at {cut}", ["info", bad], 1, bad)
    err = expect_error("truncated data says sizes", ["info", os.path.join(tmp, f"cut{len(good) - 1}.pvr")],
                       1, contains="2048 bytes")

    def patched(name, offset, value):
        b = bytearray(good)
        b[offset:offset + 4] = struct.pack("<I", value)
        path = os.path.join(tmp, name)
        with open(path, "wb") as f:
            f.write(b)
        return path

    flipped = os.path.join(tmp, "flipped.pvr")
    with open(flipped, "wb") as f:
        f.write(b"XVR\x03" + good[4:])
    expect_error("wrong magic", ["decompress", flipped, "-o", out_png], 1, flipped, out_png, "magic")
    expect_error("big-endian magic", ["info", patched("be.pvr", 0, 0x50565203)], 1, "be.pvr",
                 contains="big-endian")
    expect_error("header claims larger size", ["decompress", patched("big.pvr", 28, 128), "-o",
                                               out_png], 1, "big.pvr", out_png, "truncated")
    expect_error("header claims smaller size", ["decompress", patched("small.pvr", 24, 32), "-o",
                                                out_png], 1, "small.pvr", out_png)
    expect_error("header claims NPOT", ["decompress", patched("npot.pvr", 28, 48), "-o", out_png],
                 1, "npot.pvr", out_png, "power-of-two")
    expect_error("header claims absurd size", ["decompress", patched("huge.pvr", 28, 0xFFFFFFFF),
                                               "-o", out_png], 1, "huge.pvr", out_png)
    expect_error("header claims too many mips", ["info", patched("mips.pvr", 44, 40)], 1, "mips.pvr",
                 contains="mip count")
    expect_error("non-PVRTC pixel format", ["info", patched("etc.pvr", 8, 6)], 1, "etc.pvr",
                 contains="ETC1")
    expect_error("cube map", ["info", patched("cube.pvr", 40, 6)], 1, "cube.pvr",
                 contains="cube")
    with open(ktx, "rb") as f:
        kgood = f.read()
    kcut = os.path.join(tmp, "cut.ktx")
    with open(kcut, "wb") as f:
        f.write(kgood[:-9])
    expect_error("truncated ktx", ["decompress", kcut, "-o", out_png], 1, kcut, out_png)

    expect_error("--level out of range", ["decompress", ktx, "-o", out_png, "--level", "6"], 1, ktx,
                 out_png, "out of range")
    expect_error("--level negative", ["decompress", ktx, "-o", out_png, "--level", "-1"], 1, ktx,
                 out_png)

    # Unwritable outputs: a folder in the way, a missing parent folder.
    folder_pvr = os.path.join(err_dir, "folder.pvr")
    os.makedirs(folder_pvr)
    # An existing folder as the output takes the texture inside it, named after the input.
    rc, _, err = run("compress", rgb, "-o", folder_pvr, "-q")
    check("output is a directory: written inside it",
          rc == 0 and os.path.isfile(os.path.join(folder_pvr,
                                                  os.path.splitext(os.path.basename(rgb))[0]
                                                  + ".pvr")), err)
    folder_png = os.path.join(err_dir, "folder.png")
    os.makedirs(folder_png)
    rc, _, err = run("decompress", os.path.join(tmp, "rgb-fast.pvr"), "-o", folder_png, "-q")
    check("decompress output is a directory: written inside it",
          rc == 0 and os.listdir(folder_png) == ["rgb-fast_level0.png"], err)
    no_parent = os.path.join(err_dir, "nope", "x.pvr")
    expect_error("output folder missing", ["compress", rgb, "-o", no_parent], 1, no_parent, no_parent)
    check("no temporary files left", leftovers(err_dir, {"folder.pvr", "folder.png"}) == [],
          str(leftovers(err_dir, {"folder.pvr", "folder.png"})))

    # --- Usage errors (exit 2) ---------------------------------------------------------------
    expect_error("bad --format", ["compress", rgb, "-o", out_pvr, "--format", "pvrtc2"], 2,
                 no_output=out_pvr)
    expect_error("bad --quality", ["compress", rgb, "-o", out_pvr, "--quality", "best"], 2,
                 no_output=out_pvr)
    expect_error("missing -o", ["compress", rgb], 2)
    expect_error("--iterations below -1", ["compress", rgb, "-o", out_pvr, "--iterations", "-2"],
                 2, no_output=out_pvr)
    expect_error("negative --exact-search-rounds",
                 ["compress", rgb, "-o", out_pvr, "--exact-search-rounds", "-1"], 2,
                 no_output=out_pvr)
    expect_error("unknown extension", ["compress", rgb, "-o", os.path.join(err_dir, "x.dds")], 2,
                 no_output=os.path.join(err_dir, "x.dds"))
    expect_error("non-numeric --level", ["decompress", ktx, "-o", out_png, "--level", "abc"], 2,
                 no_output=out_png)
    expect_error("info without file", ["info"], 2)
    check("inputs untouched", inputs <= set(os.listdir(tmp)))
finally:
    shutil.rmtree(tmp, ignore_errors=True)

sys.exit(finish())
