#!/usr/bin/env python3
"""Regenerates the committed seed corpora in fuzz/corpus/<target>/ (tiny valid files).

Usage: make_corpus.py PATH/TO/tessera [OUT_DIR (default: fuzz/corpus next to this script)]
PVR v3 / KTX 1.1 seeds are made with `tessera compress` from small generated PNGs; KTX 2.0
seeds (with and without Zstandard levels) by ktx2_oracle_writer beside the CLI in the build's
bin folder (tests/oracle/ktx2_oracle_writer.cpp: real encodes, written by the library); the
pvrtc::decode seeds are the fuzzer's input layout (format byte, int32 width, int32 height,
block data), the pvrtc::encode seeds that fuzzer's layout (sizes, options, texels); image
seeds are PNGs (written here with the standard library) plus JPEG, BMP and TGA when Pillow is
available. Every file stays under 8 KiB (the fuzzers' -max_len).
"""
import math
import os
import struct
import subprocess
import sys
import tempfile
import zlib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests",
                                "support"))
from cli_harness import png_bytes as harness_png_bytes  # noqa: E402
from cli_harness import png_chunk  # noqa: E402

TESSERA = sys.argv[1]
OUT = sys.argv[2] if len(sys.argv) > 2 else os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                         "corpus")


def png_bytes(width, height, channels, pixel):
    """cli_harness.png_bytes at zlib level 9 (the committed seeds' bytes)."""
    return harness_png_bytes(width, height, channels, pixel, level=9)


def filtered_png_bytes(width, height, channels, pixel, extra_chunks=(), idat_parts=1):
    """An 8-bit PNG whose row y uses filter y % 5 (None, Sub, Up, Average, Paeth)."""
    colour_type = {1: 0, 2: 4, 3: 2, 4: 6}[channels]
    rows = [bytes(v for x in range(width) for v in pixel(x, y)[:channels]) for y in range(height)]
    raw = bytearray()
    prev = bytes(len(rows[0]))
    for y, row in enumerate(rows):
        kind = y % 5
        raw.append(kind)
        for i, v in enumerate(row):
            a = row[i - channels] if i >= channels else 0
            b = prev[i]
            c = prev[i - channels] if i >= channels else 0
            p = a + b - c
            pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            paeth = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
            raw.append((v - (0, a, b, (a + b) // 2, paeth)[kind]) % 256)
        prev = row
    stream = zlib.compress(bytes(raw), 9)
    step = -(-len(stream) // idat_parts)
    idats = b"".join(png_chunk(b"IDAT", stream[i:i + step]) for i in range(0, len(stream), step))
    ihdr = struct.pack(">IIBBBBB", width, height, 8, colour_type, 0, 0, 0)
    extras = b"".join(png_chunk(kind, data) for kind, data in extra_chunks)
    return b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", ihdr) + extras + idats + png_chunk(b"IEND", b"")


def png_diff_seeds():
    """Seeds for fuzz_png_diff: files the PNG fast path takes, every filter and colour type."""
    phys = (b"pHYs", struct.pack(">IIB", 2835, 2835, 1))
    text = (b"tEXt", b"Comment\0seed")
    write("fuzz_png_diff", "rgb-filters.png", filtered_png_bytes(7, 10, 3, pattern, [phys]))
    write("fuzz_png_diff", "rgba-filters.png", filtered_png_bytes(9, 10, 4, pattern, [], 3))
    write("fuzz_png_diff", "grey-filters.png", filtered_png_bytes(6, 10, 1, pattern, [text]))
    write("fuzz_png_diff", "grey-alpha-filters.png", filtered_png_bytes(5, 10, 2, pattern))
    write("fuzz_png_diff", "rgb-1-wide.png", filtered_png_bytes(1, 5, 3, pattern))


def pattern(x, y):
    return (int(128 + 120 * math.sin(x * 0.7)), int(128 + 120 * math.cos(y * 0.5)), (x * 16 + y * 8) % 256,
            0 if (x + y) % 5 == 0 else 255 - 8 * x)


def encode_seeds():
    """pvrtc::encode seeds in fuzz_pvrtc_encode.cpp's layout: log2 width, log2 height, flags
    (bit 0 2 bpp, bits 1-2 quality, bit 3 alpha, bit 4 no punch-through, bit 5 force alpha,
    bits 6-7 fill), exact-search rounds, then the texel source."""
    texels = bytes(v for x in range(64) for v in pattern(x % 8, x // 8))
    seeds = [  # (name, log2 w, log2 h, flags, rounds, source)
        ("8x8-4bpp-fast-rgba", 3, 3, 0b00001000, 0, texels),
        ("16x16-4bpp-normal-rgb", 4, 4, 0b00000010, 0, texels),
        ("16x8-4bpp-high-rgba", 4, 3, 0b00001100, 0, texels),
        ("32x16-2bpp-high-rgb", 5, 4, 0b00000101, 0, texels),
        ("1x1-4bpp-fast-rgba", 0, 0, 0b00001000, 0, texels[:4]),
        ("2x32-2bpp-normal-rgba", 1, 5, 0b00001011, 2, texels),
        ("64x4-4bpp-fast-sweep-palette", 6, 2, 0b01000110, 0, texels[:40]),
        ("8x64-4bpp-normal-ramp-nopunch", 3, 6, 0b10011010, 3, texels[:12]),
        ("32x32-4bpp-high-uniform", 5, 5, 0b11000100, 0, bytes([200, 40, 90, 255])),
        ("16x16-2bpp-fast-force-alpha", 4, 4, 0b00100001, 0, texels),
    ]
    for name, lw, lh, flags, rounds, src in seeds:
        write("fuzz_pvrtc_encode", name + ".bin", bytes([lw, lh, flags, rounds]) + src)


def ktx2_seeds():
    """fuzz_parse_ktx2 seeds: a few of ktx2_oracle_writer's variants (2D, array, cube map array;
    4 and 2 bpp; none, zstd 3 and zstd 19)."""
    writer = os.path.join(os.path.dirname(os.path.abspath(TESSERA)), "ktx2_oracle_writer")
    names = ["4bpp-linear-opaque", "4bpp-array1", "2bpp-cube-array2-srgb-mips",
             "4bpp-srgb-alpha-mips-zstd3", "2bpp-linear-opaque-zstd19"]
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run([writer, tmp], check=True, capture_output=True)
        for name in names:
            with open(os.path.join(tmp, name + ".ktx2"), "rb") as f:
                write("fuzz_parse_ktx2", name + ".ktx2", f.read())


def write(target, name, data):
    folder = os.path.join(OUT, target)
    os.makedirs(folder, exist_ok=True)
    assert len(data) <= 8192, (name, len(data))
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data)


def shape_seeds(tmp):
    """Cube map, array and cube map array seeds for the PVR v3 and KTX 1.1 readers."""
    faces = []
    for i in range(12):
        path = os.path.join(tmp, "face%d.png" % i)
        with open(path, "wb") as f:
            f.write(png_bytes(8, 8, 4 if i % 2 else 3,
                              lambda x, y, i=i: tuple((v + 37 * i) % 256 for v in pattern(x, y))))
        faces.append(path)
    shapes = [  # (name, inputs, args)
        ("8x8-4bpp-cube-mips", faces[:6], ["--cube", "--mipmaps"]),
        ("8x8-2bpp-array3", faces[:3], ["--array", "--format", "pvrtc1-2"]),
        ("8x8-4bpp-cube-array2", faces, ["--cube", "--array"]),
    ]
    for name, inputs, args in shapes:
        for ext, target in ((".pvr", "fuzz_parse_pvr3"), (".ktx", "fuzz_parse_ktx1")):
            out = os.path.join(tmp, name + ext)
            subprocess.run([TESSERA, "-j", "1", "compress", *inputs, "-o", out, "--quality", "fast",
                            *args], check=True, capture_output=True)
            with open(out, "rb") as f:
                write(target, name + ext, f.read())


def main():
    with tempfile.TemporaryDirectory() as tmp:
        textures = [  # (name, width, height, alpha, args)
            ("4x4-4bpp-rgba", 4, 4, True, ["--format", "pvrtc1-4"]),
            ("8x8-2bpp-rgb-mips", 8, 8, False, ["--format", "pvrtc1-2", "--mipmaps"]),
            ("16x8-4bpp-rgb-srgb-mips", 16, 8, False, ["--mipmaps", "--srgb"]),
            ("32x16-2bpp-rgba", 32, 16, True, ["--format", "pvrtc1-2"]),
            ("8x32-4bpp-rgba-mips", 8, 32, True, ["--mipmaps", "--quality", "fast"]),
        ]
        for name, w, h, alpha, args in textures:
            src = os.path.join(tmp, name + ".png")
            with open(src, "wb") as f:
                f.write(png_bytes(w, h, 4 if alpha else 3, pattern))
            for ext, target in ((".pvr", "fuzz_parse_pvr3"), (".ktx", "fuzz_parse_ktx1")):
                out = os.path.join(tmp, name + ext)
                subprocess.run([TESSERA, "-j", "1", "compress", src, "-o", out, *args], check=True,
                               capture_output=True)
                with open(out, "rb") as f:
                    write(target, name + ext, f.read())
            # pvrtc::decode seed: level 0 of the .pvr (after the 52-byte header + 15 metadata).
            with open(os.path.join(tmp, name + ".pvr"), "rb") as f:
                pvr = f.read()
            bpp2 = "pvrtc1-2" in args
            block_w = 8 if bpp2 else 4
            level0 = max(w // block_w, 2) * max(h // 4, 2) * 8
            header = struct.pack("<Bii", 1 if bpp2 else 0, w, h)
            write("fuzz_pvrtc_decode", name + ".bin", header + pvr[67:67 + level0])

        shape_seeds(tmp)

    ktx2_seeds()
    png_diff_seeds()
    encode_seeds()
    write("fuzz_decode_image", "rgb.png", png_bytes(7, 5, 3, pattern))
    write("fuzz_decode_image", "rgba.png", png_bytes(9, 4, 4, pattern))
    write("fuzz_decode_image", "grey.png", png_bytes(6, 6, 1, pattern))
    write("fuzz_decode_image", "grey-alpha.png", png_bytes(5, 3, 2, pattern))
    try:
        from PIL import Image  # optional: Debian's python3-pil
    except ImportError:
        print("Pillow not available: PNG image seeds only")
        return
    img = Image.new("RGB", (8, 8))
    img.putdata([pattern(x, y)[:3] for y in range(8) for x in range(8)])
    for fmt, name in (("JPEG", "tiny.jpg"), ("BMP", "tiny.bmp"), ("TGA", "tiny.tga")):
        path = os.path.join(OUT, "fuzz_decode_image", name)
        img.save(path, fmt)
    pal = img.convert("P", palette=Image.ADAPTIVE, colors=8)
    pal.save(os.path.join(OUT, "fuzz_decode_image", "palette.png"), "PNG")


if __name__ == "__main__":
    main()
