#!/usr/bin/env python3
"""Runs a Google Benchmark program and writes its results as a Markdown table in docs/.

Usage: bench/gbench_to_md.py BINARY OUT.md [--title T] [--repetitions N] [-- extra benchmark args]
Each row: benchmark name, median real and CPU time per iteration, and items/s (what the
benchmark counts with SetItemsProcessed: pixels, samples, triangles...), over N repetitions.
The page records the machine, the date, the load average and the exact command.
"""
import argparse
import datetime
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchlib import cpu_model  # noqa: E402


def human(v):
    for unit, div in (("G", 1e9), ("M", 1e6), ("k", 1e3)):
        if v >= div:
            return f"{v / div:.2f} {unit}"
    return f"{v:.1f}"


def duration(ns):
    """A time in nanoseconds with a readable unit."""
    for unit, div in (("s", 1e9), ("ms", 1e6), ("µs", 1e3)):
        if ns >= div:
            return f"{ns / div:.3g} {unit}"
    return f"{ns:.3g} ns"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("binary")
    ap.add_argument("out")
    ap.add_argument("--title", default=None)
    ap.add_argument("--repetitions", type=int, default=5)
    ap.add_argument("extra", nargs="*")
    a = ap.parse_args()
    load = os.getloadavg()[0]
    cmd = [a.binary, "--benchmark_format=json", f"--benchmark_repetitions={a.repetitions}",
           "--benchmark_report_aggregates_only=true", *a.extra]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"gbench_to_md: {a.binary} failed: {p.stderr.strip()}")
    data = json.loads(p.stdout)
    rows = []
    for b in data["benchmarks"]:
        if b.get("aggregate_name") != "median":
            continue
        name = b["run_name"]
        scale = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}[b.get("time_unit", "ns")]
        ips = b.get("items_per_second")
        rows.append(f"| `{name}` | {duration(b['real_time'] * scale)} | "
                    f"{duration(b['cpu_time'] * scale)} | "
                    f"{human(ips) + '/s' if ips else '-'} |")
    title = a.title or os.path.basename(a.binary)
    # Name the binary as a user's build tree has it, wherever this copy was built.
    rel = os.path.join("build", "bin", os.path.basename(a.binary))
    lines = [f"# {title}", "",
             f"Machine: {cpu_model()}, {os.cpu_count()} logical CPUs; date "
             f"{datetime.date.today().isoformat()}; 1-minute load average at start {load:.1f} "
             "(the machine is shared: CPU time is the steadier column).", "",
             f"Command: `python3 bench/gbench_to_md.py {rel} {os.path.relpath(a.out)} "
             f"--repetitions {a.repetitions}` (medians of {a.repetitions} repetitions).", "",
             "| benchmark | real time | CPU time | items/s |", "|---|---:|---:|---:|", *rows, ""]
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    with open(a.out + ".tmp", "w") as f:
        f.write("\n".join(lines))
    os.replace(a.out + ".tmp", a.out)
    print("wrote", a.out)


if __name__ == "__main__":
    main()
