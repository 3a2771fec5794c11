#!/usr/bin/env python3
"""Quality against encode time for PVRTC encoder schedules (tessera's presets and variants).

Usage (from the repository root):
    /usr/bin/python3 bench/pvrtc_schedules.py [--tessera build/bin/tessera] [--runs N]
        [--images ../shared/data/images] [--bpp 4|2] [--out docs/benchmarks/pvrtc_schedules.md]
        [--schedule "LABEL=ARGS"]...

Each schedule is a set of `tessera compress` options (for example
"fast + 1 sweep=--quality fast --iterations 1"); without --schedule the default list below runs.
For every power-of-two PNG (ldr-rgb-10.png, 127x128, is skipped) and every schedule, tessera
-j 1 compress --json reports the in-process encode time (time_ms: no process start-up, PNG read
or file write) and the PSNR / SSIM of the result. Times are medians of N runs, the schedules of
one image run round-robin; each image's time is scaled to a 512² image (x 512² / its pixels) and
the means give every image the same weight, as the speed targets do. Whole-process times and
the PVRTexTool peer are in bench/pvrtc_vs_peers.py. Standard library only.
"""
import argparse
import datetime
import json
import os
import platform
import shlex
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchlib import cpu_model, write_report  # noqa: E402
from pvrtc_vs_peers import is_pow2, png_size, source_commit  # noqa: E402

DEFAULT_SCHEDULES = [
    ("fast (preset: the paper's dilation)", "--quality fast"),
    ("fast + 1 least-squares sweep", "--quality fast --iterations 1"),
    ("fast + 2 least-squares sweeps", "--quality fast --iterations 2"),
    ("normal (preset)", "--quality normal"),
    ("normal, 2 exact-search rounds", "--quality normal --exact-search-rounds 2"),
    ("high without the crossover", "--quality high --iterations 3"),
    ("high (preset)", "--quality high"),
]


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError(f"{shlex.join(cmd)} failed ({p.returncode}): {p.stderr.strip()}")
    return p.stdout


def mean(values):
    values = [v for v in values if v is not None]
    return sum(values) / len(values) if values else None


def fmt(v, spec=".2f"):
    return "-" if v is None else format(v, spec)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--tessera", default=os.path.join(ROOT, "build", "bin", "tessera"))
    ap.add_argument("--runs", type=int, default=3, help="timed runs per schedule and image")
    ap.add_argument("--images", default=os.path.join(ROOT, "..", "shared", "data", "images"))
    ap.add_argument("--bpp", type=int, choices=(4, 2), default=4)
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "benchmarks",
                                                  "pvrtc_schedules.md"))
    ap.add_argument("--schedule", action="append", metavar="LABEL=ARGS",
                    help="a schedule: a label, '=', then tessera compress options")
    args = ap.parse_args()
    if args.runs < 1:
        sys.exit("pvrtc_schedules: --runs must be at least 1")
    if not os.path.isfile(args.tessera):
        sys.exit(f"pvrtc_schedules: {args.tessera} not found (build tessera first)")
    if not os.path.isdir(args.images):
        sys.exit(f"pvrtc_schedules: {args.images} not found (the shared data folder)")
    schedules = DEFAULT_SCHEDULES
    if args.schedule:
        schedules = []
        for s in args.schedule:
            label, sep, opts = s.partition("=")
            if not sep or not label.strip():
                sys.exit(f"pvrtc_schedules: --schedule {s!r}: expected LABEL=ARGS")
            schedules.append((label.strip(), opts.strip()))

    images = []
    for name in sorted(os.listdir(args.images)):
        path = os.path.join(args.images, name)
        size = png_size(path) if name.endswith(".png") else None
        if size and is_pow2(size[0]) and is_pow2(size[1]):
            images.append((name, path, size))
    if not images:
        sys.exit(f"pvrtc_schedules: no power-of-two PNG in {args.images}")

    rows = {label: [] for label, _ in schedules}  # per image: ms per 512², psnr, alpha, ssim
    with tempfile.TemporaryDirectory(prefix="pvrtc-schedules-") as tmp:
        for name, path, (w, h) in images:
            print(f"{name} ({w}x{h})", flush=True)
            times = {label: [] for label, _ in schedules}
            last = {}
            for _ in range(args.runs):
                for k, (label, opts) in enumerate(schedules):
                    out = os.path.join(tmp, f"s{k}.pvr")
                    j = json.loads(run([args.tessera, "-j", "1", "compress", path, "-o", out,
                                        "--format", f"pvrtc1-{args.bpp}", "--json",
                                        *shlex.split(opts)]))
                    times[label].append(j["time_ms"])
                    last[label] = j
            for label, _ in schedules:
                j = last[label]
                ms = statistics.median(times[label]) * 512 * 512 / (w * h)
                alpha = j.get("psnr_alpha")
                rows[label].append(dict(ms=ms, psnr=j["psnr_rgb"], ssim=j["ssim_gray"],
                                        alpha=alpha if j["has_alpha"] else None,
                                        opaque=not j["has_alpha"]))
                print(f"  {label:40s} {ms:9.2f} ms/512² PSNR {fmt(j['psnr_rgb'])} "
                      f"SSIM {fmt(j['ssim_gray'], '.4f')}", flush=True)

    n_opaque = sum(1 for r in rows[schedules[0][0]] if r["opaque"])
    command = "/usr/bin/python3 " + shlex.join([os.path.relpath(sys.argv[0], ROOT), *sys.argv[1:]])
    commit = source_commit(args.tessera)
    lines = [
        f"# PVRTC1 {args.bpp}bpp encoder schedules: quality against encode time",
        "",
        f"Generated by `bench/pvrtc_schedules.py` on "
        f"{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M UTC}.",
        "",
        f"- Machine: {cpu_model()}, {os.cpu_count()} hardware threads (`nproc`), "
        f"{platform.system()} {platform.release()}",
        f"- Command: `{command}` (from the repository root)",
        f"- tessera binary: `{args.tessera}`"
        + (f", built from commit {commit}" if commit else ""),
        f"- Images: {len(images)} power-of-two PNGs from `{os.path.relpath(args.images, ROOT)}` "
        f"({n_opaque} opaque); every image weighs the same in the means",
        f"- Time: `tessera -j 1 compress --json` time_ms (the encode in process, one thread; no "
        f"start-up, PNG read or file write), median of {args.runs} runs (schedules run "
        "round-robin), scaled to a 512² image (x 512² / its pixels)",
        "- Quality: PSNR over RGB (dB), alpha PSNR over the images with alpha (finite values), "
        "SSIM on Rec.709 grey, of the decoded level against the input",
        "",
        "| schedule | `tessera compress` options | encode ms per 512² | PSNR RGB (dB) | "
        "PSNR RGB, opaque images | PSNR alpha (dB) | SSIM grey |",
        "|---|---|---:|---:|---:|---:|---:|",
    ]
    for label, opts in schedules:
        rs = rows[label]
        lines.append(
            f"| {label} | `{opts}` | {fmt(mean([r['ms'] for r in rs]), '.1f')} | "
            f"{fmt(mean([r['psnr'] for r in rs]))} | "
            f"{fmt(mean([r['psnr'] for r in rs if r['opaque']]))} | "
            f"{fmt(mean([r['alpha'] for r in rs if r['alpha'] is not None]))} | "
            f"{fmt(mean([r['ssim'] for r in rs]), '.4f')} |")
    lines.append("")
    write_report(args.out, lines, "<!-- notes: kept by bench/pvrtc_schedules.py -->")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
