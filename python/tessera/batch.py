"""Compress a directory tree of images to PVRTC1 over a Dask cluster.

    python3 -m tessera.batch SRC DST [--scheduler ADDRESS] [--workers N] [--format pvrtc1-4]
                             [--quality normal] [--container pvr|ktx|ktx2] [--zstd LEVEL]
                             [--mipmaps] [--mip-levels N] [--mip-filter box|lanczos|kaiser]
                             [--srgb] [--flip-y] [--premultiply] [--alpha-bleed] [--alpha-weighted]
                             [--normal-map] ...

Every image under SRC (recursively: .png, .jpg, .jpeg, .tga, .bmp, any case) becomes
DST/<same relative folder>/<stem>.pvr (or .ktx, .ktx2), byte-identical to
``tessera compress IN -o OUT`` with the same options: each task runs ``tessera.encode_file`` and
``Texture.write``, the library calls the CLI makes. The options are the CLI's per-image ones
(``compress_tree``'s keywords are encode's: ``tessera.ENCODE_DEFAULTS``); each image is its own
2D texture: cube maps and arrays (``tessera compress --cube`` / ``--array``,
``tessera.encode_file(paths, cube=True)``) are not made here. A --premultiply'd image without
alpha is left as it is, as by the CLI, and the CLI's warning is reported with its file.

Tasks: each Dask task compresses a group of files. Dask spends milliseconds of scheduler and
worker CPU on every task (a sizeable part of a small file's encode: docs/benchmarks/python.md),
so a task of one small file spends a good part of the machine on bookkeeping, while large tasks
at the end leave workers idle. By default the groups
are guided (`group_jobs`): the largest files (by input bytes) first, each task about the
remaining work / (2 x workers), at most 16 files, down to single files at the end (200 equal
files on 2 workers: 21 tasks, the first nine of 16 files, the last four of one).
``--files-per-task N`` gives groups of N files in tree order instead (1: one task per file).
Grouping changes nothing else: every file still has its own result, its own failure and its own
sidecar, and the bytes are the same.

Cluster: ``--scheduler ADDRESS`` (e.g. tcp://host:8786, a running ``dask-scheduler`` with
``dask-worker ADDRESS`` processes that can import ``tessera`` and see SRC and DST at the same
absolute paths, e.g. on a shared filesystem) or, without it, a LocalCluster of
``--workers`` processes (default: one per CPU), one thread each, with Dask's periodic
housekeeping slowed down (`LOCAL_CLUSTER_CONFIG`: no statistical profiler, 1 s event-loop ticks,
1 s memory checks, so that an idle cluster leaves the CPU to the encoders; docs/benchmarks/python.md
has its cost). ``--threads`` sets the encoder threads per task (default 1: the parallelism is across
files). Before the first task, every worker imports tessera (counted as set-up time).

Resuming: next to each output, ``OUT.pvr.json`` (the "sidecar", the library's up-to-date
record: ``tessera.up_to_date_record``) records the options, the tessera version and the input's
size and modification time: the record ``tessera compress --skip-up-to-date`` writes, byte for
byte. A file is skipped when its output is up to date (``tessera.is_up_to_date``: it exists, is
newer than the input, and its sidecar matches the current options and input); otherwise it is
compressed again (``--force`` always recompresses). The sidecar is written after the output, so
an interrupted run never leaves an output that looks complete without being so.

A file that fails (not a power of two without --resize-pot, corrupt, unreadable, unwritable
output) fails alone: it is reported, with the message ``tessera compress`` prints for it (its
flags: "--resize-pot"), and the other files go on. Bad options: ``compress_tree`` raises
ValueError naming the keyword (the words of ``tessera.encode``'s errors); the command line names
the flag (the words of ``tessera compress``'s usage errors) and exits with 2. The run prints a
summary (files done / skipped / failed, MPixel/s) and exits with 1 when any file failed, else 0.
"""

import argparse
import json
import logging
import os
import sys
import time
import warnings
from pathlib import Path

import tessera

SIDECAR_SUFFIX = ".json"
_FORMATS = ("pvrtc1-4", "pvrtc1-2")
_QUALITIES = ("fast", "normal", "high")
_CONTAINERS = ("pvr", "ktx", "ktx2")
_MIP_FILTERS = ("box", "lanczos", "kaiser")
_TYPES = {"format": str, "quality": str, "mipmaps": bool, "srgb": bool, "iterations": int,
          "exact_search_rounds": int, "resize_pot": bool, "mip_levels": int, "mip_filter": str,
          "flip_y": bool, "premultiply": bool, "alpha_bleed": bool, "alpha_weighted": bool,
          "normal_map": bool}


def _flag(keyword):
    return "--" + keyword.replace("_", "-")


def _usage_problem(o, container, zstd, flags):
    """The options that conflict, as the CLI's usage errors: in flags (`flags`, the command
    line) or keywords (compress_tree, in the words of tessera.encode's errors); None if none."""
    n = _flag if flags else str
    if o["normal_map"] and o["srgb"]:
        return f"{n('normal_map')} and {n('srgb')}: a normal map holds vectors, never sRGB colour"
    if o["premultiply"] and o["alpha_bleed"]:
        return (f"{n('alpha_bleed')} and {n('premultiply')}: bleeding is for straight alpha "
                "(premultiplied transparent texels are black already)")
    if o["alpha_weighted"] and o["premultiply"]:
        return (f"{n('alpha_weighted')} and {n('premultiply')}: weighting is for straight alpha "
                "(premultiplied colour carries alpha already)")
    if o["alpha_weighted"] and o["format"] == "pvrtc1-2":
        fmt = "--format pvrtc1-2" if flags else "format='pvrtc1-2'"
        return (f"{n('alpha_weighted')} and {fmt}: alpha-weighted colour error is for 4 bpp "
                "only")
    if o["mip_filter"] != "box" and not o["mipmaps"] and not o["mip_levels"]:
        if flags:
            return f"--mip-filter {o['mip_filter']} needs --mipmaps or --mip-levels N"
        return f"mip_filter={o['mip_filter']!r} needs mipmaps=True or mip_levels=N"
    if zstd and container != "ktx2":
        if flags:
            return "--zstd needs a KTX 2.0 output (--container ktx2)"
        return "zstd needs a KTX 2.0 output (container='ktx2')"
    return None


def _check_options(options, container, threads, zstd=0):
    shapes = sorted({"cube", "array"} & set(options))
    if shapes:
        raise ValueError(f"{', '.join(shapes)}: tessera.batch makes one 2D texture of each image "
                         "(cube maps and arrays: tessera.encode_file(paths, cube=True) or "
                         "tessera compress --cube / --array)")
    unknown = set(options) - set(tessera.ENCODE_DEFAULTS)
    if unknown:
        raise ValueError("unknown encode option(s): " + ", ".join(sorted(unknown)))
    o = dict(tessera.ENCODE_DEFAULTS, **options)
    o = {k: _TYPES[k](v) for k, v in o.items()}  # numpy integers, 1 for True: the CLI's types
    if o["format"] not in _FORMATS:
        raise ValueError(f"format: {o['format']!r} is not one of {', '.join(_FORMATS)}")
    if o["quality"] not in _QUALITIES:
        raise ValueError(f"quality: {o['quality']!r} is not one of {', '.join(_QUALITIES)}")
    if not -1 <= o["iterations"] <= 1000:
        raise ValueError(f"iterations: {o['iterations']} is not in [-1, 1000]")
    if not 0 <= o["exact_search_rounds"] <= 1000:
        raise ValueError(f"exact_search_rounds: {o['exact_search_rounds']} is not in [0, 1000]")
    if not 0 <= o["mip_levels"] <= 17:
        raise ValueError(f"mip_levels: {o['mip_levels']} is not in [0, 17]")
    if o["mip_filter"] not in _MIP_FILTERS:
        raise ValueError(f"mip_filter: {o['mip_filter']!r} is not one of "
                         f"{', '.join(map(repr, _MIP_FILTERS))}")
    if container not in _CONTAINERS:
        raise ValueError(f"container: {container!r} is not one of {', '.join(_CONTAINERS)}")
    if not 0 <= zstd <= 22:
        raise ValueError(f"zstd: {zstd} is not in [0, 22]")
    if threads < 0:
        raise ValueError(f"threads: {threads} is negative")
    problem = _usage_problem(o, container, zstd, flags=False)
    if problem:
        raise ValueError(problem)
    return o


def plan(src, dst, container="pvr"):
    """Lists the work: [(input path, output path)] for every image under `src`, sorted, and
    [(input path, message)] for inputs whose output name another input already took (a.png and
    a.jpg both give a.pvr; the first in sorted order wins)."""
    src, dst = Path(src), Path(dst)
    jobs, clashes, taken = [], [], {}
    for folder, dirs, files in os.walk(src):
        dirs.sort()
        for name in sorted(files):
            path = Path(folder) / name
            if path.suffix.lower() not in tessera.IMAGE_EXTENSIONS:
                continue
            out = dst / path.relative_to(src).with_suffix("." + container)
            if out in taken:
                clashes.append((str(path), f"{path}: output {out} is also made from {taken[out]}"))
                continue
            taken[out] = path
            jobs.append((str(path), str(out)))
    return jobs, clashes


def is_up_to_date(src, out, options, container, zstd=0):
    """True when `out` exists, is newer than `src`, and its sidecar records these options and
    this input (size and modification time): ``tessera.is_up_to_date``."""
    return tessera.is_up_to_date(src, out, container=container, zstd=zstd, **options)


def _cli_words(message):
    """A message of tessera.encode_file as `tessera compress` prints it (its flags)."""
    for keyword, flag in (("with resize_pot=True", "with --resize-pot"),
                          (": premultiply leaves", ": --premultiply leaves")):
        message = message.replace(keyword, flag, 1)
    return message


def compress_one(src, out, options, container, threads, zstd=0):
    """The task: compress one file like ``tessera compress SRC -o OUT``, then write the sidecar.
    Returns a result dict; errors are returned (status 'failed', with the CLI's message), never
    raised; warnings (premultiply on an image without alpha) are returned in 'warnings', as
    the CLI words them."""
    t0 = time.perf_counter()
    try:
        # The input as it was before the encode: if it changes meanwhile, the record says so.
        record = tessera.up_to_date_record(src, container=container, zstd=zstd, **options)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            texture = tessera.encode_file(src, threads=threads, **options)
        os.makedirs(os.path.dirname(out) or ".", exist_ok=True)
        texture.write(out, zstd=zstd)
        tessera.write_up_to_date_record(out, record)
        return {"src": src, "out": out, "status": "done",
                "pixels": texture.width * texture.height,
                "seconds": time.perf_counter() - t0,
                "warnings": [_cli_words(str(w.message)) for w in caught]}
    except (tessera.Error, OSError, ValueError) as e:
        return {"src": src, "out": out, "status": "failed", "error": _cli_words(str(e)),
                "seconds": time.perf_counter() - t0}


def compress_group(group, options, container, threads, zstd=0):
    """One task: `compress_one` for each (src, out) pair of `group`, in order; a list of their
    results (each file succeeds or fails alone)."""
    return [compress_one(s, o, options, container, threads, zstd) for s, o in group]


MAX_FILES_PER_TASK = 16


def group_jobs(jobs, files_per_task=None, workers=1, weights=None):
    """Splits `jobs` into the groups of files that one Dask task each compresses.

    `files_per_task` N: consecutive groups of N files, in the order of `jobs`.
    None: guided self-scheduling. The jobs, heaviest first (`weights`, e.g. input bytes; all
    equal when None; ties keep their order), are cut into groups that each take about the
    remaining weight / (2 x `workers`), at most MAX_FILES_PER_TASK files and at least one: few
    large tasks while there is much work left (each task costs Dask milliseconds), single files
    at the end, so that the workers finish together."""
    if files_per_task is not None:
        if files_per_task < 1:
            raise ValueError(f"files_per_task: {files_per_task} is not at least 1")
        return [jobs[i:i + files_per_task] for i in range(0, len(jobs), files_per_task)]
    if weights is None:
        weights = [1] * len(jobs)
    order = sorted(range(len(jobs)), key=lambda i: -weights[i])
    remaining = sum(weights[i] for i in order)
    groups, i = [], 0
    while i < len(order):
        target = remaining / (2 * max(1, workers))
        group, weight = [], 0
        while i < len(order) and len(group) < MAX_FILES_PER_TASK and (not group or
                                                                      weight < target):
            group.append(jobs[order[i]])
            weight += weights[order[i]]
            i += 1
        remaining -= weight
        groups.append(group)
    return groups


# Dask's periodic work, slowed down for the LocalCluster that compress_tree starts: the worker's
# statistical profiler samples every thread's stack every 10 ms, the event loops tick every 20
# ms and the memory and system monitors poll psutil several times a second: CPU that the
# encoders do not get (an idle LocalCluster's cost with and without these values:
# docs/benchmarks/python.md).
LOCAL_CLUSTER_CONFIG = {
    "distributed.worker.profile.enabled": False,
    "distributed.admin.tick.interval": "1s",
    "distributed.admin.system-monitor.interval": "5s",
    "distributed.worker.memory.monitor-interval": "1s",
}


def _input_bytes(path):
    """The weight `group_jobs` gives a file: its size in bytes (0 when it cannot be read; its
    task then reports why)."""
    try:
        return os.stat(path).st_size
    except OSError:
        return 0


def _import_tessera():
    import tessera as _  # noqa: F401  (the worker's first task should not pay the import)
    return os.getpid()


def _open_client(scheduler, workers):
    import dask
    from dask.distributed import Client, LocalCluster

    if scheduler:
        return Client(scheduler), None
    with dask.config.set(LOCAL_CLUSTER_CONFIG):
        cluster = LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1,
                               processes=True, dashboard_address=None,
                               silence_logs=logging.ERROR)
        return Client(cluster), cluster


def compress_tree(src, dst, *, scheduler=None, workers=None, client=None, container="pvr",
                  zstd=0, threads=1, force=False, on_result=None, files_per_task=None,
                  **options):
    """Compresses every image under `src` into the mirrored tree `dst` (see the module doc).

    Cluster: `client` (a dask.distributed.Client to use as is), else `scheduler` (an address),
    else a LocalCluster of `workers` single-threaded processes, closed at the end. `container`
    'pvr', 'ktx' or 'ktx2' (`zstd`: its Zstandard level, 1-22, 0 = none, as --zstd); `options`
    are encode's keywords (format, quality, mipmaps, mip_levels, mip_filter, srgb, iterations,
    exact_search_rounds, resize_pot, flip_y, premultiply, alpha_bleed, alpha_weighted,
    normal_map: see
    tessera.ENCODE_DEFAULTS; not cube / array); `threads` is the encoder's thread count per
    task; `files_per_task` the files of one Dask task (None: `group_jobs`'s guided groups,
    weighted by input bytes).
    `on_result(result)` is called for each finished file. Returns the summary dict: files,
    done, skipped, failed, failures ([{src, error}]), warnings ([{src, warning}]), pixels
    (level-0 texels encoded), seconds (from the first task submitted to the last result),
    mpixels_per_s, workers, setup_seconds (starting / connecting the cluster).
    Raises ValueError for bad options (naming the keyword: "normal_map and srgb: ..."); a failing
    file is reported, never raised.
    """
    options = _check_options(options, container, threads, zstd)
    if files_per_task is not None and files_per_task < 1:
        raise ValueError(f"files_per_task: {files_per_task} is not at least 1")
    if scheduler or client is not None:
        # Workers elsewhere: send absolute paths (SRC and DST must be mounted at the same place
        # on the workers). A LocalCluster's workers share this process's working directory, so
        # paths stay as given and messages name files as the CLI would.
        src, dst = os.path.abspath(src), os.path.abspath(dst)
    if not Path(src).is_dir():
        raise ValueError(f"{src}: not a directory")
    jobs, clashes = plan(src, dst, container)
    todo = [(s, o) for s, o in jobs
            if force or not is_up_to_date(s, o, options, container, zstd)]
    summary = {"files": len(jobs) + len(clashes), "done": 0, "skipped": len(jobs) - len(todo),
               "failed": len(clashes), "failures": [{"src": s, "error": e} for s, e in clashes],
               "warnings": [],
               "pixels": 0, "seconds": 0.0, "mpixels_per_s": 0.0, "workers": 0,
               "setup_seconds": 0.0}
    if not todo:
        return summary

    from dask.distributed import as_completed

    t_setup = time.perf_counter()
    cluster = None
    own = client is None
    if own:
        client, cluster = _open_client(scheduler, workers)
    try:
        summary["workers"] = len(client.scheduler_info().get("workers", {}))
        client.run(_import_tessera)
        t0 = time.perf_counter()
        summary["setup_seconds"] = t0 - t_setup
        groups = group_jobs(todo, files_per_task, summary["workers"],
                            [_input_bytes(s) for s, _ in todo])
        futures = [client.submit(compress_group, g, options, container, threads, zstd,
                                 pure=False, retries=0) for g in groups]
        group_of = {f.key: g for f, g in zip(futures, groups)}
        for future in as_completed(futures):
            try:
                results = future.result()
            except Exception as e:  # the worker died (e.g. killed): its files fail, alone
                results = [{"src": s, "status": "failed", "error": f"{s}: task failed: {e!r}"}
                           for s, _ in group_of[future.key]]
            for result in results:
                if result["status"] == "done":
                    summary["done"] += 1
                    summary["pixels"] += result["pixels"]
                    summary["warnings"] += [{"src": result["src"], "warning": w}
                                            for w in result["warnings"]]
                else:
                    summary["failed"] += 1
                    summary["failures"].append({"src": result["src"], "error": result["error"]})
                if on_result is not None:
                    on_result(result)
        summary["seconds"] = time.perf_counter() - t0
    finally:
        if own:
            client.close()
            if cluster is not None:
                cluster.close()
    summary["failures"].sort(key=lambda f: f["src"])
    summary["warnings"].sort(key=lambda w: w["src"])
    if summary["seconds"] > 0:
        summary["mpixels_per_s"] = summary["pixels"] / 1e6 / summary["seconds"]
    return summary


def format_summary(summary):
    lines = [f"tessera.batch: {summary['files']} file(s): {summary['done']} done, "
             f"{summary['skipped']} skipped, {summary['failed']} failed; "
             f"{summary['pixels'] / 1e6:.2f} MPixel in {summary['seconds']:.2f} s "
             f"({summary['mpixels_per_s']:.2f} MPixel/s) on {summary['workers']} worker(s)"]
    lines += [f"  failed: {f['error']}" for f in summary["failures"]]
    lines += [f"  warning: {w['warning']}" for w in summary.get("warnings", [])]
    return "\n".join(lines)


def _int_in(low, high):
    """An argparse type: an integer in [low, high] (the CLI's range checks)."""
    def parse(text):
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not an integer") from None
        if not low <= value <= high:
            raise argparse.ArgumentTypeError(f"{value} is not in [{low}, {high}]")
        return value
    return parse


def main(argv=None):
    p = argparse.ArgumentParser(
        prog="python3 -m tessera.batch",
        description="Compress every image under SRC (recursively) to PVRTC1 in the mirrored "
                    "tree DST over a Dask cluster; outputs equal `tessera compress`'s.")
    p.add_argument("src", metavar="SRC")
    p.add_argument("dst", metavar="DST")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="Dask scheduler address (default: start a LocalCluster)")
    p.add_argument("--workers", type=int, default=None,
                   help="LocalCluster worker processes (default: one per CPU)")
    p.add_argument("--threads", type=int, default=1, help="encoder threads per task (0 = all)")
    p.add_argument("--files-per-task", type=int, default=None, metavar="N",
                   help="files compressed by one Dask task (default: guided, largest files "
                        "first, 16 files per task down to 1 at the end)")
    p.add_argument("--format", choices=_FORMATS, default="pvrtc1-4")
    p.add_argument("--quality", choices=_QUALITIES, default="normal")
    p.add_argument("--container", choices=_CONTAINERS, default="pvr")
    p.add_argument("--iterations", type=int, default=-1)
    p.add_argument("--exact-search-rounds", type=int, default=0)
    p.add_argument("--zstd", type=_int_in(1, 22), default=0, metavar="LEVEL",
                   help="KTX 2.0: Zstandard supercompression at LEVEL (1-22)")
    p.add_argument("--mipmaps", action="store_true")
    p.add_argument("--mip-levels", type=_int_in(1, 17), default=0, metavar="N",
                   help="encode at most N levels, level 0 included (implies --mipmaps)")
    p.add_argument("--mip-filter", choices=_MIP_FILTERS, default="box")
    p.add_argument("--srgb", action="store_true")
    p.add_argument("--resize-pot", action="store_true")
    p.add_argument("--flip-y", action="store_true", help="flip the images upside down first")
    p.add_argument("--premultiply", action="store_true",
                   help="multiply colour by alpha and mark the textures premultiplied")
    p.add_argument("--alpha-bleed", action="store_true",
                   help="give fully transparent texels the colour of the nearest visible one")
    p.add_argument("--alpha-weighted", action="store_true",
                   help="4 bpp: weight colour error by alpha (no bits on invisible colour)")
    p.add_argument("--normal-map", action="store_true",
                   help="the images are normal maps (vectors: renormalised mips; never sRGB)")
    p.add_argument("--force", action="store_true", help="recompress up-to-date outputs too")
    p.add_argument("--json", action="store_true", help="print the summary as one JSON object")
    p.add_argument("-v", "--verbose", action="store_true", help="print one line per file")
    args = p.parse_args(argv)
    options = {k: getattr(args, k) for k in tessera.ENCODE_DEFAULTS}
    # Conflicting flags: the CLI's usage errors, in its flags.
    problem = _usage_problem(options, args.container, args.zstd, flags=True)
    if problem:
        print(f"tessera.batch: {problem}", file=sys.stderr)
        return 2

    def report(result):
        if result["status"] != "done":
            print(f"tessera.batch: {result['error']}", file=sys.stderr, flush=True)
            return
        for warning in result["warnings"]:
            print(f"tessera.batch: warning: {warning}", file=sys.stderr, flush=True)
        if args.verbose:
            print(f"wrote {result['out']} ({result['seconds'] * 1e3:.1f} ms)", flush=True)

    try:
        summary = compress_tree(
            args.src, args.dst, scheduler=args.scheduler, workers=args.workers,
            container=args.container, zstd=args.zstd, threads=args.threads, force=args.force,
            on_result=report, files_per_task=args.files_per_task, **options)
    except ValueError as e:
        print(f"tessera.batch: {e}", file=sys.stderr)
        return 2
    print(json.dumps(summary, indent=2) if args.json else format_summary(summary))
    return 1 if summary["failed"] else 0


if __name__ == "__main__":
    sys.exit(main())
