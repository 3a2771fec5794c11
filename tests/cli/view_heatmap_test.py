#!/usr/bin/env python3
"""`tessera view`'s heatmaps made by the page (view_heatmap.mjs in headless Chromium, on a
`tessera view --html` export of two texture + reference pairs): the scale control changes what
is drawn and the colour bar follows it; at scale 64 the page's pixels are `tessera compare
--heatmap`'s; a single bad texel still shows at fit (max filter); the keyboard shortcuts; the
readout's texels are the PNGs'. Screenshots go to OUT (the build tree).

Usage: view_heatmap_test.py PATH/TO/tessera PUPPETEER_DIR OUT [CHROMIUM]
"""
import base64
import json
import math
import os
import random
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, finish, write_png  # noqa: E402
from view_harness import ViewTest  # noqa: E402

T = ViewTest("view_heatmap")
TESSERA, PUPPETEER, OUT, CHROMIUM, SCRIPT = T.tessera, T.puppeteer, T.out, T.chromium, T.script

# Every check needs the browser: without it the test is skipped (exit 77), or fails under
# TESSERA_TEST_REQUIRE.
T.require_browser()

from PIL import Image  # noqa: E402  (python3-pil, after the skips)


def run(*args, cwd=None):
    p = subprocess.run([TESSERA, *args], capture_output=True, text=True, timeout=600, cwd=cwd)
    check("tessera " + " ".join(args[:1]) + " runs", p.returncode == 0, p.stderr)
    return p


def pattern(x, y):
    return ((x * 37 + y * 11) % 256, (x * 4) % 256, (255 - y * 2) % 256)


def make_pair(tmp, name, n, spoil):
    """name.pvr (a fast encode of a pattern) and ref/name.png: its decoded texels with
    spoil(pixels, width, height) applied. Returns (decoded PNG, reference PNG)."""
    src = write_png(os.path.join(tmp, name + "_src.png"), n, n, pattern, False)
    run("compress", src, "-o", os.path.join(tmp, name + ".pvr"), "--quality", "fast", "-q")
    dec = os.path.join(tmp, name + "_dec.png")
    run("decompress", os.path.join(tmp, name + ".pvr"), "-o", dec, "-q")
    im = Image.open(dec).convert("RGB")
    spoil(im.load(), n, n)
    ref = os.path.join(tmp, "ref", name + ".png")
    im.save(ref)
    return dec, ref


def low_noise(px, w, h):
    """Error 1 on about half the texels, 4 on a few (under 1%): max 4, 99th percentile 1."""
    rng = random.Random(7)
    for y in range(h):
        for x in range(w):
            r, g, b = px[x, y]
            d = 4 if rng.random() < 0.004 else rng.choice((0, 1))
            px[x, y] = (r - d if r >= d else r + d, g, b)


def one_texel(px, w, h):
    r, g, b = px[513, 301]  # odd coordinates: a nearest-sampled half-size view skips them
    px[513, 301] = ((r + 128) % 256, g, b)


def normal(x, y):
    """A bumpy tangent-space normal map (RGB = 127.5 (n + 1))."""
    nx, ny = math.sin(x / 5.0) * 0.6, math.cos(y / 7.0) * 0.6
    nz = math.sqrt(max(0.0, 1 - nx * nx - ny * ny))
    return tuple(int(round(127.5 * (c + 1))) for c in (nx, ny, nz))


def field_stats(ref, dec):
    """(max, 99th percentile) of the max abs channel difference, as the page computes them."""
    a, b = Image.open(ref).convert("RGB").tobytes(), Image.open(dec).convert("RGB").tobytes()
    diffs = sorted(max(abs(a[i + c] - b[i + c]) for c in range(3)) for i in range(0, len(a), 3))
    n = len(diffs)
    p99 = next(v for i, v in enumerate(diffs) if i + 1 >= 0.99 * n)
    return diffs[-1], p99


def same_as_compare(name, step, ref, dec, tmp):
    heat = os.path.join(tmp, name + "_heat.png")
    run("compare", ref, dec, "--heatmap", heat, "-q")
    if not step:
        check(name + ": zoom-1 pixels read", False)
        return
    x0, y0, w, h = step["texels"]
    got = base64.b64decode(step["rgba"])
    want = Image.open(heat).convert("RGBA").crop((x0, y0, x0 + w, y0 + h)).tobytes()
    bad = sum(1 for i in range(0, len(want), 4) if got[i:i + 3] != want[i:i + 3])
    check(f"{name}: scale 64 at zoom 1 = tessera compare --heatmap ({w}x{h} texels)",
          len(got) == len(want) and w * h > 1000 and bad == 0, f"{bad} pixels differ")


def texel(png, x, y):
    return list(Image.open(png).convert("RGBA").getpixel((x, y)))


def main():
    shutil.rmtree(OUT, ignore_errors=True)
    os.makedirs(OUT, exist_ok=True)
    tmp = tempfile.mkdtemp(prefix="tessera-heat-")
    try:
        os.makedirs(os.path.join(tmp, "ref"))
        low_dec, low_ref = make_pair(tmp, "low", 256, low_noise)
        one_dec, one_ref = make_pair(tmp, "one", 1024, one_texel)
        page = os.path.join(tmp, "view.html")
        run("view", "--html", "-o", page, "--quality", "fast", "low.pvr", "one.pvr", "ref/low.png",
            "ref/one.png", cwd=tmp)
        write_png(os.path.join(tmp, "alpha.png"), 128, 128,
                  lambda x, y: (*pattern(x, y), (x * 2 + y) % 256), True)
        write_png(os.path.join(tmp, "nrm.png"), 128, 128, normal, False)
        page2 = os.path.join(tmp, "maps.html")
        run("view", "--html", "-o", page2, "--quality", "fast", "alpha.png", cwd=tmp)
        page3 = os.path.join(tmp, "nrm.html")
        run("view", "--html", "-o", page3, "--quality", "fast", "--normal-map", "nrm.png", cwd=tmp)
        p = subprocess.run(["node", SCRIPT, PUPPETEER, CHROMIUM, "file://" + page, OUT,
                            "file://" + page2, "file://" + page3],
                           capture_output=True, text=True, timeout=900)
        try:
            r = json.loads(p.stdout.strip().splitlines()[-1])
        except (ValueError, IndexError):
            check("browser script output", False, (p.stdout + p.stderr)[-1500:])
            return
        check("no page errors", r["errors"] == [], r["errors"])
        s = r["steps"]
        mx, p99 = field_stats(low_ref, low_dec)
        check("low: max 4 and 99th percentile 1 (the test's own premise)", (mx, p99) == (4, 1),
              (mx, p99))
        l64, lmax, lp99 = s.get("low64", {}), s.get("lowmax", {}), s.get("lowp99", {})
        check("scale 64: the colour bar says 64 levels", l64.get("bar", {}).get("scale") == "64"
              and l64.get("bar", {}).get("unit") == "levels" and not l64["bar"].get("hidden"), l64)
        check("auto max: the colour bar follows (the image's max)",
              lmax.get("bar", {}).get("scale") == str(mx), lmax.get("bar"))
        check("auto max: brighter than scale 64 on a low error",
              lmax.get("mean", 0) > 3 * l64.get("mean", 1e9) and lmax.get("bright", 0) > 0
              and l64.get("bright") == 0, (l64, lmax))
        check("auto 99th percentile: saturates more than auto max",
              lp99.get("bright", 0) > lmax.get("bright", 0) and "99th percentile" in lp99.get("caption", ""),
              (lp99, lmax))
        check("captions name the scale", "scale 64 levels" in l64.get("caption", "")
              and f"scale {mx} levels" in lmax.get("caption", ""), (l64, lmax))
        same_as_compare("low", s.get("low_zoom1"), low_ref, low_dec, tmp)
        same_as_compare("one", s.get("one_zoom1"), one_ref, one_dec, tmp)
        for name, kind in (("alpha", "heatmap"), ("alpha", "heatmap_premultiplied"),
                           ("nrm", "angle_map"), ("nrm", "heatmap")):
            m = s.get(f"{name}_{kind}", {})
            check(f"{name}: the page's {kind} at the server's scale = the server's PNG",
                  m.get("n", 0) == 128 * 128 and m.get("differ") == 0, m)
        am = s.get("angle_max", {})
        check("angular map: the colour bar in degrees, auto max below 10",
              am.get("unit") == "angle" and 0 < float(am.get("scale", 0)) < 45
              and "°" in am.get("caption", ""), am)
        f = s.get("one_fit", {})
        check("one bad texel at fit (zoom < 1): a bright pixel is drawn (max filter)",
              f.get("fit_zoom", 1) < 1 and 1 <= f.get("bright", 0) <= 4, f)
        k = s.get("keys", {})
        want = [("two", "right", "heatmap"), ("four", "right", "heatmap"), ("one", "right", "result"),
                ("h", "right", "heatmap"), ("h2", "right", "result"), ("plus", "zoom", 1),
                ("plus2", "zoom", 2), ("minus", "zoom", 1), ("c", "channel", "r"),
                ("w", "mode", "wipe"), ("w2", "mode", "side"), ("help", "help", True),
                ("help2", "help", False), ("in_field", "mode", "side")]
        for step, field, value in want:
            check(f"key {step}: {field} {value}", k.get(step, {}).get(field) == value, k.get(step))
        for name in ("readout_result", "readout_heatmap"):
            ro = s.get(name, {})
            ok = "x" in ro
            x, y = (int(ro["x"]), int(ro["y"])) if ok else (0, 0)
            check(f"{name}: decoded texel as tessera decompress", ok and
                  [int(v) for v in ro["decoded"].split(",")] == texel(one_dec, x, y), ro)
            check(f"{name}: original texel as the reference PNG", ok and
                  [int(v) for v in ro["original"].split(",")] == texel(one_ref, x, y), ro)
        for shot in ("heat-low-64.png", "heat-low-max.png", "heat-one-fit.png", "heat-keys-help.png"):
            check("screenshot " + shot, os.path.exists(os.path.join(OUT, shot)))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


main()
sys.exit(finish())
