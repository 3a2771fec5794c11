#!/usr/bin/env python3
"""A quick side-by-side of tessera's top level against PVRTexTool's: whole-process wall time of
`tessera -j 2 compress IMAGE --quality high` and `PVRTexToolCLI -q pvrtcbest` (its own threads),
interleaved per run, medians of N runs, and their ratio per image. For the full table with
quality use bench/pvrtc_vs_peers.py; this is the check to run when only the top level changed.

Usage (from the repository root):
    /usr/bin/python3 bench/pvrtc_high_vs_best.py [--tessera build/bin/tessera]
        [--pvrtextool PATH] [--runs 3] IMAGE...
On a shared machine run it under `chrt -f 50` (as root) so that other jobs do not take the
cores from either tool. Standard library only.
"""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def wall_ms(cmd):
    t = time.perf_counter()
    subprocess.run(cmd, check=True, capture_output=True)
    return (time.perf_counter() - t) * 1000.0


def has_alpha(image):
    # PVRTexTool's RGB or RGBA format by the PNG's colour type (RGBA or grey + alpha: RGBA).
    with open(image, "rb") as f:
        head = f.read(26)
    return head[:8] == b"\x89PNG\r\n\x1a\n" and head[25] in (4, 6)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tessera", default=os.path.join(ROOT, "build", "bin", "tessera"))
    ap.add_argument("--pvrtextool", default=os.environ.get(
        "TESSERA_PVRTEXTOOL", os.path.expanduser("~/.cache/tessera/peers/PVRTexToolCLI")))
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("images", nargs="+")
    a = ap.parse_args()
    ratios = []
    print("| image | tessera high -j 2 (ms) | pvrtcbest (ms) | pvrtcbest / tessera |")
    print("|---|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        for image in a.images:
            fmt = "PVRTC1_4,UBN,lRGB" if has_alpha(image) else "PVRTC1_4_RGB,UBN,lRGB"
            t, p = [], []
            for _ in range(a.runs):
                t.append(wall_ms([a.tessera, "-j", "2", "compress", image, "--quality", "high",
                                  "-o", os.path.join(tmp, "t.pvr"), "-q"]))
                p.append(wall_ms([a.pvrtextool, "-i", image, "-o", os.path.join(tmp, "p.pvr"),
                                  "-f", fmt, "-q", "pvrtcbest", "-shh"]))
            mt, mp = statistics.median(t), statistics.median(p)
            ratios.append(mp / mt)
            print(f"| {os.path.basename(image)} | {mt:.0f} | {mp:.0f} | {mp / mt:.1f}x |",
                  flush=True)
    print(f"\nmedian ratio: {statistics.median(ratios):.1f}x")


if __name__ == "__main__":
    sys.exit(main())
