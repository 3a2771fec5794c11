#!/usr/bin/env python3
"""tessera view's images are exact and its job progress is honest.

The page reads originals from PNG blobs with its own decoder (view_png.js) and decodes results
from their .pvr blobs (view_pvrtc.js); here, in headless Chromium, every texel it reads is
checked against the input PNG (original) and `tessera decompress` of the same `tessera compress`
(decoded): for a translucent input whose alpha takes every value 0..255 (a canvas would
premultiply those), an opaque one (stored as RGB), 2 bpp, a .pvr opened as it is, a cube map,
a --resize-pot input, a 128x32 one (4 and 2 bpp) and a --normal-map one, in the static export
(--html) and from the server, with mip chains. Without a browser (chromium,
node, puppeteer-core) the browser parts are skipped and the rest runs. From the server, over
HTTP: the heatmap (made when first asked for) is `tessera compare --heatmap`'s, texel for texel;
a job's fraction never goes back, stays below 1 until the job is done and is 1 then.

Usage: view_texels_test.py TESSERA [PUPPETEER_DIR] [CHROMIUM]
"""
import base64
import http.client
import io
import json
import os
import select
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, finish, missing_part, write_png  # noqa: E402

TESSERA = os.path.abspath(sys.argv[1])
PUPPETEER = sys.argv[2] if len(sys.argv) > 2 else ""
CHROMIUM = sys.argv[3] if len(sys.argv) > 3 else shutil.which("chromium")
SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "view_texels.mjs")


def browser_missing():
    if not CHROMIUM or not os.path.exists(CHROMIUM):
        return "chromium", "chromium not found (scripts/setup.sh installs it)"
    if not shutil.which("node"):
        return "puppeteer", "node not found (scripts/setup.sh installs nodejs)"
    if not PUPPETEER or not os.path.isfile(os.path.join(PUPPETEER, "node_modules",
                                                        "puppeteer-core", "package.json")):
        return "puppeteer", f"puppeteer-core not found in '{PUPPETEER}'"
    return None


MISSING = browser_missing()
if MISSING:
    missing_part(MISSING[0], MISSING[1] + ": the browser parts are skipped")

from PIL import Image  # noqa: E402  (python3-pil)


def translucent(x, y):
    """Every alpha 0..255 (x + 64 y, wrapped), colour under alpha 0 included."""
    return ((x * 37 + y * 11) % 256, (x * 4 + y) % 256, (255 - y * 4) % 256, (x + 64 * y) % 256)


def opaque(x, y):
    return ((x * 5 + y * 3) % 256, (x * y) % 256, (x * 4 - y * 2) % 256)


def run(*args, cwd=None):
    p = subprocess.run([TESSERA, *args], capture_output=True, text=True, timeout=600, cwd=cwd)
    return p.returncode, p.stdout, p.stderr


def rgba_bytes(path):
    return Image.open(path).convert("RGBA").tobytes()


COMPRESSED = {}


def expected_decoded(tmp, compress_args, level, face=None):
    """RGBA bytes of `tessera decompress --level LEVEL [--face FACE]` of `tessera compress
    ARGS`."""
    key = tuple(compress_args)
    if key not in COMPRESSED:
        COMPRESSED[key] = os.path.join(tmp, f"e{len(COMPRESSED)}.pvr")
        run("compress", *compress_args, "-o", COMPRESSED[key], "-q")
    png = os.path.join(tmp, "e.png")
    face_args = [] if face is None else ["--face", str(face)]
    run("decompress", COMPRESSED[key], "--level", str(level), *face_args, "-o", png, "-q")
    return rgba_bytes(png)


def browse(url):
    if MISSING:
        return None
    p = subprocess.run(["node", SCRIPT, PUPPETEER, CHROMIUM, url], capture_output=True, text=True,
                       timeout=900, env={**os.environ, "PUPPETEER_SKIP_DOWNLOAD": "1"})
    try:
        r = json.loads(p.stdout.strip().splitlines()[-1])
    except (ValueError, IndexError):
        check("browser script output", False, (p.stdout + p.stderr)[-1500:])
        return None
    check("no page errors", r["errors"] == [], r["errors"])
    return r["results"]


def check_texels(name, results, tmp, compress_args, levels, src=None, faces=1):
    """Every image of the one result is decompress's of `tessera compress COMPRESS_ARGS`
    (decoded, in the page from the result's .pvr) and, with `src`, level 0's original is the
    input's."""
    check(f"{name}: one result", results is not None and len(results) == 1,
          None if results is None else len(results))
    if not results or len(results) != 1:
        return
    images = results[0]["images"]
    check(f"{name}: {levels} level(s) x {faces} face(s)", len(images) == levels * faces,
          len(images))
    for im in images:
        lv, f = im["level"], im["face"]
        check(f"{name}: level {lv} face {f} decoded in the page from the .pvr",
              im["key"].startswith("pvrtc:"), im["key"])
        dec = base64.b64decode(im["decoded"])
        check(f"{name}: level {lv} face {f} decoded texels as tessera decompress",
              dec == expected_decoded(tmp, compress_args, lv, f if faces > 1 else None),
              f"{len(dec)} bytes, {im['width']}x{im['height']}")
    if src:
        orig = base64.b64decode(images[0]["original"])
        check(f"{name}: level 0 original texels as the input PNG", orig == rgba_bytes(src),
              f"{len(orig)} bytes")


def check_static(tmp, name, view_args, compress_args, levels, src=None, faces=1):
    """`tessera view VIEW_ARGS --html`: its page's texels (check_texels)."""
    html = os.path.join(tmp, name.replace(" ", "_") + ".html")
    rc, _, err = run("view", *view_args, "--html", "-o", html, "-q")
    check(f"static {name}: written", rc == 0, err)
    if rc == 0:
        results = browse("file://" + html)
        if results is not None:
            check_texels(f"static {name}", results, tmp, compress_args, levels, src, faces)


def request(port, path, body=None):
    c = http.client.HTTPConnection("127.0.0.1", port, timeout=60)
    c.request("POST" if body else "GET", path, body=body,
              headers={"Content-Type": "application/json"} if body else {})
    r = c.getresponse()
    data = r.read()
    c.close()
    return r.status, data


def check_server(tmp, src):
    p = subprocess.Popen([TESSERA, "view", src, "--no-open", "--mip-levels", "3"], cwd=tmp,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        ready, _, _ = select.select([p.stdout], [], [], 120)
        url = p.stdout.readline().strip() if ready else ""
        check("server prints its URL", url.startswith("http://127.0.0.1:"), url)
        if not url.startswith("http://127.0.0.1:"):
            return
        port, token = int(url.split(":")[2].split("/")[0]), url.split("token=")[1]
        results = browse(url)
        if results is not None:
            check_texels("server", results, tmp, [src, "--mip-levels", "3"], 3, src)
        # Progress: a high-quality encode polled until done.
        body = json.dumps({"input": 0, "settings": {"quality": "high", "mip_levels": 2}})
        status, data = request(port, "/api/encode?token=" + token, body)
        check("progress: encode accepted", status == 200, data[:200])
        if status != 200:
            return
        job = json.loads(data)
        seen = [(job["state"], job["fraction"])]
        for _ in range(60000):  # bounded by the encode's end (at most 10 minutes of polls)
            if job["state"] in ("done", "error"):
                break
            select.select([], [], [], 0.01)
            job = json.loads(request(port, f"/api/job?token={token}&id={job['id']}")[1])
            seen.append((job["state"], job["fraction"]))
        fr = [f for _, f in seen]
        check("progress: done", job["state"] == "done", job.get("error"))
        check("progress: never goes back", fr == sorted(fr), fr)
        check("progress: below 1 until done", all(f < 1 for s, f in seen if s != "done"), seen)
        check("progress: 1 when done", seen[-1] == ("done", 1.0), seen[-3:])
        # The heatmap, made when asked for: tessera compare --heatmap's.
        im = job["result"]["images"][0]
        status, png = request(port, f"/blob/{im['heatmap']}?token={token}")
        check("heatmap: served", status == 200 and png[:4] == b"\x89PNG", status)
        pvr, dec, heat = (os.path.join(tmp, n) for n in ("h.pvr", "h.png", "heat.png"))
        run("compress", src, "-o", pvr, "-q", "--quality", "high", "--mip-levels", "2")
        run("decompress", pvr, "-o", dec, "-q")
        run("compare", src, dec, "--heatmap", heat)
        if status == 200:
            check("heatmap: as tessera compare --heatmap",
                  Image.open(io.BytesIO(png)).convert("RGBA").tobytes() == rgba_bytes(heat))
    finally:
        p.terminate()
        p.wait(timeout=60)


def main():
    tmp = tempfile.mkdtemp(prefix="tessera-view-texels-")
    try:
        for name, pixel, alpha in (("translucent", translucent, True), ("opaque", opaque, False)):
            src = write_png(os.path.join(tmp, name + ".png"), 64, 64, pixel, alpha)
            fast = ["--quality", "fast"]
            check_static(tmp, name, [src, *fast], [src, *fast], 1, src)
        src = os.path.join(tmp, "translucent.png")
        two = ["--format", "pvrtc1-2", "--quality", "fast", "--mip-levels", "3"]
        check_static(tmp, "2 bpp", [src, *two], [src, *two], 3, src)
        # A .pvr opened as it is (2 bpp, translucent): decoded in the page too.
        pvr = os.path.join(tmp, "opened.pvr")
        run("compress", src, "-o", pvr, "-q", *two)
        check_static(tmp, "opened .pvr", [pvr], [src, *two], 3)
        faces = [write_png(os.path.join(tmp, f"face{f}.png"), 32, 32,
                           lambda x, y, f=f: ((x * 8 + f * 40) % 256, (y * 8) % 256, f * 50, 255),
                           False) for f in range(6)]
        cube = ["--quality", "fast", "--mip-levels", "2"]
        check_static(tmp, "cube", ["--cube", *faces, *cube], ["--cube", *faces, *cube], 2,
                     faces=6)
        npot = write_png(os.path.join(tmp, "npot.png"), 48, 40, translucent, True)
        pot = ["--resize-pot", "--quality", "fast"]
        check_static(tmp, "resize-pot", [npot, *pot], [npot, *pot], 1)
        wide = write_png(os.path.join(tmp, "wide.png"), 128, 32, translucent, True)
        mips = ["--quality", "fast", "--mip-levels", "4"]
        check_static(tmp, "128x32", [wide, *mips], [wide, *mips], 4, wide)
        check_static(tmp, "128x32 2 bpp", [wide, "--format", "pvrtc1-2", *mips],
                     [wide, "--format", "pvrtc1-2", *mips], 4, wide)
        normal = write_png(os.path.join(tmp, "normal.png"), 64, 64, opaque, False)
        nm = ["--normal-map", "--quality", "fast"]
        check_static(tmp, "normal map", [normal, *nm], [normal, *nm], 1, normal)
        check_server(tmp, os.path.join(tmp, "translucent.png"))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


main()
sys.exit(finish())
