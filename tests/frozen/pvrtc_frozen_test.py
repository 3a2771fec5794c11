#!/usr/bin/env python3
"""Frozen bytes of `tessera compress` (labels cli, unit): the SHA-256 of the files it writes for
fixed generated images under every kind of option, so that any change to the pipeline's output
fails here. The rows without the asset options (cube maps, arrays, flips, premultiplied alpha,
alpha bleed, normal maps, mip levels and filters, KTX 2.0) were computed with tessera before
those options existed: they prove that leaving the new options out gives the old bytes.

Changing a value is a deliberate act: check first that the new output is at least as good
(bench/pvrtc_quality, the oracle tests), then run this script with --print and paste the table.

Usage: pvrtc_frozen_test.py PATH/TO/tessera [--print]
"""
import hashlib
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, finish, write_png  # noqa: E402

TESSERA = sys.argv[1]
PRINT = "--print" in sys.argv[2:]


def photo(seed):
    """Smooth gradients, rings and a hashed texture: photo-like, every channel busy."""
    def pixel(x, y):
        h = (x * 73856093 ^ y * 19349663 ^ seed * 83492791) & 0xFF
        r = 128 + 90 * math.sin(x / (7.0 + seed) + y / 13.0)
        g = 128 + 90 * math.cos(math.hypot(x - 20, y - 30) / (5.0 + seed))
        b = (x * 3 + y * 2 + seed * 40) % 256
        return (int(r + h / 16) % 256, int(g) % 256, int(b + h / 8) % 256, 255)
    return pixel


def sprite(seed):
    """Colour with hard (punch-through) and soft alpha and transparent regions."""
    base = photo(seed)

    def pixel(x, y):
        r, g, b, _ = base(x, y)
        d = math.hypot(x - 31.5, y - 31.5)
        a = 255 if d < 18 else (0 if d > 26 else int(255 * (26 - d) / 8))
        if (x // 4 + y // 4) % 7 == 0:
            a = 0
        return (r, g, b, a)
    return pixel


def normal_map(x, y):
    nx = math.sin(x / 5.0) * 0.5
    ny = math.cos(y / 7.0) * 0.5
    nz = math.sqrt(max(0.0, 1 - nx * nx - ny * ny))
    return (int(round((nx + 1) * 127.5)), int(round((ny + 1) * 127.5)), int(round((nz + 1) * 127.5)),
            255)


# (name, inputs, output extension, options); inputs name the generated images below.
CASES = [
    # Without the asset options: bytes from before they existed.
    ("rgb-fast", ["rgb"], ".pvr", ["--quality", "fast"]),
    ("rgb-normal", ["rgb"], ".pvr", ["--quality", "normal"]),
    ("rgb-high", ["rgb"], ".pvr", ["--quality", "high"]),
    ("rgb-2bpp-normal", ["rgb"], ".pvr", ["--format", "pvrtc1-2"]),
    ("rgb-2bpp-high", ["rgb"], ".pvr", ["--format", "pvrtc1-2", "--quality", "high"]),
    ("rgb-mips-srgb", ["rgb"], ".pvr", ["--mipmaps", "--srgb"]),
    ("rgb-mips-ktx", ["rgb"], ".ktx", ["--mipmaps", "--quality", "fast"]),
    ("npot-resize", ["npot"], ".pvr", ["--resize-pot", "--mipmaps"]),
    ("rgba-fast", ["rgba"], ".pvr", ["--quality", "fast"]),
    ("rgba-normal", ["rgba"], ".pvr", ["--quality", "normal"]),
    ("rgba-high", ["rgba"], ".pvr", ["--quality", "high"]),
    ("rgba-2bpp-high", ["rgba"], ".ktx", ["--format", "pvrtc1-2", "--quality", "high"]),
    ("rgba-mips-srgb", ["rgba"], ".pvr", ["--mipmaps", "--srgb", "--quality", "fast"]),
    # With the asset options.
    ("cube-mips", ["rgb", "rgba", "rgb2", "rgb", "rgba", "rgb2"], ".pvr",
     ["--cube", "--mipmaps", "--quality", "fast"]),
    ("array-ktx", ["rgb", "rgb2", "rgba"], ".ktx", ["--array", "--quality", "fast"]),
    ("cube-array-ktx2-zstd", ["rgb", "rgba", "rgb2"] * 4, ".ktx2",
     ["--cube", "--array", "--mip-levels", "3", "--zstd", "9", "--quality", "fast"]),
    ("rgba-bleed", ["rgba"], ".pvr", ["--alpha-bleed"]),
    ("rgba-premultiply-srgb", ["rgba"], ".pvr", ["--premultiply", "--srgb", "--mipmaps"]),
    ("rgb-flip-lanczos", ["rgb"], ".pvr", ["--flip-y", "--mipmaps", "--mip-filter", "lanczos",
                                          "--quality", "fast"]),
    ("rgba-kaiser", ["rgba"], ".pvr", ["--mip-levels", "4", "--mip-filter", "kaiser",
                                       "--quality", "fast"]),
    ("normal-map", ["normal"], ".pvr", ["--normal-map", "--mipmaps"]),
    ("normal-map-2bpp", ["normal"], ".ktx2", ["--normal-map", "--format", "pvrtc1-2"]),
]

FROZEN = {
    # Computed with tessera e1c3d51, before the asset options existed.
    "rgb-fast": "771e590369e931f58c53d7a46f8f87f86a368d38e54ecc97f9f0b699f815f394",
    "rgb-normal": "ae9d7289978e1ec1d0d1acf45fb3bf9281c2aab9c357a069d1e8a3b17fe918e0",
    "rgb-high": "885958f09dcb034ac7204c2967f6b5329f2fc4901fa2b6c0466f4d285ddbb384",
    "rgb-2bpp-normal": "fb19282a20318241aa6a96bef6b1221779c9de0eb29d43ac314207f3b14e1aa0",
    "rgb-2bpp-high": "2363f2b7e5f8dab22905c6557837a288188bb109ea88ba06b11673f2727b3754",
    "rgb-mips-srgb": "129888b52cf529e67cb5a8482ea15efda1e6e5a09bc093617bdc7764295b2297",
    "rgb-mips-ktx": "d1d8687ee88e508d883f242a93e8fd74142bc68c52f066a99c8967f9a1b295c6",
    "npot-resize": "3ab24474dcc3919b67433f7fbc0d0b409812ee477c153837cfedab8ff4e30011",
    "rgba-fast": "dd3558a1a5c2e61f847a40645385a63a6672da6fc57085e7eefb0fadc762ed71",
    "rgba-normal": "52a21636750bffab12fc6715d69dd86c2b7358c89086ecb5caf2ca3b3f63040e",
    "rgba-high": "241cfb6cb1a359fee298f28bd0ce0c22ecd9c0c18fa808a9877e5f2e1bad82bb",
    "rgba-2bpp-high": "d11b959452e72d4171a23bd247801d6e908812928b3267c8fa93b18d89e13660",
    "rgba-mips-srgb": "693739e7508022d537eb5d59860f7179cd3e0ba773271dcc19fa2b15baa01a1a",
    # The asset options, as first built.
    "cube-mips": "f8d5be72168dd03e3af94937537d0257e02e798d7a7d02576c599ead4cfdd27d",
    "array-ktx": "d71677c4f8031f5f4566ec79674ee8556d7bc87e36067353b17e8d26e350c4a7",
    "cube-array-ktx2-zstd": "86fa263046d1ad7384ae440cff740f3b6e7a1696d5a1751a149d967643d9aae9",
    "rgba-bleed": "46ef4ef1ff4695afc2fbf54d71426e371d0e314ce191453d5fd3ad341c04c770",
    "rgba-premultiply-srgb": "69a33be6b6cf1a84f78fb41b91fddac5aa9203aa453f32a12c4855dd5e55a643",
    "rgb-flip-lanczos": "a408a572b221918514cf9c7afb0810f9f62b6878a967d9853ad079e1f7281c17",
    "rgba-kaiser": "51906d3c00c9a9a64c38ff85735b68b603d653636a8f1b3970dc3dd780590b4e",
    "normal-map": "3a439cafc3d2ed0ed7e08365169b30bc8ef7ce30505864ba08aaf3d4c8ead9d7",
    "normal-map-2bpp": "ef72fa0d03aed09abd4d33244024a637b20bdb0ed8bebb9e6a8667ec5ec3f991",
}


def main():
    tmp = tempfile.mkdtemp(prefix="tessera-frozen-")
    images = {
        "rgb": write_png(os.path.join(tmp, "rgb.png"), 64, 64, photo(1), False),
        "rgb2": write_png(os.path.join(tmp, "rgb2.png"), 64, 64, photo(2), False),
        "npot": write_png(os.path.join(tmp, "npot.png"), 48, 40, photo(3), False),
        "rgba": write_png(os.path.join(tmp, "rgba.png"), 64, 64, sprite(4), True),
        "normal": write_png(os.path.join(tmp, "normal.png"), 64, 64, normal_map, False),
    }
    table = []
    for name, inputs, ext, options in CASES:
        out = os.path.join(tmp, name + ext)
        p = subprocess.run([TESSERA, "-j", "2", "compress", *[images[i] for i in inputs], "-o", out,
                            "-q", *options], capture_output=True, text=True)
        if p.returncode != 0:
            if PRINT:
                print(f"    # {name}: {p.stderr.strip()}")
                continue
            check(name + " runs", False, p.stderr)
            continue
        with open(out, "rb") as f:
            digest = hashlib.sha256(f.read()).hexdigest()
        table.append((name, digest))
        if not PRINT:
            check(name, FROZEN.get(name) == digest,
                  f"sha256 {digest}, frozen {FROZEN.get(name)} ({' '.join(options)})")
    if PRINT:
        for name, digest in table:
            print(f'    "{name}": "{digest}",')
        return 0
    # A negative control: one changed option must change the bytes.
    a, b = os.path.join(tmp, "c1.pvr"), os.path.join(tmp, "c2.pvr")
    subprocess.run([TESSERA, "compress", images["rgb"], "-o", a, "-q", "--quality", "fast"], check=True)
    subprocess.run([TESSERA, "compress", images["rgb2"], "-o", b, "-q", "--quality", "fast"], check=True)
    check("different inputs give different bytes", open(a, "rb").read() != open(b, "rb").read())
    return finish()


if __name__ == "__main__":
    sys.exit(main())
