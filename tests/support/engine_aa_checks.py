"""What the tests of the two AA example engines (tests/gl/engine_aa_test.py: examples/engine_aa on
OpenGL; tests/vk/engine_aa_vk_test.py: examples/engine_aa_vk on Vulkan) check alike: the same
frame, the same flags, the same bounds.

Bounds, measured at 160x120, m = 4 on llvmpipe and on lavapipe alike: the adaptive image is
40.2 dB from the component's own full supersampling with 41 % of its samples; the 1 spp image
(and the frame with --budget 0, the negative control) is 25.3 dB. PSNR_MIN = 35 dB sits 5 dB
under the adaptive image and 10 dB over 1 spp, so a component that shades too few samples, or
the wrong ones, fails it; the samples must stay at most 60 %.
"""
import os
import tempfile

from cli_harness import check, expect_error

SIZE = ["--size", "160x120"]
PSNR_MIN = 35.0
SAMPLES_MAX = 60.0


def check_engine(report, run, size):
    """Checks an AA engine through `report(*args)` (its --json object at `size`, exit 0
    checked) and `run(*args)` ((exit code, stdout, stderr)): the adaptive frame against its
    bounds, budget 0 as the negative control, a binding budget spent exactly, every schedule
    the same image, -o, and the usage errors. Returns the unbudgeted report."""
    r = report()
    check(f"samples % strictly between 0 and {SAMPLES_MAX}",
          0.0 < r.get("samples_percent", 0) <= SAMPLES_MAX, r)
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
        rc, _, err = run(*size, "-o", d)
        check("-o exit 0", rc == 0, err)
        for name in ("adaptive.png", "reference.png", "first.png", "samples.png"):
            path = os.path.join(d, name)
            check(f"-o writes {name}", os.path.isfile(path) and os.path.getsize(path) > 100, path)

    expect_error(run, "bad --size", ["--size", "0x3"], 1, "--size")
    expect_error(run, "bad --schedule", [*size, "--schedule", "bogus"], 1, "bogus")
    expect_error(run, "bad --m", [*size, "--m", "9"], 1, "m = 9")
    return r
