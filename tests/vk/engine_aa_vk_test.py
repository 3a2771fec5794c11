#!/usr/bin/env python3
"""The example engine examples/engine_aa_vk (a Vulkan deferred renderer of its own,
anti-aliased with tessera::vk::AdaptiveSupersampler) on this machine's Vulkan (lavapipe
without a GPU), under the validation layer with synchronization validation.

Usage: engine_aa_vk_test.py PATH/TO/engine_aa_vk
Exits 77 (CTest: skipped) when there is no Vulkan 1.3 device or no validation layer, or fails
when TESSERA_TEST_REQUIRE asks for vulkan / vulkan-validation (or is "all").

Bounds, measured at 160x120, m = 4 on lavapipe: the adaptive image is 40.2 dB from the
component's own full supersampling with 41 % of its samples; the 1 spp image (and the frame with
--budget 0, the negative control) is 25.3 dB. PSNR_MIN = 35 dB sits 5 dB under the adaptive
image and 10 dB over 1 spp. Every run must report zero validation messages (the engine exits 1
on any, and the message is named).
"""
import os
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, expect_error, finish  # noqa: E402
from engine_vk_harness import reporter, runner  # noqa: E402

ENGINE = sys.argv[1]
SIZE = ["--size", "160x120"]
PSNR_MIN = 35.0


run = runner(ENGINE)
report = reporter([ENGINE, *SIZE], "no Vulkan 1.3 device here")


r = report()
check("backend vk", r.get("backend") == "vk", r)
check("samples % strictly between 0 and 60", 0.0 < r.get("samples_percent", 0) <= 60.0, r)
check(f"PSNR >= {PSNR_MIN} dB", r.get("psnr_db", 0) >= PSNR_MIN, r)
check("1 spp below the bound", r.get("psnr_1spp_db", 99) < PSNR_MIN, r)
check("pass times", {"first", "metrics", "extra_list", "extra_shade", "extra_resolve"} <=
      set(r.get("passes_ms", {})), r)
asked = r.get("extra_samples", 0)
check("extra samples asked", asked > 0, r)

# Negative control: budget 0 is the 1 spp image, and fails the bound.
z = report("--budget", "0")
check("budget 0: no extra samples", z.get("extra_samples") == 0, z)
check("budget 0: the 1 spp PSNR", z.get("psnr_db") == z.get("psnr_1spp_db"), z)
check("budget 0: below the bound", z.get("psnr_db", 99) < PSNR_MIN, z)
# A binding budget is spent exactly; the image lies between.
b = report("--budget", str(asked // 4))
check("budget: exactly spent", b.get("extra_samples") == asked // 4, b)
check("budget: between 1 spp and unbudgeted",
      z.get("psnr_db", 0) < b.get("psnr_db", 0) < r.get("psnr_db", 0), b)
# Every schedule gives the same image.
for sch in ("tile_list", "loop"):
    s = report("--schedule", sch)
    check(f"{sch}: same PSNR and samples",
          s.get("psnr_db") == r.get("psnr_db") and s.get("extra_samples") == asked, s)

with tempfile.TemporaryDirectory() as d:
    rc, _, err = run(*SIZE, "-o", d)
    check("-o exit 0", rc == 0, err)
    for name in ("adaptive.png", "reference.png", "first.png", "samples.png"):
        path = os.path.join(d, name)
        check(f"-o writes {name}", os.path.isfile(path) and os.path.getsize(path) > 100, path)

expect_error(run, "bad --size", ["--size", "0x3"], 1, "--size")
expect_error(run, "bad --schedule", [*SIZE, "--schedule", "bogus"], 1, "bogus")
expect_error(run, "bad --m", [*SIZE, "--m", "9"], 1, "m = 9")
env = dict(os.environ, VK_ICD_FILENAMES="/nonexistent/icd.json")
expect_error(lambda *a: run(*a, env=env), "no Vulkan driver", SIZE, 1, "no Vulkan device")
sys.exit(finish())
