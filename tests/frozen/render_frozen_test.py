#!/usr/bin/env python3
"""Frozen pixels of the CPU renderers (label cli): the SHA-256 of the decoded texels of small
frames from `tessera render builtin` (1x and 4x MSAA), `tessera aa` (the adaptive, reference,
FXAA and 1x images and the sample-count map of a tiny run) and `tessera seams` (Discard and
Traverse at 1x and 4x, the reference), so that any change to a rendered byte fails here, where the
PSNR bounds of the other tests would let a small systematic change pass.

Changing a value is a deliberate act: check first what changed and why (the other render tests,
docs/benchmarks/), then run this script with --print and paste the table. Hashes are of the
decoded RGBA texels, so a different PNG encoder setting does not change them.

Usage: render_frozen_test.py PATH/TO/tessera [--print]
"""
import hashlib
import os
import subprocess
import sys
import tempfile

from PIL import Image

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, finish  # noqa: E402

TESSERA = sys.argv[1]
PRINT = "--print" in sys.argv[2:]

# (run name, command-line words after `tessera -j 2`, images to hash relative to the output)
RUNS = [
    ("render-1x", ["render", "builtin", "--width", "64", "--height", "48", "--msaa", "1", "-q"],
     ["."]),
    ("render-4x", ["render", "builtin", "--width", "64", "--height", "48", "--msaa", "4", "-q"],
     ["."]),
    ("render-ssaa2-aniso", ["render", "builtin", "--width", "48", "--height", "32", "--ssaa", "2",
                            "--filter", "aniso16", "--orbit", "1/4", "-q"], ["."]),
    ("aa", ["aa", "--width", "64", "--height", "48", "--ssaa", "2", "--frames", "1", "-q"],
     ["adaptive-2x2.png", "reference-2x2.png", "fxaa-2x2.png", "default-2x2.png",
      "samples-2x2.png", "edge_per_sample-2x2.png"]),
    ("seams", ["seams", "--frames", "1", "--msaa", "1,4", "--width", "48", "--height", "40",
               "--reference-factor", "4", "-q"],
     ["images/reference.png", "images/discard_1x.png", "images/traverse_1x.png",
      "images/discard_4x.png", "images/traverse_4x.png", "images/clamp_1x.png"]),
]

FROZEN = {
    "render-1x": "c27073be5b58108a85c67468e30c417d926c6b4272c7b258fdb40733852c0ba0",
    "render-4x": "2eab1171ba68b347aa7c3d2ba375e8630e1e5c0ac14b6971d34cf2af1713f431",
    "render-ssaa2-aniso": "bbb7f83fea7bb934f894dad7e80568e707efed61a7b4061f9a327b26358e11ba",
    "aa/adaptive-2x2.png": "5234d0ad148306d3aea21aa5ef99da0028805db5c9a71b5d6229c06757ba6e52",
    "aa/reference-2x2.png": "16f12b56fadcea35b5d292e3c009f8477a7801dd5c0a05494f0e7991e496c292",
    "aa/fxaa-2x2.png": "1e45aeb9f3454cdadea6ddb5cddd320b1c500999591a8d78a3fe7de9ab07d0a3",
    "aa/default-2x2.png": "9f3b5fe2b6bfc204e44b832ef04d5c3b0d7b1ea8345f696b86e5f152b9740ab8",
    "aa/samples-2x2.png": "3e6ffea37ceb510b873623367f7f4c16e664ff5380ce6ba57554d3b5a349d158",
    "aa/edge_per_sample-2x2.png": "e88fa68c2751ce64e7c2a547796353e9c888452273f822ebf1a8b200cfefbdbb",
    "seams/images/reference.png": "8ae8c69a19fdd3429900bcd51f97b201f73f21b62d4b58df5cafb1384b2962be",
    "seams/images/discard_1x.png": "3a0262a46a5b3d949bcbf4b9e757e7825bf972ace8ffaa68713e99118f1757f2",
    "seams/images/traverse_1x.png": "32af1219543f83da90b1d2d3db4dbef02d5c76da405371cafc62b9ca0447b74b",
    "seams/images/discard_4x.png": "808af0190d6fd65659f0700998ab95af37872248dbea95d75c79904bbaf845ba",
    "seams/images/traverse_4x.png": "295dba783c5be87f42bb641b757a2412bee9ae34c2cf7e37d567ad0d17f94a40",
    "seams/images/clamp_1x.png": "ff8e2d98bf56d7b985f1513c4d98b4cd626e9d84de287b253e6fd7a8d1378fd9",
}


def texel_hash(path):
    with Image.open(path) as img:
        return hashlib.sha256(img.convert("RGBA").tobytes()).hexdigest()


def main():
    tmp = tempfile.mkdtemp(prefix="tessera-render-frozen-")
    table = []
    for name, words, images in RUNS:
        out = os.path.join(tmp, name + (".png" if images == ["."] else ""))
        p = subprocess.run([TESSERA, "-j", "2", *words, "-o", out], capture_output=True, text=True)
        check(name + " runs", p.returncode == 0, p.stderr)
        if p.returncode != 0:
            continue
        for image in images:
            path = out if image == "." else os.path.join(out, image)
            key = name if image == "." else f"{name}/{image}"
            if not os.path.isfile(path):
                check(key + " written", False, path)
                continue
            digest = texel_hash(path)
            table.append((key, digest))
            if not PRINT:
                check(key, FROZEN.get(key) == digest, f"sha256 {digest}, frozen {FROZEN.get(key)}")
    if PRINT:
        for key, digest in table:
            print(f'    "{key}": "{digest}",')
        return 0
    # A negative control: another camera must change the pixels.
    other = os.path.join(tmp, "other.png")
    subprocess.run([TESSERA, "render", "builtin", "--width", "64", "--height", "48", "--orbit",
                    "1/8", "-q", "-o", other], check=True)
    check("another camera gives other texels",
          texel_hash(other) != FROZEN.get("render-1x"), "the same hash")
    return finish()


if __name__ == "__main__":
    sys.exit(main())
