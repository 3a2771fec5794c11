"""encode / decode / files through the Python module, byte for byte against the CLI."""

import pickle

import numpy as np
import pytest

import tessera
from conftest import SHARED_IMAGES, cli_json, make_image, run_cli


def psnr(a, b):
    mse = np.mean((a[..., :3].astype(np.float64) - b[..., :3].astype(np.float64)) ** 2)
    return 10 * np.log10(255.0 ** 2 / mse)


@pytest.mark.parametrize("channels", [3, 4])
def test_round_trip(channels):
    img = make_image(64, 128, channels)
    tex = tessera.encode(img, quality="normal")
    assert (tex.width, tex.height, tex.format, tex.level_count) == (128, 64, "pvrtc1-4", 1)
    assert tex.has_alpha == (channels == 4) and not tex.srgb
    assert len(tex.levels[0]) == (128 // 4) * (64 // 4) * 8
    out = tessera.decode(tex)
    assert out.dtype == np.uint8 and out.shape == (64, 128, channels)
    assert psnr(img, out) > 25.0
    if channels == 4:
        assert np.abs(out[..., 3].astype(int) - img[..., 3]).mean() < 12
    assert np.array_equal(tex.decode(0), out)


def test_opaque_alpha_gives_rgb_texture_and_three_channels():
    img = make_image(32, 32, 4, alpha="opaque")
    tex = tessera.encode(img)
    assert not tex.has_alpha and tex.format_name == "PVRTC1 4bpp RGB"
    assert tessera.decode(tex).shape == (32, 32, 3)
    assert tex == tessera.encode(np.ascontiguousarray(img[..., :3]))


def test_strided_arrays_equal_contiguous_copies():
    big = make_image(64, 128, 4, seed=3)
    views = [big[::2, ::2], big[::-1, 32:96], np.swapaxes(big, 0, 1)[:64, :64],
             big[:32, :64, [2, 1, 0]], big[:32, :64, :3]]
    for view in views:
        assert not view.flags["C_CONTIGUOUS"]
        assert tessera.encode(view, quality="fast") == tessera.encode(
            np.ascontiguousarray(view), quality="fast")


def test_arrays_are_read_in_place_unchanged_whatever_their_layout():
    # The encoder reads the caller's array where it lies (no copy first): read-only, broadcast,
    # flipped and padded layouts give the texture of their contiguous copy, tiny and
    # non-power-of-two arrays (resampled) and mip chains too, and no array is written to.
    base = make_image(64, 64, 4, seed=5)
    readonly = np.frombuffer(base.tobytes(), np.uint8).reshape(base.shape)
    assert not readonly.flags["WRITEABLE"]
    padded = np.zeros((64, 80, 4), np.uint8)
    padded[:, :64] = base
    cases = [readonly, readonly[..., :3], np.broadcast_to(base[:1], base.shape),
             np.broadcast_to(base[:1, :1, :3], (32, 16, 3)), base[::-1, :, :3], padded[:, :64],
             base[:2, :4], base[:48, :40]]
    for array in cases:
        before = array.copy()
        for opts in ({"quality": "fast"}, {"quality": "fast", "format": "pvrtc1-2"},
                     {"mipmaps": True, "quality": "fast"}, {"resize_pot": True}):
            if array.shape[:2] == (48, 40) and not opts.get("resize_pot"):
                with pytest.raises(tessera.InvalidArgumentError, match="power of two"):
                    tessera.encode(array, **opts)
                continue
            assert tessera.encode(array, **opts) == tessera.encode(
                np.ascontiguousarray(array), **opts), (array.shape, array.strides, opts)
        assert np.array_equal(array, before)


def test_mipmaps_levels_and_shapes():
    tex = tessera.encode(make_image(32, 128, 4), mipmaps=True, format="pvrtc1-2")
    assert tex.level_count == 8  # 128x32 down to 1x1
    assert [tex.level_shape(i) for i in (0, 1, 7)] == [(32, 128), (16, 64), (1, 1)]
    assert tessera.decode(tex, level=7).shape == (1, 1, 4)
    with pytest.raises(IndexError):
        tex.level_shape(8)


def test_file_round_trips(tmp_path):
    tex = tessera.encode(make_image(64, 64, 4), mipmaps=True, srgb=True)
    for container in ("pvr", "ktx"):
        path = tmp_path / f"t.{container}"
        tex.write(path)
        assert path.read_bytes() == tex.to_bytes(container)
        assert tessera.read(path) == tex
        assert tessera.read(str(path)).srgb
        assert tessera.from_bytes(path.read_bytes()) == tex
    tessera.write(tmp_path / "w.pvr", tex)
    assert (tmp_path / "w.pvr").read_bytes() == tex.to_bytes()
    assert pickle.loads(pickle.dumps(tex)) == tex


def test_image_io_round_trip(tmp_path):
    for channels in (3, 4):
        img = make_image(20, 12, channels)
        tessera.write_image(tmp_path / "i.png", img)
        assert np.array_equal(tessera.read_image(tmp_path / "i.png"), img)


def compress_both_ways(tmp_path, img, name, ext, cli_opts, **opts):
    """(CLI file bytes, encode(array) bytes, encode_file(png) bytes) for the same options."""
    png = tmp_path / f"{name}.png"
    tessera.write_image(png, img)
    out = tmp_path / f"{name}.{ext}"
    run_cli("compress", png, "-o", out, *cli_opts)
    return (out.read_bytes(), tessera.encode(img, **opts).to_bytes(ext),
            tessera.encode_file(png, **opts).to_bytes(ext))


@pytest.mark.parametrize("fmt", ["pvrtc1-4", "pvrtc1-2"])
@pytest.mark.parametrize("quality", ["fast", "normal"])
@pytest.mark.parametrize("mipmaps", [False, True])
def test_bytes_equal_cli(tmp_path, fmt, quality, mipmaps):
    cli_opts = ["--format", fmt, "--quality", quality] + (["--mipmaps"] if mipmaps else [])
    for i, (channels, h, w) in enumerate([(3, 64, 64), (4, 32, 128)]):
        img = make_image(h, w, channels, seed=i)
        for ext in ("pvr", "ktx"):
            cli, from_array, from_file = compress_both_ways(
                tmp_path, img, f"img{i}", ext, cli_opts, format=fmt, quality=quality,
                mipmaps=mipmaps)
            assert from_array == cli and from_file == cli, (channels, ext)


def test_bytes_equal_cli_other_options(tmp_path):
    img = make_image(64, 64, 4, seed=5)
    cases = [
        (["--srgb", "--mipmaps"], dict(srgb=True, mipmaps=True)),
        (["--iterations", "1", "--exact-search-rounds", "2"],
         dict(iterations=1, exact_search_rounds=2)),
        (["--quality", "fast", "--iterations", "2", "-j", "1"],
         dict(quality="fast", iterations=2, threads=1)),
    ]
    for cli_opts, opts in cases:
        cli, from_array, from_file = compress_both_ways(tmp_path, img, "o", "pvr", cli_opts,
                                                        **opts)
        assert from_array == cli and from_file == cli, cli_opts
    # --resize-pot on a 48x40 RGBA image, with mips and sRGB.
    odd = make_image(40, 48, 4, seed=6)
    cli, from_array, from_file = compress_both_ways(
        tmp_path, odd, "odd", "ktx", ["--resize-pot", "--mipmaps", "--srgb", "--quality", "fast"],
        resize_pot=True, mipmaps=True, srgb=True, quality="fast")
    assert from_array == cli and from_file == cli
    assert tessera.from_bytes(cli).width == 64 and tessera.from_bytes(cli).height == 32


def test_decode_equals_cli_decompress(tmp_path):
    for channels in (3, 4):
        tex = tessera.encode(make_image(32, 64, channels), mipmaps=True, quality="fast")
        tex.write(tmp_path / "d.pvr")
        for level in (0, 2):
            run_cli("decompress", tmp_path / "d.pvr", "-o", tmp_path / "d.png", "--level", level)
            assert np.array_equal(tessera.read_image(tmp_path / "d.png"),
                                  tessera.decode(tex, level=level))
        info = cli_json("info", tmp_path / "d.pvr", "--json")
        assert (info["width"], info["height"], info["has_alpha"], len(info["levels"])) == (
            tex.width, tex.height, tex.has_alpha, tex.level_count)


@pytest.mark.skipif(not SHARED_IMAGES.is_dir(), reason=f"{SHARED_IMAGES} not present")
def test_shared_images_equal_cli(tmp_path):
    # 256x256 RGB and RGBA photos, 127x128 (resized), and grey 1024x1024 (expanded to RGB).
    cases = [("ldr-rgb-00.png", "normal", []), ("ldr-rgba-01.png", "normal", ["--mipmaps"]),
             ("ldr-rgb-10.png", "fast", ["--resize-pot"]), ("ldr-l-occlusion.png", "fast", [])]
    for name, quality, extra in cases:
        src = SHARED_IMAGES / name
        out = tmp_path / (name + ".pvr")
        run_cli("compress", src, "-o", out, "--quality", quality, *extra)
        opts = dict(quality=quality, mipmaps="--mipmaps" in extra,
                    resize_pot="--resize-pot" in extra)
        assert tessera.encode_file(src, **opts).to_bytes() == out.read_bytes(), name
        assert tessera.encode(tessera.read_image(src), **opts).to_bytes() == out.read_bytes()
