#!/usr/bin/env python3
"""Where the PVRTC encoder's time goes, per pass of its schedule (src/pvrtc/encode/schedule.cpp).

Usage (from the repository root; needs `perf`, Debian's linux-perf):
    /usr/bin/python3 bench/pvrtc_profile.py [--tessera build/bin/tessera] [--quality high]
        [--frequency 400] IMAGE...

Each image is encoded once with `tessera -j 1 compress --quality Q` under `perf record` (DWARF
call graphs); every sample is given to the outermost encoder pass on its stack: the start
(principal axis or dilation), reseed, least-squares refinement, the exact endpoint search
(`search_endpoints_4bpp`), high's second encoding (`optimise_alt`: the dilation start's exact
search) and the crossover with the resumed search (`optimise_crossover`); the rest (PNG read,
file write, start-up) is "other". Prints a Markdown table of percentages per image and their mean. Standard library only.
"""
import argparse
import collections
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# (label, function names; the outermost frame naming one of them wins, checked in this order)
PASSES = [
    ("crossover + resumed search", ("optimise_crossover",)),
    ("second encoding (dilation start + exact search)", ("optimise_alt",)),
    ("start", ("start_endpoints",)),
    ("reseed", ("reseed",)),
    ("least-squares refinement", ("refine",)),
    ("exact search", ("search_endpoints_4bpp",)),
    ("2 bpp modulation descent / endpoint search",
     ("refine_modulation_2bpp", "search_endpoints_2bpp")),
    ("modulation choice", ("choose_modulation",)),
]
OTHER = "other (PNG read, file write, start-up)"
FRAME = re.compile(r"^\s*[0-9a-f]+ (.*?)(?:\+0x[0-9a-f]+)? \(")


def classify(stack):
    for label, names in PASSES:
        for frame in stack:
            if any(re.search(r"(^|::)%s(_t)?(\(|<|$)" % n, frame) for n in names):
                return label
    return OTHER


def profile(tessera, quality, image, frequency):
    with tempfile.TemporaryDirectory() as tmp:
        data = os.path.join(tmp, "perf.data")
        subprocess.run(["perf", "record", "-q", "-o", data, "--call-graph", "dwarf,16384", "-F",
                        str(frequency), tessera, "-j", "1", "compress", image, "--quality",
                        quality, "-o", os.path.join(tmp, "out.pvr"), "-q"],
                       check=True, capture_output=True)
        text = subprocess.run(["perf", "script", "-i", data], check=True, capture_output=True,
                              text=True).stdout
    counts = collections.Counter()
    stack = []
    for line in text.splitlines() + [""]:
        if not line.strip():
            if stack:
                counts[classify(list(reversed(stack)))] += 1
            stack = []
            continue
        m = FRAME.match(line)
        if m:
            stack.append(m.group(1))
    return counts


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tessera", default=os.path.join(ROOT, "build", "bin", "tessera"))
    ap.add_argument("--quality", default="high", choices=("fast", "normal", "high"))
    ap.add_argument("--frequency", type=int, default=400, help="perf samples per second")
    ap.add_argument("images", nargs="+")
    a = ap.parse_args()
    shares = {}
    for image in a.images:
        c = profile(a.tessera, a.quality, image, a.frequency)
        total = sum(c.values()) or 1
        shares[os.path.basename(image)] = ({k: 100.0 * v / total for k, v in c.items()}, total)
    labels = [l for l, _ in PASSES] + [OTHER]
    labels = [l for l in labels if any(s.get(l, 0) > 0 for s, _ in shares.values())]
    names = list(shares)
    print("| pass | " + " | ".join(f"{n} (%)" for n in names) + " | mean (%) |")
    print("|---|" + "---:|" * (len(names) + 1))
    for l in labels:
        vals = [shares[n][0].get(l, 0.0) for n in names]
        print(f"| {l} | " + " | ".join(f"{v:.1f}" for v in vals) +
              f" | {sum(vals) / len(vals):.1f} |")
    print("| samples | " + " | ".join(str(shares[n][1]) for n in names) + " | |")


if __name__ == "__main__":
    sys.exit(main())
