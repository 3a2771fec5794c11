#!/usr/bin/env python3
"""CLI tests of `tessera seams --backend gl|both` (the OpenGL backend of the seam experiment).

Usage: seams_gl_cli_test.py PATH/TO/tessera
Tiny frames (96x108, 2 orbit frames, MSAA 1,4,8) of the built-in Figure-1 scene:
  * `--backend gl` writes the usual report (the same JSON keys as the CPU's, plus `backend`,
    `gpu_renderer`, `gpu_version`, `msaa_unsupported`, `gpu_samples`, GPU-timer and wall times per
    frame); rates the driver refuses (8x on llvmpipe) are skipped and named in seams.md;
    `gpu_samples` gives each GL rate's drawn sample count and the CPU rate with its positions,
    the driver's positions on the CPU's 1/16 grid and (with `both`) what it was compared with;
  * `--backend both` writes the CPU report byte for byte as `--backend cpu` does (plots, CSV,
    images) plus `timing_gl` and `gl_vs_cpu`, whose PSNR must stay above bounds measured on
    Mesa 22.3 llvmpipe (see below);
  * no usable EGL device (TESSERA_EGL_DEVICE=7): `--backend gl` and `both` fail with one line
    `tessera: ...` naming the device, exit 1, no output folder; `--backend cpu` still works.
Exits 77 (CTest: skipped) when no OpenGL 4.5 context can be made at all.
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, finish, skip_or_fail  # noqa: E402

TESSERA = sys.argv[1]
METHODS = ("clamp", "discard", "traverse", "traverse_corners")
SIZE = ["--width", "96", "--height", "108", "--frames", "2", "--msaa", "1,4,8"]
# GL against the CPU under the experiment's 16x anisotropic filtering, 96x108, pooled over both
# frames (Mesa 22.3.6 llvmpipe, measured): clamp 35.4/36.0 dB, discard 34.6/34.9 dB at 1x/4x,
# traverse 27.0/28.6 dB, traverse_corners 25.5/27.2 dB. Hardware anisotropic filtering is
# implementation-defined (llvmpipe's is much blurrier than tessera's exact filter, and Traverse
# filters more taps across edges, so it differs most). For scale: the CPU frame against itself
# shifted by one pixel is 21.3 dB (clamp, discard) and 21.9-22.4 dB (traverse, corners), so
# these bounds fail on any misregistered, mis-textured or wrongly lit GL frame.
MIN_PSNR = {"clamp": 30.0, "discard": 30.0, "traverse": 24.0, "traverse_corners": 24.0}
# Pixels >= 0.01 apart (linear-RGB 2-norm): measured 0.37-0.60; an unrelated frame is ~0.9.
MAX_FRACTION = 0.75


def run(*args, env=None):
    e = dict(os.environ)
    e.setdefault("LP_NUM_THREADS", "2")
    if env:
        e.update(env)
    p = subprocess.run([TESSERA, "-j", "2", *args], capture_output=True, text=True, timeout=900,
                       env=e)
    return p.returncode, p.stdout, p.stderr


def load(folder):
    with open(os.path.join(folder, "seams.json")) as f:
        return json.load(f)


def same_bytes(a, b):
    with open(a, "rb") as fa, open(b, "rb") as fb:
        return fa.read() == fb.read()


tmp = tempfile.mkdtemp(prefix="tessera-seams-gl-")
try:
    gl_out = os.path.join(tmp, "gl")
    rc, so, se = run("seams", "--backend", "gl", "-q", *SIZE, "-o", gl_out)
    if rc != 0 and ("EGL" in se or "OpenGL" in se) and not os.path.exists(gl_out):
        skip_or_fail("gl", f"no OpenGL 4.5 context: {se.strip()}")
    check("gl run rc", rc == 0, se)

    cpu_out = os.path.join(tmp, "cpu")
    rc, so, se = run("seams", "--backend", "cpu", "-q", *SIZE, "-o", cpu_out)
    check("cpu run rc", rc == 0, se)
    cpu = load(cpu_out)
    check("cpu backend key", cpu.get("backend") == "cpu", str(cpu.get("backend")))
    check("cpu run has no GL keys",
          not any(k in cpu for k in ("gpu_renderer", "gl_vs_cpu", "timing_gl")), str(list(cpu)))

    # ---- --backend gl
    j = load(gl_out)
    check("gl backend key", j.get("backend") == "gl", str(j.get("backend")))
    check("gpu_renderer", isinstance(j.get("gpu_renderer"), str) and j["gpu_renderer"] != "",
          str(j.get("gpu_renderer")))
    check("gpu_version", isinstance(j.get("gpu_version"), str) and j["gpu_version"] != "",
          str(j.get("gpu_version")))
    unsupported = j.get("msaa_unsupported")
    check("msaa_unsupported is a list", isinstance(unsupported, list), str(unsupported))
    unsupported = unsupported if isinstance(unsupported, list) else []
    check("msaa_unsupported from the asked rates", set(unsupported) <= {1, 4, 8}, str(unsupported))
    if "llvmpipe" in j.get("gpu_renderer", ""):
        check("llvmpipe refuses 8x", unsupported == [8], str(unsupported))
    check("same top-level keys as cpu, plus the GL ones",
          set(j) == set(cpu) | {"gpu_renderer", "gpu_version", "msaa_unsupported", "gpu_samples",
                                "timing_note"},
          f"gl={sorted(j)} cpu={sorted(cpu)}")
    rates = [f"{r}x" for r in (1, 4, 8) if r not in unsupported]
    samples = j.get("gpu_samples", {})
    check("gl_samples per GL rate", sorted(samples) == sorted(rates), str(samples))
    for rate, p in samples.items():
        check(f"gl_samples {rate}", p["samples"] >= int(rate[:-1]) and
              p["cpu_msaa"] in (0, p["samples"]), str(p))
        # The driver's positions on the CPU's 1/16 grid (null off it); no comparison here.
        check(f"gl_samples {rate} positions", p.get("positions") is None or
              (len(p["positions"]) == p["samples"] and
               all(-8 <= v <= 7 for xy in p["positions"] for v in xy)), str(p))
        check(f"gl_samples {rate} compared_with", "compared_with" in p and
              p["compared_with"] is None, str(p))
    if "llvmpipe" in j.get("gpu_renderer", ""):
        check("llvmpipe draws the CPU's patterns",
              all(p["cpu_msaa"] == p["samples"] == int(r[:-1]) for r, p in samples.items()),
              str(samples))
    check("timed rates", sorted(j["timing"]) == sorted(rates), str(sorted(j["timing"])))
    for rate in rates:
        for m in METHODS:
            t = j["timing"][rate][m]
            check(f"gl timing {m} {rate}",
                  len(t["frame_ms"]) == 2 and len(t["wall_frame_ms"]) == 2 and
                  t["median_ms"] > 0 and t["wall_median_ms"] > 0, str(t))
        check(f"gl no shading-only {rate}", j["timing"][rate]["shading_only"]["median_ms"] is None)
        for key in ("vs_reference", "vs_reference_near_seams", "vs_reference_character_only"):
            for m in METHODS:
                q = j["quality"][key][m][rate]
                check(f"gl {key} {m} {rate}", 0 < q["mean"] < 0.5, str(q["mean"]))
        check(f"gl traverse_vs_discard {rate}", rate in j["quality"]["traverse_vs_discard"])
    check("gl quality keys as cpu", set(j["quality"]) == set(cpu["quality"]),
          f"{sorted(j['quality'])} vs {sorted(cpu['quality'])}")
    with open(os.path.join(gl_out, "seams.md")) as f:
        md = f.read()
    check("gl md says which time to read", "Which to read" in md)
    check("gl md names the renderer", j.get("gpu_renderer", "?") in md)
    for r in unsupported:
        check(f"gl md names skipped {r}x", "skipped" in md and f" {r}x" in md)
    for f in ["cdf.csv", "fig5_left.svg", "fig5_right.png", "images/reference.png"] + \
             [f"images/{m}_{r}.png" for m in METHODS for r in rates]:
        check("gl output " + f, os.path.isfile(os.path.join(gl_out, f)))

    # ---- --backend both
    both_out = os.path.join(tmp, "both")
    rc, so, se = run("seams", "--backend", "both", "-q", *SIZE, "-o", both_out)
    check("both run rc", rc == 0, se)
    b = load(both_out)
    check("both backend key", b.get("backend") == "both", str(b.get("backend")))
    check("both msaa_unsupported as gl", b.get("msaa_unsupported") == unsupported,
          str(b.get("msaa_unsupported")))
    check("both CPU timing has every rate", sorted(b["timing"]) == ["1x", "4x", "8x"],
          str(sorted(b["timing"])))
    check("both gl rates", sorted(b["gl_vs_cpu"]) == sorted(rates) and
          sorted(b["timing_gl"]) == sorted(rates), str(sorted(b.get("gl_vs_cpu", {}))))
    for rate, p in b.get("gpu_samples", {}).items():
        # What each GL rate was compared with: the CPU rate with its positions, else the CPU
        # drawn at the driver's own, else nothing (null, and gl_vs_cpu says why).
        expected = (f"cpu {p['cpu_msaa']}x" if p["cpu_msaa"] > 0 else
                    "cpu, the driver's positions" if p.get("positions") else None)
        check(f"both gl_samples {rate} compared_with", p.get("compared_with") == expected,
              str(p))
    for rate in rates:
        for m in METHODS:
            a = b["gl_vs_cpu"][rate][m]
            if "not_compared" in a:  # positions no CPU frame can have (not on llvmpipe)
                check(f"gl_vs_cpu not compared {m} {rate}", a["psnr_db"] is None and
                      b["gpu_samples"][rate]["compared_with"] is None, str(a))
            else:
                check(f"gl_vs_cpu psnr {m} {rate}",
                      a["psnr_db"] is not None and a["psnr_db"] >= MIN_PSNR[m], str(a))
                check(f"gl_vs_cpu fraction {m} {rate}",
                      0 <= a["fraction_ge_0.01"] <= MAX_FRACTION, str(a))
            t = b["timing_gl"][rate][m]
            check(f"timing_gl {m} {rate}", len(t["frame_ms"]) == 2 and
                  len(t["wall_frame_ms"]) == 2 and t["wall_median_ms"] > 0, str(t))
    # The CPU side of `both` is the `cpu` run: same numbers, same files.
    for f in ["cdf.csv", "fig5_left.svg", "fig5_right.svg", "fig5_left.png", "images/reference.png",
              "images/clamp_minus_traverse_8x.png"] + \
             [f"images/{m}_{r}x.png" for m in METHODS for r in (1, 4, 8)]:
        check("both CPU file equals cpu run: " + f,
              same_bytes(os.path.join(both_out, f), os.path.join(cpu_out, f)))
    check("both quality equals cpu", b["quality"] == cpu["quality"])
    with open(os.path.join(both_out, "seams.md")) as f:
        check("both md has the agreement table", "GL against the CPU" in f.read())

    # ---- no usable EGL device
    for backend in ("gl", "both"):
        out = os.path.join(tmp, "nodev_" + backend)
        rc, so, se = run("seams", "--backend", backend, *SIZE, "-o", out,
                         env={"TESSERA_EGL_DEVICE": "7"})
        lines = [line for line in se.splitlines() if line.strip()]
        check(f"no device {backend} exit 1", rc == 1, f"rc={rc} {se!r}")
        check(f"no device {backend} one line", len(lines) == 1 and
              lines[0].startswith("tessera: ") and "device 7" in lines[0], repr(se))
        check(f"no device {backend} leaves no folder", not os.path.exists(out))
    out = os.path.join(tmp, "nodev_cpu")
    rc, so, se = run("seams", "--backend", "cpu", "-q", *SIZE, "-o", out,
                     env={"TESSERA_EGL_DEVICE": "7"})
    check("no device cpu rc", rc == 0, se)
    if rc == 0:
        check("no device cpu same cdf", same_bytes(os.path.join(out, "cdf.csv"),
                                                   os.path.join(cpu_out, "cdf.csv")))
finally:
    shutil.rmtree(tmp, ignore_errors=True)

sys.exit(finish())
