"""tessera.batch: a directory tree over a 2-worker Dask LocalCluster, against the CLI."""

import json
import logging
import os
import subprocess
import sys
from pathlib import Path

import pytest

import tessera
import tessera.batch
from conftest import cli_error, make_image, run_cli

GOOD = {  # relative path: (height, width, channels, alpha)
    "top.png": (64, 64, 3, "ramp"),
    "a/rgba.png": (32, 64, 4, "ramp"),
    "a/b/deep.png": (128, 32, 3, "ramp"),
    "a/b/opaque.PNG": (32, 32, 4, "opaque"),
}
BAD = ["a/npot.png", "a/b/corrupt.png"]


def make_tree(root):
    for i, (rel, (h, w, c, alpha)) in enumerate(GOOD.items()):
        (root / rel).parent.mkdir(parents=True, exist_ok=True)
        tessera.write_image(root / rel, make_image(h, w, c, seed=i, alpha=alpha))
    tessera.write_image(root / BAD[0], make_image(40, 48, 3))
    (root / BAD[1]).write_bytes(b"\x89PNG\r\n\x1a\n" + b"\x00" * 40)
    (root / "a" / "notes.txt").write_text("not an image")
    return root


def output_of(dst, rel, container):
    return dst / Path(rel).with_suffix("." + container)


def check_outputs_equal_cli(src, dst, tmp_path, container, cli_opts):
    for rel in GOOD:
        ref = tmp_path / ("ref." + container)
        run_cli("compress", src / rel, "-o", ref, *cli_opts)
        out = output_of(dst, rel, container)
        assert out.read_bytes() == ref.read_bytes(), rel
        assert Path(str(out) + ".json").is_file()
    for rel in BAD:
        assert not output_of(dst, rel, container).exists()


def expected_failures(src, tmp_path):
    return sorted(cli_error("compress", src / rel, "-o", tmp_path / "x.pvr") for rel in BAD)


@pytest.fixture(scope="module")
def client():
    from dask.distributed import Client, LocalCluster

    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                           dashboard_address=None, silence_logs=logging.ERROR)
    c = Client(cluster)
    yield c
    c.close()
    cluster.close()


def test_plan_mirrors_tree_and_reports_clashes(tmp_path):
    src = make_tree(tmp_path / "src")
    (src / "a" / "rgba.tga").write_bytes(b"\0" * 18)  # a/rgba.pvr again, after a/rgba.png
    jobs, clashes = tessera.batch.plan(src, tmp_path / "dst", "ktx")
    rels = [Path(s).relative_to(src).as_posix() for s, _ in jobs]
    assert sorted(rels) == sorted(set(GOOD) | set(BAD))
    for s, o in jobs:
        assert Path(o) == output_of(tmp_path / "dst", Path(s).relative_to(src), "ktx")
    assert [(Path(s).name, e) for s, e in clashes] == [
        ("rgba.tga", f"{src}/a/rgba.tga: output {tmp_path}/dst/a/rgba.ktx is also made from "
                     f"{src}/a/rgba.png")]


def test_compress_tree_resumes_and_fails_alone(tmp_path, client):
    src, dst = make_tree(tmp_path / "src"), tmp_path / "dst"
    results = []
    s1 = tessera.batch.compress_tree(src, dst, client=client, quality="fast", mipmaps=True,
                                     on_result=results.append)
    assert (s1["files"], s1["done"], s1["skipped"], s1["failed"]) == (6, 4, 0, 2)
    assert s1["workers"] == 2 and len(results) == 6
    assert sorted(f["error"] for f in s1["failures"]) == expected_failures(src, tmp_path)
    assert s1["pixels"] == sum(h * w for h, w, _, _ in GOOD.values())
    assert s1["mpixels_per_s"] > 0
    check_outputs_equal_cli(src, dst, tmp_path, "pvr", ["--quality", "fast", "--mipmaps"])
    sidecar = json.loads(Path(str(dst / "top.pvr") + ".json").read_text())
    assert sidecar["options"]["quality"] == "fast" and sidecar["options"]["mipmaps"] is True

    s2 = tessera.batch.compress_tree(src, dst, client=client, quality="fast", mipmaps=True)
    assert (s2["done"], s2["skipped"], s2["failed"]) == (0, 4, 2)

    # Other options: everything is compressed again.
    s3 = tessera.batch.compress_tree(src, dst, client=client, quality="normal")
    assert (s3["done"], s3["skipped"], s3["failed"]) == (4, 0, 2)
    check_outputs_equal_cli(src, dst, tmp_path, "pvr", ["--quality", "normal"])

    # An output older than its input is compressed again, alone.
    out = dst / "a" / "rgba.pvr"
    st = os.stat(src / "a" / "rgba.png")
    os.utime(out, ns=(st.st_atime_ns, st.st_mtime_ns - 1_000_000_000))
    s4 = tessera.batch.compress_tree(src, dst, client=client, quality="normal")
    assert (s4["done"], s4["skipped"], s4["failed"]) == (1, 3, 2)
    # So is one whose sidecar is missing.
    os.remove(str(dst / "top.pvr") + ".json")
    s5 = tessera.batch.compress_tree(src, dst, client=client, quality="normal")
    assert (s5["done"], s5["skipped"]) == (1, 3)
    check_outputs_equal_cli(src, dst, tmp_path, "pvr", ["--quality", "normal"])


def test_compress_tree_rejects_bad_options(tmp_path):
    src = make_tree(tmp_path / "src")
    with pytest.raises(ValueError, match="quality: 'best'"):
        tessera.batch.compress_tree(src, tmp_path / "dst", quality="best")
    with pytest.raises(ValueError, match="container: 'dds'"):
        tessera.batch.compress_tree(src, tmp_path / "dst", container="dds")
    with pytest.raises(ValueError, match="unknown encode option"):
        tessera.batch.compress_tree(src, tmp_path / "dst", qualty="fast")
    with pytest.raises(ValueError, match="not a directory"):
        tessera.batch.compress_tree(tmp_path / "nothing", tmp_path / "dst")
    assert not (tmp_path / "dst").exists()


def run_batch(*args):
    return subprocess.run([sys.executable, "-m", "tessera.batch", *map(str, args)],
                          capture_output=True, text=True)


def test_batch_command_line(tmp_path):
    src, dst = make_tree(tmp_path / "src"), tmp_path / "dst"
    opts = ["--format", "pvrtc1-2", "--container", "ktx", "--srgb"]
    r = run_batch(src, dst, "--workers", "2", *opts)
    assert r.returncode == 1, r.stderr
    assert "6 file(s): 4 done, 0 skipped, 2 failed" in r.stdout
    for message in expected_failures(src, tmp_path):
        assert f"tessera.batch: {message}\n" in r.stderr
        assert f"  failed: {message}\n" in r.stdout + "\n"
    check_outputs_equal_cli(src, dst, tmp_path, "ktx", ["--format", "pvrtc1-2", "--srgb"])

    r = run_batch(src, dst, "--workers", "2", "--json", *opts)
    assert r.returncode == 1
    summary = json.loads(r.stdout)
    assert (summary["done"], summary["skipped"], summary["failed"]) == (0, 4, 2)

    for rel in BAD:
        os.remove(src / rel)
    r = run_batch(src, dst, *opts)
    assert r.returncode == 0, r.stderr
    assert "4 file(s): 0 done, 4 skipped, 0 failed" in r.stdout

    r = run_batch(src, dst, "--quality", "best")
    assert r.returncode == 2 and "invalid choice" in r.stderr


def test_sidecars_shared_with_cli_skip_up_to_date(tmp_path, client):
    # `tessera compress --skip-up-to-date` keeps the same sidecar record: each side skips what
    # the other made with the same options, and redoes what it made with others.
    src, dst = make_tree(tmp_path / "src"), tmp_path / "dst"
    tessera.batch.compress_tree(src, dst, client=client, quality="fast")
    r = run_cli("compress", src / "top.png", "-o", dst / "top.pvr", "--quality", "fast",
                "--skip-up-to-date")
    assert r.stdout.startswith("skipped ")
    run_cli("compress", src / "a/rgba.png", "-o", dst / "a/rgba.pvr", "--quality", "normal",
            "--skip-up-to-date")
    s = tessera.batch.compress_tree(src, dst, client=client, quality="normal")
    assert (s["done"], s["skipped"]) == (3, 1)


def test_up_to_date_record_is_the_clis(tmp_path):
    # tessera.up_to_date_record gives the bytes `tessera compress --skip-up-to-date` writes
    # (cube maps included), and tessera.is_up_to_date takes the CLI's record for its own.
    src = make_tree(tmp_path / "src")
    img = src / "top.png"
    out = tmp_path / "top.ktx2"
    run_cli("compress", img, "-o", out, "-q", "--mip-levels", "2", "--zstd", "4", "--flip-y",
            "--skip-up-to-date")
    keywords = dict(container="ktx2", zstd=4, mip_levels=2, flip_y=True)
    record = tessera.up_to_date_record(img, **keywords)
    assert Path(f"{out}.json").read_text() == record
    assert json.loads(record)["options"]["mip_levels"] == 2
    assert tessera.is_up_to_date(img, out, **keywords)
    assert not tessera.is_up_to_date(img, out, **dict(keywords, quality="fast"))
    faces = [str(tmp_path / f"f{i}.png") for i in range(6)]
    for i, face in enumerate(faces):
        tessera.write_image(face, make_image(16, 16, 4, seed=i))
    cube = tmp_path / "cube.pvr"
    run_cli("compress", *faces, "--cube", "-o", cube, "-q", "--skip-up-to-date")
    assert Path(f"{cube}.json").read_text() == tessera.up_to_date_record(faces, cube=True)
    # Written atomically beside the output; bad keywords and inputs raise, naming them.
    other = tmp_path / "other.ktx2"
    other.write_bytes(out.read_bytes())
    tessera.write_up_to_date_record(other, record)
    assert Path(f"{other}.json").read_text() == record
    with pytest.raises(tessera.InvalidArgumentError, match="container: 'dds'"):
        tessera.up_to_date_record(img, container="dds")
    with pytest.raises(tessera.InvalidArgumentError, match="zstd needs a KTX 2.0"):
        tessera.up_to_date_record(img, zstd=3)
    with pytest.raises(tessera.Error, match="gone.png"):
        tessera.up_to_date_record(tmp_path / "gone.png")


def test_group_jobs_sizes_and_order():
    jobs = [(f"s{i}", f"o{i}") for i in range(200)]
    # Guided: equal files keep their order, 16 per task while there is much work left, each
    # task about the remaining work / (2 x workers), single files at the end.
    groups = tessera.batch.group_jobs(jobs, None, 2)
    assert [j for g in groups for j in g] == jobs
    assert [len(g) for g in groups] == [16] * 9 + [14, 11, 8, 6, 5, 3, 3, 2, 1, 1, 1, 1]
    assert [len(g) for g in tessera.batch.group_jobs(jobs, None, 100)] == [1] * 200
    assert max(len(g) for g in tessera.batch.group_jobs(jobs * 100, None, 2)) == 16
    # Weighted: heaviest first (ties in order), a heavy file alone, light ones grouped.
    weights = [1, 50, 1, 1, 30, 1, 1, 1]
    groups = tessera.batch.group_jobs(jobs[:8], None, 2, weights)
    assert groups == [[jobs[1]], [jobs[4]], [jobs[0], jobs[2]], [jobs[3]], [jobs[5]], [jobs[6]],
                      [jobs[7]]]
    # Fixed: consecutive groups in tree order.
    assert [len(g) for g in tessera.batch.group_jobs(jobs[:7], 3, 2)] == [3, 3, 1]
    with pytest.raises(ValueError, match="files_per_task: 0"):
        tessera.batch.group_jobs(jobs, 0, 2)


def test_grouped_tasks_write_the_same_bytes_and_fail_alone(tmp_path, client):
    # Three files per task: the two bad files share tasks with good ones and still fail alone.
    src = make_tree(tmp_path / "src")
    results = []
    s = tessera.batch.compress_tree(src, tmp_path / "dst", client=client, quality="fast",
                                    files_per_task=3, on_result=results.append)
    assert (s["files"], s["done"], s["failed"]) == (6, 4, 2) and len(results) == 6
    assert sorted(f["error"] for f in s["failures"]) == expected_failures(src, tmp_path)
    check_outputs_equal_cli(src, tmp_path / "dst", tmp_path, "pvr", ["--quality", "fast"])
    with pytest.raises(ValueError, match="files_per_task: 0"):
        tessera.batch.compress_tree(src, tmp_path / "dst2", files_per_task=0)


# The per-image options added with the asset features: (compress_tree keywords, the CLI's flags,
# container, zstd level).
NEW_OPTIONS = [
    (dict(mip_levels=3, mip_filter="kaiser", flip_y=True, premultiply=True, quality="fast"),
     ["--mip-levels", "3", "--mip-filter", "kaiser", "--flip-y", "--premultiply", "--quality",
      "fast"], "ktx2", 7),
    (dict(alpha_bleed=True, alpha_weighted=True, normal_map=True, mipmaps=True,
          mip_filter="lanczos", quality="fast"),
     ["--alpha-bleed", "--alpha-weighted", "--normal-map", "--mipmaps", "--mip-filter", "lanczos",
      "--quality", "fast"], "pvr", 0),
]


def check_outputs_and_sidecars_equal_cli(src, dst, tmp_path, container, cli_opts):
    for rel in GOOD:
        out = output_of(dst, rel, container)
        # The CLI takes the batch's sidecar for its own ...
        r = run_cli("compress", src / rel, "-o", out, *cli_opts, "--skip-up-to-date")
        assert r.stdout.startswith(f"skipped {out}: up to date"), (rel, r.stdout)
        # ... and writes the same bytes, texture and sidecar.
        ref = tmp_path / f"ref.{container}"
        for stale in (ref, Path(f"{ref}.json")):
            stale.unlink(missing_ok=True)
        run_cli("compress", src / rel, "-o", ref, "-q", *cli_opts, "--skip-up-to-date")
        assert out.read_bytes() == ref.read_bytes(), rel
        assert Path(f"{out}.json").read_bytes() == Path(f"{ref}.json").read_bytes(), rel


def rgb_inputs(src):
    return sorted(str(src / rel) for rel, (_, _, c, _) in GOOD.items() if c == 3)


def test_new_options_write_the_cli_bytes_and_sidecars(tmp_path, client):
    src = make_tree(tmp_path / "src")
    keywords, flags, container, zstd = NEW_OPTIONS[0]
    dst = tmp_path / "dst"
    s1 = tessera.batch.compress_tree(src, dst, client=client, container=container, zstd=zstd,
                                     **keywords)
    assert (s1["done"], s1["skipped"], s1["failed"]) == (4, 0, 2)
    cli_flags = [*flags, "--zstd", str(zstd)]
    check_outputs_and_sidecars_equal_cli(src, dst, tmp_path, container, cli_flags)
    record = json.loads(Path(f"{dst}/top.ktx2.json").read_text())["options"]
    assert {k: record[k] for k in ("mip_levels", "mip_filter", "flip_y", "premultiply", "zstd")} \
        == {"mip_levels": 3, "mip_filter": "kaiser", "flip_y": True, "premultiply": True,
            "zstd": 7}
    assert "alpha_bleed" not in record and "normal_map" not in record
    assert "alpha_weighted" not in record
    # --premultiply on the RGB inputs: the CLI's warning, with the file.
    expected = []
    for path in rgb_inputs(src):
        r = run_cli("compress", path, "-o", tmp_path / "w.pvr", "--premultiply")
        expected += [{"src": path, "warning": line.removeprefix("tessera: warning: ")}
                     for line in r.stderr.splitlines() if "warning" in line]
    assert len(expected) == 2 and s1["warnings"] == expected

    s2 = tessera.batch.compress_tree(src, dst, client=client, container=container, zstd=zstd,
                                     **keywords)
    assert (s2["done"], s2["skipped"]) == (0, 4)
    # Another zstd level is another record: everything again, and the level is no default.
    s3 = tessera.batch.compress_tree(src, dst, client=client, container=container, zstd=0,
                                     **keywords)
    assert (s3["done"], s3["skipped"]) == (4, 0)
    assert "zstd" not in json.loads(Path(f"{dst}/top.ktx2.json").read_text())["options"]
    check_outputs_and_sidecars_equal_cli(src, dst, tmp_path, container, flags)


def test_new_options_on_the_command_line(tmp_path):
    src, dst = make_tree(tmp_path / "src"), tmp_path / "dst"
    for rel in BAD:
        os.remove(src / rel)
    keywords, flags, container, _ = NEW_OPTIONS[1]
    r = run_batch(src, dst, "--workers", "2", "--container", container, *flags)
    assert r.returncode == 0, r.stderr
    assert "4 file(s): 4 done, 0 skipped, 0 failed" in r.stdout
    check_outputs_and_sidecars_equal_cli(src, dst, tmp_path, container, flags)

    # --premultiply's warnings, as the CLI prints them.
    r = run_batch(src, tmp_path / "dst2", "--workers", "1", "--premultiply", "--container",
                  "ktx2", "--zstd", "5")
    assert r.returncode == 0, r.stderr
    for path in rgb_inputs(src):
        assert (f"tessera.batch: warning: {path} has no alpha channel: --premultiply leaves it "
                "as it is\n") in r.stderr
    check_outputs_and_sidecars_equal_cli(src, tmp_path / "dst2", tmp_path, "ktx2",
                                         ["--premultiply", "--zstd", "5"])


@pytest.mark.parametrize("flags", [["--normal-map", "--srgb"], ["--premultiply", "--alpha-bleed"],
                                   ["--mip-filter", "kaiser"],
                                   ["--alpha-weighted", "--premultiply"],
                                   ["--alpha-weighted", "--format", "pvrtc1-2"]])
def test_command_line_conflicts_are_the_cli_usage_errors(tmp_path, flags):
    src = make_tree(tmp_path / "src")
    cli = run_cli("compress", src / "top.png", "-o", tmp_path / "x.pvr", *flags, check=False)
    assert cli.returncode == 2
    r = run_batch(src, tmp_path / "dst", *flags)
    assert r.returncode == 2
    assert r.stderr == cli.stderr.replace("tessera compress: ", "tessera.batch: ")
    assert not (tmp_path / "dst").exists()


def test_command_line_range_and_zstd_errors(tmp_path):
    src = make_tree(tmp_path / "src")
    for args, message in [(["--zstd", "3"], "--zstd needs a KTX 2.0 output (--container ktx2)"),
                          (["--mip-levels", "18"], "--mip-levels: 18 is not in [1, 17]"),
                          (["--zstd", "0", "--container", "ktx2"], "--zstd: 0 is not in [1, 22]"),
                          (["--mip-filter", "gauss"], "invalid choice: 'gauss'"),
                          (["--container", "dds"], "invalid choice: 'dds'")]:
        r = run_batch(src, tmp_path / "dst", *args)
        assert r.returncode == 2 and message in r.stderr, (args, r.stderr)
    assert not (tmp_path / "dst").exists()


def test_compress_tree_keyword_errors_are_the_module_s(tmp_path):
    src = make_tree(tmp_path / "src")
    img = make_image(16, 16, 4)
    for keywords in (dict(normal_map=True, srgb=True), dict(premultiply=True, alpha_bleed=True),
                     dict(premultiply=True, alpha_weighted=True),
                     dict(alpha_weighted=True, format="pvrtc1-2"), dict(mip_filter="lanczos"),
                     dict(mip_filter="gauss", mipmaps=True),
                     dict(mip_levels=18)):
        with pytest.raises(ValueError) as module:
            tessera.encode(img, **keywords)
        with pytest.raises(ValueError) as batch:
            tessera.batch.compress_tree(src, tmp_path / "dst", **keywords)
        assert str(batch.value) == str(module.value)
        assert "--" not in str(batch.value)
    with pytest.raises(ValueError) as module:
        tessera.encode(img).to_bytes("pvr", zstd=3)
    with pytest.raises(ValueError) as batch:
        tessera.batch.compress_tree(src, tmp_path / "dst", zstd=3)
    assert str(batch.value) == str(module.value)
    with pytest.raises(ValueError, match=r"zstd: 23 is not in \[0, 22\]"):
        tessera.batch.compress_tree(src, tmp_path / "dst", container="ktx2", zstd=23)
    with pytest.raises(ValueError, match="^cube: tessera.batch makes one 2D texture of each "):
        tessera.batch.compress_tree(src, tmp_path / "dst", cube=True)
    assert not (tmp_path / "dst").exists()
