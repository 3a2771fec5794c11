#!/usr/bin/env python3
"""The progress bar of a single long `tessera compress`: on a terminal (a pty) a 512x512
--quality high encode draws a bar on stderr (fraction, MPixel/s, ETA) and erases it before the
summary line; piped, or with -q or --json, there is no bar; and the texture's bytes are the same
either way. The bar's delay is set for each run (TESSERA_PROGRESS_DELAY), so no check depends on
how long an encode takes.

Usage: cli_progress_test.py PATH/TO/tessera
"""
import os
import struct
import subprocess
import shutil
import sys
import tempfile
import zlib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
import cli_harness  # noqa: E402
from cli_harness import check, finish  # noqa: E402

TESSERA = os.path.abspath(sys.argv[1])
SIZE = 512


def write_png(path, width, height):
    """A deterministic RGB test image with edges, gradients and texture (no imaging library)."""
    rows = []
    for y in range(height):
        row = bytearray(1 + 3 * width)  # filter byte 0
        for x in range(width):
            i = 1 + 3 * x
            row[i] = (x ^ y) & 255
            row[i + 1] = (x * 3 + y * 5 + ((x * y) >> 7)) & 255
            row[i + 2] = 255 if ((x >> 5) + (y >> 5)) & 1 else (x * x + y * y) >> 13 & 255
        rows.append(bytes(row))

    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data +
                struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(b"".join(rows), 6)))
        f.write(chunk(b"IEND", b""))


def run_on_pty(args, delay=None):
    """Runs tessera on a terminal; `delay` sets TESSERA_PROGRESS_DELAY (the bar's delay, s)."""
    if delay is not None:
        os.environ["TESSERA_PROGRESS_DELAY"] = str(delay)
    else:
        os.environ.pop("TESSERA_PROGRESS_DELAY", None)
    """Runs tessera on a new terminal; returns (exit code, bytes)."""
    return cli_harness.run_on_pty(TESSERA, args)


tmp = tempfile.mkdtemp(prefix="tessera-progress-")
try:
    png = os.path.join(tmp, "big.png")
    write_png(png, SIZE, SIZE)
    tty_pvr, piped_pvr = os.path.join(tmp, "tty.pvr"), os.path.join(tmp, "piped.pvr")
    base = ["compress", png, "--quality", "high"]

    rc, text = run_on_pty([*base, "-o", tty_pvr], delay=0)
    check("terminal: exit 0", rc == 0, repr(text[-300:]))
    check("terminal: a bar is drawn", text.count(b"\r[") >= 2, repr(text[:300]))
    check("terminal: the bar shows a percentage, MPixel/s and the time left",
          b"%  " in text and b" MPixel/s  ETA " in text, repr(text[:300]))
    check("terminal: the bar reaches the end",
          b"[" + b"=" * 27 in text, repr(text[-300:]))
    summary_at = text.find(b"wrote ")
    check("terminal: the summary follows",
          summary_at > 0 and b"PSNR" in text[summary_at:], repr(text[-300:]))
    check("terminal: the bar is erased before the summary",
          text[:summary_at].endswith(b"\r\x1b[K"), repr(text[max(0, summary_at - 80):summary_at]))
    check("terminal: nothing after the summary line",
          b"\r[" not in text[summary_at:], repr(text[summary_at:]))

    p = subprocess.run([TESSERA, *base, "-o", piped_pvr], capture_output=True, timeout=600)
    check("piped: exit 0", p.returncode == 0, p.stderr.decode(errors="replace"))
    check("piped: no bar", b"\r" not in p.stderr and b"ETA" not in p.stderr and
          b"\x1b" not in p.stderr and b"ETA" not in p.stdout, repr(p.stderr[:300]))
    check("piped: the summary line", p.stdout.startswith(b"wrote "), repr(p.stdout[:200]))
    with open(tty_pvr, "rb") as a, open(piped_pvr, "rb") as b:
        check("the bar does not change the texture", a.read() == b.read())

    # -q and --json: no bar, even with the delay at 0 (the same command without them draws one:
    # the negative control).
    mid = os.path.join(tmp, "mid.png")
    write_png(mid, 128, 128)
    rc, text = run_on_pty(["compress", mid, "--quality", "high", "-o",
                           os.path.join(tmp, "flag.pvr")], delay=0)
    check("terminal, delay 0: a bar", rc == 0 and b"\r[" in text, repr(text[:300]))
    for flag in ("-q", "--json"):
        rc, text = run_on_pty(["compress", mid, "--quality", "high", "-o",
                               os.path.join(tmp, "flag.pvr"), flag], delay=0)
        check(f"terminal {flag}: exit 0", rc == 0, repr(text[-300:]))
        check(f"terminal {flag}: no bar", b"\r[" not in text and b"ETA" not in text,
              repr(text[:300]))
        if flag == "-q":
            check("terminal -q: prints nothing", text == b"", repr(text[:300]))
        else:
            check("terminal --json: the JSON object only", text.startswith(b"{"),
                  repr(text[:300]))

    # An encode shorter than the delay leaves no bar on a terminal (the delay set far beyond it).
    small = os.path.join(tmp, "small.png")
    write_png(small, 64, 64)
    rc, text = run_on_pty(["compress", small, "-o", os.path.join(tmp, "small.pvr")], delay=600)
    check("terminal, short encode: no bar", rc == 0 and b"\r[" not in text and
          text.startswith(b"wrote "), repr(text[:300]))
finally:
    shutil.rmtree(tmp, ignore_errors=True)

sys.exit(finish())
