#!/usr/bin/env python3
"""`tessera view`'s server against what a careless file system or a hostile process of the same
user can do, through real HTTP requests (no browser): a file name that is not UTF-8, a second
server on the same --port, chunked and over-long bodies, connections that send half a request
or trickle one a byte every 2 s, results kept under --memory over many re-encodes, links out of
an input folder, the token kept out of the browser launcher's argv, and exact Host/Origin checks
(rebinding-style names, a duplicate Host). Each part ends by checking that the server still answers a real request.

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
        check("non-UTF-8 name: the command names its bytes, by the path as typed",
              r["command"] == f"tessera compress $'{d}/ic\\xf4ne.png' -o $'ic\\xf4ne.pvr' --quality fast",
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


def part_port(tmp):
    """--port on a port where a tessera view listens: the second one fails with one line and
    does not share the port; every request still reaches the first."""
    write_png(os.path.join(tmp, "sprite.png"), 32, 32, sprite, False)
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        fixed = s.getsockname()[1]
    p, _, port, token = start_server(["sprite.png", "--port", str(fixed)], tmp)
    if not port:
        return
    try:
        second = subprocess.run([TESSERA, "view", "sprite.png", "--port", str(fixed), "--no-open"],
                                cwd=tmp, capture_output=True, text=True, timeout=30)
        rc, err = second.returncode, second.stderr
    except subprocess.TimeoutExpired as e:
        rc, err = "still serving", (e.stderr or b"").decode() if isinstance(e.stderr, bytes) else ""
    lines = [x for x in err.splitlines() if x.strip()]
    check("--port in use: the second server exits non-zero", rc not in (0, "still serving"), rc)
    check("--port in use: one line naming the port", len(lines) == 1 and str(fixed) in err, err)
    ok = sum(get(port, "/?token=" + token)[0] == 200 for _ in range(20))
    check("--port in use: all 20 requests reach the first server", ok == 20, ok)
    stop(p)


def part_body(tmp):
    """A chunked 16 MiB body with the token: 413 while it streams, RSS bounded; an over-limit
    Content-Length: 413 at once, before any of the body; a small chunked body is read."""
    write_png(os.path.join(tmp, "sprite.png"), 32, 32, sprite, False)
    p, _, port, token = start_server(["sprite.png"], tmp)
    if not port:
        return
    time.sleep(0.5)
    before = rss_kib(p.pid)
    s = socket.create_connection(("127.0.0.1", port), timeout=20)
    s.sendall((f"POST /api/encode?token={token} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n"
               "Content-Type: application/json\r\nTransfer-Encoding: chunked\r\n\r\n").encode())
    reply = {}
    reader = threading.Thread(target=lambda: reply.update(r=read_reply(s)))
    reader.start()
    chunk = b"x" * 65536
    sent = 0
    try:
        while sent < 16 << 20:
            s.sendall(b"10000\r\n" + chunk + b"\r\n")
            sent += len(chunk)
        s.sendall(b"0\r\n\r\n")
    except (BrokenPipeError, ConnectionResetError, socket.timeout):
        pass
    reader.join(30)
    s.close()
    status = reply.get("r", (0, b""))[0]
    check("chunked 16 MiB body: 413", status == 413, (status, reply.get("r", (0, b""))[1][:200]))
    check("chunked 16 MiB body: not read whole", sent < 16 << 20, f"{sent} bytes sent")
    peak, after = rss_kib(p.pid, "VmHWM"), rss_kib(p.pid)
    print(f"chunked 16 MiB body: RSS {before} KiB before, {after} KiB after, peak {peak} KiB; "
          f"{sent} bytes sent")
    check("chunked 16 MiB body: RSS bounded (under +8 MiB, peak included)",
          peak - before < 8192 and after - before < 8192, (before, peak, after))
    # A declared length over the cap, none of it sent: refused at once.
    t0 = time.monotonic()
    status, _ = raw(port, (f"POST /api/encode?token={token} HTTP/1.1\r\nHost: 127.0.0.1:{port}"
                           "\r\nContent-Type: application/json\r\nContent-Length: 1073741824"
                           "\r\n\r\n").encode())
    took = time.monotonic() - t0
    check("over-limit Content-Length: 413 before the body", status == 413 and took < 2,
          (status, f"{took:.2f} s"))
    # A chunked body within the cap is read.
    body = b'{"input":0,"settings":{"quality":"fast"}}'
    status, got = raw(port, (f"POST /api/encode?token={token} HTTP/1.1\r\nHost: 127.0.0.1:{port}"
                             "\r\nContent-Type: application/json\r\nTransfer-Encoding: chunked"
                             "\r\nConnection: close\r\n\r\n").encode()
                      + b"%x\r\n" % len(body) + body + b"\r\n0\r\n\r\n")
    check("small chunked body: accepted", status == 200 and b'"state"' in got, got[-200:])
    # A body where none is read (another path): refused before reading it.
    status, _ = raw(port, (f"POST /api/job?token={token} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n"
                           "Transfer-Encoding: chunked\r\n\r\n").encode())
    check("chunked body to another path: refused", status in (404, 413), status)
    answers(port, token, "bodies")
    stop(p)


def part_line(tmp):
    """An endless request line, no token: the connection is shut down past 4 MiB (cpp-httplib
    0.11 would buffer all of it) and RSS stays bounded."""
    write_png(os.path.join(tmp, "sprite.png"), 32, 32, sprite, False)
    p, _, port, token = start_server(["sprite.png"], tmp)
    if not port:
        return
    time.sleep(0.5)
    before = rss_kib(p.pid)
    s = socket.create_connection(("127.0.0.1", port), timeout=20)
    sent = 0
    try:
        s.sendall(b"GET /")
        while sent < 64 << 20:
            s.sendall(b"a" * 65536)
            sent += 65536
    except (BrokenPipeError, ConnectionResetError, socket.timeout):
        pass
    s.close()
    time.sleep(0.2)
    peak = rss_kib(p.pid, "VmHWM")
    print(f"endless request line: {sent >> 20} MiB sent; RSS {before} KiB before, peak {peak} KiB")
    check("endless request line: the connection is cut before 64 MiB", sent < 64 << 20, sent)
    check("endless request line: peak RSS under +32 MiB", peak - before < 32768, (before, peak))
    answers(port, token, "endless request line")
    err = stop(p).decode(errors="replace")
    check("endless request line: one line in the terminal",
          len([x for x in err.splitlines() if "sent over" in x]) == 1, err)


def part_slow(tmp):
    """64 connections that send only a request line do not hold up a valid request; they are
    closed when their read times out."""
    write_png(os.path.join(tmp, "sprite.png"), 32, 32, sprite, False)
    p, _, port, token = start_server(["sprite.png"], tmp)
    if not port:
        return
    slow = []
    for _ in range(64):
        c = socket.create_connection(("127.0.0.1", port), timeout=30)
        c.sendall(b"GET / HTTP/1.1\r\n")
        slow.append(c)
    time.sleep(0.5)
    t0 = time.monotonic()
    status, body = get(port, "/?token=" + token, timeout=10)
    took = time.monotonic() - t0
    print(f"64 slow connections: a valid request answered in {took:.3f} s")
    check("64 slow connections: a valid request answered (10 s socket timeout)",
          status == 200 and b"tessera view" in body, (status, f"{took:.2f} s"))
    t0 = time.monotonic()
    closed = 0
    for c in slow:
        try:
            c.settimeout(max(0.1, 20 - (time.monotonic() - t0)))
            status, _ = read_reply(c)
            closed += 1
        except OSError:
            pass
        c.close()
    print(f"64 slow connections: closed by the server within {time.monotonic() - t0:.1f} s")
    check("64 slow connections: the server closes them (read timeout)",
          closed == 64 and time.monotonic() - t0 < 20, closed)
    answers(port, token, "slow connections")
    stop(p)


def part_trickle(tmp):
    """64 connections that send a request one byte every 2 s (each read well within the 3 s read
    timeout) do not hold up a valid request, which is answered while they are connected; the
    server closes each at its header deadline (10 s for the request line and headers), long
    before its ~100-byte request could be sent whole (about 200 s)."""
    write_png(os.path.join(tmp, "sprite.png"), 32, 32, sprite, False)
    p, _, port, token = start_server(["sprite.png"], tmp)
    if not port:
        return
    request = (f"GET /?token={token} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n"
               "\r\n").encode()
    sent = [0] * 64   # bytes each had sent when the server closed it
    closed = [False] * 64
    done = threading.Event()

    def trickle(i):
        c = socket.create_connection(("127.0.0.1", port), timeout=30)
        try:
            for b in request:
                if done.is_set():
                    return
                c.sendall(bytes([b]))
                sent[i] += 1
                ready, _, _ = select.select([c], [], [], 2.0)
                if ready:  # the server closed it (an end of file or a reset)
                    try:
                        gone = c.recv(1) == b""
                    except OSError:
                        gone = True
                    if gone:
                        closed[i] = True
                        return
        except OSError:
            closed[i] = True
        finally:
            c.close()

    threads = [threading.Thread(target=trickle, args=(i,), daemon=True) for i in range(64)]
    for t in threads:
        t.start()
    time.sleep(4)  # every one is mid-request, past a read timeout's worth of time
    connected = sum(1 for c in closed if not c)
    status, body = get(port, "/?token=" + token, timeout=10)
    still = sum(1 for c in closed if not c)
    print(f"64 trickling connections: {connected} connected before, {still} after a valid request")
    check("64 trickling connections: a valid request answered while they are connected",
          status == 200 and b"tessera view" in body and connected == 64 and still == 64,
          (status, connected, still))
    for t in threads:
        t.join(timeout=120)
    done.set()
    print(f"64 trickling connections: {sum(closed)} closed by the server, after "
          f"{min(sent)} to {max(sent)} of {len(request)} bytes")
    check("64 trickling connections: the server closes each before its request is whole "
          "(header deadline)", all(closed) and max(sent) < len(request), (sum(closed), max(sent)))
    answers(port, token, "trickling connections")
    err = stop(p).decode(errors="replace")
    check("trickling connections: a line in the terminal", "to send a request's headers" in err,
          err[-300:])


def part_memory(tmp):
    """30 re-encodes of a SIZE x SIZE input (noise: nothing shared between results) under
    --memory 64: RSS stays under the start's RSS plus the budget plus a margin, the oldest
    results are evicted (their job is gone, their blobs 404) and the pinned one is kept."""
    size = int(os.environ.get("TESSERA_VIEW_MEMORY_TEST_SIZE", "2048"))
    rows = b"".join(b"\0" + os.urandom(size * 3) for _ in range(size))
    with open(os.path.join(tmp, "noise.png"), "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", struct.pack(">IIBBBBB", size, size, 8, 2,
                                                                     0, 0, 0))
                + png_chunk(b"IDAT", zlib.compress(rows, 1)) + png_chunk(b"IEND", b""))
    budget = 32  # MiB: less than 30 results' .pvr files (1-2.7 MiB each) and the originals
    p, _, port, token = start_server(["noise.png", "--memory", str(budget)], tmp)
    if not port:
        return
    time.sleep(0.5)
    start = rss_kib(p.pid)
    settings = [{"quality": "fast", "format": f, "mip_levels": m}
                for m in range(15) for f in ("pvrtc1-4", "pvrtc1-2")][:30]
    jobs, rss = [], []
    t0 = time.monotonic()
    for i, s in enumerate(settings):
        job = encode(port, token, 0, s)
        jobs.append(job)
        if i == 0 and job.get("state") == "done":
            status, _ = get(port, f"/api/pin?token={token}&id={job['result']['id']}&pinned=1")
            check("memory: pin the first result", status == 200, status)
        rss.append(rss_kib(p.pid))
    took = time.monotonic() - t0
    done = sum(j.get("state") == "done" for j in jobs)
    check("memory: 30 encodes done", done == 30, [j.get("error") for j in jobs if j.get("state") != "done"])
    print(f"memory: {size}x{size}, --memory {budget}: RSS {start} KiB at start, "
          f"{max(rss)} KiB at most, {rss[-1]} KiB after 30 encodes ({took:.1f} s)")
    limit = start + (budget + 96) * 1024
    check(f"memory: RSS under start + {budget} MiB + 96 MiB after every encode", max(rss) < limit,
          (start, max(rss), limit))
    if done == 30:
        pinned, old = jobs[0]["result"], jobs[1]["result"]
        check("memory: the pinned result's texture is still served",
              get(port, f"/blob/{pinned['file']}?token={token}")[0] == 200)
        check("memory: an old unpinned result was evicted (its texture 404)",
              get(port, f"/blob/{old['file']}?token={token}")[0] == 404)
        check("memory: its job is forgotten",
              get(port, f"/api/job?token={token}&id={jobs[1]['id']}")[0] == 404)
        again = encode(port, token, 0, settings[1])
        check("memory: the same settings again encode again", again.get("state") == "done"
              and again.get("id") != jobs[1]["id"], again.get("id"))
        last = jobs[-1]["result"]
        check("memory: the newest result is served",
              get(port, f"/blob/{last['file']}?token={token}")[0] == 200)
    answers(port, token, "memory")
    stop(p)


def part_symlink(tmp):
    """A link in an input folder that resolves outside it is skipped, with a line naming it; a
    link to a file inside the folder is kept."""
    d = os.path.join(tmp, "linked")
    outside = os.path.join(tmp, "outside")
    os.makedirs(d)
    os.makedirs(outside)
    write_png(os.path.join(d, "a.png"), 32, 32, sprite, False)
    write_png(os.path.join(outside, "secret.png"), 32, 32, sprite, False)
    os.symlink(os.path.join(outside, "secret.png"), os.path.join(d, "out.png"))
    os.symlink(os.path.join("..", "outside", "secret.png"), os.path.join(d, "out2.png"))
    os.symlink("a.png", os.path.join(d, "in.png"))
    p, _, port, token = start_server([d], tmp)
    if not port:
        return
    status, body = get(port, "/?token=" + token)
    names = [i["name"] for i in page_data(body.decode())["inputs"]] if status == 200 else []
    check("symlinks: the links out of the folder are not inputs; the one inside is",
          names == ["a.png", "in.png"], names)
    answers(port, token, "symlinks")
    err = stop(p).decode(errors="replace")
    for name in ("out.png", "out2.png"):
        lines = [x for x in err.splitlines() if name in x]
        check(f"symlinks: one line in the terminal names {name}",
              len(lines) == 1 and "outside" in lines[0], err)
    check("symlinks: nothing said of the link inside", "in.png" not in err, err)


def part_opener(tmp):
    """The browser launcher gets a private page that redirects to the URL, never the token."""
    write_png(os.path.join(tmp, "sprite.png"), 32, 32, sprite, False)
    log = os.path.join(tmp, "opener.json")
    opener = os.path.join(tmp, "opener.py")
    with open(opener, "w") as f:
        f.write("#!/usr/bin/env python3\nimport json, os, stat, sys\n"
                "a = sys.argv[1:]\n"
                "info = {'argv': a}\n"
                "if a and os.path.isfile(a[0]):\n"
                "    info['mode'] = stat.S_IMODE(os.stat(a[0]).st_mode)\n"
                "    info['dir_mode'] = stat.S_IMODE(os.stat(os.path.dirname(a[0])).st_mode)\n"
                "    info['text'] = open(a[0]).read()\n"
                f"open({log!r} + '.tmp', 'w').write(json.dumps(info))\n"
                f"os.rename({log!r} + '.tmp', {log!r})\n")
    os.chmod(opener, 0o755)
    env = {**os.environ, "DISPLAY": ":99", "TESSERA_VIEW_OPENER": opener}
    p, _, port, token = start_server(["sprite.png"], tmp, env=env, no_open=False)
    if not port:
        return
    for _ in range(300):
        if os.path.exists(log):
            break
        time.sleep(0.1)
    info = json.load(open(log)) if os.path.exists(log) else {}
    argv = info.get("argv", [])
    check("opener: started with one argument", len(argv) == 1, info)
    check("opener: no token in its argv", argv and all(token not in a for a in argv), argv)
    check("opener: the page it opens is private (0600 in a 0700 folder)",
          info.get("mode") == 0o600 and info.get("dir_mode") == 0o700, info)
    check("opener: the page redirects to the URL with the token",
          f"http://127.0.0.1:{port}/?token={token}" in info.get("text", ""), info.get("text"))
    answers(port, token, "opener")
    stop(p)
    check("opener: the page is removed when the server stops",
          bool(argv) and not os.path.exists(argv[0]), argv)


def part_hosts(tmp):
    """Host and Origin must name this server exactly: rebinding-style names, a Host without a
    port, a duplicate Host are refused; then a real request still passes."""
    write_png(os.path.join(tmp, "sprite.png"), 32, 32, sprite, False)
    p, _, port, token = start_server(["sprite.png"], tmp)
    if not port:
        return
    t = "/?token=" + token
    for host in (f"localhost.evil.example:{port}", f"127.0.0.1.evil.example:{port}",
                 "127.0.0.1", "localhost", f"127.0.0.1:{port}.evil.example",
                 f"evil.example:{port}", f"127.0.0.1:{port + 1}", ""):
        status, _ = get(port, t, host=host)
        check(f"Host '{host}': refused", status in (400, 403), status)
    for origin in ("http://127.0.0.1.evil.example", f"http://127.0.0.1.evil.example:{port}",
                   f"http://localhost.evil.example:{port}", f"http://127.0.0.1:{port}.evil.example",
                   "http://127.0.0.1", "null", f"https://127.0.0.1:{port}"):
        status, _ = get(port, t, origin=origin)
        check(f"Origin '{origin}': refused", status == 403, status)
    for first, second in ((f"127.0.0.1:{port}", "evil.example"),
                          (f"127.0.0.1:{port}", f"127.0.0.1:{port}")):
        status, _ = raw(port, (f"GET {t} HTTP/1.1\r\nHost: {first}\r\nHost: {second}\r\n"
                               "Connection: close\r\n\r\n").encode())
        check(f"two Host headers ({second}): 400", status == 400, status)
    status, _ = get(port, t, origin=f"http://localhost:{port}", host=f"localhost:{port}")
    check("Host and Origin localhost:PORT pass", status == 200, status)
    answers(port, token, "hosts")
    stop(p)


PARTS = {"utf8": part_utf8, "port": part_port, "body": part_body, "line": part_line,
         "slow": part_slow, "trickle": part_trickle,
         "symlink": part_symlink, "opener": part_opener, "hosts": part_hosts,
         "memory": part_memory}


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
