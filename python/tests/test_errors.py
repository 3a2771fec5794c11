"""Errors: Python exception types, and the CLI's message text."""

import numpy as np
import pytest

import tessera
from conftest import cli_error, make_image


def test_exception_hierarchy():
    assert issubclass(tessera.Error, RuntimeError)
    assert issubclass(tessera.InvalidArgumentError, tessera.Error)
    assert issubclass(tessera.InvalidArgumentError, ValueError)
    assert not issubclass(tessera.Error, ValueError)


def python_words(cli_message):
    """The CLI's message as the Python module shows it: its flag as the keyword."""
    return cli_message.replace("with --resize-pot", "with resize_pot=True")


def test_non_power_of_two_matches_cli(tmp_path):
    img = make_image(48, 64, 3)
    png = tmp_path / "npot.png"
    tessera.write_image(png, img)
    cli = cli_error("compress", png, "-o", tmp_path / "npot.pvr")
    assert cli.endswith("resample to 64x64 with --resize-pot")
    expected = python_words(cli)
    assert expected.endswith("resample to 64x64 with resize_pot=True") and "--" not in expected
    with pytest.raises(tessera.InvalidArgumentError) as info:
        tessera.encode_file(png)
    assert str(info.value) == expected and info.value.code == "invalid_argument"
    with pytest.raises(ValueError) as info:
        tessera.encode(img, name=str(png))
    assert str(info.value) == expected
    with pytest.raises(tessera.Error, match=r"^<array>: size 64x48 is not a power of two"):
        tessera.encode(img)
    assert not (tmp_path / "npot.pvr").exists()


def test_non_power_of_two_layers_match_cli(tmp_path):
    # The cube map / array path (compress_images) words its message the same way.
    png = tmp_path / "npot.png"
    tessera.write_image(png, make_image(48, 64, 4))
    cli = cli_error("compress", png, png, "--array", "-o", tmp_path / "npot.ktx2")
    assert cli.endswith("with --resize-pot")
    with pytest.raises(tessera.InvalidArgumentError) as info:
        tessera.encode_file([png, png], array=True)
    assert str(info.value) == python_words(cli) and "--" not in str(info.value)
    with pytest.raises(tessera.InvalidArgumentError) as info:
        tessera.encode([make_image(48, 64, 4)] * 2, array=True, name=str(png))
    assert str(info.value) == python_words(cli).replace(str(png), f"{png}[0]", 1)


@pytest.mark.parametrize("bad, message", [
    (np.zeros((8, 8, 4), np.float32), "dtype float32 is not uint8"),
    (np.zeros((8, 8, 4), np.uint16), "dtype uint16 is not uint8"),
    (np.zeros((8, 8, 4), np.int8), "dtype int8 is not uint8"),
    (np.zeros((8, 8), np.uint8), r"shape \(8, 8\) is not \(H, W, 3\) or \(H, W, 4\)"),
    (np.zeros((8, 8, 2), np.uint8), r"shape \(8, 8, 2\) is not"),
    (np.zeros((0, 8, 3), np.uint8), r"shape \(0, 8, 3\) is empty"),
    ([[[0, 0, 0]]], "expected a numpy uint8 array .* got list"),
])
def test_bad_arrays_raise_value_error(bad, message):
    with pytest.raises(ValueError, match=message) as info:
        tessera.encode(bad)
    assert not isinstance(info.value, tessera.Error)
    with pytest.raises(ValueError, match=message):
        tessera.compare(bad, bad)


@pytest.mark.parametrize("kwargs, message", [
    (dict(quality="best"), "quality: 'best' is not one of 'fast', 'normal', 'high'"),
    (dict(format="pvrtc1-8"), "format: 'pvrtc1-8' is not one of 'pvrtc1-4', 'pvrtc1-2'"),
    (dict(iterations=-2), r"iterations: -2 is not in \[-1, 1000\]"),
    (dict(exact_search_rounds=1001), r"exact_search_rounds: 1001 is not in \[0, 1000\]"),
    (dict(threads=-1), "threads: -1 is negative"),
])
def test_bad_options_raise_value_error(kwargs, message):
    with pytest.raises(ValueError, match=message):
        tessera.encode(make_image(8, 8, 3), **kwargs)


def test_unknown_keyword_is_a_type_error():
    with pytest.raises(TypeError):
        tessera.encode(make_image(8, 8, 3), qualiti="fast")


def test_missing_files_match_cli(tmp_path):
    missing = tmp_path / "missing.png"
    expected = cli_error("compress", missing, "-o", tmp_path / "x.pvr")
    for call in (tessera.encode_file, tessera.read_image):
        with pytest.raises(tessera.Error) as info:
            call(missing)
        assert str(info.value) == expected and info.value.code == "io_error"
        assert not isinstance(info.value, ValueError)
    missing_tex = tmp_path / "missing.pvr"
    expected = cli_error("info", missing_tex)
    with pytest.raises(tessera.Error) as info:
        tessera.read(missing_tex)
    assert str(info.value) == expected


def test_corrupt_files_match_cli(tmp_path):
    bad_png = tmp_path / "bad.png"
    bad_png.write_bytes(b"\x89PNG\r\n\x1a\n" + b"\0" * 20)
    expected = cli_error("compress", bad_png, "-o", tmp_path / "x.pvr")
    with pytest.raises(tessera.Error) as info:
        tessera.encode_file(bad_png)
    assert str(info.value) == expected
    # A PVR file cut short inside its level data.
    data = tessera.encode(make_image(32, 32, 4)).to_bytes("pvr")
    cut = tmp_path / "cut.pvr"
    cut.write_bytes(data[:-16])
    expected = cli_error("info", cut)
    with pytest.raises(tessera.Error) as info:
        tessera.read(cut)
    assert str(info.value) == expected and info.value.code == "corrupt_data"
    with pytest.raises(tessera.Error, match="^<bytes>: "):
        tessera.from_bytes(data[:-16])


def test_texture_argument_errors(tmp_path):
    tex = tessera.encode(make_image(16, 16, 3), quality="fast")
    with pytest.raises(ValueError, match="level 1 is out of range"):
        tessera.decode(tex, level=1)
    with pytest.raises(ValueError, match="container: 'dds' is not one of 'pvr', 'ktx', 'ktx2'$"):
        tex.to_bytes("dds")
    with pytest.raises(ValueError, match="unknown texture extension"):
        tex.write(tmp_path / "t.dds")
    with pytest.raises(tessera.Error) as info:
        tex.write(tmp_path / "no" / "such" / "dir" / "t.pvr")
    assert info.value.code == "io_error"
    with pytest.raises(TypeError):
        tessera.Texture()


def test_compare_size_mismatch_matches_cli(tmp_path):
    a, b = tmp_path / "a.png", tmp_path / "b.png"
    tessera.write_image(a, make_image(16, 16, 3))
    tessera.write_image(b, make_image(16, 32, 3))
    expected = cli_error("compare", a, b)
    with pytest.raises(tessera.Error) as info:
        tessera.compare(a, b)
    assert str(info.value) == expected and info.value.code == "size_mismatch"
