#!/usr/bin/env python3
"""Two tessera binaries side by side (before / after a change that keeps the bytes):
`tessera -j 1 compress IMG -o OUT.pvr --quality Q --format F` per case, the binaries alternated
run by run (ABBA order) after one untimed run of each; prints a Markdown row per case with the
medians of wall time and of the process's CPU time (user + sys, steadier on a shared machine).

  bench/pvrtc_ab_times.py BEFORE AFTER RUNS "IMG QUALITY FORMAT [FLAG ...]" ...

IMG is a file name under ../shared/data/images (TESSERA_SHARED overrides ../shared/data); any
further words of a case are passed to `compress` after the others (e.g. --alpha-weighted) and
shown in the quality column.
"""
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(binary, path, quality, fmt, out, extra=()):
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run([binary, "-j", "1", "compress", path, "-o", out, "--quality", quality,
                    "--format", fmt, *extra], check=True, stdout=subprocess.DEVNULL)
    t1 = time.perf_counter()
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
    return (t1 - t0) * 1e3, cpu * 1e3


def main():
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    before, after, runs = sys.argv[1], sys.argv[2], int(sys.argv[3])
    shared = os.environ.get("TESSERA_SHARED", os.path.join(ROOT, "..", "shared", "data"))
    print("| image | quality | format | wall ms before | wall ms after | CPU ms before | "
          "CPU ms after | CPU after / before |")
    print("|---|---|---|---:|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out.pvr")
        for case in sys.argv[4:]:
            img, quality, fmt, *extra = case.split()
            path = os.path.join(shared, "images", img)
            times = {before: [], after: []}
            for b in (before, after):
                run(b, path, quality, fmt, out, extra)
            for i in range(runs):
                for b in ((before, after) if i % 2 == 0 else (after, before)):
                    times[b].append(run(b, path, quality, fmt, out, extra))
            wall = {b: statistics.median(w for w, _ in v) for b, v in times.items()}
            cpu = {b: statistics.median(c for _, c in v) for b, v in times.items()}
            label = " ".join([quality, *extra])
            print(f"| {img} | {label} | {fmt} | {wall[before]:.1f} | {wall[after]:.1f} | "
                  f"{cpu[before]:.1f} | {cpu[after]:.1f} | {cpu[after] / cpu[before]:.3f} |",
                  flush=True)


if __name__ == "__main__":
    main()
