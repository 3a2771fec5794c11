#!/usr/bin/env python3
"""Folder throughput: `tessera -j 2 compress IMAGES... -o DIR` against PVRTexToolCLI run once per
file, two at a time (`xargs -P 2`), on the shared images, for each pair of quality levels.

Usage (from the repository root):
    /usr/bin/python3 bench/pvrtc_batch.py [--runs 5] [--tessera build/bin/tessera]
        [--pvrtextool PATH] [--images ../shared/data/images] [--out docs/benchmarks/pvrtc_batch.md]

Both sides get the same files, 2 cores, and write one texture per input. ldr-rgb-10.png (127x128,
not a power of two) is given to both and fails alone in both. PVRTexTool is told RGB or RGBA per
file as tessera decides (tessera writes RGB where alpha is 255 everywhere): the RGB files go
through one `xargs -P 2` and the RGBA files through a second, one after the other. Timing is the
wall time of the whole folder, median of --runs runs, tessera and PVRTexTool alternated. Quality:
every output decoded with `tessera decompress` (bit-exact with PVRTexTool's decoder) and compared
with the input by `tessera compare --json`; the tables give the mean over the power-of-two
images. Standard library only.
"""
import argparse
import datetime
import json
import os
import platform
import shlex
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchlib import cpu_model, write_report  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PAIRS = [("fast", "pvrtcfastest"), ("normal", "pvrtcnormal"), ("high", "pvrtcbest")]


def timed(cmd, **kw):
    t0 = time.perf_counter()
    subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, **kw)
    return time.perf_counter() - t0


def quality(tessera, src, tex, tmp):
    dec = os.path.join(tmp, "dec.png")
    if subprocess.run([tessera, "decompress", tex, "-o", dec, "-q"]).returncode != 0:
        return None
    out = subprocess.run([tessera, "compare", src, dec, "--json"], capture_output=True, text=True)
    j = json.loads(out.stdout)
    return j["psnr_rgb"], j["ssim_gray"], j.get("psnr_alpha")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--tessera", default=os.path.join(ROOT, "build", "bin", "tessera"))
    cache = os.environ.get("TESSERA_CACHE",
                           os.path.join(os.environ.get("XDG_CACHE_HOME",
                                                       os.path.expanduser("~/.cache")), "tessera"))
    ap.add_argument("--pvrtextool", default=os.path.join(cache, "peers", "PVRTexToolCLI"))
    ap.add_argument("--images", default=os.path.join(ROOT, "..", "shared", "data", "images"))
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "benchmarks", "pvrtc_batch.md"))
    ap.add_argument("--pairs", default="fast,normal,high",
                    help="tessera levels to run, each against its PVRTexTool pair")
    args = ap.parse_args()
    pairs = [p for p in PAIRS if p[0] in args.pairs.split(",")]

    images = sorted(os.path.join(args.images, n) for n in os.listdir(args.images)
                    if n.endswith(".png"))
    tmp = tempfile.mkdtemp(prefix="tessera-batch-bench-")
    try:
        # tessera's RGB/RGBA decision per file (from a fast batch with --json).
        probe = subprocess.run([args.tessera, "compress", *images, "-o",
                                os.path.join(tmp, "probe"), "--quality", "fast", "--json"],
                               capture_output=True, text=True)
        alpha, ok, mpix = {}, [], 0.0
        for line in probe.stdout.splitlines():
            j = json.loads(line)
            if j.get("status") == "done":
                alpha[j["input"]] = j["has_alpha"]
                ok.append(j["input"])
                mpix += j["width"] * j["height"] / 1e6
        rows = []
        for tq, pq in pairs:
            t_dir, p_dir = os.path.join(tmp, "t-" + tq), os.path.join(tmp, "p-" + pq)
            t_cmd = [args.tessera, "-j", "2", "compress", *images, "-o", t_dir, "--quality", tq,
                     "--quiet"]
            # One xargs per RGB/RGBA group; every input (the non-power-of-two one included).
            groups = {False: [], True: []}
            for img in images:
                groups[alpha.get(img, False)].append(img)
            p_script = []
            for has_alpha, files in groups.items():
                if not files:
                    continue
                fmt = "PVRTC1_4,UBN,lRGB" if has_alpha else "PVRTC1_4_RGB,UBN,lRGB"
                p_script.append(
                    "printf '%s\\n' " + " ".join(shlex.quote(os.path.basename(f)) for f in files) +
                    f" | xargs -P 2 -I{{}} {shlex.quote(args.pvrtextool)} -i {{}} -o "
                    f"{shlex.quote(p_dir)}/{{}}.pvr -f {fmt} -q {pq} -shh")
            p_cmd = ["bash", "-c", "cd " + shlex.quote(args.images) + " && " +
                     " ; ".join(p_script)]
            t_times, p_times = [], []
            for _ in range(args.runs):
                for d in (t_dir, p_dir):
                    shutil.rmtree(d, ignore_errors=True)
                    os.makedirs(d)
                t_times.append(timed(t_cmd))
                p_times.append(timed(p_cmd))
            qs = {"t": [], "p": []}
            for img in ok:
                stem = os.path.splitext(os.path.basename(img))[0]
                qs["t"].append(quality(args.tessera, img, os.path.join(t_dir, stem + ".pvr"), tmp))
                qs["p"].append(quality(args.tessera, img,
                                       os.path.join(p_dir, os.path.basename(img) + ".pvr"), tmp))
            made_t = len([n for n in os.listdir(t_dir) if n.endswith(".pvr")])
            made_p = len([n for n in os.listdir(p_dir) if n.endswith(".pvr")])

            def mean(side, k):
                vals = [q[k] for q in qs[side] if q and q[k] is not None]
                return statistics.mean(vals) if vals else float("nan")

            tm, pm = statistics.median(t_times), statistics.median(p_times)
            rows.append((tq, pq, tm, pm, made_t, made_p, mean("t", 0), mean("p", 0),
                         mean("t", 1), mean("p", 1)))
            print(f"{tq} {tm:.3f}s vs {pq} {pm:.3f}s: {pm / tm:.1f}x", flush=True)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)

    date = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    lines = [
        "# PVRTC folder throughput: tessera batch vs PVRTexToolCLI per file",
        "",
        f"Machine: {cpu_model()}, {os.cpu_count()} logical CPUs, {platform.system()} "
        f"{platform.release()}. Date: {date}. Both sides on 2 cores.",
        "",
        f"Command: `/usr/bin/python3 bench/pvrtc_batch.py --runs {args.runs}`"
        + (f" `--pairs {args.pairs}`" if args.pairs != "fast,normal,high" else ""),
        "",
        f"Input: the {len(images)} PNGs of `{os.path.relpath(args.images, ROOT)}` ({mpix:.2f} MPixel in the "
        f"{len(ok)} power-of-two ones; ldr-rgb-10.png, 127x128, fails alone on both sides).",
        "",
        "- tessera: `tessera -j 2 compress IMAGES... -o DIR --quality Q --quiet` (one process, "
        "files spread over 2 workers).",
        "- PVRTexTool 4.17: `xargs -P 2 PVRTexToolCLI -i IMG -o OUT -f PVRTC1_4[_RGB],UBN,lRGB "
        "-q Q -shh` (one process per file, two at a time; RGB/RGBA as tessera decides).",
        "- Time: wall time of the whole folder, median of the runs, the two sides alternated.",
        "- Quality: mean PSNR (RGB, dB) and SSIM (Rec.709 grey) over the power-of-two images, "
        "every file decoded by `tessera decompress`.",
        "",
        "| tessera | PVRTexTool | tessera s | PVRTexTool s | speed-up | files written (t / P) | "
        "PSNR t | PSNR P | SSIM t | SSIM P |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for tq, pq, tm, pm, mt, mp, pt, pp, st, sp in rows:
        lines.append(f"| {tq} | {pq} | {tm:.3f} | {pm:.3f} | **{pm / tm:.1f}x** | {mt} / {mp} | "
                     f"{pt:.3f} | {pp:.3f} | {st:.4f} | {sp:.4f} |")
    lines.append("")
    write_report(args.out, lines, "## Notes")


if __name__ == "__main__":
    main()
