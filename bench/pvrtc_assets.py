#!/usr/bin/env python3
"""Alpha and normal maps, tessera vs PVRTexToolCLI: the quality a renderer sees.

Usage (from the repository root):
    /usr/bin/python3 bench/pvrtc_assets.py [--tessera build/bin/tessera] [--pvrtextool PATH]
        [--images ../shared/data/images] [--out docs/benchmarks/pvrtc_assets.md] [--quick]

Alpha table: RGBA textures with transparent regions, PVRTC1 4 bpp. The error a blending
renderer shows is that of colour x alpha, so the table gives `tessera compare --premultiplied`
(PSNR of colour x alpha, peak 255) and the alpha PSNR, each decode against the original:
  * tessera --quality normal / high, each without options, with --alpha-bleed, with
    --alpha-weighted (colour error weighted by alpha) and with both;
  * PVRTexToolCLI -q pvrtcnormal / pvrtcbest, without and with -l (its alpha bleed).
The configurations are the table's rows, the images its columns.
Images: ldr-rgba-00 (foliage, 256x256), ldr-rgba-base (1024x1024, cropped to its 512x512
top-left quarter), and sprites made here from the shared photographs: `logo` (strokes on
transparent black, 84 % transparent), `disc` (ldr-rgb-03 under a soft disc, 69 % transparent,
the photograph left under the transparent texels), `disc-noise` (the same with noise under the
transparent texels) and `cutout` (ldr-rgb-05 where its luma exceeds its median: hard edges).

Normal table: normal maps, PVRTC1 4 bpp, angular error in degrees (`tessera compare --normal`:
mean, 99th percentile), against:
  * tessera --quality normal / high, without and with --normal-map;
  * PVRTexToolCLI -q pvrtcnormal / pvrtchigh / pvrtcbest.
Images: ldr-xy-normal1 (512x512 crop), and normal maps PVRTexTool makes from height maps
(`-n SCALE,xyz`, written uncompressed): ldr-l-occlusion (512 crop, scale 1), ldr-rgb-diffuse
(resized to 512, scale 1), ldr-rgb-00 (scale 1) and, as noisy extremes, ldr-rgb-00 and -05 at
scale 4.

Each configuration runs once (the outputs are deterministic); the table is quality only. Needs
numpy and PIL (Debian python3-numpy, python3-pil).
"""
import argparse
import datetime
import json
import os
import platform
import shlex
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image, ImageDraw

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchlib import cpu_model, write_report  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
NOTES = "<!-- notes: kept when the tables are regenerated -->"


def run(cmd):
    p = subprocess.run([str(c) for c in cmd], capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(map(str, cmd))}: {p.stderr.strip()}")
    return p.stdout


def save(path, array):
    Image.fromarray(np.ascontiguousarray(array.astype(np.uint8))).save(path)
    return path


def alpha_images(src, tmp):
    """(name, path) of the RGBA inputs, the derived sprites written into tmp."""
    out = [("ldr-rgba-00", os.path.join(src, "ldr-rgba-00.png"))]
    base = np.asarray(Image.open(os.path.join(src, "ldr-rgba-base.png")).convert("RGBA"))
    out.append(("ldr-rgba-base (512 crop)", save(os.path.join(tmp, "base.png"), base[:512, :512])))
    photo = np.asarray(Image.open(os.path.join(src, "ldr-rgb-03.png")).convert("RGB")).astype(int)
    h, w = photo.shape[:2]
    y, x = np.mgrid[0:h, 0:w]
    mask = Image.new("L", (w, h), 0)
    draw = ImageDraw.Draw(mask)
    for i in range(6):
        draw.ellipse([20 + 35 * i, 90, 50 + 35 * i, 170], outline=255, width=7)
    draw.rectangle([30, 40, 220, 60], fill=255)
    a = np.asarray(mask).astype(int)
    colour = np.stack([np.full((h, w), 230), 80 + x // 2, 40 + y // 3], -1)
    logo = np.dstack([np.where(a[..., None] > 0, colour, 0), a])
    out.append(("logo", save(os.path.join(tmp, "logo.png"), logo)))
    disc = np.clip((80 - np.hypot(x - 128, y - 128)) * 8, 0, 255).astype(int)
    out.append(("disc", save(os.path.join(tmp, "disc.png"), np.dstack([photo, disc]))))
    noise = np.random.default_rng(1).integers(0, 256, photo.shape)
    under = np.where(disc[..., None] > 0, photo, noise)
    out.append(("disc-noise", save(os.path.join(tmp, "disc-noise.png"), np.dstack([under, disc]))))
    p5 = np.asarray(Image.open(os.path.join(src, "ldr-rgb-05.png")).convert("RGB")).astype(int)
    luma = p5 @ np.array([0.2126, 0.7152, 0.0722])
    cut = np.where(luma > np.median(luma), 255, 0)
    out.append(("cutout", save(os.path.join(tmp, "cutout.png"), np.dstack([p5, cut]))))
    return out


def normal_images(src, tmp, pvrtextool):
    out = []
    n1 = Image.open(os.path.join(src, "ldr-xy-normal1.png")).convert("RGB").crop((0, 0, 512, 512))
    n1.save(os.path.join(tmp, "n1.png"))
    out.append(("ldr-xy-normal1 (512 crop)", os.path.join(tmp, "n1.png")))
    heights = [
        ("ldr-l-occlusion", Image.open(os.path.join(src, "ldr-l-occlusion.png")).crop((0, 0, 512, 512)), 1),
        ("ldr-rgb-diffuse", Image.open(os.path.join(src, "ldr-rgb-diffuse.png")).resize((512, 512)), 1),
        ("ldr-rgb-00", Image.open(os.path.join(src, "ldr-rgb-00.png")), 1),
        ("ldr-rgb-00", Image.open(os.path.join(src, "ldr-rgb-00.png")), 4),
        ("ldr-rgb-05", Image.open(os.path.join(src, "ldr-rgb-05.png")), 4),
    ]
    for name, img, scale in heights:
        stem = os.path.join(tmp, f"h-{name}-{scale}")
        img.convert("RGB").save(stem + ".png")
        run([pvrtextool, "-i", stem + ".png", "-o", stem + "-n.pvr", "-f", "r8g8b8a8",
             "-n", f"{scale},xyz", "-d", stem + "-n.png", "-shh"])
        # Drop the alpha channel PVRTexTool writes, so both tools get an RGB normal map.
        Image.open(stem + "-n.png").convert("RGB").save(stem + "-n.png")
        out.append((f"{name} height, -n {scale}", stem + "-n.png"))
    return out


def compare(tessera, a, b, flag):
    return json.loads(run([tessera, "compare", a, b, flag, "--json"]))


def tessera_decode(tessera, png, args, tmp):
    tex, dec = os.path.join(tmp, "t.pvr"), os.path.join(tmp, "t.png")
    run([tessera, "compress", png, "-o", tex, "-q", *args])
    run([tessera, "decompress", tex, "-o", dec, "-q"])
    return dec


def pvrtextool_decode(tool, png, quality, extra, tmp):
    tex, dec = os.path.join(tmp, "p.pvr"), os.path.join(tmp, "p.png")
    has_alpha = Image.open(png).mode == "RGBA"
    fmt = "PVRTC1_4" if has_alpha else "PVRTC1_4_RGB"
    run([tool, "-i", png, "-o", tex, "-f", f"{fmt},UBN,lRGB", "-q", quality, "-d", dec, "-shh",
         *extra])
    return dec


def fmt(v):
    return "∞" if v is None else f"{v:.2f}"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--tessera", default=os.path.join(ROOT, "build", "bin", "tessera"))
    ap.add_argument("--pvrtextool", default=os.path.expanduser("~/.cache/tessera/peers/PVRTexToolCLI"))
    ap.add_argument("--images", default=os.path.join(ROOT, "..", "shared", "data", "images"))
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "benchmarks", "pvrtc_assets.md"))
    ap.add_argument("--quick", action="store_true", help="two images per table (a smoke run)")
    args = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="tessera-assets-bench-")

    alpha_cols = []
    for q in ("normal", "high"):
        for extra in ([], ["--alpha-bleed"], ["--alpha-weighted"],
                      ["--alpha-bleed", "--alpha-weighted"]):
            alpha_cols.append((" ".join(["tessera", q, *extra]), "t", ["--quality", q, *extra]))
    alpha_cols += [
                  ("PVRTexTool pvrtcnormal", "p", ("pvrtcnormal", [])),
                  ("PVRTexTool pvrtcnormal -l", "p", ("pvrtcnormal", ["-l"])),
                  ("PVRTexTool pvrtcbest", "p", ("pvrtcbest", [])),
                  ("PVRTexTool pvrtcbest -l", "p", ("pvrtcbest", ["-l"]))]
    images = alpha_images(args.images, tmp)
    if args.quick:
        images = images[:2]
    alpha_rows = []
    for name, png in images:
        cells = []
        for label, kind, spec in alpha_cols:
            if kind == "t":
                dec = tessera_decode(args.tessera, png, spec, tmp)
            else:
                dec = pvrtextool_decode(args.pvrtextool, png, spec[0], spec[1], tmp)
            c = compare(args.tessera, png, dec, "--premultiplied")
            cells.append((c["psnr_premultiplied"], c.get("psnr_alpha")))
            print(f"{name:28s} {label:45s} premultiplied {fmt(cells[-1][0])} alpha {fmt(cells[-1][1])}",
                  flush=True)
        a = np.asarray(Image.open(png).convert("RGBA"))[..., 3]
        alpha_rows.append((name, float((a == 0).mean()), cells))

    normal_cols = [("tessera normal", "t", ["--quality", "normal"]),
                   ("tessera normal --normal-map", "t", ["--quality", "normal", "--normal-map"]),
                   ("tessera high", "t", ["--quality", "high"]),
                   ("tessera high --normal-map", "t", ["--quality", "high", "--normal-map"]),
                   ("PVRTexTool pvrtcnormal", "p", "pvrtcnormal"),
                   ("PVRTexTool pvrtchigh", "p", "pvrtchigh"),
                   ("PVRTexTool pvrtcbest", "p", "pvrtcbest")]
    nimages = normal_images(args.images, tmp, args.pvrtextool)
    if args.quick:
        nimages = nimages[:2]
    normal_rows = []
    for name, png in nimages:
        cells = []
        for label, kind, spec in normal_cols:
            dec = (tessera_decode(args.tessera, png, spec, tmp) if kind == "t"
                   else pvrtextool_decode(args.pvrtextool, png, spec, [], tmp))
            c = compare(args.tessera, png, dec, "--normal")
            cells.append((c["angular_error_mean_deg"], c["angular_error_p99_deg"]))
            print(f"{name:28s} {label:30s} mean {cells[-1][0]:.3f} p99 {cells[-1][1]:.2f}", flush=True)
        normal_rows.append((name, cells))

    lines = [
        "# PVRTC assets: alpha and normal maps against PVRTexTool",
        "",
        f"Machine: {cpu_model()}, {os.cpu_count()} CPUs, {platform.system()} {platform.release()}. "
        f"Date: {datetime.date.today().isoformat()}. PVRTC1 4 bpp.",
        "",
        "Command: `" + " ".join(shlex.quote(a) for a in ["/usr/bin/python3", "bench/pvrtc_assets.py",
                                                          *sys.argv[1:]]) + "`",
        "",
        "## Alpha: the colour a blending renderer shows",
        "",
        "Cells: PSNR of colour x alpha (`tessera compare --premultiplied`, dB) / alpha PSNR (dB), "
        "each decode against the original; the last column is the mean of colour x alpha. "
        "The header gives each image's share of fully transparent texels.",
        "",
        "| encoder, options | " +
        " | ".join(f"{name} ({100 * transparent:.0f} %)" for name, transparent, _ in alpha_rows) +
        " | mean |",
        "|---|" + "---:|" * (len(alpha_rows) + 1),
    ]
    for k, (label, _, _) in enumerate(alpha_cols):
        vals = [r[2][k][0] for r in alpha_rows if r[2][k][0] is not None]
        mean = sum(vals) / len(vals) if vals else None
        lines.append(f"| {label} | " + " | ".join(f"{fmt(r[2][k][0])} / {fmt(r[2][k][1])}"
                                                 for r in alpha_rows) +
                     f" | {fmt(mean)} |")
    lines += [
        "",
        "## Normal maps: the angle a renormalising renderer sees",
        "",
        "Cells: mean / 99th-percentile angular error in degrees (`tessera compare --normal`), "
        "each decode against the normal map given to both tools.",
        "",
        "| normal map | " + " | ".join(c[0] for c in normal_cols) + " |",
        "|---|" + "---:|" * len(normal_cols),
    ]
    for name, cells in normal_rows:
        lines.append(f"| {name} | " + " | ".join(f"{m:.3f} / {p:.2f}" for m, p in cells) + " |")
    nmeans = [sum(r[1][k][0] for r in normal_rows) / len(normal_rows) for k in range(len(normal_cols))]
    lines.append("| **mean** | " + " | ".join(f"**{m:.3f}**" for m in nmeans) + " |")
    lines.append("")
    write_report(args.out, lines, NOTES)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
