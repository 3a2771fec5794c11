#!/usr/bin/env python3
"""vk::AdaptiveSupersampler in an engine's frame loop (examples/engine_aa_vk --frame-loop):
frames in flight, two views, the render scale cycling 100 % -> 70 % -> 85 % (dynamic
resolution, one component, no re-create). Prints a Markdown table of tessera's GPU time per
view and frame (the component's own timestamps, read from its profile after each frame's
fence) and the extra samples, medians per render scale, for docs/benchmarks/frame_loop_vk.md.

Usage: frame_loop_vk.py PATH/TO/engine_aa_vk [--size WxH] [--m M] [--frames N]
       [--frames-in-flight F] [--views V]
The first three frames (one per scale) also pay the driver's first use of each pipeline and
are left out of the medians. Without a GPU this is lavapipe: a CPU-run GPU pipeline.
"""
import argparse
import datetime
import json
import os
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchlib import cpu_model  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("engine")
    ap.add_argument("--size", default="640x360")
    ap.add_argument("--m", default="4")
    ap.add_argument("--frames", type=int, default=30)
    ap.add_argument("--frames-in-flight", default="3")
    ap.add_argument("--views", default="2")
    a = ap.parse_args()
    cmd = [a.engine, "--size", a.size, "--m", a.m, "--frame-loop", str(a.frames),
           "--frames-in-flight", a.frames_in_flight, "--views", a.views, "--json"]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"failed: {' '.join(cmd)}\n{p.stderr}")
    j = json.loads(p.stdout)
    by_scale = {}
    for f in j["frames"][3:]:
        for v in f["views"]:
            e = by_scale.setdefault(f["scale_percent"], {"size": v["render_size"], "ms": [],
                                                         "extra": [], "pixels": 0})
            e["ms"].append(v["tessera_gpu_ms"])
            e["extra"].append(v["extra_samples"])
            e["pixels"] = v["render_size"][0] * v["render_size"][1]
    print(f"Command: `python3 bench/frame_loop_vk.py build/bin/engine_aa_vk --size {a.size} "
          f"--m {a.m} --frames {a.frames} --frames-in-flight {a.frames_in_flight} "
          f"--views {a.views}`  ")
    print(f"Device: {j['device']}; CPU: {cpu_model()}; "
          f"{datetime.date.today().isoformat()}; validation layer "
          f"{'on' if j.get('validation') else 'off'}, {j.get('validation_messages')} messages.")
    print()
    print("| render scale | render size | view-frames | tessera GPU ms (median) | "
          "ms per megapixel | extra samples per pixel (median) |")
    print("|---:|---:|---:|---:|---:|---:|")
    for scale in sorted(by_scale, reverse=True):
        e = by_scale[scale]
        ms = statistics.median(e["ms"])
        extra = statistics.median(e["extra"]) / e["pixels"]
        print(f"| {scale} % | {e['size'][0]}x{e['size'][1]} | {len(e['ms'])} | {ms:.2f} | "
              f"{ms / (e['pixels'] / 1e6):.1f} | {extra:.2f} |")


if __name__ == "__main__":
    main()
