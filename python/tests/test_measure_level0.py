"""tessera.measure_level0 (texture_file::measure_level0) against `tessera compress --json`."""

import numpy as np
import pytest

import tessera
from conftest import cli_json, make_image


def test_measure_level0_equals_cli_compress_json(tmp_path):
    for i, (img, opts) in enumerate([(make_image(64, 64, 3, seed=1), ()),
                                     (make_image(32, 64, 4, seed=2), ("--quality", "fast"))]):
        png = tmp_path / f"in{i}.png"
        tessera.write_image(png, img)
        report = cli_json("compress", png, "-o", tmp_path / f"out{i}.pvr", "--json", *opts)
        tex = tessera.read(tmp_path / f"out{i}.pvr")
        got = tessera.measure_level0(tex, img, threads=1)
        assert (got["width"], got["height"], got["images"]) == (img.shape[1], img.shape[0], 1)
        assert got["psnr_rgb"] == report["psnr_rgb"], i
        assert got["ssim_gray"] == report["ssim_gray"], i
        assert got.get("psnr_alpha") == report.get("psnr_alpha"), i
        # The same numbers as compare on the decoded image: one image pools to itself.
        single = tessera.compare(img, tessera.decode(tex))
        assert {k: got[k] for k in single} == single


def test_measure_level0_pools_cube_faces(tmp_path):
    faces = np.stack([make_image(32, 32, 3, seed=s) for s in range(6)])
    tex = tessera.encode(faces, cube=True)
    got = tessera.measure_level0(tex, faces)
    decoded = tessera.decode(tex)
    per_face = [tessera.compare(faces[f], decoded[f]) for f in range(6)]
    assert got["images"] == 6
    assert got["mse"] == pytest.approx(np.mean([c["mse"] for c in per_face]), rel=1e-12)
    assert got["ssim_gray"] == pytest.approx(np.mean([c["ssim_gray"] for c in per_face]),
                                             rel=1e-12)
    assert got["max_abs"] == max(c["max_abs"] for c in per_face)
    # A list of the faces is the same input.
    assert tessera.measure_level0(tex, list(faces)) == got
    # Negative control: the faces in another order are measured against the wrong sources.
    assert tessera.measure_level0(tex, faces[::-1].copy())["mse"] > 2 * got["mse"]


def test_measure_level0_errors():
    img = make_image(32, 32, 3)
    tex = tessera.encode(img)
    with pytest.raises(tessera.InvalidArgumentError, match="2 source image"):
        tessera.measure_level0(tex, [img, img])
    with pytest.raises(tessera.Error, match="size"):
        tessera.measure_level0(tex, make_image(16, 16, 3))
