#!/usr/bin/env python3
"""What linking the library into a shared object costs the encoder (why the Python module is
linked with --exclude-libs,ALL), and how much the same static call moves with its code layout.

    /usr/bin/python3 bench/encode_call_linking.py [--build build] [--pairs 151] [--threads 1]
                                                   [--format pvrtc1-4] [--quality fast]

Links bench/encode_call.cpp against the same build/lib/libtessera.a: statically (as the CLI),
through a shared object that exports the library's symbols (so calls between the library's
functions go through the PLT and globals through the GOT, as in a module linked without
--exclude-libs), through the same shared object linked -Bsymbolic, and statically again with
16, 32 and 48 bytes of padding linked before all of the code (the same machine code, every
function and loop moved by that many bytes relative to the 32- and 64-byte windows the CPU
fetches and caches decoded instructions in: what a different binary, e.g. the Python module,
does to the same code). Then times one 512x512 crop of ldr-rgb-diffuse.png through each,
single calls alternating between the `--serve` processes (order flipping every round), and
prints a Markdown table of medians and ratios to the static binary.
"""

import argparse
import json
import statistics
import subprocess
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
LIBS = ["-ltbb", "-lspng", "-ldeflate", "-lz", "-lpthread"]


def build(build_dir, tmp):
    lib = build_dir / "lib" / "libtessera.a"
    src = ROOT / "bench" / "encode_call.cpp"
    cxx = ["g++", "-std=c++20", "-O3", "-DNDEBUG", f"-I{ROOT / 'include'}"]
    binaries = {"static (as the CLI)": build_dir / "bin" / "encode_call"}
    for name, extra in (("shared object, exported symbols", []),
                        ("shared object, -Bsymbolic", ["-Wl,-Bsymbolic"])):
        d = tmp / name.split(",")[1].strip().replace(" ", "-")
        d.mkdir()
        subprocess.run(["g++", "-shared", "-o", str(d / "libtess.so"), *extra,
                        "-Wl,--whole-archive", str(lib), "-Wl,--no-whole-archive", *LIBS],
                       check=True)
        subprocess.run([*cxx, str(src), f"-L{d}", "-ltess", f"-Wl,-rpath,{d}", "-o",
                        str(d / "encode_call")], check=True)
        binaries[name] = d / "encode_call"
    for pad in (16, 32, 48):
        d = tmp / f"pad{pad}"
        d.mkdir()
        # A .text of `pad` bytes (alignment 1) linked before every other object of the program.
        (d / "pad.c").write_text(f'__asm__(".text\\n.skip {pad}, 0x90\\n");\n')
        subprocess.run(["gcc", "-c", "-o", str(d / "pad.o"), str(d / "pad.c")], check=True)
        subprocess.run([*cxx, str(d / "pad.o"), str(src), str(lib), *LIBS, "-o",
                        str(d / "encode_call")], check=True)
        binaries[f"static, code moved by {pad} bytes"] = d / "encode_call"
    return binaries


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--build", default=str(ROOT / "build"))
    p.add_argument("--pairs", type=int, default=151)
    p.add_argument("--threads", type=int, default=1)
    p.add_argument("--format", default="pvrtc1-4")
    p.add_argument("--quality", default="fast")
    args = p.parse_args()
    import tessera
    with tempfile.TemporaryDirectory(prefix="tessera-linking-") as t:
        tmp = Path(t)
        img = tessera.read_image(ROOT.parent / "shared" / "data" / "images" /
                                 "ldr-rgb-diffuse.png")[:512, :512].copy()
        png = tmp / "crop.png"
        tessera.write_image(png, img)
        binaries = build(Path(args.build), tmp)
        servers = [subprocess.Popen([str(b), str(png), "--format", args.format, "--quality",
                                     args.quality, "--threads", str(args.threads), "--serve"],
                                    stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
                   for b in binaries.values()]
        for s in servers:
            s.stdout.readline()  # warm-up
        ms = [[] for _ in servers]
        for i in range(args.pairs):
            order = list(range(len(servers)))
            for k in (order if i % 2 == 0 else order[::-1]):
                servers[k].stdin.write("1\n")
                servers[k].stdin.flush()
                ms[k].append(json.loads(servers[k].stdout.readline())["ms"][0])
        for s in servers:
            s.stdin.close()
            s.wait()
    base = statistics.median(ms[0])
    print(f"{args.format} {args.quality}, 512x512, {args.threads} thread(s), {args.pairs} "
          "alternating calls per binary:\n")
    print("| encode_call linked | median ms | ratio | paired |\n|---|---:|---:|---:|")
    for name, m in zip(binaries, ms):
        paired = statistics.median(a / b for a, b in zip(m, ms[0]))
        print(f"| {name} | {statistics.median(m):.2f} | **{statistics.median(m) / base:.3f}** | "
              f"{paired:.3f} |")


if __name__ == "__main__":
    main()
