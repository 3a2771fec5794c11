"""Shared fixtures of the tessera Python tests.

CTest sets PYTHONPATH (the build tree's python/ folder) and TESSERA_CLI (build/bin/tessera).
Run by hand from the repository root, the defaults find both in ./build:
    /usr/bin/python3 -m pytest -q python/tests
"""

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
BUILD = Path(os.environ.get("TESSERA_BUILD_DIR", ROOT / "build"))
if not os.environ.get("PYTHONPATH"):
    sys.path.insert(0, str(BUILD / "python"))
    # Subprocesses (python3 -m tessera.batch) get the package through the environment.
    os.environ["PYTHONPATH"] = str(BUILD / "python")

CLI = Path(os.environ.get("TESSERA_CLI", BUILD / "bin" / "tessera"))
SHARED_IMAGES = Path(os.environ.get("TESSERA_SHARED", ROOT.parent / "shared")) / "data" / "images"


def run_cli(*args, check=True):
    """Runs the tessera CLI; returns the CompletedProcess (text mode)."""
    assert CLI.exists(), f"{CLI} is missing: build the tessera_cli target"
    r = subprocess.run([str(CLI), *map(str, args)], capture_output=True, text=True)
    if check:
        assert r.returncode == 0, r.stderr
    return r


def cli_json(*args):
    return json.loads(run_cli(*args).stdout)


def cli_error(*args):
    """Runs a CLI command that must fail with exit code 1; returns its message without the
    'tessera: ' prefix."""
    r = run_cli(*args, check=False)
    assert r.returncode == 1, (r.returncode, r.stdout, r.stderr)
    line = r.stderr.strip()
    assert line.startswith("tessera: "), line
    return line[len("tessera: "):]


def make_image(height, width, channels, seed=0, alpha="ramp"):
    """Deterministic test content: smooth colour gradients, a few sharp edges and noise.
    alpha: 'ramp' (translucent gradient with a cut-out), 'opaque' (255 everywhere)."""
    rng = np.random.default_rng(seed)
    y, x = np.mgrid[0:height, 0:width].astype(np.float64)
    r = 128 + 100 * np.sin(x / max(width, 1) * 6.28 + seed)
    g = 128 + 100 * np.cos(y / max(height, 1) * 4.0)
    b = np.where((x // 8 + y // 8) % 2 == 0, 40.0, 210.0)
    rgb = np.stack([r, g, b], axis=-1) + rng.normal(0, 6, (height, width, 3))
    img = np.clip(np.rint(rgb), 0, 255).astype(np.uint8)
    if channels == 3:
        return img
    if alpha == "opaque":
        a = np.full((height, width), 255, np.uint8)
    else:
        a = np.clip(255 * (x + y) / max(width + height - 2, 1), 0, 255).astype(np.uint8)
        a[height // 4: height // 2, width // 4: width // 2] = 0
    return np.concatenate([img, a[..., None]], axis=-1)


def make_normal_map(height, width, seed=0):
    """Unit vectors (a bumpy surface) mapped from [-1, 1] to [0, 255], RGB."""
    y, x = np.mgrid[0:height, 0:width].astype(np.float64)
    nx = 0.5 * np.sin(x / width * 12.6 + seed)
    ny = 0.4 * np.cos(y / height * 9.4)
    n = np.stack([nx, ny, np.ones_like(nx)], axis=-1)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    return np.clip(np.rint((n + 1) * 127.5), 0, 255).astype(np.uint8)


def pytest_configure(config):
    # distributed 2022.12 on Debian's tornado 6.2 warns on every LocalCluster start.
    config.addinivalue_line("filterwarnings",
                            "ignore:make_current is deprecated:DeprecationWarning")
