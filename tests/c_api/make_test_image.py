#!/usr/bin/env python3
"""The C API consumers' test image (tests/c_api/consumer_test.sh, scripts/package.sh): 64x64
RGBA8 with a transparent corner and an alpha ramp, written raw (for the C and ctypes consumers)
and as the same texels in a PNG (for `tessera compress`).

Usage: make_test_image.py OUT.rgba OUT.png"""
import struct
import sys
import zlib

w = h = 64
px = bytearray()
for y in range(h):
    for x in range(w):
        a = 0 if (x < 16 and y < 16) else 96 + (x * 159) // (w - 1)
        px += bytes((x * 4 & 255, (y * 4 + 30) & 255, 200 if (x // 8 + y // 8) % 2 else 40, a))
with open(sys.argv[1], "wb") as f:
    f.write(px)


def chunk(kind, data):
    body = kind + data
    return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))


rows = b"".join(b"\0" + bytes(px[y * w * 4:(y + 1) * w * 4]) for y in range(h))
png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0))
       + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))
with open(sys.argv[2], "wb") as f:
    f.write(png)
