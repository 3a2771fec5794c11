#!/usr/bin/env python3
"""`tessera view`'s workflow over many inputs, in headless Chromium (view_flow.mjs) and over plain
HTTP: the overview of a folder sorted worst-first against `tessera compress` + `compare`, files
opened from the page (the picker; a bad file; an over-cap body refused as it streams; no token),
downloads (.ktx and .ktx2 bytes as `tessera compress` writes them, the decoded PNG's texels as
`tessera decompress` writes them), a result evicted under --memory encoded again when shown, and
the static export's overview. Screenshots go to OUT (the build tree).

Usage: view_flow_test.py PATH/TO/tessera PUPPETEER_DIR OUT [CHROMIUM]
"""
import base64
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
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, finish, png_bytes, write_png  # noqa: E402
from view_harness import ViewTest  # noqa: E402

T = ViewTest("view_flow")
TESSERA, PUPPETEER, OUT, CHROMIUM, SCRIPT = T.tessera, T.puppeteer, T.out, T.chromium, T.script


MISSING = T.note_missing_browser()

from PIL import Image  # noqa: E402  (python3-pil)


run = T.run


def start_server(args, cwd):
    """`tessera view ARGS --no-open`: (process, URL, port, token), the URL read with a bounded
    wait."""
    p = subprocess.Popen([TESSERA, "view", *args, "--no-open"], cwd=cwd, stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    ready, _, _ = select.select([p.stdout], [], [], 120)
    line = p.stdout.readline().strip() if ready else ""
    ok = line.startswith("http://127.0.0.1:") and "token=" in line
    check("server prints its URL", ok, line)
    if not ok:
        p.kill()
        return p, "", 0, ""
    return p, line, int(line.split(":")[2].split("/")[0]), line.split("token=")[1]


def stop(p):
    p.send_signal(signal.SIGTERM)
    try:
        p.wait(timeout=60)
    except subprocess.TimeoutExpired:
        p.kill()
        p.wait()
    return p.stderr.read()


def request(port, method, path, body=b"", headers=None, timeout=60):
    """(status, body bytes) of one request on its own connection (Connection: close)."""
    h = {"Host": f"127.0.0.1:{port}", "Connection": "close", **(headers or {})}
    if method == "POST":
        h.setdefault("Content-Length", str(len(body)))
    head = f"{method} {path} HTTP/1.1\r\n" + "".join(f"{k}: {v}\r\n" for k, v in h.items()) + "\r\n"
    s = socket.create_connection(("127.0.0.1", port), timeout=timeout)
    try:
        s.sendall(head.encode() + body)
        got = b""
        while True:
            chunk = s.recv(1 << 20)
            if not chunk:
                break
            got += chunk
    except (ConnectionResetError, BrokenPipeError, socket.timeout):
        pass
    finally:
        s.close()
    status = int(got.split(b" ", 2)[1]) if got.startswith(b"HTTP/1.1 ") else 0
    head, _, data = got.partition(b"\r\n\r\n")
    if b"transfer-encoding: chunked" in head.lower():
        data = dechunk(data)
    return status, data


def dechunk(data):
    out = b""
    while data:
        size, _, rest = data.partition(b"\r\n")
        n = int(size, 16)
        if n == 0:
            break
        out += rest[:n]
        data = rest[n + 2:]
    return out


def browse(url, mode, *files):
    if MISSING:
        return None
    p = subprocess.run(["node", SCRIPT, PUPPETEER, CHROMIUM, url, OUT, mode, *files],
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


# Inputs of different difficulty for PVRTC: flat (exact), a gentle gradient, stripes, a
# 1-texel checkerboard of strong colours, noise.
def flat(x, y):
    return (90, 140, 200)


def gradient(x, y):
    return (x * 4, y * 4, 128)


def stripes(x, y):
    return ((255, 0, 0), (0, 200, 0), (0, 0, 255), (250, 250, 250), (20, 20, 20))[(x + 2 * y) % 5]


def checker(x, y):
    return (255, 255, 0) if (x + y) % 2 else (0, 40, 255)


def noise(x, y):
    v = (x * 7919 + y * 104729 + x * y * 31) % 251
    return (v, (v * 37) % 256, (v * 91) % 256)


KINDS = {"a_flat": flat, "b_checker": checker, "c_gradient": gradient, "d_noise": noise,
         "e_stripes": stripes}


def worst_first(entries):
    """entries: (name, psnr or None, max_abs); the overview's order."""
    return sorted(entries, key=lambda e: (float("inf") if e[1] is None else e[1], -e[2]))


def overview_json(port, token, want_done=True):
    """GET /api/overview, polled until every image is measured (bounded)."""
    j = {}
    for _ in range(1200):  # 2 minutes at most
        status, data = request(port, "GET", f"/api/overview?token={token}")
        if status != 200:
            return {"status": status}
        j = json.loads(data)
        if not want_done or all(x["state"] in ("done", "error", "texture") for x in j["inputs"]):
            break
        time.sleep(0.1)
    return j


def part_overview(tmp):
    """The overview's order is the order of `tessera compare` PSNRs of `tessera compress` outputs;
    the downloads of a result are what `tessera compress -o .ktx/.ktx2` and `decompress` write."""
    folder = os.path.join(tmp, "folder")
    os.makedirs(folder)
    expected = []
    for name, fn in KINDS.items():
        png = write_png(os.path.join(folder, name + ".png"), 64, 64, fn, False)
        pvr = os.path.join(tmp, name + ".pvr")
        dec = os.path.join(tmp, name + "-dec.png")
        rc, _, err = run("compress", png, "-o", pvr, "-q")
        check(f"{name}: compress", rc == 0, err)
        run("decompress", pvr, "-o", dec, "-q")
        rc, so, err = run("compare", png, dec, "--json")
        j = json.loads(so) if rc == 0 else {}
        expected.append((name + ".png", j.get("psnr_rgb"), j.get("max_abs")))
    order = [e[0] for e in worst_first(expected)]
    print("compare, worst first:", [(n, p, m) for n, p, m in worst_first(expected)])
    check("the inputs differ in difficulty (distinct PSNRs)",
          len({e[1] for e in expected}) == len(expected), expected)

    p, url, port, token = start_server(["folder"], tmp)
    if not port:
        return
    try:
        ov = overview_json(port, token)
        items = {x["name"]: x for x in ov.get("inputs", [])}
        for name, psnr, max_abs in expected:
            x = items.get(name, {})
            same = (x.get("psnr") is None and psnr is None) or (
                x.get("psnr") is not None and psnr is not None and abs(x["psnr"] - psnr) < 0.01)
            check(f"overview {name}: PSNR as tessera compare (0.01 dB)", same, (x.get("psnr"), psnr))
            check(f"overview {name}: max error as tessera compare", x.get("max_abs") == max_abs,
                  (x.get("max_abs"), max_abs))
            check(f"overview {name}: a thumbnail blob", len(x.get("thumbnail", "")) == 16, x)
        thumb = items.get("a_flat.png", {}).get("thumbnail", "")
        status, data = request(port, "GET", f"/blob/{thumb}?token={token}")
        check("thumbnail: a PNG", status == 200 and data.startswith(b"\x89PNG"), status)
        status, _ = request(port, "GET", "/api/overview")
        check("overview without the token: 403", status == 403, status)

        steps = browse(url, "overview")
        if steps:
            shown = [x["name"] for x in steps.get("order", [])]
            check("page overview: worst first, as tessera compare orders them", shown == order,
                  (shown, order))
            check("page overview: thumbnails loaded",
                  all(x["thumbnail"] for x in steps.get("order", [])), steps.get("order"))
            names = [x["name"] for x in steps.get("order", [])]
            second = names[1] if len(names) > 1 else ""
            clicked = steps.get("clicked", {})
            check("page overview: a click opens that input",
                  clicked.get("overview_hidden") is True and second
                  and ov["inputs"][clicked.get("input", -1)]["name"] == second, (clicked, second))
            check("page: download links (.ktx, .ktx2, decoded .png, heatmap .png)",
                  [a for a, _ in steps.get("downloads", [])] == ["ktx", "ktx2", "png", "heatmap"],
                  steps.get("downloads"))
            check_page_ktx2("page", steps.get("ktx2", {}), tmp)
        check_downloads(port, token, tmp, os.path.join(folder, "d_noise.png"),
                        [x["index"] for x in ov["inputs"] if x["name"] == "d_noise.png"][0])
    finally:
        stop(p)

    # The static export's overview: the same order from the exported results.
    html = os.path.join(tmp, "folder.html")
    rc, _, err = run("view", "folder", "--html", "-o", html, cwd=tmp)
    check("static export", rc == 0, err)
    steps = browse("file://" + html, "overview") if rc == 0 else None
    if steps:
        shown = [x["name"] for x in steps.get("order", [])]
        check("static overview: worst first, as tessera compare orders them", shown == order,
              (shown, order))
        # A static view stays small: the .pvr and the heatmap, no other containers inline.
        check("static page: no .ktx2 inline (the export stays small)",
              steps.get("ktx2", "missing") is None, steps.get("ktx2"))


def check_page_ktx2(name, k, tmp):
    """The page's .ktx2 link holds what its command writes with -o NAME.ktx2."""
    words = shlex.split(k.get("command", ""))
    check(name + ": a tessera compress command", words[:2] == ["tessera", "compress"], k)
    if words[:2] != ["tessera", "compress"] or "-o" not in words:
        return
    out = os.path.join(tmp, "page.ktx2")
    words[words.index("-o") + 1] = out
    rc, _, err = run(*words[1:], "-q", cwd=tmp)
    with open(out, "rb") as f:
        check(name + ": its .ktx2 download is the bytes of its command with -o NAME.ktx2",
              rc == 0 and f.read() == base64.b64decode(k.get("file", "")), (words, err))


def check_downloads(port, token, tmp, png, index):
    """A result's downloads against the CLI, with settings other than the defaults."""
    settings = {"quality": "high", "mip_levels": 3}
    status, data = request(port, "POST", f"/api/encode?token={token}",
                           json.dumps({"input": index, "settings": settings}).encode(),
                           {"Content-Type": "application/json"})
    job = json.loads(data) if status == 200 else {}
    for _ in range(1200):
        if job.get("state") not in ("queued", "running"):
            break
        time.sleep(0.1)
        status, data = request(port, "GET", f"/api/job?token={token}&id={job['id']}")
        job = json.loads(data)
    check("downloads: the encode ran", job.get("state") == "done", job)
    if job.get("state") != "done":
        return
    rid = job["result"]["id"]
    for ext in ("ktx", "ktx2", "pvr"):
        out = os.path.join(tmp, "cli." + ext)
        rc, _, err = run("compress", png, "-o", out, "--quality", "high", "--mip-levels", "3", "-q")
        status, data = request(port, "GET", f"/api/download?id={rid}&as={ext}&token={token}")
        with open(out, "rb") as f:
            check(f"download .{ext}: the bytes of tessera compress -o x.{ext}",
                  rc == 0 and status == 200 and data == f.read(), (status, len(data), err))
    dec = os.path.join(tmp, "cli-dec.png")
    run("decompress", os.path.join(tmp, "cli.pvr"), "-o", dec, "-q")
    status, data = request(port, "GET", f"/api/download?id={rid}&as=png&token={token}")
    got = os.path.join(tmp, "page-dec.png")
    with open(got, "wb") as f:
        f.write(data)
    same = False
    if status == 200:
        a, b = Image.open(got).convert("RGBA"), Image.open(dec).convert("RGBA")
        same = a.size == b.size and a.tobytes() == b.tobytes()
    check("download decoded .png: the texels of tessera decompress", same, status)
    status, data = request(port, "GET", f"/api/download?id={rid}&as=heatmap&token={token}")
    check("download heatmap: a PNG", status == 200 and data.startswith(b"\x89PNG"), status)
    status, _ = request(port, "GET", f"/api/download?id=r999&as=ktx&token={token}")
    check("download of no result: 404", status == 404, status)
    status, _ = request(port, "GET", f"/api/download?id={rid}&as=exe&token={token}")
    check("download as something unknown: 400", status == 400, status)


def part_open(tmp):
    """Files through the page's picker and over HTTP: a good image (named in the command by its
    file name), a bad file (an input with a one-line error), a body over the cap refused as it
    streams (413), no token (403), a body past the 4 MiB flood cap of header lines accepted."""
    write_png(os.path.join(tmp, "first.png"), 32, 32, gradient, False)
    picked = write_png(os.path.join(tmp, "picked sprite.png"), 64, 32, checker, False)
    bad = os.path.join(tmp, "broken.png")
    with open(bad, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\nnot an image at all")
    p, url, port, token = start_server(["first.png"], tmp)
    if not port:
        return
    try:
        steps = browse(url, "open", picked, bad)
        if steps:
            opened = steps.get("open", [])
            check("open: two files opened", len(opened) == 2, opened)
            if len(opened) == 2:
                good, broken = opened
                check("open: the image is a new input, selected",
                      good["input"]["name"] == "picked sprite.png" and good["selected"] == 1
                      and good["options"] == 2, good)
                check("open: the command names the file by its name",
                      good["command"] == "tessera compress 'picked sprite.png' -o 'picked sprite.pvr'",
                      good["command"])
                check("open: a bad file is an input with a one-line error",
                      "error" in broken["input"] and "\n" not in broken["input"]["error"]
                      and broken["options"] == 3, broken)
        with open(bad, "rb") as f:
            status, data = request(port, "POST", f"/api/open?name=x%2F..%2Fbad.png&token={token}",
                                   f.read())
        j = json.loads(data) if status == 200 else {}
        check("HTTP open of bad bytes: 200, an input with an error",
              status == 200 and "error" in j.get("input", {}), (status, data[:200]))
        check("HTTP open: the name is a file name, no path", j.get("input", {}).get("name") == "bad.png",
              j.get("input"))
        status, _ = request(port, "POST", "/api/open?name=a.png", b"abc")
        check("open without the token: 403", status == 403, status)
        status, _ = request(port, "POST", f"/api/open?name=a.png&token={token}", b"",
                            {"Content-Length": str(300 << 20)})
        check("open declaring 300 MiB: 413 before reading", status == 413, status)
        check("a chunked body past 256 MiB: 413 as it streams", chunked_over_cap(port, token))
        big = png_bytes(1200, 1200, 4, lambda x, y: (x % 256, y % 256, (x * y) % 256, 255), level=0)
        status, data = request(port, "POST", f"/api/open?name=big.png&token={token}", big)
        j = json.loads(data) if status == 200 else {}
        check(f"open of a {len(big) >> 20} MiB file (past the header flood cap)",
              status == 200 and j.get("input", {}).get("width") == 1200, (status, data[:200]))
        status, data = request(port, "GET", f"/?token={token}")
        check("the page lists the opened inputs after a reload",
              status == 200 and b"big.png" in data and b"picked sprite.png" in data, status)
    finally:
        stop(p)


def chunked_over_cap(port, token):
    """Streams a chunked body until the server answers 413 and closes (true), or 300 MiB were
    sent without that (false)."""
    s = socket.create_connection(("127.0.0.1", port), timeout=60)
    s.sendall((f"POST /api/open?name=huge.png&token={token} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n"
               "Transfer-Encoding: chunked\r\n\r\n").encode())
    chunk = b"%x\r\n" % (1 << 20) + b"\0" * (1 << 20) + b"\r\n"
    sent = 0
    try:
        while sent < 300:
            s.sendall(chunk)
            sent += 1
    except (BrokenPipeError, ConnectionResetError):
        pass
    got = b""
    try:
        while True:
            c = s.recv(65536)
            if not c:
                break
            got += c
    except (ConnectionResetError, socket.timeout):
        pass
    s.close()
    print(f"chunked open: {sent} MiB sent before the server stopped it; reply {got[:12]!r}")
    return got.startswith(b"HTTP/1.1 413") and sent < 300


def part_evict(tmp):
    """Under --memory 16, input 0's result is evicted by input 1's (2048x2048 noise: one result
    of it is over the budget); showing input 0 again encodes its settings again with a one-line
    note (no 404 on the page)."""
    for name, side in (("big0.png", 1024), ("big1.png", 2048)):  # noise: nothing shared
        Image.frombytes("RGB", (side, side), os.urandom(side * side * 3)).save(
            os.path.join(tmp, name), compress_level=1)
    p, url, port, token = start_server(["big0.png", "big1.png", "--memory", "16"], tmp)
    if not port:
        return
    try:
        steps = browse(url, "evict")
        if steps:
            first, after = steps.get("first", {}), steps.get("after", {})
            check("evict: input 0's result was evicted before it was shown again",
                  steps.get("evicted_before") == 404, steps.get("evicted_before"))
            check("evict: shown again, a new result of the same settings",
                  after.get("input") == 0 and after.get("id") != first.get("id")
                  and after.get("settings") == first.get("settings"), (first, after))
            check("evict: a one-line note, no error",
                  "again" in after.get("note", "") and "\n" not in after.get("note", "")
                  and after.get("error") == "", after)
            check("evict: its tab is there", after.get("tabs", 0) >= 1, after)
    finally:
        stop(p)


PARTS = {"overview": part_overview, "open": part_open, "evict": part_evict}


def main():
    shutil.rmtree(OUT, ignore_errors=True)
    os.makedirs(OUT, exist_ok=True)
    for name, part in PARTS.items():
        if len(sys.argv) > 5 and name not in sys.argv[5:]:
            continue
        tmp = tempfile.mkdtemp(prefix=f"tessera-flow-{name}-")
        t0 = time.monotonic()
        try:
            part(tmp)
        finally:
            shutil.rmtree(tmp, ignore_errors=True)
        print(f"part {name}: {time.monotonic() - t0:.1f} s")


main()
sys.exit(finish())
