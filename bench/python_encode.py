#!/usr/bin/env python3
"""The Python module's cost over the C++ encoder, and tessera.batch on 1 vs 2 Dask workers.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_encode.py [--cli build/bin/tessera]

1. `encode` on a 512x512 image (a crop of ../shared/data/images/ldr-rgb-diffuse.png when
   present, else generated content), from an RGB and an RGBA array, against the same C++ call,
   in --pairs single calls per side alternating: in one process of one binary (the bench module
   `_tessera_bench`, the module's sources plus bench/python_native_calls.cpp, whose
   `native_encode_ms` times `compress_view` in C++: the binding's cost and nothing else), and
   across two processes (the installed module's `tessera.encode` against `compress_image` in a
   warm `build/bin/encode_call --serve`, bench/encode_call.cpp: what two binaries on this
   machine differ by); the CLI's whole process for scale; and the binding's cost on an 8x8
   crop.
2. `tessera.batch.compress_tree` over a generated tree of --files images (--file-size square,
   RGB and RGBA, 20 folders) on a LocalCluster of 1 and of 2 single-threaded workers, with the
   default (guided) task grouping and with one task per file; without Dask, the same task
   function in 1 and in 2 warm Python processes (the machine's own scaling, Dask's ceiling);
   all --batch-rounds times alternating; and the same files through one `tessera compress -j 1`
   process each, one after another. "Workers busy" is the files' own time (each file's seconds
   inside its task: read, encode, write, sidecar) over workers x wall time, i.e. what Dask
   leaves to the work; "paired" the median of the per-round ratios (the 1- and 2-worker runs of
   a round are adjacent in time).

Prints Markdown tables. Reports, asserts nothing but byte equality of the outputs.
"""

import argparse
import hashlib
import json
import os
import platform
import shutil
import statistics
import subprocess
import sys
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


# The in-process comparison, in an interpreter of its own: `_tessera_bench` (the module's sources
# plus bench/python_native_calls.cpp, built in python/CMakeLists.txt) registers the same C++
# types as tessera._tessera, so the two cannot be imported into one process.
_IN_PROCESS = """
import hashlib, json, sys, time
import numpy as np
import _tessera_bench as b
inputs = {name: np.load(path) for name, path in json.loads(sys.argv[1]).items()}
kw, pairs = json.loads(sys.argv[2]), int(sys.argv[3])
py, native, sha = {n: [] for n in inputs}, {n: [] for n in inputs}, {}
for n, a in inputs.items():  # warm-up
    sha[n] = hashlib.sha256(b.encode(a, **kw).to_bytes()).hexdigest()
    b.native_encode_ms(a, 1, **kw)
for n, a in inputs.items():  # one input after the other (see in_process_calls)
    fresh = np.empty_like(a)
    for i in range(pairs):
        for side in (("py", "native") if i % 2 == 0 else ("native", "py")):
            np.copyto(fresh, a)  # freshly written input on both sides, untimed, no allocation
            if side == "py":
                t0 = time.perf_counter()
                b.encode(fresh, **kw)
                py[n].append((time.perf_counter() - t0) * 1e3)
            else:
                native[n].append(b.native_encode_ms(fresh, 1, **kw)[0])
print(json.dumps({"py": py, "native": native, "sha256": sha}))
"""


def in_process_calls(module_dir, npy, kw, pairs):
    """Times `_tessera_bench.encode(array, **kw)` against `native_encode_ms`, the same C++ call
    timed in C++, in one process of the same binary: `pairs` single calls per side and input
    ({name: .npy path}), alternating, the order flipping every pair. Returns {"py": {name:
    [ms]}, "native": {name: [ms]}, "sha256": {name: hex digest of the texture file}}.

    Each call's input is rewritten into one buffer per input (not a new copy), and the inputs
    take turns by input, not call by call: with a new array per call and RGB and RGBA calls
    interleaved, glibc handed the RGB encode's 1 MiB RGBA buffer back to the kernel between
    calls on one side only (page faults that lengthened every 512x512 fast call), an effect of
    the harness's allocations on the heap, not of the binding."""
    env = dict(os.environ, PYTHONPATH=str(module_dir))
    r = subprocess.run([sys.executable, "-c", _IN_PROCESS, json.dumps(npy), json.dumps(kw),
                        str(pairs)], env=env, capture_output=True, text=True, check=True)
    return json.loads(r.stdout)


def with_alpha(img):
    return np.concatenate([img, np.full(img.shape[:2] + (1,), 255, np.uint8)], -1)


def encode_table(cli, bench_module, size, pairs, tmp):
    img, source = bench_image(size)
    inputs = {"RGB": img, "RGBA": with_alpha(img)}
    npy = {}
    for name, array in inputs.items():
        npy[name] = str(tmp / f"{name}.npy")
        np.save(npy[name], array)
    png = tmp / "bench.png"
    tessera.write_image(png, img)
    encode_call = Path(cli).parent / "encode_call"
    rows = []
    for fmt in ("pvrtc1-4", "pvrtc1-2"):
        for quality in ("fast", "normal"):
            for threads in (1, 0):
                kw = dict(format=fmt, quality=quality, threads=threads)
                same_process = in_process_calls(bench_module, npy, kw, pairs)
                py_ms, cpp_ms, textures = paired_calls(encode_call, png, inputs, kw, pairs)
                out = tmp / "bench.pvr"
                proc_ms = [run_cli(cli, "compress", png, "-o", out, "--format", fmt,
                                   "--quality", quality, "-j", threads)[1] for _ in range(3)]
                cli_bytes = out.read_bytes()
                cli_sha = hashlib.sha256(cli_bytes).hexdigest()
                cpp = statistics.median(cpp_ms)
                for name in inputs:
                    same = textures[name].to_bytes() == cli_bytes and \
                        same_process["sha256"][name] == cli_sha
                    bp, bn = same_process["py"][name], same_process["native"][name]
                    ratio = statistics.median(bp) / statistics.median(bn)
                    paired = statistics.median(p / c for p, c in zip(bp, bn))
                    py = statistics.median(py_ms[name])
                    rows.append(f"| {fmt} | {quality} | {threads or os.cpu_count()} | {name} | "
                                f"{statistics.median(bp):.2f} | {statistics.median(bn):.2f} | "
                                f"**{ratio:.3f}** | {paired:.3f} | {py:.2f} | {cpp:.2f} | "
                                f"{py / cpp:.3f} | {statistics.median(proc_ms):.1f} | "
                                f"{'yes' if same else 'NO'} |")
    head = [f"{size}x{size} image ({source}; the RGBA array is the same image with alpha 255); "
            f"{pairs} single calls per side and input, alternating, each call on a freshly "
            f"copied input (untimed) on both sides; medians. Same process: "
            f"`_tessera_bench.encode` against the same C++ call (`compress_view`) timed in C++ "
            f"by `native_encode_ms`, one process, one binary. Two processes: the installed "
            f"module's `tessera.encode` against `compress_image` timed in `bench/encode_call.cpp "
            f"--serve`.", "",
            "| format | quality | threads | array | Python `encode` ms | same C++ call ms | "
            "ratio | paired | `tessera.encode` ms | `encode_call` ms | ratio | CLI process ms | "
            "same bytes |",
            "|---|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---|"]
    # What the binding itself costs: the same-process comparison on an 8x8 image, where the
    # encode is a few microseconds and the rest is the call.
    small = {"RGB": img[:8, :8].copy()}
    small["RGBA"] = with_alpha(small["RGB"])
    small_npy = {}
    for name, array in small.items():
        small_npy[name] = str(tmp / f"small-{name}.npy")
        np.save(small_npy[name], array)
    kw = dict(format="pvrtc1-4", quality="fast", threads=1)
    r = in_process_calls(bench_module, small_npy, kw, pairs)
    parts = []
    for name in small:
        py_us = statistics.median(r["py"][name]) * 1e3
        native_us = statistics.median(r["native"][name]) * 1e3
        parts.append(f"{name} array: C++ {native_us:.1f} µs, Python {py_us:.1f} µs "
                     f"(+{py_us - native_us:.1f} µs)")
    tail = ["", f"The binding's own cost, the same-process comparison on an 8x8 crop (pvrtc1-4, "
            f"fast, 1 thread, {pairs} pairs): " + "; ".join(parts) + "."]
    return "\n".join(head + rows + tail)


def make_tree(root, files, size):
    for i in range(files):
        folder = root / f"set{(i // 2) % 10:02d}" / ("alpha" if i % 2 else "opaque")
        folder.mkdir(parents=True, exist_ok=True)
        tessera.write_image(folder / f"img{i:03d}.png", test_image(size, seed=i,
                                                                 channels=4 if i % 2 else 3))


# One process of the "no Dask" control: imports tessera, says so, then compresses the (src, out)
# pairs it reads from stdin with tessera.batch's own task function and prints its times.
_PLAIN_PROCESS = """
import json, sys, time
import tessera.batch as b
print("ready", flush=True)
jobs, quality = json.loads(sys.stdin.readline())
options = b._check_options({"quality": quality}, "pvr", 1)
t0 = time.time()
results = [b.compress_one(s, o, options, "pvr", 1) for s, o in jobs]
print(json.dumps({"start": t0, "end": time.time(), "own": sum(r["seconds"] for r in results),
                  "done": sum(r["status"] == "done" for r in results)}), flush=True)
"""


def plain_processes(src, dst, processes, quality):
    """The ceiling for Dask on this machine: `processes` Python processes, started and warm
    before the clock starts, each compressing every `processes`-th file with
    tessera.batch.compress_one. Returns the summary fields batch_table reads."""
    jobs, _ = tessera.batch.plan(src, dst, "pvr")
    procs = [subprocess.Popen([sys.executable, "-c", _PLAIN_PROCESS], stdin=subprocess.PIPE,
                              stdout=subprocess.PIPE, text=True) for _ in range(processes)]
    for proc in procs:
        assert proc.stdout.readline().strip() == "ready"
    for k, proc in enumerate(procs):
        proc.stdin.write(json.dumps([jobs[k::processes], quality]) + "\n")
        proc.stdin.flush()
    out = [json.loads(proc.stdout.readline()) for proc in procs]
    for proc in procs:
        proc.stdin.close()
        proc.wait()
    return {"done": sum(o["done"] for o in out), "failed": len(jobs) - sum(o["done"] for o in out),
            "seconds": max(o["end"] for o in out) - min(o["start"] for o in out),
            "setup_seconds": 0.0, "own": sum(o["own"] for o in out)}


def batch_table(cli, files, size, quality, rounds, tmp):
    src = tmp / "tree"
    make_tree(src, files, size)
    # Six configurations, alternating in each round (1 and 2 workers; guided task grouping, one
    # task per file, and plain processes without Dask); the median over the rounds of each.
    configs = [(1, None), (2, None), (1, "plain"), (2, "plain"), (2, 1), (1, 1)]
    times = {c: [] for c in configs}
    setup = {c: [] for c in configs}
    busy = {c: [] for c in configs}  # the files' own seconds / (workers x wall seconds)
    outputs = {}
    for r in range(rounds):
        for workers, per_task in (configs if r % 2 == 0 else configs[::-1]):
            dst = tmp / f"out{workers}-{per_task}"
            shutil.rmtree(dst, ignore_errors=True)
            own = []  # each file's seconds inside its task: read, encode, write, sidecar
            if per_task == "plain":
                s = plain_processes(src, dst, workers, quality)
                own.append(s["own"])
            else:
                s = tessera.batch.compress_tree(src, dst, workers=workers, quality=quality,
                                                files_per_task=per_task,
                                                on_result=lambda res: own.append(res["seconds"]))
            assert s["done"] == files and s["failed"] == 0, s
            outputs[(workers, per_task)] = dst
            times[(workers, per_task)].append(s["seconds"])
            setup[(workers, per_task)].append(s["setup_seconds"])
            busy[(workers, per_task)].append(sum(own) / (workers * s["seconds"]))
    mpx = files * size * size / 1e6
    med = {c: statistics.median(t) for c, t in times.items()}
    rows = []
    for workers, per_task in [(1, None), (2, None), (1, 1), (2, 1), (1, "plain"), (2, "plain")]:
        c = (workers, per_task)
        n = len(tessera.batch.group_jobs(list(range(files)), None, workers))
        if per_task == "plain":
            what = (f"no Dask: {workers} warm Python process(es), `compress_one` over every "
                    f"{'second ' if workers == 2 else ''}file")
        else:
            what = (f"tessera.batch, LocalCluster {workers} worker(s) x 1 thread, " +
                    (f"guided grouping ({n} tasks)" if per_task is None else "one task per file"))
        speed, paired = "1", ""
        if workers == 2:
            speed = f"**{med[(1, per_task)] / med[c]:.2f}x**"
            by_round = [a / b for a, b in zip(times[(1, per_task)], times[c])]
            paired = f"{statistics.median(by_round):.2f}x"
        rows.append(f"| {what} | "
                    f"{statistics.median(setup[c]):.2f} | {med[c]:.2f} | "
                    f"{' / '.join(f'{t:.2f}' for t in times[c])} | {mpx / med[c]:.2f} | "
                    f"{100 * statistics.median(busy[c]):.1f} % | {speed} | {paired} |")
    # The same files through the CLI, one process each, sequentially.
    dst = tmp / "outcli"
    jobs, _ = tessera.batch.plan(src, dst, "pvr")
    t0 = time.perf_counter()
    for s_path, o_path in jobs:
        os.makedirs(os.path.dirname(o_path), exist_ok=True)
        run_cli(cli, "-j", 1, "compress", s_path, "-o", o_path, "--quality", quality)
    seconds = time.perf_counter() - t0
    rows.append(f"| `tessera -j 1 compress`, one process per file, sequential | 0 | "
                f"{seconds:.2f} | {seconds:.2f} | {mpx / seconds:.2f} | | | |")
    same = all(Path(o).read_bytes() == (out / Path(o).relative_to(dst)).read_bytes()
               for _, o in jobs for out in outputs.values())
    head = [f"{files} files of {size}x{size} (half RGB, half RGBA) in 20 folders, quality "
            f"{quality}, pvrtc1-4, each file on one thread; {rounds} rounds, configurations "
            f"alternating; outputs byte-identical across all runs and the CLI: "
            f"{'yes' if same else 'NO'}:", "",
            "| run | cluster start s | compress s (median) | each round s | MPixel/s | "
            "workers busy | vs 1 worker | paired |", "|---|---:|---:|---:|---:|---:|---:|---:|"]
    return "\n".join(head + rows)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--cli", default=str(ROOT / "build" / "bin" / "tessera"))
    p.add_argument("--bench-module", default=str(ROOT / "build" / "bench" / "python"),
                   help="folder of the _tessera_bench module (TESSERA_BUILD_BENCH)")
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
            print(encode_table(args.cli, args.bench_module, args.size, args.pairs, tmp))
            print()
        if not args.skip_batch:
            print(batch_table(args.cli, args.files, args.file_size, args.quality,
                              args.batch_rounds, tmp))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
