#!/usr/bin/env python3
"""tessera vs PVRTexToolCLI, side by side: PVRTC1 (4bpp, or 2bpp with --bpp 2) on the power-of-two shared images.

Usage (from the repository root):
    /usr/bin/python3 bench/pvrtc_vs_peers.py [--runs N] [--tessera build/bin/tessera]
        [--pvrtextool PATH] [--images ../shared/data/images] [--max-size PIXELS]
        [--out docs/benchmarks/pvrtc.md] [--bench-binary build/bin/pvrtc_bench] [--bpp 4|2]
        [--save-results RAW.json] [--from-results RAW.json]

For every power-of-two image (ldr-rgb-10.png, 127x128, is skipped; nothing is resized):
  * tessera compress --quality fast|normal|high, with -j 1 and with all hardware threads;
  * PVRTexToolCLI -f PVRTC1_4[_RGB],UBN,lRGB (PVRTC1_2 with --bpp 2) -q pvrtcfastest|pvrtcfast|pvrtcnormal|pvrtchigh|
    pvrtcbest (it picks its own thread count: one core for fastest/fast, more for the others).
Timing is whole-process wall time (PNG read + encode + file write), median of N runs; the runs
of an image's configurations are interleaved round-robin, so a burst of load on a shared machine
spoils one run of several configurations rather than every run of one.
Quality: tessera's file decoded by `tessera decompress`, PVRTexTool's by PVRTexTool itself
(-d), both compared against the original with `tessera compare --json`: PSNR over RGB, alpha
PSNR when the image has alpha, SSIM on Rec.709 grey. The RGB/RGBA variant follows the image
(tessera chooses RGB when alpha is 255 everywhere; PVRTexTool is told the same).
Writes a Markdown report (machine, date, command, per-image and mean tables, ratios) and, if the
Google Benchmark binary exists, the in-process MPixel/s it measures. Standard library only.
"""
import argparse
import datetime
import json
import os
import platform
import shlex
import statistics
import struct
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchlib import cpu_model, write_report as write_report_file  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TESSERA_QUALITIES = ["fast", "normal", "high"]
PVR_QUALITIES = ["pvrtcfastest", "pvrtcfast", "pvrtcnormal", "pvrtchigh", "pvrtcbest"]
# Pairs compared in the ratio table (tessera setting, PVRTexTool setting).
PAIRS = [("fast", "pvrtcfastest"), ("fast", "pvrtcfast"), ("normal", "pvrtcnormal"),
         ("high", "pvrtchigh"), ("high", "pvrtcbest")]


def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    if head[:8] != b"\x89PNG\r\n\x1a\n":
        return None
    return struct.unpack(">II", head[16:24])


def is_pow2(n):
    return n > 0 and n & (n - 1) == 0


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError(f"{shlex.join(cmd)} failed ({p.returncode}): {p.stderr.strip()}")
    return p.stdout


def timed(cmd, runs):
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        run(cmd)
        times.append((time.perf_counter() - t0) * 1000.0)
    return statistics.median(times)


def compare(tessera, ref, test):
    j = json.loads(run([tessera, "compare", ref, test, "--json"]))
    return {"psnr_rgb": j["psnr_rgb"], "ssim": j["ssim_gray"], "psnr_alpha": j.get("psnr_alpha")}


def source_commit(binary):
    """Short git commit of the tree the binary was built in (None outside a git checkout)."""
    try:
        p = subprocess.run(["git", "-C", os.path.dirname(os.path.abspath(binary)), "rev-parse",
                            "--short", "HEAD"], capture_output=True, text=True)
        return p.stdout.strip() if p.returncode == 0 else None
    except OSError:
        return None


def fmt(v, spec=".2f"):
    if v is None:
        return "-"
    if isinstance(v, float) and v == float("inf"):
        return "inf"
    return format(v, spec)


def google_benchmark(binary):
    if not binary or not os.path.isfile(binary):
        return None
    try:
        out = run([binary, "--benchmark_format=json", "--benchmark_min_time=0.3"])
    except RuntimeError as e:
        return [f"(running {binary} failed: {e})"]
    rows = []
    for b in json.loads(out).get("benchmarks", []):
        ips = b.get("items_per_second")
        if ips:
            extra = f", PSNR {b['psnr_rgb']:.2f} dB" if "psnr_rgb" in b else ""
            scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}.get(b.get("time_unit"), None)
            t = f"{b['real_time'] * scale:.2f} ms" if scale else f"{b['real_time']:.2f} {b['time_unit']}"
            rows.append(f"| `{b['name']}` | {ips / 1e6:.2f} | {t}{extra} |")
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", type=int, default=3, help="timed runs per configuration (median)")
    ap.add_argument("--tessera", default=os.path.join(ROOT, "build", "bin", "tessera"))
    ap.add_argument("--pvrtextool", default=os.environ.get(
        "TESSERA_PVRTEXTOOL", os.path.expanduser("~/.cache/tessera/peers/PVRTexToolCLI")))
    ap.add_argument("--images", default=os.path.join(ROOT, "..", "shared", "data", "images"))
    ap.add_argument("--max-size", type=int, default=0,
                    help="skip images with more pixels than this (0 = no limit)")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "benchmarks", "pvrtc.md"))
    ap.add_argument("--bench-binary", default=os.path.join(ROOT, "build", "bin", "pvrtc_bench"))
    ap.add_argument("--bpp", type=int, choices=(4, 2), default=4, help="PVRTC1 4 or 2 bpp")
    ap.add_argument("--save-results", metavar="JSON",
                    help="also write the raw per-image results to this JSON file")
    ap.add_argument("--from-results", metavar="JSON",
                    help="re-render the report from a --save-results file (no runs)")
    args = ap.parse_args()

    if args.from_results:
        with open(args.from_results) as f:
            saved = json.load(f)
        for key in ("runs", "images", "max_size", "bpp", "tessera", "bench_binary"):
            setattr(args, key, saved["args"][key])
        # Results saved before the runs were interleaved say nothing about it.
        args.interleaved = saved["args"].get("interleaved", False)
        write_report(args, saved["results"], [tuple(i) for i in saved["images"]],
                     saved["nthreads"], saved["gbench"], saved["generated"], saved["command"])
        print(f"wrote {args.out}")
        return

    for tool in (args.tessera, args.pvrtextool):
        if not os.path.isfile(tool):
            sys.exit(f"pvrtc_vs_peers: {tool} not found (build tessera; run scripts/setup.sh)")
    if not os.path.isdir(args.images):
        sys.exit(f"pvrtc_vs_peers: {args.images} not found (the shared data folder)")
    nthreads = os.cpu_count() or 1

    images = []
    for name in sorted(os.listdir(args.images)):
        path = os.path.join(args.images, name)
        size = png_size(path) if name.endswith(".png") else None
        if not size or not (is_pow2(size[0]) and is_pow2(size[1])):
            print(f"skip {name}: not a power-of-two PNG")
            continue
        if args.max_size and size[0] * size[1] > args.max_size:
            print(f"skip {name}: {size[0]}x{size[1]} over --max-size")
            continue
        images.append((name, path, size))

    args.interleaved = True
    results = []  # dicts: image, size, encoder, setting, ms1, msn, psnr_rgb, ssim, psnr_alpha
    with tempfile.TemporaryDirectory(prefix="pvrtc-bench-") as tmp:
        for name, path, (w, h) in images:
            print(f"{name} ({w}x{h})", flush=True)
            # An untimed first encode: whether tessera writes alpha (the PVRTexTool format
            # follows it), and the PNG in the page cache for every timed run alike.
            probe = os.path.join(tmp, "probe.pvr")
            run([args.tessera, "-j", "1", "compress", path, "-o", probe, "--quality", "fast",
                 "--format", f"pvrtc1-{args.bpp}"])
            has_alpha = json.loads(run([args.tessera, "info", probe, "--json"]))["has_alpha"]
            fmt_arg = f"PVRTC1_{args.bpp}{'' if has_alpha else '_RGB'},UBN,lRGB"
            # Every timed configuration of this image, run round-robin: run r of each before
            # run r + 1 of any, so a burst of load on the shared machine lands on one run of
            # several configurations (and the median drops it) instead of on every run of one.
            configs = {}  # key -> (command, output file)
            for q in TESSERA_QUALITIES:
                for j in (1, nthreads):
                    out = os.path.join(tmp, f"t-{q}-j{j}.pvr")
                    configs[("tessera", q, j)] = (
                        [args.tessera, "-j", str(j), "compress", path, "-o", out, "--quality", q,
                         "--format", f"pvrtc1-{args.bpp}", "--quiet"], out)
            for q in PVR_QUALITIES:
                out = os.path.join(tmp, f"p-{q}.pvr")
                configs[("PVRTexTool", q, 0)] = (
                    [args.pvrtextool, "-i", path, "-o", out, "-f", fmt_arg, "-q", q, "-shh"], out)
            times = {key: [] for key in configs}
            for _ in range(args.runs):
                for key, (cmd, _out) in configs.items():
                    times[key].append(timed(cmd, 1))
            ms = {key: statistics.median(t) for key, t in times.items()}
            for q in TESSERA_QUALITIES:
                out1, outn = configs[("tessera", q, 1)][1], configs[("tessera", q, nthreads)][1]
                with open(out1, "rb") as f1, open(outn, "rb") as fn:
                    if f1.read() != fn.read():
                        raise RuntimeError(f"{name} {q}: output differs between -j 1 and -j {nthreads}")
                if json.loads(run([args.tessera, "info", out1, "--json"]))["has_alpha"] != has_alpha:
                    raise RuntimeError(f"{name} {q}: the .pvr and the PNG disagree on alpha")
                dec = os.path.join(tmp, f"t-{q}.png")
                run([args.tessera, "decompress", out1, "-o", dec])
                m = compare(args.tessera, path, dec)
                ms1, msn = ms[("tessera", q, 1)], ms[("tessera", q, nthreads)]
                results.append(dict(image=name, size=f"{w}x{h}", encoder="tessera", setting=q,
                                    ms1=ms1, msn=msn, alpha=has_alpha, **m))
                print(f"  tessera {q:7s} {ms1:9.1f} ms (-j1) {msn:9.1f} ms (-j{nthreads}) "
                      f"PSNR {fmt(m['psnr_rgb'])} SSIM {fmt(m['ssim'], '.4f')}", flush=True)
            for q in PVR_QUALITIES:
                out = configs[("PVRTexTool", q, 0)][1]
                dec = os.path.join(tmp, f"p-{q}.png")
                run([args.pvrtextool, "-i", out, "-o", os.path.join(tmp, "scratch.pvr"), "-f",
                     "r8g8b8a8", "-d", dec, "-shh"])
                m = compare(args.tessera, path, dec)
                t = ms[("PVRTexTool", q, 0)]
                results.append(dict(image=name, size=f"{w}x{h}", encoder="PVRTexTool", setting=q,
                                    ms1=None, msn=t, alpha=has_alpha, **m))
                print(f"  PVRTexTool {q:12s} {t:9.1f} ms PSNR {fmt(m['psnr_rgb'])} "
                      f"SSIM {fmt(m['ssim'], '.4f')}", flush=True)

    gbench = google_benchmark(args.bench_binary)
    generated = f"{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M UTC}"
    command = "/usr/bin/python3 " + shlex.join([os.path.relpath(sys.argv[0], ROOT), *sys.argv[1:]])
    if args.save_results:
        with open(args.save_results, "w") as f:
            json.dump(dict(results=results, images=images, nthreads=nthreads, gbench=gbench,
                           generated=generated, command=command,
                           args={k: getattr(args, k) for k in ("runs", "images", "max_size", "bpp",
                                                              "tessera", "bench_binary",
                                                              "interleaved")}),
                      f, indent=1)
    write_report(args, results, images, nthreads, gbench, generated, command)
    print(f"wrote {args.out}")


def mean(values):
    values = [v for v in values if v is not None and v != float("inf")]
    return statistics.fmean(values) if values else None


def shown(path):
    """A path relative to the repository when inside it, else as given."""
    rel = os.path.relpath(os.path.abspath(path), ROOT)
    return path if rel.startswith("..") else rel


NOTES_MARKER = "<!-- notes: kept by bench/pvrtc_vs_peers.py -->"


def group_means(results, enc, setting, keep):
    rs = [r for r in results if r["encoder"] == enc and r["setting"] == setting and keep(r)]
    return dict(n=len(rs), ms1=mean([r["ms1"] for r in rs]), msn=mean([r["msn"] for r in rs]),
                psnr=mean([r["psnr_rgb"] for r in rs]),
                alpha=mean([r["psnr_alpha"] for r in rs if r["alpha"]]),
                ssim=mean([r["ssim"] for r in rs]))


def pixels(r):
    w, h = r["size"].split("x")
    return int(w) * int(h)


# Subsets reported separately: the speed targets are per 512^2 image, and RGBA images trade
# RGB error against alpha error differently in each encoder.
GROUPS = [
    ("opaque (RGB) images", lambda r: not r["alpha"]),
    ("images with alpha (RGBA)", lambda r: r["alpha"]),
    ("256x256 images", lambda r: pixels(r) <= 256 * 256),
    ("512x512 and larger", lambda r: pixels(r) >= 512 * 512),
]


def write_report(args, results, images, nthreads, gbench, generated, cmd):
    lines = [
        f"# PVRTC1 {args.bpp}bpp: tessera vs PVRTexToolCLI",
        "",
        f"Generated by `bench/pvrtc_vs_peers.py` on {generated}.",
        "",
        f"- Machine: {cpu_model()}, {nthreads} hardware threads (`nproc`), {platform.system()} "
        f"{platform.release()}",
        f"- Command: `{cmd}` (from the repository root)",
        f"- tessera binary: `{args.tessera}`"
        + (f", built from commit {source_commit(args.tessera)}" if source_commit(args.tessera) else "")
        + " (Release)",
        f"- Runs per configuration: {args.runs} (median whole-process wall time: PNG read, "
        "encode, file write)"
        + ("; an image's configurations run round-robin (run r of each before run r + 1 of any), "
           "after one untimed encode of the image" if args.interleaved else ""),
        f"- Images: {len(images)} power-of-two PNGs from `{os.path.relpath(args.images, ROOT)}` "
        "(ldr-rgb-10.png, 127x128, is skipped; nothing is resized)"
        + (f", at most {args.max_size} pixels" if args.max_size else ""),
        "- tessera: `tessera -j 1|" + str(nthreads) + " compress IMG -o OUT.pvr --quality "
        "fast|normal|high --format pvrtc1-" + str(args.bpp) + "`; decoded with `tessera decompress`.",
        f"- PVRTexToolCLI 4.17: `-f PVRTC1_{args.bpp}[_RGB],UBN,lRGB -q pvrtcfastest|...|pvrtcbest`; it "
        "chooses its own threads (one core for fastest/fast, all cores for normal and above); "
        "decoded with its own `-d`.",
        "- Quality: `tessera compare --json` against the original: PSNR over RGB (dB), alpha "
        "PSNR for images with alpha, SSIM on Rec.709 grey.",
        "- Wall times on a shared machine are noisy; compare settings within one run.",
        "",
        "## Mean over all images",
        "",
        "| encoder | setting | time -j 1 (ms) | time all threads (ms) | PSNR RGB (dB) | "
        "PSNR alpha (dB) | SSIM grey |",
        "|---|---|---:|---:|---:|---:|---:|",
    ]
    means = {}
    for enc, settings in (("tessera", TESSERA_QUALITIES), ("PVRTexTool", PVR_QUALITIES)):
        for s in settings:
            rs = [r for r in results if r["encoder"] == enc and r["setting"] == s]
            m = dict(ms1=mean([r["ms1"] for r in rs]), msn=mean([r["msn"] for r in rs]),
                     psnr=mean([r["psnr_rgb"] for r in rs]),
                     alpha=mean([r["psnr_alpha"] for r in rs if r["alpha"]]),
                     ssim=mean([r["ssim"] for r in rs]))
            means[(enc, s)] = m
            lines.append(f"| {enc} | {s} | {fmt(m['ms1'], '.1f')} | {fmt(m['msn'], '.1f')} | "
                         f"{fmt(m['psnr'])} | {fmt(m['alpha'])} | {fmt(m['ssim'], '.4f')} |")
    lines += [
        "",
        "## Ratios tessera / PVRTexTool (means over all images)",
        "",
        "Time ratio < 1: tessera faster (tessera with all threads; PVRTexTool as it runs). "
        "ΔPSNR and ΔSSIM > 0: tessera better.",
        "",
        "| tessera | PVRTexTool | time ratio (all threads) | time ratio (tessera -j 1) | "
        "ΔPSNR RGB (dB) | ΔSSIM |",
        "|---|---|---:|---:|---:|---:|",
    ]
    for t, p in PAIRS:
        a, b = means[("tessera", t)], means[("PVRTexTool", p)]
        if None in (a["msn"], b["msn"], a["psnr"], b["psnr"]):
            continue
        lines.append(f"| {t} | {p} | {a['msn'] / b['msn']:.3f} | {a['ms1'] / b['msn']:.3f} | "
                     f"{a['psnr'] - b['psnr']:+.2f} | {a['ssim'] - b['ssim']:+.4f} |")
    # The target metric: whole-process time per 512^2 image (each image's time scaled by
    # 512^2 / its pixels), averaged over the images, tessera on one thread. Unlike the ratios of
    # mean times above, every image counts the same (the 2048^2 image does not dominate).
    lines += [
        "",
        "## Time per 512² image",
        "",
        "Each image's whole-process time scaled to a 512² image (× 512² / its pixels), then "
        "averaged over the images: every image counts equally. tessera -j 1; PVRTexTool as it "
        "runs. \"Mean of per-image ratios\" averages each image's own time ratio.",
        "",
        "| images | tessera | PVRTexTool | tessera ms per 512² | PVRTexTool ms per 512² | "
        "ratio | faster by | mean of per-image ratios |",
        "|---|---|---|---:|---:|---:|---:|---:|",
    ]
    by_key = {(r["image"], r["encoder"], r["setting"]): r for r in results}
    for label, keep in (("all", lambda r: True), ("512x512 and larger", GROUPS[3][1]),
                        ("256x256", GROUPS[2][1])):
        for t, p in PAIRS:
            tv, pv, ratios = [], [], []
            for r in results:
                if r["encoder"] != "tessera" or r["setting"] != t or not keep(r):
                    continue
                q = by_key.get((r["image"], "PVRTexTool", p))
                if q is None or r["ms1"] is None or q["msn"] is None:
                    continue
                scale = 512 * 512 / pixels(r)
                tv.append(r["ms1"] * scale)
                pv.append(q["msn"] * scale)
                ratios.append(r["ms1"] / q["msn"])
            if not tv:
                continue
            ratio = mean(tv) / mean(pv)
            lines.append(f"| {label} ({len(tv)}) | {t} | {p} | {mean(tv):.1f} | {mean(pv):.1f} | "
                         f"{ratio:.3f} | {1 / ratio:.1f}x | {mean(ratios):.3f} |")
    lines += [
        "",
        "## Means over subsets",
        "",
        "Time: tessera -j 1 and PVRTexTool as it runs; ΔPSNR and ΔSSIM > 0: tessera better.",
        "",
        "| subset | images | tessera | PVRTexTool | time ratio (tessera -j 1) | tessera PSNR RGB | "
        "PVRTexTool PSNR RGB | ΔPSNR RGB (dB) | Δ alpha PSNR (dB) | ΔSSIM |",
        "|---|---:|---|---|---:|---:|---:|---:|---:|---:|",
    ]
    for label, keep in GROUPS:
        for t, p in PAIRS:
            a = group_means(results, "tessera", t, keep)
            b = group_means(results, "PVRTexTool", p, keep)
            if a["n"] == 0 or None in (a["ms1"], b["msn"], a["psnr"], b["psnr"]):
                continue
            dalpha = (f"{a['alpha'] - b['alpha']:+.2f}"
                      if a["alpha"] is not None and b["alpha"] is not None else "-")
            lines.append(f"| {label} | {a['n']} | {t} | {p} | {a['ms1'] / b['msn']:.3f} | "
                         f"{a['psnr']:.2f} | {b['psnr']:.2f} | {a['psnr'] - b['psnr']:+.2f} | "
                         f"{dalpha} | {a['ssim'] - b['ssim']:+.4f} |")
    lines += [
        "",
        "## Per image",
        "",
        "| image | size | encoder | setting | time -j 1 (ms) | time all threads (ms) | "
        "PSNR RGB (dB) | PSNR alpha (dB) | SSIM grey |",
        "|---|---|---|---|---:|---:|---:|---:|---:|",
    ]
    for r in results:
        lines.append(f"| {r['image']} | {r['size']} | {r['encoder']} | {r['setting']} | "
                     f"{fmt(r['ms1'], '.1f')} | {fmt(r['msn'], '.1f')} | {fmt(r['psnr_rgb'])} | "
                     f"{fmt(r['psnr_alpha']) if r['alpha'] else '-'} | {fmt(r['ssim'], '.4f')} |")
    lines += ["", "## In-process throughput (Google Benchmark)", ""]
    if gbench is None:
        lines.append(f"`{shown(args.bench_binary)}` was not built; run it for "
                     "in-process MPixel/s without process start-up and PNG I/O.")
    else:
        lines += [f"From `{shown(args.bench_binary)}` in the same run (pixels encoded or decoded "
                  "per second, on the benchmark's own image: see bench/pvrtc_bench.cpp):", "",
                  "| benchmark | MPixel/s | time per iteration |", "|---|---:|---:|", *gbench]
    lines.append("")
    # Hand-written notes after the marker survive regeneration.
    write_report_file(args.out, lines, NOTES_MARKER)


if __name__ == "__main__":
    main()
