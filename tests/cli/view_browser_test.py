#!/usr/bin/env python3
"""`tessera view` in a real browser (headless Chromium driven by puppeteer-core, view_browser.mjs)
and over plain HTTP: the server's guards (token, Host, Origin, paths, body size), the page's
encodes against `tessera compress` + `compare` (same bytes, PSNR to 0.01 dB), texel values
against `tessera decompress`, a cube map's faces and levels, a bad input, clean shutdown on
SIGINT and SIGTERM, and the static export. Screenshots go to OUT (the build tree).

Usage: view_browser_test.py PATH/TO/tessera PUPPETEER_DIR OUT [CHROMIUM]
"""
import base64
import http.client
import json
import os
import select
import shlex
import shutil
import signal
import socket
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, finish, write_png  # noqa: E402
from view_harness import ViewTest, page_data  # noqa: E402

T = ViewTest("view_browser")
TESSERA, PUPPETEER, OUT, CHROMIUM, SCRIPT = T.tessera, T.puppeteer, T.out, T.chromium, T.script


MISSING = T.note_missing_browser()

from PIL import Image  # noqa: E402  (python3-pil, after the skips)


run = T.run


def sprite(x, y):
    d = (x - 31.5) ** 2 + (y - 31.5) ** 2
    a = 255 if d < 300 else 0 if d > 700 else int(255 * (700 - d) / 400)
    return ((x * 37 + y * 11) % 256, (x * 4) % 256, (255 - y * 4) % 256, a)


def start_server(args, cwd):
    """Starts `tessera view ARGS --no-open`; returns (process, URL, port). The URL is the first
    line of stdout, read with a bounded wait."""
    p = subprocess.Popen([TESSERA, "view", *args, "--no-open"], cwd=cwd, stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    ready, _, _ = select.select([p.stdout], [], [], 120)
    line = p.stdout.readline().strip() if ready else ""
    check("server prints its URL", line.startswith("http://127.0.0.1:") and "token=" in line, line)
    port = int(line.split(":")[2].split("/")[0]) if line.startswith("http://127.0.0.1:") else 0
    return p, line, port


def request(port, method, path, host=None, origin=None, body=None):
    """(status, body) of one request to 127.0.0.1:port with the given Host / Origin."""
    c = http.client.HTTPConnection("127.0.0.1", port, timeout=30)
    headers = {"Host": host or f"127.0.0.1:{port}"}
    if origin:
        headers["Origin"] = origin
    if body is not None:
        headers["Content-Type"] = "application/json"
    c.request(method, path, body=body, headers=headers)
    r = c.getresponse()
    data = r.read()
    c.close()
    return r.status, data


def stop(p, sig, name):
    p.send_signal(sig)
    try:
        rc = p.wait(timeout=60)
    except subprocess.TimeoutExpired:
        p.kill()
        rc = "hung"
    check(f"{name}: exits 0", rc == 0, f"rc={rc}")


def port_closed(port):
    s = socket.socket()
    s.settimeout(5)
    try:
        return s.connect_ex(("127.0.0.1", port)) != 0
    finally:
        s.close()


def browse(url, mode):
    if MISSING:
        return None
    p = subprocess.run(["node", SCRIPT, PUPPETEER, CHROMIUM, url, OUT, mode], capture_output=True,
                       text=True, timeout=900, env={**os.environ, "PUPPETEER_SKIP_DOWNLOAD": "1"})
    try:
        r = json.loads(p.stdout.strip().splitlines()[-1])
    except (ValueError, IndexError):
        check(f"{mode}: browser script output", False, (p.stdout + p.stderr)[-1500:])
        return None
    check(f"{mode}: no page errors", r["errors"] == [], r["errors"])
    check(f"{mode}: nothing fetched from elsewhere", r["external"] == [], r["external"])
    return r["steps"]


def check_against_cli(name, step, tmp):
    """The page's texture is what its command line writes, and its PSNR what `compare` says."""
    words = shlex.split(step["command"])
    check(name + ": command is tessera compress", words[:2] == ["tessera", "compress"], words)
    out = os.path.join(tmp, step["file_name"])
    rc, _, err = run(*words[1:], "-q", cwd=tmp)
    check(name + ": command runs", rc == 0, err)
    with open(out, "rb") as f:
        check(name + ": same bytes as tessera compress", f.read() == base64.b64decode(step["file"]))
    dec = os.path.join(tmp, "dec.png")
    run("decompress", out, "-o", dec, "-q")
    rc, so, err = run("compare", os.path.join(tmp, "sprite.png"), dec, "--json", "--premultiplied")
    j = json.loads(so) if rc == 0 else {}
    page = float(step["metrics"].get("psnr_rgb", "nan"))
    check(name + ": PSNR RGB as tessera compare (0.01 dB)", abs(page - j.get("psnr_rgb", 1e9)) < 0.01,
          f"page {page} compare {j.get('psnr_rgb')}")
    pa = float(step["metrics"].get("psnr_alpha", "nan"))
    check(name + ": PSNR alpha as tessera compare", abs(pa - j.get("psnr_alpha", 1e9)) < 0.01,
          f"page {pa} compare {j.get('psnr_alpha')}")
    pp = float(step["metrics"].get("psnr_premultiplied", "nan"))
    check(name + ": PSNR colour x alpha as tessera compare",
          abs(pp - j.get("psnr_premultiplied", 1e9)) < 0.01, f"{pp} vs {j.get('psnr_premultiplied')}")
    return dec


def texel_of(png, x, y):
    return list(Image.open(png).convert("RGBA").getpixel((x, y)))


def check_guards(port, token):
    """Requests without the token, with a foreign Host or Origin, outside the inputs, or too
    big are refused and create nothing (no job appears); the right request passes."""
    t = "?token=" + token
    cases = [
        ("no token", "GET", "/", None, None, None, 403),
        ("wrong token", "GET", "/?token=" + "0" * len(token), None, None, None, 403),
        ("foreign Host", "GET", "/" + t, "evil.example:%d" % port, None, None, 403),
        ("foreign Origin", "GET", "/" + t, None, "http://evil.example", None, 403),
        ("encode without token", "POST", "/api/encode", None, None, '{"input":0,"settings":{}}', 403),
        ("encode from a foreign Origin", "POST", "/api/encode" + t, None, "http://evil.example",
         '{"input":0,"settings":{}}', 403),
        ("encode with a foreign Host", "POST", "/api/encode" + t, "rebound.example:%d" % port, None,
         '{"input":0,"settings":{}}', 403),
        ("oversized body", "POST", "/api/encode" + t, None, None,
         '{"input":0,"settings":{},"pad":"' + "x" * 200000 + '"}', 413),
        ("a path outside the inputs", "GET", "/etc/passwd" + t, None, None, None, 404),
        ("a dot-dot path", "GET", "/blob/../../etc/passwd" + t, None, None, None, 404),
        ("an unknown blob", "GET", "/blob/0123456789abcdef" + t, None, None, None, 404),
        ("a file parameter", "GET", "/api/file" + t + "&path=/etc/passwd", None, None, None, 404),
        ("a texture input is not encoded", "POST", "/api/encode" + t, None, None,
         '{"input":1,"settings":{}}', 404),
        ("bad settings", "POST", "/api/encode" + t, None, None,
         '{"input":0,"settings":{"quality":"ultra"}}', 400),
        ("conflicting settings", "POST", "/api/encode" + t, None, None,
         '{"input":0,"settings":{"premultiply":true,"alpha_bleed":true}}', 400),
    ]
    for name, method, path, host, origin, body, want in cases:
        status, data = request(port, method, path, host, origin, body)
        check("guard: " + name, status == want, f"{status} {data[:200]!r}")
    status, _ = request(port, "GET", "/api/job" + t + "&id=j0")
    check("guards: refused requests started no encode", status == 404, status)
    # Positive controls: the same requests pass with the token and this server's names.
    status, data = request(port, "GET", "/" + t, origin=f"http://127.0.0.1:{port}")
    check("guard: the page with the token", status == 200 and b"tessera view" in data, status)
    status, _ = request(port, "GET", "/" + t, host=f"localhost:{port}")
    check("guard: Host localhost passes", status == 200, status)


def main():
    shutil.rmtree(OUT, ignore_errors=True)  # this run's screenshots only
    os.makedirs(OUT, exist_ok=True)
    tmp = tempfile.mkdtemp(prefix="tessera-view-")
    try:
        write_png(os.path.join(tmp, "sprite.png"), 64, 64, sprite, True)
        faces = []
        for f in range(6):
            faces.append(write_png(os.path.join(tmp, f"face{f}.png"), 32, 32,
                                   lambda x, y, f=f: ((x * 8) % 256, (y * 8) % 256, 40 * f, 255),
                                   False))
        rc, _, err = run("compress", *faces, "--cube", "--mipmaps", "-o",
                         os.path.join(tmp, "cube.pvr"), "-q")
        check("cube map made", rc == 0, err)
        with open(os.path.join(tmp, "bad.png"), "wb") as f:
            f.write(b"\x89PNG\r\n\x1a\nnot really")

        p, url, port = start_server(["sprite.png", "cube.pvr", "bad.png"], tmp)
        if not port:
            p.kill()
            return
        token = url.split("token=")[1]
        check_guards(port, token)
        steps = browse(url, "server")
        stop(p, signal.SIGINT, "SIGINT")
        check("SIGINT: port closed", port_closed(port))
        err = p.stderr.read()
        bad_lines = [line for line in err.splitlines() if "bad.png" in line]
        check("bad input: one line in the terminal", len(bad_lines) == 1, err)
        if steps:
            check_steps(steps, tmp)

        with socket.socket() as s:  # a free port for --port
            s.bind(("127.0.0.1", 0))
            fixed = s.getsockname()[1]
        p, url, port = start_server(["sprite.png", "--quality", "fast", "--port", str(fixed)], tmp)
        check("--port: the URL has that port", port == fixed, url)
        if port:
            token = url.split("token=")[1]
            status, _ = request(port, "GET", "/?token=" + token)
            check("second server answers", status == 200, status)
            check_progress(port, token)
            stop(p, signal.SIGTERM, "SIGTERM")
            check("SIGTERM: port closed", port_closed(port))

        check_static(tmp)
        check_normal_map_and_demo(tmp)
        check_texture_and_folder_export(tmp)
        check_usage(tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def check_steps(s, tmp):
    first, high, weighted = s.get("first"), s.get("high"), s.get("weighted")
    if not (first and high and weighted):
        check("server scenario ran to its end", False, list(s))
        return
    check("first encode: the default command",
          first["command"] == "tessera compress sprite.png -o sprite.pvr", first["command"])
    check("quality: the command changed", high["command"].endswith("--quality high"), high["command"])
    check("quality: the image changed", high["drawn"] != first["drawn"] and high["file"] != first["file"],
          (first["drawn"], high["drawn"], first["file"] == high["file"]))
    check("alpha-weighted: the command changed",
          weighted["command"].endswith("--quality high --alpha-weighted"), weighted["command"])
    check("alpha-weighted: the metrics changed", weighted["metrics"] != high["metrics"])
    check("earlier results stay as tabs (normal, high, weighted)", weighted.get("tabs", 0) >= 3,
          weighted.get("tabs"))
    for name, step in (("normal", first), ("high", high), ("weighted", weighted)):
        dec = check_against_cli(name, step, tmp)
    # The last one decoded is --alpha-weighted: the one shown when the texel was read.
    t = s.get("sprite_texel", {})
    if t:
        x, y = int(t["x"]), int(t["y"])
        check("zoom 32: the texel under the middle is the centre one", (x, y) in ((31, 31), (32, 32), (31, 32), (32, 31)), (x, y))
        check("zoom 32: decoded value as tessera decompress",
              [int(v) for v in t["decoded"].split(",")] == texel_of(dec, x, y), t)
        check("zoom 32: original value as the PNG",
              [int(v) for v in t["original"].split(",")] == list(sprite(x, y)), t)
    w = s.get("wheel", {})
    check("wheel zoom on the cursor: the texel under it stays",
          w.get("before") is not None and w.get("before") == w.get("after")
          and w.get("zoom_before") == 32 and w.get("zoom_after") == 16, w)
    check("readout refreshed by a change under a still pointer (level 1 read)",
          "level 1" in s.get("cube_readout", ""), s.get("cube_readout"))
    check("pin: one pinned row", s.get("pinned_rows") == 1, s.get("pinned_rows"))
    check("heatmap: colour bar shown", s.get("colourbar") is True)
    check("heatmap of colour x alpha shown", "colour x alpha" in s.get("premultiplied_heatmap", ""))
    check("phone: no sideways scrolling", s.get("phone_overflow") is False)
    cube = s.get("cube", {})
    check("cube: 6 faces with mips in the metrics",
          "cube map" in cube.get("metrics", {}).get("shape", ""), cube.get("metrics"))
    ct = s.get("cube_texel", {})
    if ct:
        dec = os.path.join(tmp, "face3-level1.png")
        run("decompress", os.path.join(tmp, "cube.pvr"), "--level", "1", "--face", "3", "-o", dec, "-q")
        x, y = int(ct["x"]), int(ct["y"])
        check("cube: level 1 face 3 texel as tessera decompress",
              [int(v) for v in ct["decoded"].split(",")] == texel_of(dec, x, y), ct)
        other = os.path.join(tmp, "face0-level1.png")
        run("decompress", os.path.join(tmp, "cube.pvr"), "--level", "1", "--face", "0", "-o", other, "-q")
        check("cube: (negative control) face 0 differs there", texel_of(other, x, y) != texel_of(dec, x, y))
    check("bad input: a one-line error on the page naming it",
          "bad.png" in s.get("bad_error", "") and "\n" not in s.get("bad_error", ""), s.get("bad_error"))
    check("server keeps running after the bad input", s.get("back", {}).get("drawn", "").startswith("r"))
    for shot in ("view-1366x768.png", "view-390x844.png", "view-heatmap-1366x768.png",
                 "view-cube-cross-1366x768.png", "view-zoom32-1366x768.png"):
        path = os.path.join(OUT, shot)
        ok = os.path.exists(path) and Image.open(path).size in ((1366, 768), (390, 844))
        check("screenshot " + shot, ok)


def check_progress(port, token):
    """An encode through the API: its job's fraction never goes back and is 1.0 when done
    (EncodeOptions::progress, what the page's progress bar shows); the same settings again
    give the same job (no second encode)."""
    body = '{"input":0,"settings":{"quality":"high","alpha_bleed":true}}'
    status, data = request(port, "POST", "/api/encode?token=" + token, body=body)
    check("progress: encode accepted", status == 200, data[:200])
    if status != 200:
        return
    job = json.loads(data)
    fractions = [job["fraction"]]
    for _ in range(6000):  # bounded: 10 minutes at most
        if job["state"] in ("done", "error"):
            break
        select.select([], [], [], 0.1)
        job = json.loads(request(port, "GET", f"/api/job?token={token}&id={job['id']}")[1])
        fractions.append(job["fraction"])
    check("progress: the encode finished", job["state"] == "done", job.get("error"))
    check("progress: fractions never go back", fractions == sorted(fractions), fractions)
    check("progress: 1.0 when done", fractions[-1] == 1.0, fractions[-5:])
    status, data = request(port, "POST", "/api/encode?token=" + token, body=body)
    again = json.loads(data) if status == 200 else {}
    check("progress: the same settings are the same job", again.get("id") == job["id"], again)
    check("progress: the result is the command's", job.get("result", {}).get("command") ==
          "tessera compress sprite.png -o sprite.pvr --quality high --alpha-bleed")


def check_texture_and_folder_export(tmp):
    """A cube map with mips exports every face of every level; a folder gives its images and
    textures (not other files), in name order."""
    html = os.path.join(tmp, "cube.html")
    rc, _, err = run("view", os.path.join(tmp, "cube.pvr"), "--html", "-o", html, "-q")
    check("cube export", rc == 0, err)
    if rc == 0:
        images = page_data(html)["results"][0]["images"]
        check("cube export: 6 faces x 6 levels", sorted((i["level"], i["face"]) for i in images)
              == [(lv, f) for lv in range(6) for f in range(6)], len(images))
    # An image and a texture of the same stem: the texture is a result of the image, measured
    # against it as tessera compare measures its decode.
    pair = os.path.join(tmp, "pair")
    os.makedirs(pair, exist_ok=True)
    shutil.copy(os.path.join(tmp, "sprite.png"), os.path.join(pair, "sprite.png"))
    run("compress", os.path.join(pair, "sprite.png"), "--quality", "fast", "-o",
        os.path.join(pair, "sprite.ktx"), "-q")
    run("decompress", os.path.join(pair, "sprite.ktx"), "-o", os.path.join(pair, "d.png"), "-q")
    rc, so, _ = run("compare", os.path.join(pair, "sprite.png"), os.path.join(pair, "d.png"), "--json")
    want = json.loads(so)["psnr_rgb"] if rc == 0 else None
    rc, _, err = run("view", os.path.join(pair, "sprite.png"), os.path.join(pair, "sprite.ktx"),
                     "--quality", "high", "--html", "-o", html, "-q")
    d = page_data(html) if rc == 0 else {"results": []}
    files = [r for r in d["results"] if r.get("label") == "file sprite.ktx" and r["input_index"] == 0]
    check("pair: the texture is a result of the image", len(files) == 1, (rc, err))
    if files:
        got = files[0]["images"][0]["metrics"]["psnr_rgb"]
        check("pair: PSNR as tessera compare", abs(got - want) < 1e-9, (got, want))
        with open(os.path.join(pair, "sprite.ktx"), "rb") as f:
            check("pair: the download is the file", base64.b64decode(
                d["blobs"][files[0]["file"]].split(",", 1)[1]) == f.read())
    # A mip chain with a filter: the same bytes as the command, every level measured against
    # the chain compress encodes (close: the encoder's error, not a wrong reference's).
    rc, _, err = run("view", os.path.join(tmp, "sprite.png"), "--mip-levels", "3", "--mip-filter",
                     "lanczos", "--srgb", "--html", "-o", html, "-q")
    d = page_data(html) if rc == 0 else {"results": []}
    check("mips export", rc == 0 and len(d["results"]) == 1, err)
    if d["results"]:
        r = d["results"][0]
        check("mips: 3 levels", [i["level"] for i in r["images"]] == [0, 1, 2], r["images"])
        out = os.path.join(tmp, r["file_name"])
        words = shlex.split(r["command"])
        run(*words[1:], "-q", cwd=tmp)
        with open(out, "rb") as f:
            check("mips: same bytes as " + r["command"],
                  f.read() == base64.b64decode(d["blobs"][r["file"]].split(",", 1)[1]))
        for im in r["images"][1:]:
            check(f"mips: level {im['level']} measured against its reference",
                  im["metrics"]["psnr_rgb"] is not None and im["metrics"]["psnr_rgb"] > 15, im["metrics"])
    # A hostile file name cannot break out of the page's data.
    odd = os.path.join(tmp, "x<!--<script>alert(1).png")
    shutil.copy(os.path.join(tmp, "sprite.png"), odd)
    rc, _, err = run("view", odd, "--quality", "fast", "--html", "-o", html, "-q")
    with open(html, encoding="utf-8") as f:
        text = f.read()
    check("odd name: no markup from it in the page", rc == 0 and "<!--<script" not in text, err)
    check("odd name: the page's data names it",
          page_data(html)["inputs"][0]["name"] == os.path.basename(odd))
    folder = os.path.join(tmp, "folder")
    os.makedirs(folder, exist_ok=True)
    shutil.copy(os.path.join(tmp, "sprite.png"), os.path.join(folder, "b.png"))
    shutil.copy(os.path.join(tmp, "cube.pvr"), os.path.join(folder, "a.pvr"))
    with open(os.path.join(folder, "notes.txt"), "w") as f:
        f.write("not an image")
    rc, _, err = run("view", folder, "--quality", "fast", "--html", "-o", html, "-q")
    d = page_data(html) if rc == 0 else {"inputs": []}
    check("folder: its image and texture, in name order",
          [i["name"] for i in d["inputs"]] == ["a.pvr", "b.png"], (rc, err, d["inputs"]))


def check_usage(tmp):
    for args, word in ((["view"], "INPUT"), (["view", "a.png", "--html"], "-o"),
                       (["view", "a.png", "-o", "v.html"], "--html"),
                       (["view", "a.png", "--quality", "best"], "--quality"),
                       (["view", "a.png", "--mip-filter", "kaiser"], "--mip-levels"),
                       (["view", "a.png", "--premultiply", "--alpha-bleed"], "--alpha-bleed"),
                       (["view", "a.png", "--port", "0"], "--port")):
        rc, _, err = run(*args, cwd=tmp)
        check(f"usage: {' '.join(args)}: exit 2 naming {word}", rc == 2 and word in err
              and len(err.strip().splitlines()) == 1, (rc, err))


def check_normal_map_and_demo(tmp):
    """--normal-map: the angular error map and the angles of `tessera compare --normal`; the
    demo report links a static view of its PVRTC images."""
    def normal(x, y):
        nx, ny = (x - 15.5) / 20, (y - 15.5) / 20
        nz = max(0.0, 1 - nx * nx - ny * ny) ** 0.5
        return (int(127.5 + 127.5 * nx), int(127.5 + 127.5 * ny), int(127.5 + 127.5 * nz), 255)
    n = write_png(os.path.join(tmp, "normal.png"), 32, 32, normal, False)
    html = os.path.join(tmp, "n.html")
    rc, _, err = run("view", n, "--normal-map", "--quality", "fast", "--html", "-o", html, "-q")
    check("normal map export", rc == 0, err)
    if rc != 0:
        return
    d = page_data(html)
    im = d["results"][0]["images"][0]
    check("normal map: one result, with an angular error map",
          len(d["results"]) == 1 and "angle_map" in im and "angle_map" in d["results"][0]["colour_bars"])
    run("compress", n, "--normal-map", "--quality", "fast", "-o", os.path.join(tmp, "n.pvr"), "-q")
    run("decompress", os.path.join(tmp, "n.pvr"), "-o", os.path.join(tmp, "n-dec.png"), "-q")
    rc, so, _ = run("compare", n, os.path.join(tmp, "n-dec.png"), "--normal", "--json")
    j = json.loads(so) if rc == 0 else {}
    for key in ("angular_error_mean_deg", "angular_error_max_deg"):
        check("normal map: " + key + " as tessera compare --normal",
              abs(im["metrics"].get(key, -1) - j.get(key, -2)) < 1e-6, (im["metrics"].get(key), j.get(key)))
    demo = os.path.join(tmp, "demo")
    rc, _, err = run("demo", "-o", demo, "--size", "32", "-q")
    check("demo runs", rc == 0, err)
    if rc == 0:
        with open(os.path.join(demo, "report.html"), encoding="utf-8") as f:
            check("demo report links its static view", 'href="pvrtc-view.html"' in f.read())
        d = page_data(os.path.join(demo, "pvrtc-view.html"))
        check("demo view: every PVRTC image with results",
              len(d["inputs"]) >= 3 and {r["input_index"] for r in d["results"]} == set(range(len(d["inputs"]))),
              [i["name"] for i in d["inputs"]])


def check_static(tmp):
    html = os.path.join(tmp, "v.html")
    rc, _, err = run("view", os.path.join(tmp, "sprite.png"), "--html", "-o", html, "-q")
    check("static export written", rc == 0 and os.path.exists(html), err)
    rc, _, err = run("view", os.path.join(tmp, "bad.png"), "--html", "-o", os.path.join(tmp, "w.html"))
    check("static export of a bad input: exit 1, one line naming it, no file",
          rc == 1 and len(err.strip().splitlines()) == 1 and "bad.png" in err
          and not os.path.exists(os.path.join(tmp, "w.html")), (rc, err))
    if rc == 0 or not os.path.exists(html):
        return
    with open(html, encoding="utf-8") as f:
        text = f.read()
    check("static export: no external references", "http://" not in text.replace("http://www.w3.org", ""))
    s = browse("file://" + html, "static")
    if not s:
        return
    commands = [r["command"] for r in s.get("results", [])]
    # The input by its path as typed (here absolute), so the command runs from anywhere.
    src = shlex.quote(os.path.join(tmp, "sprite.png"))
    check("static export: fast, normal, high, bleed, weighted", commands == [
        f"tessera compress {src} -o sprite.pvr --quality fast",
        f"tessera compress {src} -o sprite.pvr",
        f"tessera compress {src} -o sprite.pvr --quality high",
        f"tessera compress {src} -o sprite.pvr --alpha-bleed",
        f"tessera compress {src} -o sprite.pvr --alpha-weighted"], commands)
    for r in s.get("results", [])[:3] + s.get("results", [])[4:]:
        check_against_cli("static " + r["command"].split(" -o ")[-1], r, tmp)
    t = s.get("texel")
    check("static export: texel readout", bool(t and t.get("decoded")), t)


main()
sys.exit(finish())
