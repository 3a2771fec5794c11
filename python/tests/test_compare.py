"""tessera.compare against `tessera compare --json`."""

import numpy as np

import tessera
from conftest import cli_json, make_image


def test_compare_equals_cli_json(tmp_path):
    cases = [
        (make_image(48, 40, 3, seed=1), make_image(48, 40, 3, seed=2)),   # RGB vs RGB
        (make_image(48, 40, 4, seed=1), make_image(48, 40, 3, seed=1)),   # RGBA vs RGB
        (make_image(8, 8, 4, seed=3), make_image(8, 8, 4, seed=4)),       # below the SSIM window
    ]
    for i, (a, b) in enumerate(cases):
        pa, pb = tmp_path / f"a{i}.png", tmp_path / f"b{i}.png"
        tessera.write_image(pa, a)
        tessera.write_image(pb, b)
        expected = cli_json("compare", pa, pb, "--json")
        got = tessera.compare(pa, pb)
        assert got == expected, i
        from_arrays = tessera.compare(a, b, threads=1)
        assert set(expected) - set(from_arrays) == {"a", "b"}
        assert from_arrays == {k: v for k, v in expected.items() if k not in ("a", "b")}
        assert tessera.compare(str(pa), b) == {k: v for k, v in expected.items() if k != "b"}


def test_compare_identical_and_decoded(tmp_path):
    img = make_image(64, 64, 3)
    same = tessera.compare(img, img.copy())
    assert same["psnr_rgb"] is None and same["identical_rgb"] and same["max_abs"] == 0
    assert same["ssim_gray"] == 1.0 and not same["has_alpha"] and "psnr_alpha" not in same
    tex = tessera.encode(img)
    tex.write(tmp_path / "t.pvr")
    decoded = tessera.decode(tex)
    tessera.write_image(tmp_path / "in.png", img)
    tessera.write_image(tmp_path / "out.png", decoded)
    expected = cli_json("compare", tmp_path / "in.png", tmp_path / "out.png", "--json")
    got = tessera.compare(img, decoded)
    assert got["psnr_rgb"] == expected["psnr_rgb"] and got["ssim_gray"] == expected["ssim_gray"]
    assert 25 < got["psnr_rgb"] < 60 and not got["identical_rgb"]
    mse = np.mean((img.astype(np.float64) - decoded) ** 2)
    assert abs(got["mse"] - mse) <= 1e-9 * mse
