#!/usr/bin/env python3
"""The papers' experiments on the two GPU backends side by side: `tessera seams` (Toth 2013,
Table 1) and `tessera aa` (Holländer et al. 2013, Table 1) run with `--backend gl` and
`--backend vk` alternately in one session, several times, and printed as Markdown tables of
medians with the Vulkan / OpenGL ratios (docs/benchmarks/seams_vk.md, aa_vk.md).

Usage: experiments_gpu_backends.py PATH/TO/tessera [--runs N] [--seams-args ...] [--aa-args ...]
       [--only seams|aa]
Every number is the median over the runs of each run's own median (frames within a run). On a
machine without a GPU both are CPU-run GPU pipelines (llvmpipe, lavapipe): compare them as that.
"""
import argparse
import json
import os
import shlex
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchlib import cpu_model  # noqa: E402

METHODS = ("clamp", "discard", "traverse", "traverse_corners")
AA_METHODS = ("default", "fxaa", "reference", "adaptive", "edge_per_sample")


def run_json(tessera, args, out):
    cmd = [tessera, "-j", str(os.cpu_count() or 1), *args, "--json", "-q", "-o", out]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"failed: {shlex.join(cmd)}\n{p.stderr}")
    return json.loads(p.stdout)


def alternate(tessera, command, extra, runs):
    """runs x (gl, vk), alternating; returns {backend: [json, ...]}."""
    got = {"gl": [], "vk": []}
    with tempfile.TemporaryDirectory(prefix="tessera-gpu-bench-") as tmp:
        for r in range(runs):
            order = ("gl", "vk") if r % 2 == 0 else ("vk", "gl")
            for b in order:
                out = os.path.join(tmp, f"{command}-{b}-{r}")
                got[b].append(run_json(tessera, [command, "--backend", b, *extra], out))
    return got


def med(values):
    values = [v for v in values if v is not None]
    return statistics.median(values) if values else float("nan")


def seams_tables(tessera, extra, runs):
    got = alternate(tessera, "seams", extra, runs)
    gl, vk = got["gl"][0], got["vk"][0]
    rates = [r for r in vk["timing"] if r in gl["timing"]]
    lines = [f"GL: {gl['gpu_renderer']}, {gl['gpu_version']}. "
             f"Vulkan: {vk['gpu_renderer']}, {vk['gpu_version']}.", "",
             "| rate | method | GL wall ms | GL timer ms | Vulkan wall ms | Vulkan timestamps ms "
             "| Vulkan / GL (wall) |", "|---|---|---:|---:|---:|---:|---:|"]
    ratio_rows = []
    for rate in rates:
        wall = {}
        for m in METHODS:
            gw = med(j["timing"][rate][m]["wall_median_ms"] for j in got["gl"])
            gt = med(j["timing"][rate][m]["median_ms"] for j in got["gl"])
            vw = med(j["timing"][rate][m]["wall_median_ms"] for j in got["vk"])
            vt = med(j["timing"][rate][m]["median_ms"] for j in got["vk"])
            wall[m] = (gw, gt, vw, vt)
            lines.append(f"| {rate} | {m} | {gw:.2f} | {gt:.3f} | {vw:.2f} | {vt:.3f} | "
                         f"{vw / gw:.2f}x |")
        g = wall["traverse"][0] / wall["discard"][0]
        v = wall["traverse"][3] / wall["discard"][3]
        ratio_rows.append(f"| {rate} | {g:.2f}x (wall) | {v:.2f}x (timestamps) |")
    lines += ["", "Table 1's figure, Traverse / Discard:", "",
              "| rate | OpenGL | Vulkan |", "|---|---:|---:|", *ratio_rows, "",
              "Quality against the reference (mean linear-RGB error, frame-pooled; the same on "
              "every run):", "", "| rate | method | GL | Vulkan |", "|---|---|---:|---:|"]
    for rate in rates:
        for m in METHODS:
            a = gl["quality"]["vs_reference"][m][rate]["mean"]
            b = vk["quality"]["vs_reference"][m][rate]["mean"]
            lines.append(f"| {rate} | {m} | {a:.5f} | {b:.5f} |")
    lines.append(f"\nRefused rates: GL {gl['msaa_unsupported']}, Vulkan {vk['msaa_unsupported']}.")
    return lines


def aa_tables(tessera, extra, runs):
    got = alternate(tessera, "aa", extra, runs)
    gl, vk = got["gl"][0], got["vk"][0]
    lines = [f"GL: {gl['gpu_renderer']}, {gl['gpu_version']}. "
             f"Vulkan: {vk['gpu_renderer']}, {vk['gpu_version']}.", "",
             "| m | method | samples % GL / Vulkan | PSNR vs reference dB GL / Vulkan | GL ms | "
             "Vulkan ms | Vulkan GPU ms | Vulkan / GL |", "|---|---|---:|---:|---:|---:|---:|---:|"]
    for i, rate in enumerate(vk["rates"]):
        m = rate["m"]
        for k in AA_METHODS:
            gms = med(j["rates"][i][k]["frame_ms"] for j in got["gl"])
            vms = med(j["rates"][i][k]["frame_ms"] for j in got["vk"])
            vgpu = med(j["rates"][i][k]["gpu_shade_ms"] + j["rates"][i]["gbuffer_gpu_ms"]
                       for j in got["vk"])
            q = lambda j: (j["rates"][i][k].get("quality") or {}).get("psnr_db")  # noqa: E731
            pg, pv = q(gl), q(vk)
            ps = "–" if pg is None else f"{pg:.2f} / {pv:.2f}"
            sp = f"{gl['rates'][i][k]['samples_pct']:.1f} / {rate[k]['samples_pct']:.1f}"
            lines.append(f"| {m}×{m} | {k} | {sp} | {ps} | {gms:.1f} | {vms:.1f} | {vgpu:.1f} | "
                         f"{vms / gms:.2f}x |")
    lines.append("\nms = G-buffer pass + the method's shading (host wall times to glFinish / the "
                 "fence); Vulkan GPU ms = the same from GPU timestamps.")
    return lines


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("tessera")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--seams-args", default="--width 480 --height 540 --frames 4 --msaa 1,4")
    ap.add_argument("--aa-args", default="--width 480 --height 270 --ssaa 2,4 --frames 3")
    ap.add_argument("--only", choices=("seams", "aa"))
    a = ap.parse_args()
    print(f"Machine: {cpu_model()}, {os.cpu_count()} logical CPUs; "
          f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}; {a.runs} runs per backend.\n")
    if a.only in (None, "seams"):
        print(f"## seams: `tessera seams {a.seams_args}`\n")
        print("\n".join(seams_tables(a.tessera, shlex.split(a.seams_args), a.runs)) + "\n")
    if a.only in (None, "aa"):
        print(f"## aa: `tessera aa {a.aa_args}`\n")
        print("\n".join(aa_tables(a.tessera, shlex.split(a.aa_args), a.runs)) + "\n")


if __name__ == "__main__":
    main()
