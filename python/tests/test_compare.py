"""tessera.compare against `tessera compare --json`."""

import numpy as np

import tessera
from conftest import cli_json, make_image, make_normal_map


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


def test_compare_premultiplied_and_normal_equal_cli_json(tmp_path):
    rgba = make_image(32, 32, 4, seed=1)
    normal = make_normal_map(32, 32)
    cases = [  # a, b, premultiplied, normal
        (rgba, tessera.decode(tessera.encode(rgba, quality="fast")), True, False),
        (rgba, rgba.copy(), True, False),                                      # identical
        (normal, tessera.decode(tessera.encode(normal, normal_map=True)), False, True),
        (rgba, make_image(32, 32, 3, seed=2), True, True),                     # RGBA vs RGB
    ]
    for i, (a, b, premultiplied, normal_keys) in enumerate(cases):
        pa, pb = tmp_path / f"a{i}.png", tmp_path / f"b{i}.png"
        tessera.write_image(pa, a)
        tessera.write_image(pb, b)
        flags = ["--premultiplied"] * premultiplied + ["--normal"] * normal_keys
        expected = cli_json("compare", pa, pb, "--json", *flags)
        assert ("psnr_premultiplied" in expected) == premultiplied
        assert ("angular_error_mean_deg" in expected) == normal_keys
        got = tessera.compare(pa, pb, premultiplied=premultiplied, normal=normal_keys)
        assert got == expected, i
        from_arrays = tessera.compare(a, b, premultiplied=premultiplied, normal=normal_keys,
                                      threads=1)
        assert from_arrays == {k: v for k, v in expected.items() if k not in ("a", "b")}, i
        plain = tessera.compare(a, b)
        assert plain == {k: v for k, v in from_arrays.items()
                         if "premultiplied" not in k and "angular" not in k}
    same = tessera.compare(rgba, rgba, premultiplied=True)
    assert same["psnr_premultiplied"] is None and same["mse_premultiplied"] == 0.0
    coded = tessera.compare(normal, cases[2][1], normal=True)
    assert 0 < coded["angular_error_mean_deg"] <= coded["angular_error_p99_deg"] <= \
        coded["angular_error_max_deg"] < 20
