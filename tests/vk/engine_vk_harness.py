"""What the example-engine tests engine_aa_vk_test.py and engine_ptex_vk_test.py share: running
the engine, and one --json report under the validation layer (skipped or failed, per
TESSERA_TEST_REQUIRE, without a Vulkan device or the layer; any validation message fails)."""
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, run_command, skip_or_fail  # noqa: E402


def runner(engine):
    """run(*args, env=None) -> (rc, stdout, stderr) of `engine` with `args`."""
    def run(*args, env=None):
        p = subprocess.run([engine, *args], capture_output=True, text=True, timeout=600, env=env)
        return p.returncode, p.stdout, p.stderr
    return run


def reporter(command, no_device):
    """report(*args) -> the JSON of `command --json args`, checked: exit 0, the validation layer
    on, zero validation messages. `no_device` words the skip when there is no Vulkan device."""
    def report(*args):
        rc, out, err = run_command([*command, "--json", *args], timeout=600)
        if rc != 0 and "no Vulkan device" in err:
            skip_or_fail("vulkan", f"{no_device}: {err.strip()}")
        check(f"{args} exit 0", rc == 0, err)
        try:
            r = json.loads(out)
        except json.JSONDecodeError:
            check(f"{args} JSON", False, out)
            return {}
        if not r.get("validation"):
            skip_or_fail("vulkan-validation",
                         "no VK_LAYER_KHRONOS_validation (Debian: vulkan-validationlayers)")
        check(f"{args} no validation message", r.get("validation_messages") == 0, r)
        return r
    return report
