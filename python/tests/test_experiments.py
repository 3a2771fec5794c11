"""tessera.run_seams / run_aa: the library's experiments give the CLI's result format, value for
value (timings aside), and the Markdown report."""

import re

import pytest

import tessera
from conftest import cli_json


def _timing(key):
    return bool(re.search(r"(^|_)ms($|_)|speedup|^timing", key))


def _same(a, b, path=""):
    """Asserts two JSON values are equal, keys named like times aside."""
    if isinstance(a, dict):
        assert isinstance(b, dict) and set(a) == set(b), path
        for k in a:
            if not _timing(k):
                _same(a[k], b[k], f"{path}/{k}")
    elif isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), path
        for i, (x, y) in enumerate(zip(a, b)):
            _same(x, y, f"{path}[{i}]")
    else:
        assert a == b, f"{path}: {a!r} != {b!r}"


def test_run_seams_matches_the_cli(tmp_path):
    opts = dict(msaa=[1, 4], frames=2, quality_frames=1, width=32, height=36, reference_factor=2)
    report = tessera.run_seams(threads=2, **opts)
    cli = cli_json("-j", "2", "seams", "--msaa", "1,4", "--frames", "2", "--quality-frames", "1",
                   "--width", "32", "--height", "36", "--reference-factor", "2", "--json", "-q",
                   "-o", tmp_path / "seams")
    assert "zoom_window" in cli and "zoom_window" not in report  # the CLI writes images
    del cli["zoom_window"]
    _same(cli, report)
    assert report["backend"] == "cpu"
    assert set(report["quality"]["vs_reference"]["traverse"]) == {"1x", "4x"}
    md = tessera.run_seams(threads=2, markdown=True, **opts)
    assert md.startswith("# Seams experiment") and "## Images" not in md


def test_run_aa_matches_the_cli(tmp_path):
    report = tessera.run_aa(ssaa=[2], width=40, height=30, frames=1, lights=2, threads=2)
    cli = cli_json("-j", "2", "aa", "--ssaa", "2", "--width", "40", "--height", "30", "--frames",
                   "1", "--lights", "2", "--json", "-q", "-o", tmp_path / "aa")
    _same(cli, report)
    assert [r["m"] for r in report["rates"]] == [2]
    assert "adaptive-2x2" in report["rates"][0]["images"]
    md = tessera.run_aa(ssaa=[2], width=40, height=30, frames=1, lights=2, markdown=True)
    assert md.startswith("# Adaptive supersampling")


def test_bad_configurations_are_errors():
    with pytest.raises(tessera.Error):
        tessera.run_seams(msaa=[3], frames=1, width=32, height=36)
    with pytest.raises(tessera.Error):
        tessera.run_aa(ssaa=[9], width=8, height=8, frames=1)
