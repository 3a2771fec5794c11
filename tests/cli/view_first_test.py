#!/usr/bin/env python3
"""`tessera view`'s first draw before any result (view_first.mjs in headless Chromium, the
page's encode requests held back so no result exists yet): the page draws the input's original
from the server's "original" blob, says "encoding…" on the right, and its readout's texel is
the input PNG's (exact, alpha included); then the result is drawn as usual, the same texel
still read as the original. The static export has no such blob (its results are inline).
Screenshots go to OUT (the build tree).

Usage: view_first_test.py PATH/TO/tessera PUPPETEER_DIR OUT [CHROMIUM]
"""
import json
import os
import select
import shutil
import signal
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, finish, write_png  # noqa: E402
from view_harness import ViewTest, page_data  # noqa: E402

T = ViewTest("view_first")
TESSERA, PUPPETEER, OUT, CHROMIUM, SCRIPT = T.tessera, T.puppeteer, T.out, T.chromium, T.script

# Every check needs the browser: without it the test is skipped (exit 77), or fails under
# TESSERA_TEST_REQUIRE.
T.require_browser()


def texel(x, y):
    """Translucent texels: a canvas would premultiply them, the page must read them exactly."""
    return ((x * 37 + y * 11) % 256, (x * 5) % 256, (255 - y * 3) % 256, 40 + (x + y) % 200)


shutil.rmtree(OUT, ignore_errors=True)  # this run's screenshots only
os.makedirs(OUT, exist_ok=True)
with tempfile.TemporaryDirectory() as tmp:
    N = 256
    png = write_png(os.path.join(tmp, "first.png"), N, N, texel, True)
    p = subprocess.Popen([TESSERA, "view", png, "--no-open"], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    try:
        ready, _, _ = select.select([p.stdout], [], [], 120)
        url = p.stdout.readline().strip() if ready else ""
        check("server prints its URL", url.startswith("http://127.0.0.1:"), url)
        b = subprocess.run(["node", SCRIPT, PUPPETEER, CHROMIUM, url, OUT], capture_output=True,
                           text=True, timeout=600)
        try:
            r = json.loads(b.stdout.strip().splitlines()[-1])
        except (ValueError, IndexError):
            r = {"errors": ["no JSON from view_first.mjs: " + b.stderr[-2000:]], "steps": {}}
    finally:
        p.send_signal(signal.SIGTERM)
        try:
            p.wait(timeout=60)
        except subprocess.TimeoutExpired:
            p.kill()
    s = r["steps"]
    check("page: no errors", not r["errors"], r["errors"])
    first = s.get("first", {})
    check("original drawn while the encode is held: no result in the page",
          first.get("drawn") == "original:0:fit" and first.get("results") == 0
          and s.get("held", 0) >= 1, (first, s.get("held")))
    check("original: left pane 'original', right pane 'encoding…', progress shown",
          first.get("caption_a") == "original" and first.get("caption_b") == "encoding…"
          and first.get("busy"), first)
    t = s.get("texel", {})
    x, y = int(t.get("x", -1)), int(t.get("y", -1))
    want = ",".join(map(str, texel(x, y))) if 0 <= x < N and 0 <= y < N else "?"
    check("original: the readout's texel is the PNG's (exact, with alpha)",
          t.get("original") == want and t.get("decoded") == "" and "encoding" in t.get("text", ""),
          (t, want))
    check("original: wipe mode draws it too", s.get("wipe", {}).get("drawn") == "original:0:32"
          and "encoding" in s.get("wipe", {}).get("caption_a", ""), s.get("wipe"))
    check("original: no sideways scroll on a phone (390x844)", s.get("phone_overflow") is False,
          s.get("phone_overflow"))
    after = s.get("after", {})
    check("then the result is drawn as usual", after.get("drawn", "").startswith("r0:")
          and after.get("results", 0) >= 1 and after.get("caption_b") != "encoding…", after)
    a = s.get("after_texel", {})
    x, y = int(a.get("x", -1)), int(a.get("y", -1))  # the layout may move it by a texel
    want = ",".join(map(str, texel(x, y))) if 0 <= x < N and 0 <= y < N else "?"
    check("result: the readout reads the result's original (the PNG's) and a decoded texel",
          a.get("original") == want and len(a.get("decoded", "").split(",")) == 4, (a, want))

    html = os.path.join(tmp, "first.html")
    e = subprocess.run([TESSERA, "view", png, "--html", "-o", html], capture_output=True,
                       text=True, timeout=600)
    check("static export runs", e.returncode == 0, e.stderr)
    if e.returncode == 0:
        with open(html, encoding="utf-8") as f:
            data = page_data(f.read())
        check("static export: inputs carry no original blob (results are inline)",
              all("original" not in i for i in data["inputs"]) and data["results"],
              data["inputs"])
sys.exit(finish())
