#!/usr/bin/env python3
"""CLI tests of the asset features of `tessera compress` / `decompress` / `info`: cube maps and
arrays (single output and batch folders), decompressing one face/layer/level or every image
into a folder, --flip-y, --premultiply, --alpha-bleed, --normal-map, --mip-levels/--mip-filter,
KTX 2.0 with --zstd, and their bad inputs (one line naming the problem, exit 1 or 2, nothing
written). With PVRTexToolCLI it also checks that the oracle decodes our cube maps face by face.

Usage: pvrtc_assets_cli_test.py PATH/TO/tessera [PATH/TO/PVRTexToolCLI]
Needs /usr/bin/python3 with numpy and PIL (Debian python3-numpy, python3-pil).
"""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, expect_error, finish, missing_part, run_command  # noqa: E402

TESSERA = sys.argv[1]
PVRTEXTOOL = sys.argv[2] if len(sys.argv) > 2 and os.path.isfile(sys.argv[2]) else None
FACES = ["px", "nx", "py", "ny", "pz", "nz"]


def run(*args):
    return run_command([TESSERA, *args], timeout=300)


def ok(name, *args):
    rc, out, err = run(*args)
    check(name, rc == 0, f"rc={rc} stderr={err!r}")
    return out, err


def info(path):
    rc, out, err = run("info", path, "--json")
    check("info " + path, rc == 0, err)
    return json.loads(out) if rc == 0 else {}


def save(path, array):
    Image.fromarray(np.ascontiguousarray(array)).save(path)
    return path


def load(path):
    return np.asarray(Image.open(path).convert("RGBA")).astype(np.int64)


def pattern(size, seed, alpha=False):
    rng = np.random.default_rng(seed)
    y, x = np.mgrid[0:size, 0:size]
    rgb = np.stack([(x * 7 + seed * 40) % 256, (y * 5 + 30 * seed) % 256,
                    ((x + y) * 3) % 256], axis=-1)
    rgb = np.clip(rgb + rng.integers(-8, 9, rgb.shape), 0, 255)
    if not alpha:
        return rgb.astype(np.uint8)
    a = np.where((x // 8 + y // 8) % 3 == 0, 0, 255)
    return np.concatenate([rgb, a[..., None]], axis=-1).astype(np.uint8)


def main():
    tmp = tempfile.mkdtemp(prefix="tessera-assets-")
    faces = [save(os.path.join(tmp, f"sky_{n}.png"), pattern(32, i)) for i, n in enumerate(FACES)]

    # --- cube maps: single output in every container, info, decompress -----------------------
    cube = os.path.join(tmp, "sky.pvr")
    out, _ = ok("cube compress", "compress", *faces, "--cube", "--mipmaps", "--quality", "fast",
                "-o", cube, "--json")
    j = json.loads(out) if out else {}
    check("cube json", j.get("faces") == 6 and j.get("shape") == "cube map"
          and j.get("levels") == 6 and len(j.get("input", [])) == 6, out)
    i = info(cube)
    check("cube info", i.get("faces") == 6 and i.get("layers") == 1 and not i.get("array")
          and len(i.get("levels", [])) == 6 and i["levels"][0]["bytes"] == 6 * 512, i)
    cube_ktx = os.path.join(tmp, "sky.ktx")
    ok("cube ktx", "compress", *faces, "--cube", "--quality", "fast", "-o", cube_ktx, "-q")
    check("cube ktx info", info(cube_ktx).get("faces") == 6)
    # One face decoded equals the same face compressed alone.
    alone = os.path.join(tmp, "alone.pvr")
    ok("face alone", "compress", faces[3], "--mipmaps", "--quality", "fast", "-o", alone, "-q")
    ok("decompress face", "decompress", cube, "--face", "3", "--level", "1", "-o",
       os.path.join(tmp, "f3.png"), "-q")
    ok("decompress alone", "decompress", alone, "--level", "1", "-o", os.path.join(tmp, "a3.png"),
       "-q")
    check("face 3 is encoded as alone",
          np.array_equal(load(os.path.join(tmp, "f3.png")), load(os.path.join(tmp, "a3.png"))))
    expect_error(run, "cube without --face", ["decompress", cube, "-o", os.path.join(tmp, "x.png")],
                 2, "--face N")
    check("nothing written", not os.path.exists(os.path.join(tmp, "x.png")))
    expect_error(run, "face out of range",
                 ["decompress", cube, "--face", "6", "-o", os.path.join(tmp, "x.png")], 1,
                 "--face 6 is out of range")
    folder = os.path.join(tmp, "all") + "/"
    out, _ = ok("decompress folder", "decompress", cube, "-o", folder, "--json")
    names = sorted(os.listdir(folder))
    check("folder names", len(names) == 36 and "sky_face0-px_level0.png" in names
          and "sky_face5-nz_level5.png" in names, names[:8])

    # --- arrays --------------------------------------------------------------------------------
    layers = [save(os.path.join(tmp, f"layer{k}.png"), pattern(16, 10 + k, alpha=k == 1))
              for k in range(3)]
    arr = os.path.join(tmp, "layers.ktx")
    out, _ = ok("array compress", "compress", *layers, "--array", "--format", "pvrtc1-2",
                "--quality", "fast", "-o", arr, "--json")
    j = json.loads(out) if out else {}
    check("array json", j.get("layers") == 3 and j.get("has_alpha") is True, out)
    check("array info", info(arr).get("array") is True and info(arr).get("layers") == 3)
    expect_error(run, "array without --layer", ["decompress", arr, "-o", os.path.join(tmp, "x.png")],
                 2, "--layer N")
    ok("array layer 1", "decompress", arr, "--layer", "1", "-o", os.path.join(tmp, "l1.png"), "-q")

    # --- bad sets: one line, nothing written ---------------------------------------------------
    bad_out = os.path.join(tmp, "bad.pvr")
    expect_error(run, "seven faces", ["compress", *faces, faces[0], "--cube", "-o", bad_out], 1,
                 "exactly 6 faces")
    small = save(os.path.join(tmp, "small.png"), pattern(16, 3))
    expect_error(run, "face size", ["compress", *faces[:5], small, "--cube", "-o", bad_out], 1,
                 "small.png: 16x16, but")
    wide = save(os.path.join(tmp, "wide.png"), np.zeros((16, 32, 3), np.uint8))
    expect_error(run, "non-square face", ["compress", *([wide] * 6), "--cube", "-o", bad_out], 1,
                 "wide.png: 32x16 is not square")
    expect_error(run, "normal map srgb", ["compress", faces[0], "--normal-map", "--srgb", "-o",
                                          bad_out], 2, "--normal-map and --srgb")
    expect_error(run, "bleed premultiply", ["compress", faces[0], "--alpha-bleed", "--premultiply",
                                            "-o", bad_out], 2, "--alpha-bleed and --premultiply")
    expect_error(run, "weighted premultiply", ["compress", faces[0], "--alpha-weighted",
                                               "--premultiply", "-o", bad_out], 2,
                 "--alpha-weighted and --premultiply")
    expect_error(run, "weighted 2 bpp", ["compress", faces[0], "--alpha-weighted", "--format",
                                         "pvrtc1-2", "-o", bad_out], 2,
                 "--alpha-weighted and --format pvrtc1-2")
    expect_error(run, "mip filter without mips", ["compress", faces[0], "--mip-filter", "kaiser",
                                                  "-o", bad_out], 2, "--mip-filter kaiser needs")
    expect_error(run, "zstd to pvr", ["compress", faces[0], "--zstd", "5", "-o", bad_out], 2,
                 "--zstd needs a KTX 2.0 output")
    check("bad sets write nothing", not os.path.exists(bad_out))

    # --- preparation flags ----------------------------------------------------------------------
    sprite = save(os.path.join(tmp, "sprite.png"), pattern(32, 5, alpha=True))
    _, err = ok("premultiply rgb warns", "compress", faces[0], "--premultiply", "--quality", "fast",
                "-o", os.path.join(tmp, "pm_rgb.pvr"))
    check("premultiply warning", "has no alpha channel" in err, err)
    pm = os.path.join(tmp, "pm.pvr")
    ok("premultiply", "compress", sprite, "--premultiply", "--quality", "fast", "-o", pm, "-q")
    check("premultiplied flag", info(pm).get("premultiplied") is True)
    check("rgb not flagged", info(os.path.join(tmp, "pm_rgb.pvr")).get("premultiplied") is False)
    _, err = ok("premultiply to ktx warns", "compress", sprite, "--premultiply", "--quality", "fast",
                "-o", os.path.join(tmp, "pm.ktx"))
    check("ktx 1.1 premultiplied warning", "KTX 1.1 has no premultiplied-alpha flag" in err, err)
    ok("premultiply to ktx2", "compress", sprite, "--premultiply", "--quality", "fast", "-o",
       os.path.join(tmp, "pm.ktx2"), "-q")
    check("ktx2 premultiplied flag", info(os.path.join(tmp, "pm.ktx2")).get("premultiplied") is True)
    # The premultiplication itself: the texture of --premultiply holds the blocks of the image
    # premultiplied here (round(c * a / 255)), only the header's flag differs.
    rgba = pattern(32, 5, alpha=True).astype(np.int64)
    pre = rgba.copy()
    pre[..., :3] = (rgba[..., :3] * rgba[..., 3:4] + 127) // 255
    save(os.path.join(tmp, "pre.png"), pre.astype(np.uint8))
    ok("numpy premultiplied", "compress", os.path.join(tmp, "pre.png"), "--quality", "fast", "-o",
       os.path.join(tmp, "pre.pvr"), "-q")
    a_bytes = open(pm, "rb").read()
    b_bytes = open(os.path.join(tmp, "pre.pvr"), "rb").read()
    check("premultiplied blocks", a_bytes[52:] == b_bytes[52:] and a_bytes[4] == 2
          and b_bytes[4] == 0, (a_bytes[:8], b_bytes[:8]))
    # --alpha-weighted: RGB input has nothing to weigh by (same bytes); on a sprite with
    # transparent texels it changes the texture, and it is recorded in the sidecar.
    for src, same in ((faces[0], True), (sprite, False)):
        plain, weighted = os.path.join(tmp, "aw0.pvr"), os.path.join(tmp, "aw1.pvr")
        ok("plain " + src, "compress", src, "-o", plain, "-q")
        ok("alpha-weighted " + src, "compress", src, "--alpha-weighted", "-o", weighted, "-q")
        check("alpha-weighted " + ("same" if same else "differs") + " " + src,
              (open(plain, "rb").read() == open(weighted, "rb").read()) == same)
    ok("alpha-weighted sidecar", "compress", sprite, "--alpha-weighted", "--skip-up-to-date",
       "-o", os.path.join(tmp, "aw2.pvr"), "-q")
    with open(os.path.join(tmp, "aw2.pvr.json")) as f:
        recorded = json.load(f)["options"]
    check("sidecar records alpha_weighted", recorded.get("alpha_weighted") is True, recorded)
    # Flip: the flipped encode of a flipped image is the plain encode flipped back... texel for
    # texel only up to PVRTC's wrap-around, so compare against compressing the flipped PNG.
    flipped = save(os.path.join(tmp, "flipped.png"), pattern(32, 2)[::-1])
    ok("flip-y", "compress", faces[2], "--flip-y", "--quality", "fast", "-o",
       os.path.join(tmp, "fy.pvr"), "-q")
    ok("flipped png", "compress", flipped, "--quality", "fast", "-o", os.path.join(tmp, "fp.pvr"),
       "-q")
    check("flip-y equals the flipped image",
          open(os.path.join(tmp, "fy.pvr"), "rb").read() == open(os.path.join(tmp, "fp.pvr"),
                                                                  "rb").read())
    out, _ = ok("mip levels", "compress", faces[0], "--mip-levels", "3", "--mip-filter", "kaiser",
                "--quality", "fast", "-o", os.path.join(tmp, "m3.pvr"), "--json")
    check("three levels", json.loads(out).get("levels") == 3 if out else False, out)

    # --- batch: each folder one cube map --------------------------------------------------------
    tree = os.path.join(tmp, "tree")
    for name, order in (("castle", FACES), ("lake", ["right", "left", "top", "bottom", "front",
                                                     "back"])):
        os.makedirs(os.path.join(tree, name))
        for k, n in enumerate(order):
            save(os.path.join(tree, name, f"{name}_{n}.png"), pattern(16, 20 + k))
    outdir = os.path.join(tmp, "cubes") + "/"
    rc, out, err = run("compress", os.path.join(tree, "castle"), os.path.join(tree, "lake"), "--cube",
                       "--quality", "fast", "-o", outdir, "--json")
    check("batch cubes", rc == 0 and os.path.isfile(os.path.join(outdir, "castle.pvr"))
          and os.path.isfile(os.path.join(outdir, "lake.pvr")), err)
    # The lake's faces are named right/left/...: ordered by face, not by name, so face 2 (+Y) is
    # 'top' (pattern seed 22).
    ok("lake +Y", "decompress", os.path.join(outdir, "lake.pvr"), "--face", "2", "-o",
       os.path.join(tmp, "lake2.png"), "-q")
    ok("top alone", "compress", os.path.join(tree, "lake", "lake_top.png"), "--quality", "fast",
       "-o", os.path.join(tmp, "top.pvr"), "-q")
    ok("top decode", "decompress", os.path.join(tmp, "top.pvr"), "-o",
       os.path.join(tmp, "top.png"), "-q")
    check("faces ordered by name token",
          np.array_equal(load(os.path.join(tmp, "lake2.png")), load(os.path.join(tmp, "top.png"))))
    expect_error(run, "batch cube of files", ["compress", faces[0], faces[1], "--cube", "-o",
                                              outdir], 2, "a batch takes folders")

    # --- the oracle decodes our cube map face by face -------------------------------------------
    if PVRTEXTOOL:
        stem = os.path.join(tmp, "oracle")
        p = subprocess.run([PVRTEXTOOL, "-i", cube, "-o", stem + "-scratch.pvr", "-f", "r8g8b8a8",
                            "-d", stem + ".png", "-shh"], capture_output=True)
        check("oracle reads our cube map", p.returncode == 0, p.stderr)
        for k in range(6):
            ok(f"face {k}", "decompress", cube, "--face", str(k), "-o",
               os.path.join(tmp, f"ours{k}.png"), "-q")
            theirs = load(f"{stem}.Face_{k}.png")[..., :3]
            ours = load(os.path.join(tmp, f"ours{k}.png"))[..., :3]
            check(f"oracle face {k}", np.array_equal(theirs, ours))
    else:
        missing_part("pvrtextool", "PVRTexToolCLI not given: no oracle checks of the cube map")
    return finish()


if __name__ == "__main__":
    sys.exit(main())
