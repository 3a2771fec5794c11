#!/usr/bin/env python3
"""CLI tests of `tessera seams --backend vk` and `tessera aa --backend vk` (the papers'
experiments on Vulkan: lavapipe where there is no GPU), every run under the Khronos validation
layer with synchronization validation (TESSERA_VK_VALIDATION=1: any validation message fails
the command).

Checked: the reports have exactly the keys of the `--backend gl` reports (where OpenGL runs too;
else the CPU report's keys plus the GPU ones), "backend" is "vk", the device and the Vulkan
timing note are named, every rate has GPU-timestamp and wall times; the figures agree with the
other backends: the seam methods' errors against the reference within 10 % of the CPU's (the
same frames drawn by another rasteriser), the adaptive method's samples % within 0.2 points and
its PSNR against full supersampling within 0.5 dB of GL's; and the one-line errors (a rate the
device refuses, a missing Vulkan device).

Usage: vk_cli_test.py PATH/TO/tessera
Exits 77 (CTest: skipped) when there is no Vulkan device or validation layer, or fails when
TESSERA_TEST_REQUIRE asks for vulkan / vulkan-validation (cli_harness.skip_or_fail).
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, finish, missing_part, skip_or_fail  # noqa: E402

TESSERA = sys.argv[1]
METHODS = ("clamp", "discard", "traverse", "traverse_corners")
SEAMS = ["--width", "96", "--height", "108", "--frames", "2", "--msaa", "1,4",
         "--reference-factor", "4"]
AA = ["--width", "96", "--height", "72", "--ssaa", "2,4", "--frames", "1"]
GPU_KEYS = {"gpu_renderer", "gpu_version", "msaa_unsupported", "gpu_samples", "timing_note"}


def run(*args, validation=True, extra_env=None):
    env = dict(os.environ)
    env["TESSERA_VK_VALIDATION"] = "1" if validation else "0"
    env.update(extra_env or {})
    p = subprocess.run([TESSERA, "-j", "2", *args], capture_output=True, text=True,
                       timeout=900, env=env)
    return p.returncode, p.stdout, p.stderr


def skip_without_vulkan(rc, se):
    if rc == 0:
        return
    if "VK_LAYER_KHRONOS_validation" in se:
        skip_or_fail("vulkan-validation", f"no validation layer: {se.strip()}")
    if "no Vulkan" in se or "not built with the Vulkan runtime" in se:
        skip_or_fail("vulkan", f"no Vulkan: {se.strip()}")


def keys(j):
    return sorted(j) if isinstance(j, dict) else []


def seams(tmp):
    vk_out = os.path.join(tmp, "seams-vk")
    rc, so, se = run("seams", "--backend", "vk", "--json", "-q", *SEAMS, "-o", vk_out)
    skip_without_vulkan(rc, se)
    check("seams vk runs, no validation message", rc == 0, se)
    j = json.loads(so)
    check("seams vk: backend", j.get("backend") == "vk", j.get("backend"))
    check("seams vk: device", j.get("gpu_renderer", "") != "" and
          j.get("gpu_version", "").startswith("Vulkan 1."), (j.get("gpu_renderer"),
                                                             j.get("gpu_version")))
    check("seams vk: Vulkan timing note", "Vulkan" in j.get("timing_note", ""), j.get("timing_note"))
    rates = [r for r in ("1x", "4x") if int(r[:-1]) not in j.get("msaa_unsupported", [])]
    check("seams vk: 1x and 4x drawn (every Vulkan device has them)", rates == ["1x", "4x"],
          j.get("msaa_unsupported"))
    for rate in rates:
        p = j["gpu_samples"][rate]
        check(f"seams vk {rate}: standard sample positions", p["cpu_msaa"] == p["samples"] ==
              int(rate[:-1]), p)
        for m in METHODS:
            t = j["timing"][rate][m]
            check(f"seams vk {rate} {m}: GPU and wall times",
                  len(t["frame_ms"]) == 2 and t["median_ms"] > 0 and t["wall_median_ms"] > 0, t)
    cpu_out = os.path.join(tmp, "seams-cpu")
    rc, so, se = run("seams", "--backend", "cpu", "--json", "-q", *SEAMS, "-o", cpu_out)
    check("seams cpu runs", rc == 0, se)
    cpu = json.loads(so)
    gl_out = os.path.join(tmp, "seams-gl")
    rc, so, se = run("seams", "--backend", "gl", "--json", "-q", *SEAMS, "-o", gl_out)
    if rc == 0:
        gl = json.loads(so)
        check("seams vk: the keys of the GL report", keys(j) == keys(gl), (keys(j), keys(gl)))
        check("seams vk: the timing keys of GL",
              keys(j["timing"]["1x"]["discard"]) == keys(gl["timing"]["1x"]["discard"]))
    else:
        missing_part("gl", f"seams --backend gl failed, no GL comparison: {se.strip()}")
        check("seams vk: the CPU report's keys and the GPU ones", set(j) == set(cpu) | GPU_KEYS,
              keys(j))
    check("seams vk: the quality keys of the CPU", keys(j["quality"]) == keys(cpu["quality"]))
    # The same frames on another rasteriser: every method's mean error against the reference
    # within 10 % of the CPU's (a wrong method, face or filter is off by far more).
    for rate in rates:
        for m in METHODS:
            a = j["quality"]["vs_reference"][m][rate]["mean"]
            b = cpu["quality"]["vs_reference"][m][rate]["mean"]
            check(f"seams vk {rate} {m}: error vs reference as the CPU's", abs(a - b) <= 0.1 * b,
                  (a, b))
    # A rate the device refuses alone: one line, nothing written.
    refused = [r for r in (2, 8, 16) if r in j.get("msaa_unsupported", [])] or []
    rc, so, se = run("seams", "--backend", "vk", "-q", *SEAMS[:6], "--msaa", "16",
                     "-o", os.path.join(tmp, "refused"))
    if 16 not in refused:
        check("seams vk 16x: runs or is refused in one line", rc == 0 or
              (rc != 0 and se.count("\n") == 1), se)
    else:
        check("seams vk 16x refused: one line", rc != 0 and se.count("\n") == 1 and
              "refuses every MSAA rate" in se, se)
        check("seams vk 16x refused: no folder", not os.path.exists(os.path.join(tmp, "refused")))


def aa(tmp):
    vk_out = os.path.join(tmp, "aa-vk")
    rc, so, se = run("aa", "--backend", "vk", "--json", "-q", *AA, "-o", vk_out)
    skip_without_vulkan(rc, se)
    check("aa vk runs, no validation message", rc == 0, se)
    j = json.loads(so)
    check("aa vk: backend", j.get("backend") == "vk", j.get("backend"))
    check("aa vk: device", j.get("gpu_renderer", "") != "" and
          j.get("gpu_version", "").startswith("Vulkan 1."), j.get("gpu_version"))
    for r in j["rates"]:
        for key in ("default", "fxaa", "reference", "adaptive", "edge_per_sample"):
            check(f"aa vk {r['m']}: {key} GPU timestamps", "gpu_shade_ms" in r[key], keys(r[key]))
            passes = r[key].get("passes", {})
            check(f"aa vk {r['m']}: {key} passes", len(passes) > 0 and all(
                p["wall_ms"] > 0 for p in passes.values()), passes)
        pct = r["adaptive"]["samples_pct"]
        check(f"aa vk {r['m']}: adaptive shades fewer samples", 100.0 / r["m"] ** 2 < pct < 100.0,
              pct)
        # Without GL too: adaptive comes clearly closer to full supersampling than 1 spp.
        pa, p1 = r["adaptive"]["quality"]["psnr_db"], r["default"]["quality"]["psnr_db"]
        check(f"aa vk {r['m']}: adaptive >= 3 dB above 1 spp against full supersampling",
              pa is not None and p1 is not None and pa >= p1 + 3.0, (pa, p1))
    for name in ("aa.json", "aa.md"):
        check(f"aa vk: {name} written", os.path.isfile(os.path.join(vk_out, name)))
    md = open(os.path.join(vk_out, "aa.md")).read()
    check("aa vk: md names Vulkan and its timestamps", "Vulkan: `" in md and "GPU timestamps" in md)
    gl_out = os.path.join(tmp, "aa-gl")
    rc, so, se = run("aa", "--backend", "gl", "--json", "-q", *AA, "-o", gl_out)
    if rc != 0:
        missing_part("gl", f"aa --backend gl failed, no GL comparison: {se.strip()}")
        return
    gl = json.loads(so)
    check("aa vk: the keys of the GL report", keys(j) == keys(gl), (keys(j), keys(gl)))
    for rv, rg in zip(j["rates"], gl["rates"]):
        m = rv["m"]
        check(f"aa vk {m}: the rate keys of GL", keys(rv) == keys(rg), (keys(rv), keys(rg)))
        for key in ("default", "fxaa", "adaptive", "edge_per_sample"):
            check(f"aa vk {m}: {key} keys as GL's", keys(rv[key]) == keys(rg[key]))
        a, b = rv["adaptive"], rg["adaptive"]
        check(f"aa vk {m}: adaptive samples % as GL's", abs(a["samples_pct"] - b["samples_pct"])
              <= 0.2, (a["samples_pct"], b["samples_pct"]))
        pa, pb = a["quality"]["psnr_db"], b["quality"]["psnr_db"]
        check(f"aa vk {m}: adaptive PSNR vs full supersampling as GL's",
              pa is not None and pb is not None and abs(pa - pb) <= 0.5, (pa, pb))


def errors(tmp):
    # No Vulkan device: a one-line error, no output folder (the ICD list points at nothing).
    out = os.path.join(tmp, "nodevice")
    rc, so, se = run("aa", "--backend", "vk", *AA, "-o", out, validation=False,
                     extra_env={"VK_ICD_FILENAMES": os.path.join(tmp, "none.json"),
                                "VK_DRIVER_FILES": os.path.join(tmp, "none.json")})
    check("no Vulkan device: fails in one line", rc != 0 and se.count("\n") == 1 and
          "Vulkan" in se, se)
    check("no Vulkan device: no folder", not os.path.exists(out))


tmp = tempfile.mkdtemp(prefix="tessera-vk-cli-")
try:
    seams(tmp)
    aa(tmp)
    errors(tmp)
finally:
    shutil.rmtree(tmp, ignore_errors=True)
sys.exit(finish())
