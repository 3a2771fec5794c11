#!/usr/bin/env python3
"""Writes the tiny seed .ptx files of fuzz/corpus/fuzz_ptex/ (standard library only).

Usage: make_ptex_corpus.py [OUT_DIR (default: fuzz/corpus/fuzz_ptex next to this script)]
Each seed is a valid Ptex v1 quad-mesh file exercising one data type and encoding: u8 zip,
u16 zip-with-differencing, half constant faces, float tiled faces, and a mixed file. All under
8 KiB (the fuzzers' -max_len).
"""
import os
import struct
import sys
import zlib

OUT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
    os.path.dirname(os.path.abspath(__file__)), "corpus", "fuzz_ptex")

FMT = {0: "B", 1: "H", 2: "H", 3: "f"}  # u8, u16, half (raw bits), float


def value(dtype, i):
    if dtype == 0:
        return (i * 37 + 11) & 255
    if dtype == 1:
        return (i * 4099 + 7) & 65535
    if dtype == 2:
        return 0x3800 + (i % 512)  # halves in [0.5, 1)
    return (i % 17) / 16.0


def planar(pixels, w, ch, x0, y0, tw, th):
    out = []
    for c in range(ch):
        for y in range(y0, y0 + th):
            for x in range(x0, x0 + tw):
                out.append(pixels[(y * w + x) * ch + c])
    return out


def pack(dtype, values):
    return struct.pack("<%d%s" % (len(values), FMT[dtype]), *values)


def ptx(faces, dtype, ch):
    """faces: list of (ulog2, vlog2, encoding, adj[4], adjedges[4])."""
    fi, cd, hdr, data = b"", b"", b"", b""
    for n, (ul, vl, enc, adj, edges) in enumerate(faces):
        w, h = 1 << ul, 1 << vl
        px = [value(dtype, n * 1000 + i) for i in range(w * h * ch)]
        ae = sum((e & 3) << (2 * k) for k, e in enumerate(edges))
        fi += struct.pack("<bbBB4i", ul, vl, ae, 1 if enc == 0 else 0, *adj)
        cd += pack(dtype, px[:ch])
        if enc == 0:
            block = pack(dtype, px[:ch])
        elif enc in (1, 2):
            p = planar(px, w, ch, 0, 0, w, h)
            raw = pack(dtype, p)
            if enc == 2 and dtype in (0, 1):
                size = 1 if dtype == 0 else 2
                vals = list(struct.unpack("<%d%s" % (len(raw) // size, FMT[dtype]), raw))
                mod = 256 if dtype == 0 else 65536
                diff = [(v - (vals[i - 1] if i else 0)) % mod for i, v in enumerate(vals)]
                raw = pack(dtype, diff)
            block = zlib.compress(raw, 9)
        else:
            tu, tv = ul - 1, vl - 1
            th_, tiles = b"", b""
            for t in range(4):
                tx, ty = (t % 2) << tu, (t // 2) << tv
                z = zlib.compress(pack(dtype, planar(px, w, ch, tx, ty, 1 << tu, 1 << tv)), 9)
                th_ += struct.pack("<I", len(z) | (1 << 30))
                tiles += z
            zh = zlib.compress(th_, 9)
            block = struct.pack("<bbI", tu, tv, len(zh)) + zh + tiles
        hdr += struct.pack("<I", len(block) | (enc << 30))
        data += block
    zfi, zcd, zhdr = zlib.compress(fi, 9), zlib.compress(cd, 9), zlib.compress(hdr, 9)
    level = zhdr + data
    head = struct.pack("<4sIIIiHHIIIIIIQII", b"Ptex", 1, 1, dtype, -1, ch, 1, len(faces), 40,
                       len(zfi), len(zcd), 16, 3, len(level), 0, 0)
    ext = bytes(40)
    levelinfo = struct.pack("<QII", len(level), len(zhdr), len(faces))
    return head + ext + zfi + zcd + levelinfo + level


def main():
    os.makedirs(OUT, exist_ok=True)
    pair = [(2, 2, 1, [1, -1, -1, -1], [2, 0, 0, 0]), (2, 1, 1, [-1, -1, 0, -1], [0, 0, 0, 0])]
    seeds = {
        "u8-zip-2faces.ptx": ptx(pair, 0, 3),
        "u16-diffzip.ptx": ptx([(f[0], f[1], 2, f[3], f[4]) for f in pair], 1, 1),
        "half-constant.ptx": ptx([(f[0], f[1], 0, f[3], f[4]) for f in pair], 2, 4),
        "float-tiled.ptx": ptx([(2, 2, 3, [-1] * 4, [0] * 4)], 3, 3),
        "u8-mixed.ptx": ptx([(2, 2, 0, [1, -1, -1, -1], [3, 0, 0, 0]),
                             (2, 1, 1, [-1, -1, -1, 0], [0, 0, 0, 0]),
                             (1, 2, 2, [-1] * 4, [0] * 4),
                             (2, 2, 3, [-1] * 4, [0] * 4)], 0, 3),
    }
    for name, data in seeds.items():
        assert len(data) < 8192, name
        with open(os.path.join(OUT, name), "wb") as f:
            f.write(data)
        print("%s: %d bytes" % (name, len(data)))


if __name__ == "__main__":
    main()
