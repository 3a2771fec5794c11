#!/usr/bin/env python3
"""The example engine examples/engine_aa_vk (a Vulkan deferred renderer of its own,
anti-aliased with tessera::vk::AdaptiveSupersampler) on this machine's Vulkan (lavapipe
without a GPU), under the validation layer with synchronization validation.

Usage: engine_aa_vk_test.py PATH/TO/engine_aa_vk
Exits 77 (CTest: skipped) when there is no Vulkan 1.3 device or no validation layer, or fails
when TESSERA_TEST_REQUIRE asks for vulkan / vulkan-validation (or is "all").

The checks and bounds it shares with tests/gl/engine_aa_test.py are in
tests/support/engine_aa_checks.py (the frame against the component's own full supersampling,
budget 0 as the negative control, the schedules, -o, the usage errors); here: the backend, no
Vulkan driver. Every run must report zero validation messages (the engine exits 1 on any, and
the message is named).
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from cli_harness import check, expect_error, finish  # noqa: E402
from engine_aa_checks import SIZE, check_engine  # noqa: E402
from engine_vk_harness import reporter, runner  # noqa: E402

ENGINE = sys.argv[1]


run = runner(ENGINE)
report = reporter([ENGINE, *SIZE], "no Vulkan 1.3 device here")


r = check_engine(report, run, SIZE)
check("backend vk", r.get("backend") == "vk", r)

env = dict(os.environ, VK_ICD_FILENAMES="/nonexistent/icd.json")
expect_error(lambda *a: run(*a, env=env), "no Vulkan driver", SIZE, 1, "no Vulkan device")
sys.exit(finish())
