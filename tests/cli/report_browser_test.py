#!/usr/bin/env python3
"""The demo report in a real browser: headless Chromium loads out/report.html at a phone's width
and at a laptop's, and every image and plot must resolve (load with a non-zero size), the page
must not scroll sideways on the phone, and it must carry the viewport meta, the footer (version,
date, command line, machine), SVG plots and colour bars, and no literal Markdown backticks.

Usage: report_browser_test.py PATH/TO/tessera [CHROMIUM]
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, finish, missing_part  # noqa: E402

TESSERA = sys.argv[1]
CHROMIUM = sys.argv[2] if len(sys.argv) > 2 else shutil.which("chromium")

PROBE = """<script>
window.addEventListener("load", () => {
  let bad = [];
  for (const img of document.images) {
    const ok = img.complete && img.naturalWidth > 0 && img.naturalHeight > 0;
    img.setAttribute("data-ok", ok ? "1" : "0");
    if (!ok) bad.push(img.getAttribute("src"));
  }
  document.body.setAttribute("data-images", String(document.images.length));
  document.body.setAttribute("data-broken", bad.join(" "));
  document.body.setAttribute("data-overflow",
      document.documentElement.scrollWidth > window.innerWidth + 1 ? "1" : "0");
  document.body.setAttribute("data-text", document.body.innerText.includes("`") ? "1" : "0");
});
</script>"""


def load(page, width, height):
    """The DOM after load at a window of width x height, as text."""
    p = subprocess.run([CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu",
                        "--hide-scrollbars", f"--window-size={width},{height}",
                        "--virtual-time-budget=10000", "--dump-dom", "file://" + page],
                       capture_output=True, text=True, timeout=180)
    return p.stdout


def attr(dom, name):
    m = re.search(r'<body[^>]*\s' + name + r'="([^"]*)"', dom)
    return m.group(1) if m else None


if not CHROMIUM:
    print("chromium not found (scripts/setup.sh installs it)")
    print("0 passed, 1 failed")
    sys.exit(1)

tmp = tempfile.mkdtemp(prefix="tessera-report-")
try:
    out = os.path.join(tmp, "out")
    p = subprocess.run([TESSERA, "demo", "-o", out, "--size", "64", "-q"], capture_output=True,
                       text=True, timeout=600)
    check("demo runs", p.returncode == 0, p.stderr)
    with open(os.path.join(out, "report.html"), encoding="utf-8") as f:
        html = f.read()
    check("viewport meta", '<meta name="viewport"' in html)
    footer = re.search(r"<footer>(.*?)</footer>", html, re.S)
    check("footer", footer is not None, html[-500:])
    if footer:
        text = footer.group(1)
        check("footer: version", "tessera 0." in text or "tessera 1." in text, text)
        check("footer: date", re.search(r"\d{4}-\d\d-\d\d \d\d:\d\d UTC", text) is not None, text)
        check("footer: command line", "tessera demo -o" in text, text)
        check("footer: machine", "hardware threads" in text, text)
    # The first screen: the summary right under the title, one row per paper's headline, each
    # linking to a section that exists.
    summary = re.search(r'<h1>[^<]*</h1>\s*<section id="summary">(.*?)</section>', html, re.S)
    check("summary first", summary is not None, html[:600])
    if summary:
        links = re.findall(r'href="#(\w+)"', summary.group(1))
        check("summary covers the three papers", {"pvrtc", "seams", "aa"} <= set(links), links)
        for anchor in set(links):
            check(f"summary link #{anchor} resolves", f'<h2 id="{anchor}">' in html, anchor)
        if "PVRTexTool not found" in summary.group(1):
            missing_part("pvrtextool", "PVRTexToolCLI not found: the summary has no peer column")
        else:
            check("summary compares with PVRTexTool", "pvrtcbest:" in summary.group(1),
                  summary.group(1)[:300])
    svgs = re.findall(r'<img src="(img/[^"]+\.svg)"', html)
    check("SVG plots in the page", len(svgs) >= 2, str(svgs))
    check("a colour bar", any("colourbar" in s for s in svgs), str(svgs))
    check("a quality-against-time plot", any("quality-time" in s for s in svgs), str(svgs))

    page = os.path.join(out, "report_probe.html")
    with open(page, "w", encoding="utf-8") as f:
        f.write(html.replace("</body>", PROBE + "</body>"))
    for label, (w, h) in (("phone", (390, 844)), ("laptop", (1366, 768))):
        dom = load(page, w, h)
        n = attr(dom, "data-images")
        check(label + ": page loaded", n is not None, dom[:300])
        if n is None:
            continue
        check(label + ": images present", int(n) >= 20, n)
        check(label + ": every image and plot resolves", attr(dom, "data-broken") == "",
              attr(dom, "data-broken"))
        check(label + ": no literal backticks in the text", attr(dom, "data-text") == "0")
        if label == "phone":
            check("phone: no sideways scrolling", attr(dom, "data-overflow") == "0")
    # The probe must be able to fail: a page with a missing image reports it.
    with open(page, "w", encoding="utf-8") as f:
        f.write(html.replace("</body>", '<img src="img/missing.png">' + PROBE + "</body>"))
    dom = load(page, 1366, 768)
    check("a missing image is caught", "img/missing.png" in (attr(dom, "data-broken") or ""),
          attr(dom, "data-broken"))
finally:
    shutil.rmtree(tmp, ignore_errors=True)

sys.exit(finish())
