#!/usr/bin/env python3
"""Cross-checks `tessera compare --json` against scikit-image, an independent implementation.

Usage: skimage_crosscheck.py PATH/TO/tessera
For real photos (../shared/data/images when present, else $TESSERA_SHARED/data/images) and for
tessera's procedural images, makes degraded copies (noise, blur, quantisation, JPEG, a shifted
crop) and requires
  |PSNR_tessera - PSNR_skimage| <= 0.01 dB   (peak_signal_noise_ratio over RGB, data_range 255)
  |SSIM_tessera - SSIM_skimage| <= 1e-4      (structural_similarity on Rec.709 luma with
                                              gaussian_weights=True, sigma=1.5,
                                              use_sample_covariance=False, data_range=255)
"""
import io
import json
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image
from skimage.metrics import peak_signal_noise_ratio, structural_similarity

TESSERA = sys.argv[1]
HERE = os.path.dirname(os.path.abspath(__file__))
shared = os.environ.get("TESSERA_SHARED", os.path.join(HERE, "..", "..", "..", "shared"))
images_dir = os.path.join(shared, "data", "images")


def luma(x):
    x = x.astype(np.float64)
    return 0.2126 * x[..., 0] + 0.7152 * x[..., 1] + 0.0722 * x[..., 2]


def degradations(rgb, rng):
    f = rgb.astype(np.float64)
    noise = np.clip(f + rng.normal(0, 6, f.shape), 0, 255).round().astype(np.uint8)
    k = np.ones(3) / 3
    blur = f.copy()
    blur = np.apply_along_axis(lambda r: np.convolve(r, k, mode="same"), 0, blur)
    blur = np.apply_along_axis(lambda r: np.convolve(r, k, mode="same"), 1, blur)
    blur = np.clip(blur, 0, 255).round().astype(np.uint8)
    quant = ((rgb // 16) * 16 + 8).astype(np.uint8)
    buf = io.BytesIO()
    Image.fromarray(rgb).save(buf, format="JPEG", quality=40)
    jpeg = np.array(Image.open(io.BytesIO(buf.getvalue())).convert("RGB"))
    shifted = np.roll(rgb, (1, 2), axis=(0, 1))
    return {"noise": noise, "blur": blur, "quant": quant, "jpeg": jpeg, "shift": shifted}


def main():
    tmp = tempfile.mkdtemp(prefix="tessera-xcheck-")
    failures, passed = [], 0
    try:
        sources = []
        subprocess.run([TESSERA, "demo", "-o", os.path.join(tmp, "demo"), "--size", "96"],
                       check=True, capture_output=True)
        demo_img = os.path.join(tmp, "demo", "img")
        for n in sorted(os.listdir(demo_img)):
            # The demo's original procedural images: images-<kind>.png.
            if n.startswith("images-") and n.endswith(".png") and "-" not in n[len("images-"):]:
                sources.append(os.path.join(demo_img, n))
        if os.path.isdir(images_dir):
            for n in sorted(os.listdir(images_dir)):
                if n.endswith(".png"):
                    sources.append(os.path.join(images_dir, n))
        else:
            print(f"note: {images_dir} absent; procedural images only")
        rng = np.random.default_rng(7)
        for src in sources:
            rgb = np.array(Image.open(src).convert("RGB"))
            if min(rgb.shape[:2]) < 11:  # no 11x11 window fits: SSIM undefined in skimage
                continue
            if min(rgb.shape[:2]) > 512:  # keep the test quick: central 512x512 crop
                h, w = rgb.shape[:2]
                rgb = np.ascontiguousarray(rgb[(h - 512) // 2:(h + 512) // 2,
                                               (w - 512) // 2:(w + 512) // 2])
            ref_path = os.path.join(tmp, "ref.png")
            Image.fromarray(rgb).save(ref_path)
            for kind, deg in degradations(rgb, rng).items():
                deg_path = os.path.join(tmp, "deg.png")
                Image.fromarray(deg).save(deg_path)
                p = subprocess.run([TESSERA, "compare", ref_path, deg_path, "--json"],
                                   capture_output=True, text=True)
                if p.returncode != 0:
                    failures.append(f"{src} {kind}: tessera failed: {p.stderr.strip()}")
                    continue
                t = json.loads(p.stdout)
                ps = peak_signal_noise_ratio(rgb, deg, data_range=255)
                ss = structural_similarity(luma(rgb), luma(deg), data_range=255,
                                           gaussian_weights=True, sigma=1.5,
                                           use_sample_covariance=False)
                dp = abs(t["psnr_rgb"] - ps)
                ds = abs(t["ssim_gray"] - ss)
                tag = f"{os.path.basename(src)} {kind}"
                if dp > 0.01 or ds > 1e-4:
                    failures.append(f"{tag}: psnr {t['psnr_rgb']:.5f} vs {ps:.5f}, "
                                    f"ssim {t['ssim_gray']:.6f} vs {ss:.6f}")
                else:
                    passed += 1
        for f in failures:
            print("FAIL", f)
        print(f"{passed} passed, {len(failures)} failed")
        return 1 if failures or passed == 0 else 0
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
