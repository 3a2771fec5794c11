#!/usr/bin/env python3
"""The Python module's cost over the C++ encoder, and tessera.batch on 1 vs 2 Dask workers.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_encode.py [--cli build/bin/tessera]

1. `tessera.encode` on a 512x512 image (a crop of ../shared/data/images/ldr-rgb-diffuse.png
   when present, else generated content) against the same library call (`compress_image`)
   timed in a warm C++ process (build/bin/encode_call --serve, bench/encode_call.cpp), from an
   RGB and an RGBA array, in --pairs single calls per side alternating between the two
   processes, and the CLI's whole process.
2. `tessera.batch.compress_tree` over a generated tree of --files images (--file-size square,
   RGB and RGBA, 20 folders) on a LocalCluster of 1 and of 2 single-threaded workers, with the
   default task grouping and with one task per file, --batch-rounds times alternating, and the
   same files through one `tessera compress -j 1` process each, one after another.

Prints Markdown tables. Reports, asserts nothing but byte equality of the outputs.
"""

import argparse
import json
import os
import platform
import shutil
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

import tessera
import tessera.batch

ROOT = Path(__file__).resolve().parents[1]


def test_image(size, seed=0, channels=3):
    rng = np.random.default_rng(seed)
    y, x = np.mgrid[0:size, 0:size].astype(np.float64)
    r = 128 + 100 * np.sin(x / size * 12.0 + seed)
    g = 128 + 100 * np.cos(y / size * 9.0)
    b = np.where((x // 16 + y // 16) % 2 == 0, 50.0, 200.0)
    img = np.stack([r, g, b], -1) + rng.normal(0, 8, (size, size, 3))
    img = np.clip(np.rint(img), 0, 255).astype(np.uint8)
    if channels == 4:
        a = np.clip(255 * (x + y) / (2 * size - 2), 0, 255).astype(np.uint8)
        img = np.concatenate([img, a[..., None]], -1)
    return img


def bench_image(size):
    shared = ROOT.parent / "shared" / "data" / "images" / "ldr-rgb-diffuse.png"
    if shared.is_file():
        return tessera.read_image(shared)[:size, :size].copy(), f"{shared.name} crop"
    return test_image(size), "generated"


def run_cli(cli, *args):
    t0 = time.perf_counter()
    r = subprocess.run([cli, *map(str, args)], capture_output=True, text=True, check=True)
    return r.stdout, (time.perf_counter() - t0) * 1e3


def paired_calls(encode_call, png, inputs, kw, pairs):
    """Times `tessera.encode(array, **kw)` for each array in `inputs` against the C++ call
    served by `encode_call --serve` on `png`, in `pairs` single calls per side and input.
    Returns ({input: [ms]}, [C++ ms], {input: texture})."""
    server = subprocess.Popen(
        [str(encode_call), str(png), "--format", kw["format"], "--quality", kw["quality"],
         "--threads", str(kw["threads"]), "--serve"],
        stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    json.loads(server.stdout.readline())  # its warm-up call

    def cpp_call():
        server.stdin.write("1\n")
        server.stdin.flush()
        return json.loads(server.stdout.readline())["ms"][0]

    def py_call(array):
        # A freshly made input, as encode_call's copy just before its timer (and as a
        # read-then-encode pipeline has it): not the array the previous encode pushed out of
        # the cache.
        fresh = array.copy()
        t0 = time.perf_counter()
        tex = tessera.encode(fresh, **kw)
        return (time.perf_counter() - t0) * 1e3, tex

    textures = {name: tessera.encode(a, **kw) for name, a in inputs.items()}  # warm-up
    py_ms = {name: [] for name in inputs}
    cpp_ms = []
    # Single calls alternate between the two processes (the order flips every pair), so that
    # the machine's load hits both sides alike.
    for i in range(pairs):
        if i % 2:
            cpp_ms.append(cpp_call())
        for name, array in inputs.items():
            ms, textures[name] = py_call(array)
            py_ms[name].append(ms)
        if not i % 2:
            cpp_ms.append(cpp_call())
    server.stdin.close()
    server.wait()
    return py_ms, cpp_ms, textures


def with_alpha(img):
    return np.concatenate([img, np.full(img.shape[:2] + (1,), 255, np.uint8)], -1)


def encode_table(cli, size, pairs, tmp):
    img, source = bench_image(size)
    inputs = {"RGB": img, "RGBA": with_alpha(img)}
    png = tmp / "bench.png"
    tessera.write_image(png, img)
    encode_call = Path(cli).parent / "encode_call"
    rows = []
    for fmt in ("pvrtc1-4", "pvrtc1-2"):
        for quality in ("fast", "normal"):
            for threads in (1, 0):
                kw = dict(format=fmt, quality=quality, threads=threads)
                py_ms, cpp_ms, textures = paired_calls(encode_call, png, inputs, kw, pairs)
                out = tmp / "bench.pvr"
                proc_ms = [run_cli(cli, "compress", png, "-o", out, "--format", fmt,
                                   "--quality", quality, "-j", threads)[1] for _ in range(3)]
                cpp = statistics.median(cpp_ms)
                for name in inputs:
                    same = textures[name].to_bytes() == out.read_bytes()
                    py = statistics.median(py_ms[name])
                    paired = statistics.median(p / c for p, c in zip(py_ms[name], cpp_ms))
                    rows.append(f"| {fmt} | {quality} | {threads or os.cpu_count()} | {name} | "
                                f"{py:.2f} | {cpp:.2f} | **{py / cpp:.3f}** | {paired:.3f} | "
                                f"{statistics.median(proc_ms):.1f} | "
                                f"{'yes' if same else 'NO'} |")
    head = [f"`tessera.encode` vs the same C++ call (`compress_image`, timed in a warm process "
            f"by `bench/encode_call.cpp --serve`) on a {size}x{size} image ({source}; the RGBA "
            f"array is the same image with alpha 255); {pairs} single calls per side and input, "
            f"alternating between the processes, each call on a freshly copied input "
            f"(untimed) on both sides; medians:", "",
            "| format | quality | threads | array | Python `encode` ms | C++ `compress_image` ms "
            "| ratio of medians | median of paired ratios | CLI process ms | same bytes |",
            "|---|---|---:|---|---:|---:|---:|---:|---:|---|"]
    # What the binding itself costs: the same comparison on an 8x8 image, where the encode is
    # a few microseconds and the rest is the call.
    small = img[:8, :8].copy()
    tessera.write_image(tmp / "small.png", small)
    kw = dict(format="pvrtc1-4", quality="fast", threads=1)
    py_ms, cpp_ms, _ = paired_calls(encode_call, tmp / "small.png",
                                    {"RGB": small, "RGBA": with_alpha(small)}, kw, pairs)
    cpp = statistics.median(cpp_ms) * 1e3
    tail = ["", f"The binding's own cost, the same comparison on an 8x8 crop (pvrtc1-4, fast, 1 "
            f"thread, {pairs} pairs): C++ call {cpp:.1f} µs; Python "
            + ", ".join(f"{name} {statistics.median(v) * 1e3:.1f} µs "
                        f"(+{statistics.median(v) * 1e3 - cpp:.1f} µs)"
                        for name, v in py_ms.items()) + "."]
    return "\n".join(head + rows + tail)


def make_tree(root, files, size):
    for i in range(files):
        folder = root / f"set{(i // 2) % 10:02d}" / ("alpha" if i % 2 else "opaque")
        folder.mkdir(parents=True, exist_ok=True)
        tessera.write_image(folder / f"img{i:03d}.png", test_image(size, seed=i,
                                                                 channels=4 if i % 2 else 3))


def batch_table(cli, files, size, quality, rounds, tmp):
    src = tmp / "tree"
    make_tree(src, files, size)
    # Four configurations, alternating in each round (1 and 2 workers, default task grouping
    # and one task per file); the median over the rounds per configuration.
    configs = [(1, None), (2, None), (2, 1), (1, 1)]
    times = {c: [] for c in configs}
    setup = {c: [] for c in configs}
    outputs = {}
    for r in range(rounds):
        for workers, per_task in (configs if r % 2 == 0 else configs[::-1]):
            dst = tmp / f"out{workers}-{per_task}"
            shutil.rmtree(dst, ignore_errors=True)
            s = tessera.batch.compress_tree(src, dst, workers=workers, quality=quality,
                                            files_per_task=per_task)
            assert s["done"] == files and s["failed"] == 0, s
            outputs[(workers, per_task)] = dst
            times[(workers, per_task)].append(s["seconds"])
            setup[(workers, per_task)].append(s["setup_seconds"])
    mpx = files * size * size / 1e6
    med = {c: statistics.median(t) for c, t in times.items()}
    rows = []
    for workers, per_task in [(1, None), (2, None), (1, 1), (2, 1)]:
        c = (workers, per_task)
        n = len(tessera.batch.group_jobs(list(range(files)), None, workers)[0])
        grouping = "one task per file" if per_task == 1 else \
            f"default grouping ({n} file{'s' if n > 1 else ''} per task)"
        speed = f"**{med[(1, per_task)] / med[c]:.2f}x**" if workers == 2 else "1"
        rows.append(f"| tessera.batch, LocalCluster {workers} worker(s) x 1 thread, {grouping} | "
                    f"{statistics.median(setup[c]):.2f} | {med[c]:.2f} | "
                    f"{' / '.join(f'{t:.2f}' for t in times[c])} | {mpx / med[c]:.2f} | {speed} |")
    # The same files through the CLI, one process each, sequentially.
    dst = tmp / "outcli"
    jobs, _ = tessera.batch.plan(src, dst, "pvr")
    t0 = time.perf_counter()
    for s_path, o_path in jobs:
        os.makedirs(os.path.dirname(o_path), exist_ok=True)
        run_cli(cli, "-j", 1, "compress", s_path, "-o", o_path, "--quality", quality)
    seconds = time.perf_counter() - t0
    rows.append(f"| `tessera -j 1 compress`, one process per file, sequential | 0 | "
                f"{seconds:.2f} | {seconds:.2f} | {mpx / seconds:.2f} | |")
    same = all(Path(o).read_bytes() == (out / Path(o).relative_to(dst)).read_bytes()
               for _, o in jobs for out in outputs.values())
    head = [f"{files} files of {size}x{size} (half RGB, half RGBA) in 20 folders, quality "
            f"{quality}, pvrtc1-4, each file on one thread; {rounds} rounds, configurations "
            f"alternating; outputs byte-identical across all runs and the CLI: "
            f"{'yes' if same else 'NO'}:", "",
            "| run | cluster start s | compress s (median) | each round s | MPixel/s | "
            "vs 1 worker |", "|---|---:|---:|---:|---:|---:|"]
    return "\n".join(head + rows)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--cli", default=str(ROOT / "build" / "bin" / "tessera"))
    p.add_argument("--size", type=int, default=512)
    p.add_argument("--pairs", type=int, default=101,
                   help="single calls per side (and per input array) in each encode row")
    p.add_argument("--files", type=int, default=200)
    p.add_argument("--file-size", type=int, default=256)
    p.add_argument("--quality", default="normal")
    p.add_argument("--batch-rounds", type=int, default=3)
    p.add_argument("--skip-encode", action="store_true", help="only the Dask table")
    p.add_argument("--skip-batch", action="store_true", help="only the encode table")
    args = p.parse_args()
    cpu = "unknown CPU"
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next(line.split(":", 1)[1].strip() for line in f if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    print(f"Machine: {cpu}, {os.cpu_count()} logical CPUs, {platform.system()} "
          f"{platform.release()}, Python {platform.python_version()}, tessera "
          f"{tessera.__version__}; {time.strftime('%Y-%m-%d')}; load average at start "
          f"{os.getloadavg()[0]:.2f}\n")
    tmp = Path(tempfile.mkdtemp(prefix="tessera-bench-"))
    try:
        if not args.skip_encode:
            print(encode_table(args.cli, args.size, args.pairs, tmp))
            print()
        if not args.skip_batch:
            print(batch_table(args.cli, args.files, args.file_size, args.quality,
                              args.batch_rounds, tmp))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
