#!/usr/bin/env python3
"""vk::AdaptiveSupersampler::create with GLSL compiled at create (shaderc) against create from
a shader binary saved by an earlier run (options.shader_binary: no GLSL compiled), alternating
in one session: examples/engine_aa_vk --json reports its create_ms (host time of create,
including the driver's pipeline creation). Prints a Markdown table of medians for
docs/benchmarks/frame_loop_vk.md.

Usage: create_vk.py PATH/TO/engine_aa_vk [--runs N] [--size WxH] [--m M] [--schedule S]
                    [--baseline PATH/TO/OLD/engine_aa_vk] [--baseline-label TEXT]
--baseline: also an engine built from an earlier tessera, its GLSL compiled at create, in the same
alternation (before/after rows).
"""
import argparse
import datetime
import json
import os
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchlib import cpu_model  # noqa: E402


def create_ms(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"failed: {' '.join(cmd)}\n{p.stderr}")
    j = json.loads(p.stdout)
    return j["create_ms"], j["device"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("engine")
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--size", default="320x180")
    ap.add_argument("--m", default="4")
    ap.add_argument("--schedule", default="frame_list")
    ap.add_argument("--baseline", default="")
    ap.add_argument("--baseline-label", default="baseline (OLD), GLSL compiled at create",
                    help="the baseline's row in the table")
    a = ap.parse_args()
    base = [a.engine, "--size", a.size, "--m", a.m, "--schedule", a.schedule, "--json"]
    compiled, loaded, baseline = [], [], []
    old = [a.baseline] + base[1:] if a.baseline else None
    with tempfile.TemporaryDirectory() as tmp:
        binary = os.path.join(tmp, "aa.spv")
        create_ms(base + ["--shader-binary", binary])  # writes the binary
        size = os.path.getsize(binary)
        for _ in range(a.runs):
            if old:
                baseline.append(create_ms(old)[0])
            ms, device = create_ms(base)
            compiled.append(ms)
            ms, _ = create_ms(base + ["--shader-binary", binary])
            loaded.append(ms)
    mc, ml = statistics.median(compiled), statistics.median(loaded)
    extra = " --baseline OLD/engine_aa_vk" if old else ""
    print(f"Command: `python3 bench/create_vk.py build/bin/engine_aa_vk --runs {a.runs} "
          f"--size {a.size} --m {a.m} --schedule {a.schedule}{extra}`  ")
    print(f"Device: {device}; CPU: {cpu_model()}; {datetime.date.today().isoformat()}; "
          f"{a.runs} alternating runs each, validation layer on.")
    print()
    print("| create | median ms | min | max |")
    print("|---|---:|---:|---:|")
    if baseline:
        mb = statistics.median(baseline)
        print(f"| {a.baseline_label} | {mb:.1f} | {min(baseline):.1f} | "
              f"{max(baseline):.1f} |")
    print(f"| GLSL compiled at create (shaderc) | {mc:.1f} | {min(compiled):.1f} | "
          f"{max(compiled):.1f} |")
    print(f"| from the shader binary ({size / 1024:.0f} KiB) | {ml:.1f} | {min(loaded):.1f} | "
          f"{max(loaded):.1f} |")
    if baseline:
        print(f"| ratio baseline / compiled at create | {mb / mc:.2f}x | | |")
    print(f"| ratio compiled / binary | {mc / ml:.1f}x | | |")


if __name__ == "__main__":
    main()
