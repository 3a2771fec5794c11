#!/usr/bin/env python3
"""Side-by-side frame times: tessera's software rasteriser vs Mesa llvmpipe (OpenGL 4.5).

Usage: bench/raster_vs_llvmpipe.py [--scene FILE] [--frames N] [--threads T] [--out docs/benchmarks/raster.md]

Both render the same scene, orbit cameras, resolution (1024x768) and MSAA rate with unlit
trilinear texturing; each frame's time covers clear, transform, rasterisation, shading and
resolve (llvmpipe: draw + resolve blit + glFinish; read-back excluded on both sides). Both run
with the same thread count: tessera -j T, llvmpipe LP_NUM_THREADS=T. Runs alternate between the
two renderers (and the two MSAA rates) per camera position, optionally for several rounds; the
table reports medians and minima over all frames.
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

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scene", default=os.path.join(ROOT, "..", "shared", "data", "scenes",
                                                    "dungeon", "level-dungeon.gltf"))
    ap.add_argument("--frames", type=int, default=5, help="timed frames per camera position")
    ap.add_argument("--positions", type=int, default=4, help="orbit positions")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--rounds", type=int, default=1,
                    help="repeat the alternating runs (helps on a loaded machine)")
    ap.add_argument("--width", type=int, default=1024)
    ap.add_argument("--height", type=int, default=768)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "benchmarks", "raster.md"))
    args = ap.parse_args()
    tessera = os.path.join(args.build, "bin", "tessera")
    glpeer = os.path.join(args.build, "bin", "tessera-glpeer")
    if not os.path.isfile(args.scene):
        sys.exit(f"raster_vs_llvmpipe: {args.scene}: missing scene")
    env = dict(os.environ, LP_NUM_THREADS=str(args.threads))
    load_before = os.getloadavg()[0]
    rows = []
    renderer = "?"
    with tempfile.TemporaryDirectory() as tmp:
        # Rounds, then positions, then MSAA rates, then the two renderers alternate, so that a
        # change in other load on the machine affects both sides and both rates alike.
        times = {(m, r): [] for m in (1, 4) for r in ("tessera", "llvmpipe")}
        for _ in range(args.rounds):
            for pos in range(args.positions):
                for msaa in (1, 4):
                    orbit = f"{pos}/{args.positions}"
                    common = ["--width", str(args.width), "--height", str(args.height),
                              "--msaa", str(msaa), "--orbit", orbit, "--frames", str(args.frames)]
                    # Warm-up frames are included in --frames; drop the first of each run.
                    t = subprocess.run([tessera, "-j", str(args.threads), "render", args.scene,
                                        "-o", os.path.join(tmp, "t.png"), "--json", *common],
                                       check=True, capture_output=True, text=True)
                    times[(msaa, "tessera")] += json.loads(t.stdout)["frame_ms"][1:]
                    g = subprocess.run([glpeer, args.scene, "-o", os.path.join(tmp, "g.png"),
                                        "--json", "-", *common], check=True,
                                       capture_output=True, text=True, env=env)
                    gj = json.loads(g.stdout)
                    renderer = gj["renderer"]
                    times[(msaa, "llvmpipe")] += gj["frame_ms"][1:]
        for msaa in (1, 4):
            tt, tl = times[(msaa, "tessera")], times[(msaa, "llvmpipe")]
            mt, ml = statistics.median(tt), statistics.median(tl)
            bt, bl = min(tt), min(tl)
            rows.append((msaa, mt, ml, mt / ml, bt, bl, len(tt)))
            print(f"msaa {msaa}: tessera {mt:.1f} ms, llvmpipe {ml:.1f} ms, ratio {mt / ml:.2f} "
                  f"(best frames {bt:.1f} / {bl:.1f} ms, ratio {bt / bl:.2f})")
    cmd = "python3 bench/raster_vs_llvmpipe.py " + " ".join(
        f"--{k} {v}" for k, v in [("frames", args.frames), ("positions", args.positions),
                                  ("threads", args.threads), ("rounds", args.rounds)])
    lines = [
        "# Rasteriser vs Mesa llvmpipe",
        "",
        f"Machine: {cpu_model()}, {os.cpu_count()} logical CPUs; date "
        f"{datetime.date.today().isoformat()}; peer: {renderer}.",
        "",
        f"Command: `{cmd}` (after `bash scripts/setup.sh`).",
        "",
        f"Scene `{os.path.relpath(args.scene, ROOT)}`, {args.width}x{args.height}, unlit "
        f"trilinear texturing, {args.positions} orbit positions x {args.frames - 1} timed frames "
        f"each (first frame of each run dropped), {args.rounds} round(s) of alternating runs, "
        f"{args.threads} threads on both sides "
        f"(tessera `-j {args.threads}`, llvmpipe `LP_NUM_THREADS={args.threads}`). Times are "
        "medians per frame: clear, transform, raster, shade and resolve (read-back excluded); "
        "'best' is the fastest frame of each side, less sensitive to other load on the machine.",
        "",
        f"Load average (1 min) before / after: {load_before:.2f} / {os.getloadavg()[0]:.2f}.",
        "",
        "| MSAA | tessera ms/frame | llvmpipe ms/frame | ratio | best tessera | best llvmpipe "
        "| best ratio | frames |",
        "|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for msaa, mt, ml, ratio, bt, bl, n in rows:
        lines.append(f"| {msaa}x | {mt:.1f} | {ml:.1f} | {ratio:.2f} | {bt:.1f} | {bl:.1f} "
                     f"| {bt / bl:.2f} | {n} |")
    lines += ["", "Target: ratio <= 1.5 at 1x and 4x.", ""]
    # Hand-written notes below the marker (profiles, history) survive a re-run.
    marker = "<!-- notes: kept by bench/raster_vs_llvmpipe.py -->"
    if os.path.isfile(args.out):
        with open(args.out) as f:
            old = f.read()
        if marker in old:
            lines += [old[old.index(marker):].rstrip("\n"), ""]
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    tmp_out = args.out + ".tmp"
    with open(tmp_out, "w") as f:
        f.write("\n".join(lines))
    os.replace(tmp_out, args.out)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
