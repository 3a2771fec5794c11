#!/usr/bin/env python3
"""`tessera view` speed: a re-encode through the server (POST /api/encode, poll /api/job, fetch
the blobs the page draws first) against `tessera compress` on the same input and options, with
the job's progress over time; and the size and time of the static export (`--html`).

Usage (from the repository root):
    /usr/bin/python3 bench/view_speed.py [--runs 3] [--tessera build/bin/tessera]
        [--shared ../shared] [--cases 2048:fast,2048:high,4096:fast] [--json OUT.json]

Inputs, made once in a temporary folder (never in the repository): photo2048.png is the shared
2048x2048 photo-like texture data/images/ldr-rgb-diffuse.png; photo4096.png is that image
mirrored into a 2x2 tile (4096x4096, the same statistics, no upscaling blur).

One server per input: `tessera view IMG --no-open --port P -q`. A first encode (normal) plays the
page's start-up (its original's texels are then in the client's cache, as in the page). Each
timed run then POSTs the case's settings with a fresh label (so the server cannot reuse a
finished job), polls /api/job every 100 ms as view.js does, and fetches what level 0's decoded
texels come from (the result's .pvr blob, which the page decodes (view_pvrtc.js; that decode is
not timed here), or a PNG of them from a tessera older than that) and its original's when the
client has not fetched that key yet (the page's texel cache; the decoded ones are fetched every
run, as a new setting's would be): the time ends when the last of
them has arrived. `tessera compress` runs alternately with the view runs
(same input, same options, same thread count), each a fresh process. Medians of --runs. The
progress fractions seen are recorded with their times: the longest time the fraction did not
move while the job ran, and how long it sat at 1.0 before the job was done, show stalls.
Standard library only.
"""
import argparse
import json
import os
import shutil
import statistics
import struct
import subprocess
import sys
import tempfile
import time
import urllib.request
import zlib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def read_ppm(data):
    """(width, height, rgb bytes) of a binary PPM (P6, maxval 255)."""
    fields, pos = [], 0
    while len(fields) < 4:
        while data[pos:pos + 1].isspace():
            pos += 1
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    assert fields[0] == b"P6" and fields[3] == b"255", "not an 8-bit P6 PPM"
    w, h = int(fields[1]), int(fields[2])
    return w, h, data[pos + 1:pos + 1 + w * h * 3]


def write_png_rgb(path, w, h, rgb):
    rows = b"".join(b"\0" + rgb[y * w * 3:(y + 1) * w * 3] for y in range(h))

    def chunk(kind, body):
        return (struct.pack(">I", len(body)) + kind + body
                + struct.pack(">I", zlib.crc32(kind + body) & 0xffffffff))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(rows, 6)) + chunk(b"IEND", b""))


def make_inputs(shared, folder):
    """{size: path} of the 2048 and 4096 inputs (made once in `folder`)."""
    src = os.path.join(shared, "data", "images", "ldr-rgb-diffuse.png")
    if not os.path.isfile(src):
        sys.exit(f"view_speed: {src} not found (pass --shared, the folder with data/images)")
    p2, p4 = os.path.join(folder, "photo2048.png"), os.path.join(folder, "photo4096.png")
    if not os.path.isfile(p2):
        shutil.copyfile(src, p2)
    if not os.path.isfile(p4):
        # The 2048 image read through `convert FILE ppm:-` (ImageMagick, or the stand-in that
        # only converts PNG to PPM), mirrored into 2x2.
        ppm = subprocess.run(["convert", src, "ppm:-"], capture_output=True, check=True).stdout
        w, h, rgb = read_ppm(ppm)
        rows = [rgb[y * w * 3:(y + 1) * w * 3] for y in range(h)]
        flip = [b"".join(r[x * 3:x * 3 + 3] for x in range(w - 1, -1, -1)) for r in rows]
        top = [a + b for a, b in zip(rows, flip)]
        write_png_rgb(p4 + ".tmp", 2 * w, 2 * h, b"".join(top + top[::-1]))
        os.replace(p4 + ".tmp", p4)
    return {2048: p2, 4096: p4}


class Server:
    def __init__(self, tessera, image, port):
        self.proc = subprocess.Popen([tessera, "view", image, "--no-open", "--port", str(port),
                                      "-q"], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                                     text=True, env={k: v for k, v in os.environ.items()
                                                     if k != "TESSERA_VIEW_OPENER"})
        self.url = self.proc.stdout.readline().strip()
        if not self.url.startswith("http://"):
            self.proc.kill()
            sys.exit(f"view_speed: the server printed {self.url!r}, not its URL")
        self.base, self.token = self.url.split("/?token=")
        self.fetched = set()  # the page's texel cache: keys already fetched

    def get(self, path, data=None):
        sep = "&" if "?" in path else "?"
        req = urllib.request.Request(f"{self.base}{path}{sep}token={self.token}", data=data,
                                     headers={"Content-Type": "application/json"} if data else {})
        with urllib.request.urlopen(req) as r:
            return r.read()

    def encode(self, settings):
        """(seconds, blob bytes fetched, [(t, state, fraction)], result) of one encode."""
        t0 = time.perf_counter()
        trace = []
        job = json.loads(self.get("/api/encode", json.dumps({"input": 0, "settings": settings})
                                  .encode()))
        while True:
            trace.append((time.perf_counter() - t0, job["state"], job["fraction"]))
            if job["state"] not in ("queued", "running"):
                break
            time.sleep(0.1)
            job = json.loads(self.get(f"/api/job?id={job['id']}"))
        if job["state"] != "done":
            sys.exit(f"view_speed: the encode failed: {job.get('error')}")
        r = job["result"]
        im = r["images"][0]
        got = 0
        dec = im["decoded"]
        if dec.startswith("pvrtc:"):  # decoded in the page from the result's .pvr: its blob
            dec = dec.split(":")[1]
        for key in (dec, im.get("original")):
            if key and (key == dec or key not in self.fetched):
                got += len(self.get(f"/blob/{key}"))
                self.fetched.add(key)
        return time.perf_counter() - t0, got, trace, r

    def close(self):
        self.proc.terminate()
        self.proc.wait()


def compress_time(tessera, image, quality, out):
    t0 = time.perf_counter()
    subprocess.run([tessera, "compress", image, "-o", out, "--quality", quality],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - t0


def stalls(trace):
    """(longest time the fraction stood still while running, time at >= 0.999 before done,
    non-decreasing?) of a progress trace."""
    longest, since, last, at_one, mono = 0.0, None, None, None, True
    for t, state, f in trace:
        if state != "running":
            continue
        if last is not None and f < last:
            mono = False
        if f != last:
            since, last = t, f
        longest = max(longest, t - since)
        if f >= 0.999 and at_one is None:
            at_one = t
    done = trace[-1][0]
    if since is not None:
        longest = max(longest, done - since)
    return longest, (done - at_one) if at_one is not None else 0.0, mono


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--tessera", default=os.path.join(ROOT, "build", "bin", "tessera"))
    ap.add_argument("--shared", default=os.environ.get("TESSERA_SHARED",
                                                       os.path.join(ROOT, "..", "shared")))
    ap.add_argument("--inputs", default=os.path.join(tempfile.gettempdir(), "tessera-view-speed"))
    ap.add_argument("--cases", default="2048:fast,2048:high,4096:fast")
    ap.add_argument("--port", type=int, default=18731)
    ap.add_argument("--no-export", action="store_true")
    ap.add_argument("--json", help="write every number (and the traces) here")
    a = ap.parse_args()
    os.makedirs(a.inputs, exist_ok=True)
    images = make_inputs(a.shared, a.inputs)
    out = os.path.join(a.inputs, "out.pvr")
    report = {"cases": [], "export": None}
    by_size = {}
    for case in a.cases.split(","):
        size, quality = case.split(":")
        by_size.setdefault(int(size), []).append(quality)
    for size, qualities in by_size.items():
        server = Server(a.tessera, images[size], a.port)
        try:
            server.encode({"quality": "normal", "label": "start-up"})  # the page's first encode
            for q in qualities:
                view, comp, fetched, traces = [], [], [], []
                for run in range(a.runs):
                    s, got, trace, r = server.encode({"quality": q, "label": f"{q} {run}"})
                    view.append(s)
                    fetched.append(got)
                    traces.append(trace)
                    comp.append(compress_time(a.tessera, images[size], q, out))
                worst = max((stalls(t) for t in traces), key=lambda x: x[0])
                row = {"size": size, "quality": q, "view_s": statistics.median(view),
                       "compress_s": statistics.median(comp), "view_runs": view,
                       "compress_runs": comp, "fetched_bytes": statistics.median(fetched),
                       "encode_ms": r["encode_ms"], "longest_stall_s": worst[0],
                       "at_one_s": worst[1], "monotonic": all(stalls(t)[2] for t in traces),
                       "trace": traces[len(traces) // 2], "command": r["command"]}
                report["cases"].append(row)
                print(f"{size}² {q}: view {row['view_s']:.2f} s, compress {row['compress_s']:.2f}"
                      f" s (x{row['view_s'] / row['compress_s']:.2f}), encode {r['encode_ms']:.0f}"
                      f" ms, fetched {row['fetched_bytes'] / 1e6:.1f} MB, longest stall "
                      f"{worst[0]:.2f} s, at 100 % {worst[1]:.2f} s, monotonic "
                      f"{row['monotonic']}", flush=True)
                print("  trace: " + " ".join(f"{t:.1f}:{f:.2f}" for t, _, f in row["trace"]),
                      flush=True)
        finally:
            server.close()
    if not a.no_export:
        html = os.path.join(a.inputs, "v.html")
        t0 = time.perf_counter()
        subprocess.run([a.tessera, "view", images[2048], "--html", "-o", html], check=True)
        report["export"] = {"seconds": time.perf_counter() - t0, "bytes": os.path.getsize(html)}
        print(f"--html of photo2048.png: {report['export']['bytes'] / 1e6:.1f} MB in "
              f"{report['export']['seconds']:.1f} s")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(report, f, indent=1)


if __name__ == "__main__":
    main()
