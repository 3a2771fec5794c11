#!/usr/bin/env python3
"""CLI tests of `tessera compare --premultiplied` and `--normal` against a numpy reference.

Usage: compare_cli_test.py PATH/TO/tessera
Writes random RGBA PNGs, computes the premultiplied PSNR and the angular errors of the normals
with numpy from the definitions in tessera/metrics.h, and checks the JSON keys and the text
lines; without the flags the output must not change.
"""
import json
import math
import os
import shutil
import sys
import tempfile

import numpy as np
from PIL import Image

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, finish, run_command  # noqa: E402

TESSERA = sys.argv[1]


def run(*args):
    return run_command([TESSERA, *args], timeout=120)


def close(a, b, rel=1e-9):
    return a is not None and abs(a - b) <= rel * max(1.0, abs(b))


def premultiplied_reference(pa, pb):
    """MSE and PSNR of c * a / 255 (unrounded) over R, G, B."""
    fa, fb = pa.astype(np.float64), pb.astype(np.float64)
    ca = fa[..., :3] * fa[..., 3:4] / 255.0
    cb = fb[..., :3] * fb[..., 3:4] / 255.0
    mse = float(np.mean((ca - cb) ** 2))
    return mse, (math.inf if mse == 0 else 10 * math.log10(255.0**2 / mse))


def normals(p):
    v = p[..., :3].astype(np.float64) * 2 / 255 - 1
    n = np.linalg.norm(v, axis=-1, keepdims=True)
    z = np.broadcast_to(np.array([0.0, 0.0, 1.0]), v.shape)
    return np.where(n < 1e-6, z, v / np.maximum(n, 1e-300))


def angular_reference(pa, pb):
    """Mean, nearest-rank p99 and max of the per-texel angle, in degrees."""
    u, v = normals(pa), normals(pb)
    sine = np.linalg.norm(np.cross(u, v), axis=-1)
    cosine = np.sum(u * v, axis=-1)
    ang = np.degrees(np.arctan2(sine, cosine)).ravel()
    rank = -(-99 * ang.size // 100)  # ceil(0.99 n)
    return float(ang.mean()), float(np.sort(ang)[rank - 1]), float(ang.max())


tmp = tempfile.mkdtemp(prefix="tessera-compare-")
try:
    rng = np.random.default_rng(20240611)
    h, w = 37, 53
    pa = rng.integers(0, 256, (h, w, 4), dtype=np.uint8)
    pa[..., 3] = rng.choice([0, 0, 64, 200, 255], (h, w)).astype(np.uint8)
    pb = pa.copy()
    noise = rng.integers(-12, 13, (h, w, 3))
    pb[..., :3] = np.clip(pa[..., :3].astype(int) + noise, 0, 255).astype(np.uint8)
    pb[..., 3] = np.clip(pa[..., 3].astype(int) + rng.integers(-3, 4, (h, w)), 0, 255)
    pb[(pa[..., 3] == 0), 3] = 0  # keep some texels transparent in both
    a, b = os.path.join(tmp, "a.png"), os.path.join(tmp, "b.png")
    Image.fromarray(pa, "RGBA").save(a)
    Image.fromarray(pb, "RGBA").save(b)

    mse_pm, psnr_pm = premultiplied_reference(pa, pb)
    mean, p99, mx = angular_reference(pa, pb)
    check("reference: some angles differ", 0 < mean < p99 <= mx, (mean, p99, mx))

    # JSON keys against the reference.
    rc, out, err = run("compare", a, b, "--json", "--premultiplied", "--normal")
    check("compare --premultiplied --normal rc", rc == 0, err)
    j = json.loads(out)
    check("psnr_premultiplied", close(j.get("psnr_premultiplied"), psnr_pm),
          f"{j.get('psnr_premultiplied')} vs {psnr_pm}")
    check("mse_premultiplied", close(j.get("mse_premultiplied"), mse_pm),
          f"{j.get('mse_premultiplied')} vs {mse_pm}")
    check("premultiplied differs from plain PSNR",
          not close(j["psnr_premultiplied"], j["psnr_rgb"]), out)
    for key, ref in (("angular_error_mean_deg", mean), ("angular_error_p99_deg", p99),
                     ("angular_error_max_deg", mx)):
        check(key, close(j.get(key), ref), f"{j.get(key)} vs {ref}")

    # The text lines carry the same values.
    rc, out, err = run("compare", a, b, "--premultiplied", "--normal")
    check("text rc", rc == 0, err)
    check("text: premultiplied PSNR", f"premultiplied PSNR {psnr_pm:.4f} dB" in out, out)
    check("text: angular error",
          f"angular error mean {mean:.4f}°, p99 {p99:.4f}°, max {mx:.4f}°" in out, out)

    # Each flag alone adds only its own keys.
    rc, out, err = run("compare", a, b, "--json", "--normal")
    j = json.loads(out)
    check("--normal alone", "angular_error_p99_deg" in j and "psnr_premultiplied" not in j, out)
    rc, out, err = run("compare", a, b, "--json", "--premultiplied")
    j = json.loads(out)
    check("--premultiplied alone", "psnr_premultiplied" in j and "angular_error_mean_deg" not in j,
          out)

    # Without the flags the output is what it was: no new keys, no new lines.
    rc, out, err = run("compare", a, b, "--json")
    j = json.loads(out)
    check("plain json unchanged",
          sorted(j) == sorted(["a", "b", "width", "height", "psnr_rgb", "identical_rgb", "mse",
                               "ssim_gray", "max_abs", "has_alpha", "psnr_alpha", "mse_alpha"]),
          out)
    rc, out, err = run("compare", a, b)
    check("plain text unchanged", "premultiplied" not in out and "angular" not in out
          and len(out.splitlines()) == 6, out)

    # Colour under alpha 0 in both images does not count: identical colour x alpha.
    pc = pa.copy()
    clear = pa[..., 3] == 0
    pc[clear, :3] = 255 - pa[clear, :3]
    c = os.path.join(tmp, "c.png")
    Image.fromarray(pc, "RGBA").save(c)
    rc, out, err = run("compare", a, c, "--json", "--premultiplied")
    j = json.loads(out)
    check("transparent colour ignored: null PSNR",
          j["psnr_premultiplied"] is None and j["mse_premultiplied"] == 0 and j["mse"] > 0, out)
    rc, out, err = run("compare", a, c, "--premultiplied")
    check("transparent colour ignored: text", "premultiplied PSNR inf" in out, out)

    # RGB normal maps (no alpha): the angular error ignores alpha entirely.
    na, nb = os.path.join(tmp, "na.png"), os.path.join(tmp, "nb.png")
    Image.fromarray(pa[..., :3], "RGB").save(na)
    Image.fromarray(pb[..., :3], "RGB").save(nb)
    rc, out, err = run("compare", na, nb, "--json", "--normal")
    j = json.loads(out)
    check("rgb normals: same angles", close(j.get("angular_error_mean_deg"), mean)
          and close(j.get("angular_error_max_deg"), mx), out)
finally:
    shutil.rmtree(tmp, ignore_errors=True)

sys.exit(finish())
