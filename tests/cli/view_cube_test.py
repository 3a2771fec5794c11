#!/usr/bin/env python3
"""`tessera view --cube / --array`, non-power-of-two inputs and bad inputs: each group is one
input whose downloaded .pvr is `tessera compress --cube/--array`'s bytes and whose every face or
layer is measured as `tessera compare` measures its decode (PSNR to 0.01 dB); an input that is
not a power of two shows its original and the fix (--resize-pot) or, with it, a result measured
against the resized original; one bad input fails neither the others nor the --html export. The
static export is checked without a browser; the served page in headless Chromium
(view_cube.mjs). Screenshots go to OUT (the build tree).

Usage: view_cube_test.py PATH/TO/tessera PUPPETEER_DIR OUT [CHROMIUM]
"""
import base64
import json
import os
import select
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, finish  # noqa: E402
from view_harness import ViewTest, page_data  # noqa: E402

T = ViewTest("view_cube")
TESSERA, PUPPETEER, OUT, CHROMIUM, SCRIPT = T.tessera, T.puppeteer, T.out, T.chromium, T.script
FACE_NAMES = ["px", "nx", "py", "ny", "pz", "nz"]


MISSING = T.note_missing_browser()

from PIL import Image, ImageDraw  # noqa: E402  (python3-pil)


run = T.run


def make_face(path, size, k):
    """A face of its own colour and pattern: a gradient, stripes and a disc placed by `k`."""
    im = Image.new("RGB", (size, size))
    px = im.load()
    base = [(200, 60, 40), (40, 180, 70), (50, 80, 210), (220, 200, 40), (160, 50, 190),
            (40, 190, 200), (240, 140, 60)][k % 7]
    for y in range(size):
        for x in range(size):
            stripe = 40 if ((x + k * 3) // (2 + k)) % 2 else 0
            px[x, y] = tuple(min(255, c * (x + y + size) // (3 * size) + stripe) for c in base)
    ImageDraw.Draw(im).ellipse([size // 4 + k, size // 5, size // 2 + 2 * k, size // 2 + k],
                               fill=(255 - base[0], 255 - base[1], 255 - base[2]))
    im.save(path)
    return path


def blob_bytes(data, key):
    return base64.b64decode(data["blobs"][key].split(",", 1)[1])


def compare_psnr(source, texture, tmp, face=None, layer=None):
    """`tessera compare SOURCE (decompress TEXTURE --face F / --layer L)`'s PSNR RGB."""
    dec = os.path.join(tmp, "dec.png")
    extra = (["--face", str(face)] if face is not None else []) + \
            (["--layer", str(layer)] if layer is not None else [])
    rc, _, err = run("decompress", texture, *extra, "-o", dec, "-q")
    if rc != 0:
        return None
    rc, so, err = run("compare", source, dec, "--json")
    return json.loads(so)["psnr_rgb"] if rc == 0 else None


def check_same_as_command(name, command, file_bytes, tmp):
    """The page's command is `tessera compress ...`, runs, and writes the page's bytes."""
    words = shlex.split(command)
    check(name + ": command is tessera compress", words[:2] == ["tessera", "compress"], command)
    out = os.path.join(tmp, words[words.index("-o") + 1])
    if os.path.exists(out):
        os.remove(out)
    rc, _, err = run(*words[1:], "-q", cwd=tmp)
    check(name + ": command runs", rc == 0, err)
    with open(out, "rb") if rc == 0 else open(os.devnull, "rb") as f:
        check(name + ": same bytes as " + command, f.read() == file_bytes)
    return out


def check_export(tmp, faces, layers):
    html = os.path.join(tmp, "v.html")
    # A cube map from six faces: the bytes of tessera compress --cube, each face as compare.
    rc, _, err = run("view", "--cube", *faces, "--quality", "fast", "--html", "-o", html, "-q",
                     cwd=tmp)
    check("export --cube: exit 0", rc == 0, err)
    d = page_data(html) if rc == 0 else {"inputs": [], "results": []}
    check("export --cube: one input, a cube map", len(d["inputs"]) == 1
          and d["inputs"][0].get("shape") == "cube map" and d["inputs"][0]["name"] == "sky (cube map)",
          d["inputs"])
    if d["results"]:
        r = d["results"][0]
        check("export --cube: the command",
              r["command"] == "tessera compress --cube " + " ".join(faces)
              + " -o sky.pvr --quality fast", r["command"])
        ref = os.path.join(tmp, "ref-cube.pvr")
        run("compress", "--cube", *faces, "--quality", "fast", "-o", ref, "-q", cwd=tmp)
        with open(ref, "rb") as f:
            check("export --cube: bytes == tessera compress --cube", f.read() == blob_bytes(d, r["file"]))
        check_same_as_command("export --cube", r["command"], blob_bytes(d, r["file"]), tmp)
        got = {(i["face"], i["layer"]): i for i in r["images"] if i["level"] == 0}
        check("export --cube: six faces", sorted(got) == [(f, 0) for f in range(6)], sorted(got))
        for f in range(6):
            want = compare_psnr(os.path.join(tmp, faces[f]), ref, tmp, face=f)
            page = got.get((f, 0), {}).get("metrics", {}).get("psnr_rgb")
            check(f"export --cube: face {f} PSNR as tessera compare (0.01 dB)",
                  want is not None and page is not None and abs(page - want) < 0.01, (page, want))
            check(f"export --cube: face {f} has its original and heatmap",
                  "original" in got.get((f, 0), {}) and "heatmap" in got.get((f, 0), {}))
    # The cube map file with its faces (same stem): measured against them.
    shutil.copy(os.path.join(tmp, "ref-cube.pvr"), os.path.join(tmp, "sky.pvr"))
    rc, _, err = run("view", "sky.pvr", "--cube", *faces, "--quality", "fast", "--html", "-o",
                     html, "-q", cwd=tmp)
    d = page_data(html) if rc == 0 else {"results": []}
    files = [r for r in d["results"] if r.get("label") == "file sky.pvr" and r["input_index"] == 1]
    check("pair: sky.pvr is a result of the --cube input", len(files) == 1, (rc, err))
    if files:
        im = [i for i in files[0]["images"] if i["level"] == 0 and i["face"] == 2][0]
        want = compare_psnr(os.path.join(tmp, faces[2]), os.path.join(tmp, "sky.pvr"), tmp, face=2)
        check("pair: face 2 measured as tessera compare", abs(im["metrics"]["psnr_rgb"] - want) < 0.01,
              (im["metrics"], want))
    # An array of 3 layers.
    rc, _, err = run("view", "--array", *layers, "--html", "-o", html, "-q", cwd=tmp)
    check("export --array: exit 0", rc == 0, err)
    d = page_data(html) if rc == 0 else {"results": []}
    if d["results"]:
        r = d["results"][1]  # fast, normal, high: normal
        check("export --array: the command", r["command"] == "tessera compress --array "
              + " ".join(layers) + " -o lay.pvr", r["command"])
        out = check_same_as_command("export --array", r["command"], blob_bytes(d, r["file"]), tmp)
        for layer in range(3):
            im = [i for i in r["images"] if i["level"] == 0 and i["layer"] == layer][0]
            want = compare_psnr(os.path.join(tmp, layers[layer]), out, tmp, layer=layer)
            check(f"export --array: layer {layer} PSNR as tessera compare",
                  want is not None and abs(im["metrics"]["psnr_rgb"] - want) < 0.01,
                  (im["metrics"], want))


def check_npot_and_bad(tmp):
    html = os.path.join(tmp, "v.html")
    rc, _, err = run("view", "npot.png", "--html", "-o", html, "-q", cwd=tmp)
    d = page_data(html) if rc == 0 else {"inputs": [{}], "results": []}
    inp = d["inputs"][0]
    check("npot: exit 0, the original shown", rc == 0 and len(inp.get("originals", [])) == 1
          and inp["originals"][0]["width"] == 100, (rc, err, inp))
    check("npot: no results, no error", d["results"] == [] and "error" not in inp, inp)
    check("npot: a one-line note naming --resize-pot",
          "--resize-pot" in inp.get("note", "") and "\n" not in inp.get("note", ""), inp.get("note"))
    check("npot: the note on stderr", "npot.png" in err and "--resize-pot" in err, err)
    rc, _, err = run("view", "npot.png", "--resize-pot", "--html", "-o", html, "-q", cwd=tmp)
    d = page_data(html) if rc == 0 else {"results": []}
    check("--resize-pot: three results (fast, normal, high)", len(d["results"]) == 3, (rc, err))
    if d["results"]:
        r = d["results"][1]
        check("--resize-pot: the command", r["command"] ==
              "tessera compress npot.png -o npot.pvr --resize-pot", r["command"])
        check_same_as_command("--resize-pot", r["command"], blob_bytes(d, r["file"]), tmp)
        check("--resize-pot: resized from 100x60 to 128x64", r.get("resized_from") == [100, 60]
              and r["texture"]["width"] == 128 and r["texture"]["height"] == 64, r["texture"])
        check("--resize-pot: measured against the resized original",
              r["images"][0]["width"] == 128 and "original" in r["images"][0])
    # One bad input fails neither the others nor the export.
    rc, _, err = run("view", "good.png", "bad.png", "npot.png", "--quality", "fast", "--html",
                     "-o", html, cwd=tmp)
    check("bad input: export exits 0", rc == 0, err)
    d = page_data(html) if rc == 0 else {"inputs": [{}, {}, {}], "results": []}
    check("bad input: the good input has its result",
          [r["input_index"] for r in d["results"]] == [0], d["results"])
    e = d["inputs"][1].get("error", "")
    check("bad input: its one-line error on the page", "bad.png" in e and "\n" not in e, e)
    check("bad input: the npot input shows its original",
          "originals" in d["inputs"][2] and "error" not in d["inputs"][2], d["inputs"][2])
    if not MISSING and rc == 0:
        check_static_page(html)
    lines = [line for line in err.splitlines() if line.startswith("tessera:")]
    check("bad input: one stderr line each for bad.png and npot.png",
          len(lines) == 2 and "bad.png" in lines[0] and "npot.png" in lines[1], err)
    # Nothing works: an error, and no file.
    os.remove(html)
    rc, _, err = run("view", "bad.png", "--html", "-o", html, cwd=tmp)
    check("only bad inputs: exit 1, one line, no file",
          rc == 1 and len(err.strip().splitlines()) == 1 and not os.path.exists(html), (rc, err))
    # Usage: a cube map takes six faces; something to view is needed.
    rc, _, err = run("view", "--cube", "good.png", "good.png", "--html", "-o", html, cwd=tmp)
    check("--cube with 2 files: refused", rc != 0 and "cube" in err, (rc, err))
    rc, _, err = run("view", "--html", "-o", html, cwd=tmp)
    check("nothing to view: a usage error", rc == 2, (rc, err))
    rc, _, err = run("view", "--cube", *[f"sky_{n}.png" for n in FACE_NAMES], "good.png", "--html",
                     "-o", html, cwd=tmp)
    check("--cube with 7 files: one line saying so", rc == 1 and "got 7" in err
          and len(err.strip().splitlines()) == 1, (rc, err))


def start_server(args, cwd):
    p = subprocess.Popen([TESSERA, "view", *args, "--no-open"], cwd=cwd, stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    ready, _, _ = select.select([p.stdout], [], [], 120)
    line = p.stdout.readline().strip() if ready else ""
    check("server prints its URL", line.startswith("http://127.0.0.1:"), line)
    return p, line


def browse(url, mode, *extra):
    p = subprocess.run(["node", SCRIPT, PUPPETEER, CHROMIUM, url, OUT, mode, *extra],
                       capture_output=True, text=True, timeout=900,
                       env={**os.environ, "PUPPETEER_SKIP_DOWNLOAD": "1"})
    try:
        r = json.loads(p.stdout.strip().splitlines()[-1])
    except (ValueError, IndexError):
        check(f"{mode}: browser script output", False, (p.stdout + p.stderr)[-1500:])
        return None
    check(f"{mode}: no page errors", r["errors"] == [], r["errors"])
    check(f"{mode}: nothing fetched from elsewhere", r["external"] == [], r["external"])
    return r["steps"]


def check_static_page(html):
    """The export with a bad input in the browser: each input shows what it can."""
    s = browse("file://" + html, "static")
    if not s:
        return
    check("static: the good input drawn", s.get("good", {}).get("drawn", "").startswith("r"), s.get("good"))
    e = s.get("bad_error", "")
    check("static: the bad input's one-line error", "bad.png" in e and "\n" not in e, e)
    npot = s.get("npot", {})
    check("static: the npot input's original drawn with its note",
          npot.get("caption_a") == "original" and npot.get("original_lit", 0) > 1000
          and "--resize-pot" in npot.get("note", ""), npot)
    check("static: phone, no sideways scrolling", s.get("phone_overflow") is False)


def check_browser(tmp, faces, layers):
    run("compress", "--cube", *faces, "-o", "lone.pvr", "-q", cwd=tmp)
    p, url = start_server(["npot.png", "lone.pvr", "--cube", *faces, "--array", *layers], tmp)
    if not url.startswith("http"):
        p.kill()
        return
    s = browse(url, "cube")
    p.send_signal(signal.SIGINT)
    try:
        p.wait(timeout=60)
    except subprocess.TimeoutExpired:
        p.kill()
    if not s:
        return
    npot = s.get("npot", {})
    check("page npot: the original drawn", npot.get("caption_a") == "original"
          and npot.get("original_lit", 0) > 1000, npot)
    check("page npot: the note names --resize-pot", "--resize-pot" in npot.get("note", ""), npot)
    check("page npot: not encoded said in the metrics", "resize-pot" in npot.get("metrics", {}).get("note", ""),
          npot.get("metrics"))
    rs = s.get("npot_resized", {})
    check("page --resize-pot: the command", rs.get("command") ==
          "tessera compress npot.png -o npot.pvr --resize-pot", rs.get("command"))
    check("page --resize-pot: measured against the resized original (metrics say so)",
          "resized from 100x60 to 128x64" in rs.get("metrics", {}).get("reference", ""), rs.get("metrics"))
    check("page --resize-pot: the resized original drawn", "resized to 128x64" in rs.get("caption_a", "")
          and rs.get("original_lit", 0) > 1000, rs.get("caption_a"))
    if rs.get("file"):
        check_same_as_command("page --resize-pot", rs["command"], base64.b64decode(rs["file"]), tmp)
    lone = s.get("lone", {})
    check("page lone cube file: no reference said", "no reference" in lone.get("metrics", {}).get("note", ""),
          lone.get("metrics"))
    check("page lone cube file: heatmap option disabled", lone.get("heatmap_disabled") is True, lone)
    check("page lone cube file: the heatmap choice answered with a note",
          "no heatmap" in lone.get("heatmap_caption", ""), lone.get("heatmap_caption"))
    cube = s.get("cube", {})
    want_cmd = "tessera compress --cube " + " ".join(faces) + " -o sky.pvr"
    check("page cube: the command", cube.get("command") == want_cmd, cube.get("command"))
    ref = os.path.join(tmp, "page-ref-cube.pvr")
    run("compress", "--cube", *faces, "-o", ref, "-q", cwd=tmp)
    with open(ref, "rb") as f:
        check("page cube: downloaded .pvr == tessera compress --cube bytes",
              base64.b64decode(cube.get("file", "")) == f.read())
    for f, face in enumerate(s.get("faces", [])):
        want = compare_psnr(os.path.join(tmp, faces[f]), ref, tmp, face=f)
        page = float(face["metrics"].get("psnr_rgb", "nan"))
        check(f"page cube face {f}: PSNR as tessera compare (0.01 dB)",
              want is not None and abs(page - want) < 0.01, (page, want))
        check(f"page cube face {f}: the heatmap drawn (other pixels than the result)",
              face["heatmap"]["hash"] != face["result"]["hash"] and face["heatmap"]["lit"] > 1000
              and "heatmap" in face["heatmap_caption"], (face["heatmap"], face["result"]))
        check(f"page cube face {f}: its original beside it", face["caption_a"] == "original"
              and face["original"]["lit"] > 1000, face["caption_a"])
    check("page cube: six faces looked at", len(s.get("faces", [])) == 6)
    hashes = {face["result"]["hash"] for face in s.get("faces", [])}
    check("page cube: the faces differ", len(hashes) == 6, hashes)
    cr, ch = s.get("cross_result", {}), s.get("cross_heatmap", {})
    check("page cube cross: drawn, heatmap differs from the result",
          cr.get("lit", 0) > 6000 and ch.get("lit", 0) > 0 and cr.get("hash") != ch.get("hash"), (cr, ch))
    check("page cube cross: heatmap caption", "heatmap" in s.get("cross_caption", ""), s.get("cross_caption"))
    check("page phone: no sideways scrolling", s.get("phone_overflow") is False)
    arr = s.get("array", {})
    check("page array: the command", arr.get("command") ==
          "tessera compress --array " + " ".join(layers) + " -o lay.pvr", arr.get("command"))
    if arr.get("file"):
        out = check_same_as_command("page array", arr["command"], base64.b64decode(arr["file"]), tmp)
        for layer, step in enumerate(s.get("layers", [])):
            want = compare_psnr(os.path.join(tmp, layers[layer]), out, tmp, layer=layer)
            page = float(step["metrics"].get("psnr_rgb", "nan"))
            check(f"page array layer {layer}: PSNR as tessera compare", want is not None
                  and abs(page - want) < 0.01, (page, want))
    for shot in ("view-cube-cross-heatmap-1366x768.png", "view-cube-cross-heatmap-390x844.png",
                 "view-array-1366x768.png"):
        path = os.path.join(OUT, shot)
        check("screenshot " + shot, os.path.exists(path)
              and Image.open(path).size in ((1366, 768), (390, 844)))


def main():
    shutil.rmtree(OUT, ignore_errors=True)
    os.makedirs(OUT, exist_ok=True)
    tmp = tempfile.mkdtemp(prefix="tessera-view-cube-")
    try:
        faces = [os.path.basename(make_face(os.path.join(tmp, f"sky_{n}.png"), 64, k))
                 for k, n in enumerate(FACE_NAMES)]
        layers = [os.path.basename(make_face(os.path.join(tmp, f"lay{k}.png"), 32, k + 1))
                  for k in range(3)]
        make_face(os.path.join(tmp, "good.png"), 64, 6)
        Image.open(os.path.join(tmp, "good.png")).resize((100, 60)).save(os.path.join(tmp, "npot.png"))
        with open(os.path.join(tmp, "bad.png"), "wb") as f:
            f.write(b"\x89PNG\r\n\x1a\nnot really")
        check_export(tmp, faces, layers)
        check_npot_and_bad(tmp)
        if not MISSING:
            check_browser(tmp, faces, layers)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


main()
sys.exit(finish())
