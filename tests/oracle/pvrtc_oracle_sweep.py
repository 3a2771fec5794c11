#!/usr/bin/env python3
"""Randomised conformance sweep through the CLI against PVRTexToolCLI (label `oracle`).

Usage: pvrtc_oracle_sweep.py TESSERA PVRTEXTOOL [--seed S] [--cases N]

Each case draws a power-of-two size (1 to 256 texels each way, at most 64K texels), content
(noise; a 1-4 colour palette with flat areas and uniform blocks; ramps; one colour with sparse
dots; optionally alpha made binary for punch-through), RGB or RGBA, a format, a quality (high up
to 128x128), a container (.pvr / .ktx) and optionally --mipmaps or --srgb. `tessera compress`
writes the file; PVRTexTool transcodes it to uncompressed r8g8b8a8 (every mip level); each level
must equal `tessera decompress --level L` byte for byte. PVRTexTool converts sRGB-flagged files
to linear values, and 4.17 refuses KTX files with the EXT_pvrtc_sRGB internal formats (it writes
sRGB PVRTC to KTX under the linear ones), so for --srgb it reads a copy flagged linear (PVR v3
colour space field, or the KTX internal format's linear twin): the blocks are the same. Without
PVRTexTool it skips.
"""
import argparse
import os
import struct
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import skip_or_fail  # noqa: E402

# KTX 1.1 glInternalFormat: sRGB PVRTC formats and their linear twins.
KTX_LINEAR = {0x8A54: 0x8C01, 0x8A55: 0x8C00, 0x8A56: 0x8C03, 0x8A57: 0x8C02}


def make_image(rng, w, h):
    kind = int(rng.integers(0, 4))
    if kind == 0:
        a = rng.integers(0, 256, (h, w, 4), dtype=np.uint8)
    elif kind == 1:
        pal = rng.integers(0, 256, (int(rng.integers(1, 5)), 4), dtype=np.uint8)
        a = pal[rng.integers(0, len(pal), (h, w))]
    elif kind == 2:
        y, x = np.mgrid[0:h, 0:w]
        a = np.stack([x * 255 // max(w - 1, 1), y * 255 // max(h - 1, 1), (x + y) * 7 % 256,
                      255 - x * 3 % 256], -1).astype(np.uint8)
    else:
        a = np.zeros((h, w, 4), np.uint8)
        a[...] = rng.integers(0, 256, 4, dtype=np.uint8)
        a[::3, ::5] = rng.integers(0, 256, 4, dtype=np.uint8)
    if rng.integers(0, 3) == 0:
        a[..., 3] = np.where(a[..., 3] < 128, 0, 255)
    return a, ["noise", "palette", "ramps", "dots"][kind]


def oracle_levels(tool, path, tmp):
    """Every level of `path` as PVRTexTool decodes it: a list of (h, w, 4) uint8 arrays."""
    out = os.path.join(tmp, "oracle.pvr")
    subprocess.run([tool, "-i", path, "-o", out, "-f", "r8g8b8a8", "-shh"], check=True,
                   capture_output=True)
    with open(out, "rb") as f:
        data = f.read()
    (_, _, pf, _, _, h, w, depth, surfaces, faces, mips, meta) = struct.unpack("<IIQIIIIIIIII",
                                                                                data[:52])
    assert pf == 0x0808080861626772 and depth == surfaces == faces == 1, (pf, depth, surfaces)
    levels, off = [], 52 + meta
    for lv in range(mips):
        lw, lh = max(w >> lv, 1), max(h >> lv, 1)
        n = lw * lh * 4
        levels.append(np.frombuffer(data[off:off + n], np.uint8).reshape(lh, lw, 4))
        off += n
    assert off == len(data), (off, len(data))
    return levels


def linear_copy(path, tmp):
    with open(path, "rb") as f:
        b = bytearray(f.read())
    if path.endswith(".pvr"):
        b[16:20] = bytes(4)  # colour space: linear
    else:
        fmt = struct.unpack_from("<I", b, 28)[0]
        struct.pack_into("<I", b, 28, KTX_LINEAR.get(fmt, fmt))
    out = os.path.join(tmp, "linear" + os.path.splitext(path)[1])
    with open(out, "wb") as f:
        f.write(b)
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("tessera")
    ap.add_argument("pvrtextool", nargs="?", default="")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--cases", type=int, default=40)
    args = ap.parse_args()
    if not args.pvrtextool or not os.path.isfile(args.pvrtextool):
        skip_or_fail("pvrtextool", "PVRTexToolCLI not given: no oracle sweep")
    rng = np.random.default_rng(args.seed)
    failures = 0
    with tempfile.TemporaryDirectory() as tmp:
        for case in range(args.cases):
            w, h = 1 << int(rng.integers(0, 9)), 1 << int(rng.integers(0, 9))
            if w * h > 65536:
                h = 65536 // w
            pixels, kind = make_image(rng, w, h)
            alpha = bool(rng.integers(0, 2))
            src = os.path.join(tmp, "in.png")
            Image.fromarray(pixels if alpha else np.ascontiguousarray(pixels[..., :3])).save(src)
            fmt = ["pvrtc1-4", "pvrtc1-2"][int(rng.integers(0, 2))]
            qualities = ["fast", "normal", "high"] if w * h <= 16384 else ["fast", "normal"]
            quality = qualities[int(rng.integers(0, len(qualities)))]
            ext = [".pvr", ".ktx"][int(rng.integers(0, 2))]
            extra = [[], ["--mipmaps"], ["--srgb"], ["--mipmaps", "--srgb"]][int(rng.integers(0, 4))]
            name = (f"case {case}: {w}x{h} {kind} {'RGBA' if alpha else 'RGB'} {fmt} {quality} "
                    f"{ext} {' '.join(extra)}")
            out = os.path.join(tmp, "out" + ext)
            subprocess.run([args.tessera, "compress", src, "-o", out, "--format", fmt,
                            "--quality", quality, *extra], check=True, capture_output=True)
            oracle = oracle_levels(args.pvrtextool,
                                   linear_copy(out, tmp) if "--srgb" in extra else out, tmp)
            expected = 1 + int(np.log2(max(w, h))) if "--mipmaps" in extra else 1
            if len(oracle) != expected:
                print(f"FAIL {name}: the oracle reads {len(oracle)} levels, expected {expected}")
                failures += 1
                continue
            for lv, ref in enumerate(oracle):
                png = os.path.join(tmp, "ours.png")
                subprocess.run([args.tessera, "decompress", out, "-o", png, "--level", str(lv)],
                               check=True, capture_output=True)
                ours = np.asarray(Image.open(png).convert("RGBA"))
                if ours.shape != ref.shape or (ours != ref).any():
                    diff = "shape" if ours.shape != ref.shape else int((ours != ref).sum())
                    print(f"FAIL {name}: level {lv} differs from the oracle ({diff} bytes)")
                    failures += 1
            print(f"ok   {name} ({len(oracle)} level(s))")
    print(f"{args.cases} cases, {failures} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
