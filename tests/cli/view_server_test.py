#!/usr/bin/env python3
"""`tessera view`'s server against what a careless file system or a hostile process of the same
user can do, through real HTTP requests (no browser): a file name that is not UTF-8, a second
server on the same --port, chunked and over-long bodies, connections that send half a request,
results kept under --memory over many re-encodes, links out of an input folder, the token kept
out of the browser launcher's argv, and exact Host/Origin checks (rebinding-style names, a
duplicate Host). Each part ends by checking that the server still answers a real request.

Usage: view_server_test.py PATH/TO/tessera [PART...]   (parts: the names in PARTS)
"""
import json
import os
import select
import shutil
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import threading
import time
import zlib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, finish, png_chunk, write_png  # noqa: E402

TESSERA = os.path.abspath(sys.argv[1])
ONLY = sys.argv[2:]


def sprite(x, y):
    return ((x * 37 + y * 11) % 256, (x * 4) % 256, (255 - y * 4) % 256, 255)


def start_server(args, cwd, env=None, no_open=True):
    """Starts `tessera view ARGS`; returns (process, URL, port, token). The URL is the first line
    of stdout, read with a bounded wait."""
    extra = ["--no-open"] if no_open else []
    p = subprocess.Popen([TESSERA, "view", *args, *extra], cwd=cwd, stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, env=env)
    ready, _, _ = select.select([p.stdout], [], [], 120)
    line = p.stdout.readline().decode().strip() if ready else ""
    ok = line.startswith("http://127.0.0.1:") and "token=" in line
    check("server prints its URL", ok, line)
    if not ok:
        p.kill()
        return p, "", 0, ""
    port = int(line.split(":")[2].split("/")[0])
    return p, line, port, line.split("token=")[1]


def stop(p):
    """SIGTERM; returns stderr (bytes)."""
    p.send_signal(signal.SIGTERM)
    try:
        p.wait(timeout=60)
    except subprocess.TimeoutExpired:
        p.kill()
        p.wait()
    return p.stderr.read()


def raw(port, data, timeout=10, read=True):
    """Sends `data` (bytes) on a new connection; returns (status, headers+body bytes) of the reply
    (status 0 when none came)."""
    s = socket.create_connection(("127.0.0.1", port), timeout=timeout)
    try:
        s.sendall(data)
        if not read:
            return 0, b""
        return read_reply(s)
    finally:
        s.close()


def read_reply(s):
    got = b""
    try:
        while True:
            chunk = s.recv(65536)
            if not chunk:
                break
            got += chunk
            head, sep, body = got.partition(b"\r\n\r\n")
            if sep:
                length = [int(h.split(b":")[1]) for h in head.split(b"\r\n")
                          if h.lower().startswith(b"content-length:")]
                if length and len(body) >= length[0]:
                    break
    except (socket.timeout, ConnectionResetError):
        pass
    try:
        status = int(got.split(b" ", 2)[1]) if got.startswith(b"HTTP/1.1 ") else 0
    except ValueError:
        status = 0
    return status, got


def get(port, path, host=None, origin=None, timeout=30):
    """(status, body bytes) of GET `path`."""
    h = f"Host: {f'127.0.0.1:{port}' if host is None else host}\r\n"
    if origin:
        h += f"Origin: {origin}\r\n"
    status, got = raw(port, f"GET {path} HTTP/1.1\r\n{h}Connection: close\r\n\r\n".encode(),
                      timeout=timeout)
    return status, got.partition(b"\r\n\r\n")[2]


def post(port, path, body, timeout=30):
    data = body.encode()
    status, got = raw(port, (f"POST {path} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nContent-Type: "
                             f"application/json\r\nContent-Length: {len(data)}\r\nConnection: "
                             "close\r\n\r\n").encode() + data, timeout=timeout)
    return status, got.partition(b"\r\n\r\n")[2]


def answers(port, token, name):
    """The server keeps running: a real request gets the page."""
    status, body = get(port, "/?token=" + token)
    check(name + ": the server still answers a real request",
          status == 200 and b"tessera view" in body, status)


def encode(port, token, index, settings, wait=True):
    """Posts an encode; returns the job (waited for when `wait`; bounded)."""
    status, data = post(port, "/api/encode?token=" + token,
                        json.dumps({"input": index, "settings": settings}))
    if status != 200:
        return {"state": "http", "status": status, "error": data[:200]}
    job = json.loads(data)
    for _ in range(6000):  # 10 minutes at most
        if not wait or job["state"] in ("done", "error"):
            break
        time.sleep(0.1)
        status, data = get(port, f"/api/job?token={token}&id={job['id']}")
        if status != 200:
            return {"state": "http", "status": status, "error": data[:200]}
        job = json.loads(data)
    return job


def page_data(html):
    start = html.index('<script id="tessera-data" type="application/json">')
    start = html.index(">", start) + 1
    return json.loads(html[start:html.index("</script>", start)])


def rss_kib(pid, field="VmRSS"):
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith(field + ":"):
                return int(line.split()[1])
    return 0


# ---- the parts ---------------------------------------------------------------------------------

def part_utf8(tmp):
    """A file name that is not UTF-8: the export does not abort; the server shows the name with
    U+FFFD for the bad byte, encodes the file by its bytes and gives the command that names it."""
    d = os.path.join(tmp, "utf8")
    os.makedirs(d)
    bad = os.path.join(d.encode(), b"ic\xf4ne.png")
    write_png(bad, 32, 32, sprite, False)
    write_png(os.path.join(d, "plain.png"), 32, 32, sprite, False)
    html = os.path.join(tmp, "utf8.html")
    p = subprocess.run([TESSERA, "view", d, "--quality", "fast", "--html", "-o", html, "-q"],
                       capture_output=True, timeout=300)
    check("non-UTF-8 name: --html exits 0", p.returncode == 0, (p.returncode, p.stderr[-300:]))
    if p.returncode == 0:
        with open(html, encoding="utf-8") as f:
            names = [i["name"] for i in page_data(f.read())["inputs"]]
        check("non-UTF-8 name: the export names it with U+FFFD", "ic\ufffdne.png" in names, names)
    p, _, port, token = start_server([d], tmp)
    if not port:
        return
    status, body = get(port, "/?token=" + token)
    check("non-UTF-8 name: the page is served", status == 200, (status, body[:200]))
    names = []
    if status == 200:
        names = [i["name"] for i in page_data(body.decode())["inputs"]]
        check("non-UTF-8 name: the page names it with U+FFFD", "ic\ufffdne.png" in names, names)
    index = names.index("ic\ufffdne.png") if "ic\ufffdne.png" in names else 0
    job = encode(port, token, index, {"quality": "fast"})
    check("non-UTF-8 name: its encode is done", job.get("state") == "done", job)
    if job.get("state") == "done":
        r = job["result"]
        check("non-UTF-8 name: the command names its bytes",
              r["command"] == "tessera compress $'ic\\xf4ne.png' -o $'ic\\xf4ne.pvr' --quality fast",
              r["command"])
        status, tex = get(port, f"/blob/{r['file']}?token={token}")
        words = ["bash", "-c", r["command"].replace("tessera ", shlex_quote(TESSERA) + " ", 1) + " -q"]
        made = subprocess.run(words, cwd=d, capture_output=True, timeout=300)
        out = os.path.join(d.encode(), b"ic\xf4ne.pvr")
        same = made.returncode == 0 and os.path.exists(out) and open(out, "rb").read() == tex
        check("non-UTF-8 name: the texture served is the command's", status == 200 and same,
              (status, made.returncode, made.stderr[-200:]))
    answers(port, token, "non-UTF-8 name")
    stop(p)


def shlex_quote(s):
    import shlex
    return shlex.quote(s)


PARTS = {"utf8": part_utf8}


def main():
    for name, part in PARTS.items():
        if ONLY and name not in ONLY:
            continue
        tmp = tempfile.mkdtemp(prefix=f"tessera-view-{name}-")
        t0 = time.monotonic()
        try:
            part(tmp)
        finally:
            shutil.rmtree(tmp, ignore_errors=True)
        print(f"part {name}: {time.monotonic() - t0:.1f} s")


main()
sys.exit(finish())
